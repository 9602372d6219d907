"""Check: ``package.xml`` parses and validates with catkin_pkg (what colcon uses)."""

from __future__ import annotations

from pathlib import Path

from ..findings import Finding, Where
from ..model import Robot


def package_xml(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    from catkin_pkg.package import InvalidPackage, parse_package_string

    loc = Where(str(where / "package.xml"))
    try:
        pkg = parse_package_string(files["package.xml"])
        pkg.validate()
    except InvalidPackage as exc:
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
    if pkg.package_format != 3:
        return [
            Finding(
                "GEN002",
                "error",
                f"package.xml has format {pkg.package_format}, not 3",
                "check the package.xml template",
                "file:package.xml",
                loc,
            )
        ]
    return []
