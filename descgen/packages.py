"""Where a ROS package named in ``package://`` or ``$(find)`` is, among given folders.

Its own small module so that resolving an audited URDF's ``package://`` meshes does not
import the Xacro reader (minidom, the sandboxed evaluator), which a plain URDF never needs.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")


def find_package(name: str, package_paths: Sequence[Path]) -> Path | None:
    """The folder of package ``name``: ``<folder>/<name>``, a folder whose package.xml names
    it, or a subfolder whose package.xml does, for each folder of ``package_paths`` in order."""
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
