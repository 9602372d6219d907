"""Expand a Xacro in process with the PyPI ``xacro`` package.

``$(find pkg)`` normally asks the ament index; without ROS we answer it from
``--package-path`` folders: ``<folder>/<pkg>`` (or ``<folder>`` itself when its
package.xml names ``pkg``). Xacro can read files and environment variables, so only
trusted files should be expanded (reference/xacro.md, "Security").
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

from ..findings import Finding, InputError, Where

_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")


def find_package(name: str, package_paths: Sequence[Path]) -> Path | None:
    for folder in package_paths:
        direct = folder / name
        if (direct / "package.xml").is_file() or direct.is_dir():
            return direct
        manifest = folder / "package.xml"
        if manifest.is_file():
            found = _NAME.search(manifest.read_text(encoding="utf-8", errors="replace"))
            if found and found.group(1) == name:
                return folder
        for sub in sorted(folder.glob("*/package.xml")) if folder.is_dir() else []:
            found = _NAME.search(sub.read_text(encoding="utf-8", errors="replace"))
            if found and found.group(1) == name:
                return sub.parent
    return None


@contextlib.contextmanager
def _find_from(package_paths: Sequence[Path]) -> Iterator[None]:
    import xacro.substitution_args as sa

    def eval_find(pkg: str) -> str:
        found = find_package(pkg, package_paths)
        if found is None:
            raise LookupError(
                f"package '{pkg}' not found in --package-path {', '.join(map(str, package_paths)) or '(none)'}"
            )
        return str(found.resolve())

    saved = sa._eval_find, sa._eval_dict.get("find")
    sa._eval_find = eval_find
    sa._eval_dict["find"] = eval_find
    try:
        yield
    finally:
        sa._eval_find = saved[0]
        sa._eval_dict["find"] = saved[1]


def expand(
    path: Path, display: str, mappings: Mapping[str, str] | None = None, package_paths: Sequence[Path] = ()
) -> bytes:
    """The expanded XML of a Xacro file, or an InputError saying why xacro refused it."""
    import xacro

    try:
        with _find_from(package_paths):
            doc = xacro.process_file(str(path), mappings=dict(mappings or {}))
    except Exception as exc:  # xacro raises XacroException, XML errors, lookup errors, ...
        message = " ".join(str(exc).split()) or type(exc).__name__
        raise InputError(
            [
                Finding(
                    "READ004",
                    "error",
                    f"xacro could not expand the file: {message}",
                    "pass --xacro-arg name:=value for its arguments and --package-path for $(find)",
                    "file",
                    Where(display),
                )
            ]
        ) from None
    return str(doc.toxml()).encode("utf-8")
