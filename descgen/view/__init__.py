"""``descgen view``: the robot in the browser (viser). This module computes what the viewer shows
(sliders, presets, frames, the known-pose markers), with no viser import, so it is tested
without a browser; ``server.py`` draws it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import kinematics, mimic
from ..findings import Finding, InputError, Where
from ..model import ONE_DOF, Robot

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class Slider:
    joint: str
    lower: float
    upper: float
    prismatic: bool


@dataclass(frozen=True)
class Marker:
    """A measured frame position of a known pose beside where the model puts that frame."""

    pose: str
    frame: str
    measured: Vec3  # in the root frame
    model: Vec3
    error_mm: float  # the largest axis difference
    tolerance_mm: float


def sliders(robot: Robot) -> list[Slider]:
    """One per independent joint (mimic followers are set from their leaders), within its limits;
    a continuous joint (no limits) turns one full revolution either way."""
    followers = mimic.analyse(robot)
    out = []
    for j in robot.joints:
        if j.type not in ONE_DOF or j.mimic is not None or followers.problem(j.name) is not None:
            continue
        lo, hi = (j.limit.lower, j.limit.upper) if j.limit is not None and j.type != "continuous" else (None, None)
        if lo is None or hi is None or not lo < hi:
            lo, hi = -math.pi, math.pi
        out.append(Slider(j.name, float(lo), float(hi), j.type == "prismatic"))
    return out


def presets(robot: Robot) -> dict[str, dict[str, float]]:
    """Buttons: every known pose, then every SRDF group state (values not listed are zero)."""
    out = {f"pose: {kp.name}": dict(kp.joints) for kp in robot.known_poses}
    for st in robot.semantic.states if robot.semantic is not None else ():
        out.setdefault(f"state: {st.name}", dict(st.values))
    return out


def frames(robot: Robot, q: dict[str, float]) -> dict[str, np.ndarray]:
    """Every link's pose in the root frame (mimic joints follow their leaders)."""
    return kinematics.forward(robot, q)


def markers(robot: Robot, pose: str) -> list[Marker]:
    """The measured positions of one known pose and the model's, both in the root frame."""
    kp = next((k for k in robot.known_poses if k.name == pose), None)
    if kp is None:
        return []
    poses = kinematics.forward(robot, dict(kp.joints))
    out = []
    for fm in kp.frames:
        if fm.frame not in poses:
            continue
        base = poses.get(fm.relative_to, np.eye(4)) if fm.relative_to else np.eye(4)
        measured = base @ np.array([*fm.xyz, 1.0])
        model = poses[fm.frame][:3, 3]
        rel = np.linalg.inv(base) @ poses[fm.frame]
        err = max(abs(float(rel[i, 3]) - fm.xyz[i]) for i in range(3))
        out.append(
            Marker(
                kp.name,
                fm.frame,
                (float(measured[0]), float(measured[1]), float(measured[2])),
                (float(model[0]), float(model[1]), float(model[2])),
                err * 1000.0,
                fm.tolerance * 1000.0,
            )
        )
    return out


def joint_axes(robot: Robot, q: dict[str, float]) -> list[tuple[str, Vec3, Vec3]]:
    """(joint, origin, unit axis) of every moving joint in the root frame, at ``q``."""
    poses = kinematics.forward(robot, q)
    out = []
    for j in robot.joints:
        if j.type not in ONE_DOF or j.axis is None or j.parent not in poses:
            continue
        at = poses[j.parent] @ kinematics.joint_transform(j, 0.0)
        axis = np.asarray(j.axis, dtype=float)
        n = float(np.linalg.norm(axis))
        if n == 0:
            continue
        d = at[:3, :3] @ (axis / n)
        o = at[:3, 3]
        out.append((j.name, (float(o[0]), float(o[1]), float(o[2])), (float(d[0]), float(d[1]), float(d[2]))))
    return out


def require_viser() -> None:
    """VIEW001 (exit 2) when the optional viewer is not installed, with the command that installs it."""
    try:
        import viser  # noqa: F401
        import yourdfpy  # noqa: F401
    except ImportError:
        raise InputError(
            [
                Finding(
                    "VIEW001",
                    "error",
                    "descgen view needs viser with its URDF support, which is not installed",
                    "pip install 'descgen[view]' (or: pip install 'viser[urdf]')",
                    "option",
                    Where("<command line>"),
                )
            ]
        ) from None


def load(path: Path, package_paths: tuple[Path, ...] = ()) -> tuple[Robot, str]:
    """The model and the URDF text of a spec, URDF or Xacro (a Xacro expanded in the sandbox)."""
    from ..audit.inputs import Options, kind_of, load_description

    robot, _ = load_description(path, Options(package_paths=package_paths))
    kind = kind_of(path)
    if kind == "spec":
        from ..render import render_package

        files = render_package(robot, path.name)
        text = next(v for k, v in files.items() if k.startswith("urdf/") and k.endswith(".urdf"))
    elif kind == "xacro":
        from ..readers.xacro_file import expand_located

        xml = expand_located(path, str(path), {}, package_paths, False).xml
        text = xml.decode("utf-8") if isinstance(xml, bytes) else str(xml)
    else:
        from ..safeio import read_bounded

        text = read_bounded(path, "URDF", display=str(path)).decode("utf-8", "replace")
    return robot, text
