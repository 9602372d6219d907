"""Checks that prove the rendered files before anything is written.

Each check takes the rendered package (path -> text) and the model, and returns
findings. ``CHECKS`` is the order ``generate`` and ``check`` run them in.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..findings import Finding
from ..model import Robot
from .controllers import controllers_yaml
from .package import package_xml
from .xacro_expand import xacro_matches_urdf

Files = dict[str, str]
Check = Callable[[Files, Robot, Path], list[Finding]]

CHECKS: list[tuple[str, Check]] = [
    ("xacro expands to the URDF", xacro_matches_urdf),
    ("package.xml is a valid format 3 manifest", package_xml),
    ("controllers YAML names existing joints and interfaces", controllers_yaml),
]


def run_all(files: Files, robot: Robot, where: Path) -> list[Finding]:
    """Every check; ``where`` is the package folder the files are destined for (for messages)."""
    out: list[Finding] = []
    for _, check in CHECKS:
        out.extend(check(files, robot, where))
    return out
