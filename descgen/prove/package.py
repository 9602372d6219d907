"""Check: ``package.xml`` parses and validates with catkin_pkg (what colcon uses).

catkin_pkg is the oracle for every package.xml descgen writes (here and in moveit/proof.py),
but importing it (pyparsing) costs more than the rest of the check. What the proofs use of
its reading of a valid manifest (:class:`Manifest`) is kept in the result cache
(descgen/infra/result_cache.py) under the sha256 of the text and the versions of catkin_pkg and
pyparsing: the same bytes, the same verdict. A manifest catkin_pkg refuses, or warns about, is
never cached: catkin_pkg reads it again and says so every time.
"""

from __future__ import annotations

import sys
from pathlib import Path

from descgen.core.findings import Finding, Where
from descgen.core.model import Robot
from descgen.core.record import record
from descgen.infra import result_cache
from descgen.infra.evidence_hash import sha256

_KIND = "catkin-package"


@record
class Manifest:
    """What catkin_pkg read from a manifest it parsed and validated without warnings."""

    format: int
    name: str
    exec_depends: tuple[str, ...]


def invalid_package() -> type[Exception]:
    """catkin_pkg's InvalidPackage, imported only when an exception is being matched
    (``except invalid_package():`` evaluates it then), so a cache hit never imports catkin_pkg."""
    from catkin_pkg.package import InvalidPackage

    found: type[Exception] = InvalidPackage
    return found


def read_manifest(text: str) -> Manifest:
    """catkin_pkg's ``parse_package_string`` and ``validate`` of ``text``; raises what they
    raise (InvalidPackage, ValueError), and prints their warnings as catkin_pkg does."""
    key = result_cache.key(_KIND, sha256(text), ("catkin_pkg", "pyparsing"))
    hit = _manifest(result_cache.get(_KIND, key))
    if hit is not None:
        return hit
    from catkin_pkg.package import parse_package_string

    warnings: list[str] = []
    try:
        pkg = parse_package_string(text, warnings=warnings)
        pkg.validate(warnings=warnings)
    finally:  # printed also when validate then refuses the manifest, as catkin_pkg itself does
        for warning in warnings:
            print("WARNING: " + warning, file=sys.stderr)  # as catkin_pkg prints them (warnings=None)
    found = Manifest(int(pkg.package_format), str(pkg.name), tuple(str(d.name) for d in pkg.exec_depends))
    if not warnings:
        result_cache.put(_KIND, key, {"format": found.format, "name": found.name, "exec_depends": found.exec_depends})
    return found


def _manifest(doc: object) -> Manifest | None:
    if not isinstance(doc, dict):
        return None
    fmt, name, deps = doc.get("format"), doc.get("name"), doc.get("exec_depends")
    if type(fmt) is not int or not isinstance(name, str) or not isinstance(deps, list):
        return None
    if not all(isinstance(d, str) for d in deps):
        return None
    return Manifest(fmt, name, tuple(deps))


def package_xml(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    loc = Where(str(where / "package.xml"))
    try:
        pkg = read_manifest(files["package.xml"])
    except invalid_package() as exc:
        return [
            Finding(
                "GEN002",
                "error",
                f"package.xml is invalid: {exc}",
                "check the package: section of the spec",
                "file:package.xml",
                loc,
            )
        ]
    if pkg.format != 3:
        return [
            Finding(
                "GEN002",
                "error",
                f"package.xml has format {pkg.format}, not 3",
                "check the package.xml template",
                "file:package.xml",
                loc,
            )
        ]
    return []
