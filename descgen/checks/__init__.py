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
from .known_poses import known_poses
from .package import package_xml
from .semantic_roundtrip import controllers_roundtrip, ros2_control_roundtrip, srdf_roundtrip
from .urdf_roundtrip import urdf_roundtrip
from .urdfdom import check_urdf
from .xacro_expand import xacro_matches_urdf, xacro_variants_match

__all__ = [
    "CHECKS",
    "Finding",
    "check_urdf",
    "controllers_roundtrip",
    "controllers_yaml",
    "known_poses",
    "package_xml",
    "ros2_control_roundtrip",
    "run_all",
    "srdf_roundtrip",
    "urdf_roundtrip",
    "xacro_matches_urdf",
    "xacro_variants_match",
]

Files = dict[str, str]
Check = Callable[[Files, Robot, Path], list[Finding]]

CHECKS: list[tuple[str, Check]] = [
    ("xacro expands to the URDF", xacro_matches_urdf),
    ("xacro hardware:=gazebo|real expands to the model's variants", xacro_variants_match),
    ("package.xml is a valid format 3 manifest", package_xml),
    ("controllers YAML names existing joints and interfaces", controllers_yaml),
    ("yourdfpy reads back the model from the URDF", urdf_roundtrip),
    ("the SRDF reads back as the model's semantics", srdf_roundtrip),
    ("the ros2_control block reads back as the model's", ros2_control_roundtrip),
    ("the controllers YAML reads back as the model's", controllers_roundtrip),
    ("urdfdom's check_urdf accepts the URDF", check_urdf),
    ("known poses match forward kinematics", known_poses),
]


def run_all(files: Files, robot: Robot, where: Path) -> list[Finding]:
    """Every check; ``where`` is the package folder the files are destined for (for messages)."""
    out: list[Finding] = []
    for _, check in CHECKS:
        out.extend(check(files, robot, where))
    return out
