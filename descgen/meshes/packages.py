"""Where a ROS package named in ``package://`` or ``$(find)`` is, among given folders.

Its own small module so that resolving an audited URDF's ``package://`` meshes does not
import the Xacro reader (minidom, the sandboxed evaluator), which a plain URDF never needs.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

from descgen.infra.safeio import MIB, inside, read_head

_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")
_MANIFEST_BYTES = 1 * MIB  # the <name> of a package.xml is in its first lines; real ones are a few kB


def find_package(name: str, package_paths: Sequence[Path]) -> Path | None:
    """The folder of package ``name``: ``<folder>/<name>``, a folder whose package.xml names
    it, or a subfolder whose package.xml does, for each folder of ``package_paths`` in order.

    Only what is really inside a folder counts (docs/security.md): a package folder or
    package.xml that is a link out of it is not found there. A package.xml is read like any
    input: a regular file, without blocking, at most 1 MiB (a FIFO or device names nothing)."""
    for folder in package_paths:
        direct = folder / name
        if direct.is_dir() and inside(direct, folder):
            return direct
        if manifest_name(folder / "package.xml") == name:
            return folder
        for sub in sorted(folder.glob("*/package.xml")) if folder.is_dir() else []:
            if inside(sub, folder) and manifest_name(sub) == name:
                return sub.parent
    return None


def manifest_name(manifest: Path) -> str | None:
    """The ``<name>`` a package.xml gives, or None (no such regular file, no name)."""
    found = _NAME.search(read_head(manifest, _MANIFEST_BYTES).decode("utf-8", "replace"))
    return found.group(1) if found else None
