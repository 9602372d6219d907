"""``descgen view``: the robot in the browser (viser). This module computes what the viewer shows
(sliders, presets, frames, the known-pose markers, which meshes it may read), with no viser
import, so it is tested without a browser; ``server.py`` draws it and guards the server.

The viewer reads only the meshes the one mesh resolver accepted (descgen/meshes/paths.py, as
``validate`` and ``audit`` do: ``Robot.mesh_files``), and reads them as the audit does
(descgen/meshes/load.py: at most 64 MiB, a binary STL's triangle count from its header before it
is parsed, no file an OBJ or DAE names besides itself). Every other mesh is a finding, printed
and shown on the page, and the link is drawn without it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from descgen.codes.command import VIEW001
from descgen.core.findings import Finding, InputError, Severity, Where
from descgen.core.model import ONE_DOF, Mesh, Robot
from descgen.physics import calibration, kinematics, mimic
from descgen.physics import poses as known_poses

if TYPE_CHECKING:
    from descgen.meshes.load import Loaded

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
    error_mm: float  # the largest axis difference (descgen/physics/poses.py: worst)
    tolerance_mm: float
    verdict: str  # "0.8 mm, tol 2 mm, pass": as poses, the page and the pose images say it


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
    poses = kinematics.forward(calibration.for_pose(robot, kp), dict(kp.joints))  # as poses judges it
    out = []
    for fm in kp.frames:
        if fm.frame not in poses:
            continue
        base = poses.get(fm.relative_to, np.eye(4)) if fm.relative_to else np.eye(4)
        measured = base @ np.array([*fm.xyz, 1.0])
        model = poses[fm.frame][:3, 3]
        rel = np.linalg.inv(base) @ poses[fm.frame]
        error = (float(rel[0, 3]) - fm.xyz[0], float(rel[1, 3]) - fm.xyz[1], float(rel[2, 3]) - fm.xyz[2])
        out.append(
            Marker(
                kp.name,
                fm.frame,
                (float(measured[0]), float(measured[1]), float(measured[2])),
                (float(model[0]), float(model[1]), float(model[2])),
                known_poses.worst(error) * 1000.0,
                fm.tolerance * 1000.0,
                known_poses.verdict(error, fm.tolerance),
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


# why a mesh is not shown, by the resolver's state: the audit's codes (descgen/audit/rules/geometry.py)
# and severities (the rules need not be loaded for them)
_REFUSED: dict[str, tuple[str, Severity, str, str]] = {
    "escapes": ("GEOM004", "error", "points outside its package", "use package://<pkg>/<path inside the package>"),
    "missing": ("GEOM003", "error", "does not exist", "fix the path or add the file"),
    "unresolved": (
        "GEOM005",
        "warning",
        "names a package that cannot be found",
        "fix the package name, or pass --package-path",
    ),
}


def mesh_plan(robot: Robot) -> tuple[dict[str, Loaded], list[Finding]]:
    """The meshes the viewer shows (filename as written in the URDF -> the mesh read from the
    file the resolver accepted) and a finding for every mesh it does not show: refused by the
    resolver (absolute, ``file://``, ``..`` or a link out of the package, a package that is not
    found, a missing file; the audit's GEOM003-005) or unreadable (over 64 MiB, more triangles
    than the audit reads, malformed: GEOM033). No file is opened for a refused name."""
    from descgen.audit.registry import at
    from descgen.meshes.load import MeshError
    from descgen.meshes.load import load as load_mesh

    files = dict(robot.mesh_files)  # only names the resolver accepted have a file
    status = dict(robot.mesh_status)
    shown: dict[str, Loaded] = {}
    failed: dict[str, str] = {}
    found: list[Finding] = []
    seen: set[tuple[str, str]] = set()
    for lk in robot.links:
        for shape in lk.shapes():
            g = shape.geometry
            if not isinstance(g, Mesh) or (lk.name, g.filename) in seen:
                continue
            seen.add((lk.name, g.filename))
            name = g.filename
            file = files.get(name)
            if file is None or status.get(name, "ok") != "ok":
                code, severity, why, hint = _REFUSED.get(status.get(name, "missing"), _REFUSED["missing"])
                message = f"link '{lk.name}' mesh '{name}' {why}; not shown"
                found.append(at(code, shape, message, hint, severity, lk.subject))
                continue
            if name not in shown and name not in failed:
                try:
                    shown[name] = load_mesh(Path(file))
                except MeshError as exc:
                    failed[name] = str(exc)
            if name in failed:
                found.append(
                    at(
                        "GEOM033",
                        shape,
                        f"link '{lk.name}' mesh '{name}' cannot be read: {failed[name]}; not shown",
                        "check the file opens in a mesh viewer; re-export it as binary STL",
                        "info",
                        lk.subject,
                    )
                )
    return shown, found


def require_viser() -> None:
    """VIEW001 (exit 2) when the optional viewer is not installed, with the command that installs it."""
    try:
        import viser  # noqa: F401
        import yourdfpy  # noqa: F401
    except ImportError:
        raise InputError(
            [
                VIEW001.finding(
                    "descgen view needs viser with its URDF support, which is not installed",
                    "pip install 'descgen[view]' (or: pip install 'viser[urdf]')",
                    "option",
                    Where("<command line>"),
                )
            ]
        ) from None


def load(path: Path, package_paths: tuple[Path, ...] = ()) -> tuple[Robot, str]:
    """The model and the URDF text of a spec, URDF or Xacro (a Xacro expanded in the sandbox).
    A URDF is read once: the model (and the mesh names the resolver judged) come from the very
    bytes the viewer shows."""
    from descgen.infra.safeio import check_file, read_bounded
    from descgen.read.description import Options, kind_of, load_description

    check_file(path, "description", display=str(path))  # a FIFO or a device: refused before kind_of
    kind = kind_of(path)
    given = {path: read_bounded(path, "URDF", display=str(path))} if kind == "urdf" else None
    robot, _ = load_description(path, Options(package_paths=package_paths), given)
    if kind == "spec":
        from descgen.render import render_package

        files = render_package(robot, path.name)
        text = next(v for k, v in files.items() if k.startswith("urdf/") and k.endswith(".urdf"))
    elif kind == "xacro":
        from descgen.read.xacro_file import expand_located

        xml = expand_located(path, str(path), {}, package_paths, False).xml
        text = xml.decode("utf-8") if isinstance(xml, bytes) else str(xml)
    else:
        assert given is not None
        text = given[path].decode("utf-8", "replace")
    return robot, text
