"""Checks that prove the rendered files before anything is written.

Each check takes the rendered package (path -> text) and the model, and returns
findings. ``CHECKS`` is the order ``generate`` and ``check`` run them in; ``THOROUGH``
adds the proofs too slow to start for every commit (``descgen check --thorough``).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from descgen.core.findings import Finding
from descgen.core.model import Robot
from descgen.prove.controllers import controllers_yaml
from descgen.prove.known_poses import known_poses
from descgen.prove.mujoco_model import mujoco_model
from descgen.prove.package import package_xml
from descgen.prove.semantic_roundtrip import controllers_roundtrip, ros2_control_roundtrip, srdf_roundtrip
from descgen.prove.urdf_roundtrip import urdf_roundtrip, urdf_roundtrip_yourdfpy
from descgen.prove.urdfdom import check_urdf, start_check_urdf
from descgen.prove.xacro_expand import xacro_calibration_nominal, xacro_matches_urdf, xacro_variants_match

__all__ = [
    "CHECKS",
    "THOROUGH",
    "Finding",
    "check_urdf",
    "controllers_roundtrip",
    "controllers_yaml",
    "known_poses",
    "mujoco_model",
    "package_xml",
    "ros2_control_roundtrip",
    "run_all",
    "run_named",
    "srdf_roundtrip",
    "urdf_roundtrip",
    "urdf_roundtrip_yourdfpy",
    "xacro_calibration_nominal",
    "xacro_matches_urdf",
    "xacro_variants_match",
]

Files = dict[str, str]
Check = Callable[[Files, Robot, Path], list[Finding]]

CHECKS: list[tuple[str, Check]] = [
    ("xacro expands to the URDF", xacro_matches_urdf),
    ("xacro hardware:=gazebo|real expands to the model's variants", xacro_variants_match),
    ("xacro calibration:=nominal.yaml expands to the nominal model", xacro_calibration_nominal),
    ("package.xml is a valid format 3 manifest", package_xml),
    ("controllers YAML names existing joints and interfaces", controllers_yaml),
    ("the URDF read back (lxml, urdfdom's rules) is the model", urdf_roundtrip),
    ("the SRDF reads back as the model's semantics", srdf_roundtrip),
    ("the ros2_control block reads back as the model's", ros2_control_roundtrip),
    ("the controllers YAML reads back as the model's", controllers_roundtrip),
    ("urdfdom's check_urdf accepts the URDF", check_urdf),
    ("known poses match forward kinematics", known_poses),
    ("the MuJoCo model (hardware:=mujoco) compiles and is the URDF's robot", mujoco_model),
]


# yourdfpy imports trimesh and scipy, about a second before it reads a byte: an oracle for the
# lxml read-back above (tests/test_urdf_readback.py), and a second opinion on request
THOROUGH: list[tuple[str, Check]] = [
    ("yourdfpy reads back the model from the URDF", urdf_roundtrip_yourdfpy),
]


# checks that run in another process: started before the in-process ones, collected after them
Start = Callable[[Files, Robot, Path], Callable[[], list[Finding]]]
_STARTS: dict[Check, Start] = {check_urdf: start_check_urdf}


def run_named(
    files: Files, robot: Robot, where: Path, thorough: bool = False
) -> tuple[tuple[str, tuple[Finding, ...]], ...]:
    """Every check (and ``THOROUGH`` too when asked), each one's findings by its name, in
    ``CHECKS`` order; ``where`` is the package folder the files are destined for (for
    messages). Each proof runs exactly as alone: only the order of waiting changes."""
    chosen = [*CHECKS, *(THOROUGH if thorough else [])]
    pending = {name: _STARTS[check](files, robot, where) for name, check in chosen if check in _STARTS}
    done: dict[str, list[Finding]] = {}
    try:
        done |= {name: check(files, robot, where) for name, check in chosen if name not in pending}
    finally:  # waited for even when an in-process check raised: no process or scratch file left
        done |= {name: collect() for name, collect in pending.items()}
    return tuple((name, tuple(done[name])) for name, _ in chosen)


def run_all(files: Files, robot: Robot, where: Path, thorough: bool = False) -> list[Finding]:
    """Every check's findings, in ``CHECKS`` order (run_named without the names)."""
    return [f for _, found in run_named(files, robot, where, thorough) for f in found]
