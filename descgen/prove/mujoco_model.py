"""The MJCF model of ``hardware:=mujoco`` (descgen/render/mjcf.py), compiled by MuJoCo as
mujoco_ros2_control loads it (from its file, meshes beside it in the package) and compared with
the robot: what the conversion must not change.

Compared: every moving URDF joint is an MJCF joint of that name, hinge or slide, limited as the
URDF limits it, to the same range; each commanded ros2_control joint but a mimic one has one
actuator named as the joint, driving it, of the kind its first command interface needs; each
URDF mimic is a joint equality with the URDF's offset and multiplier; the masses add up to the
URDF's. MuJoCo writes numbers to 6 significant digits, so values agree to that (TOLERANCE).
What the conversion changes on purpose (fused fixed links, dropped visuals, the floor and free
joint of a mobile base, the actuator gains) is listed in the file's header, not compared.
"""

from __future__ import annotations

import math
import shutil
import tempfile
from pathlib import Path
from typing import Any

from descgen.codes.generate import GEN097
from descgen.core.findings import Finding, Where
from descgen.core.model import Robot
from descgen.meshes.paths import own_meshes
from descgen.physics.start_state import default_base
from descgen.render import mjcf

TOLERANCE = 1e-5  # relative: MuJoCo's writer keeps 6 significant digits
KINDS = {"revolute": "hinge", "continuous": "hinge", "prismatic": "slide"}


def mujoco_model(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    path = mjcf.path(robot)
    if path not in files:
        return []
    import mujoco

    loc = Where(str(where / path))
    with tempfile.TemporaryDirectory(prefix="descgen-mjcf-") as tmp:
        root = Path(tmp)
        (root / path).parent.mkdir(parents=True)
        (root / path).write_text(files[path], encoding="utf-8")
        for rel, source in own_meshes(robot).items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, root / rel)
        try:
            model = mujoco.MjModel.from_xml_path(str(root / path))
        except ValueError as exc:
            return [_differs(f"MuJoCo refuses {path}: {' '.join(str(exc).split())}", loc)]
    return [_differs(why, loc) for why in differences(model, robot)]


def differences(model: Any, robot: Robot) -> list[str]:
    """How the compiled ``model`` differs from ``robot`` (module docstring)."""
    import mujoco

    out: list[str] = []

    def jid(name: str) -> int:
        return int(mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name))

    hinge, slide, free = mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE, mujoco.mjtJoint.mjJNT_FREE
    for j in robot.joints:
        kind = KINDS.get(j.type)
        if kind is None:
            continue
        i = jid(j.name)
        if i < 0:
            out.append(f"joint '{j.name}' is not in the MJCF")
            continue
        if model.jnt_type[i] != (hinge if kind == "hinge" else slide):
            out.append(f"joint '{j.name}' is not a {kind} in the MJCF")
        limited = j.type != "continuous" and j.limit is not None and j.limit.lower is not None
        if bool(model.jnt_limited[i]) != limited:
            out.append(f"joint '{j.name}' is {'' if model.jnt_limited[i] else 'not '}limited in the MJCF")
        elif limited and j.limit is not None:
            want = (j.limit.lower or 0.0, j.limit.upper or 0.0)
            got = tuple(float(x) for x in model.jnt_range[i])
            if not all(_close(a, b) for a, b in zip(want, got, strict=True)):
                out.append(f"joint '{j.name}' range {got} in the MJCF, {want} in the URDF")
    out += _actuators(model, robot, jid)
    out += _equalities(model, robot, jid)
    out += _kinematics(model, robot)
    rc = robot.ros2_control
    if rc is not None and rc.update_rate and model.opt.timestep > 1.0 / rc.update_rate * (1 + TOLERANCE):
        out.append(f"time step {model.opt.timestep:g} s, longer than the controller manager's period")
    if not all(_close(float(g), w) for g, w in zip(model.opt.gravity, (0.0, 0.0, -9.81), strict=True)):
        out.append(f"gravity {tuple(float(g) for g in model.opt.gravity)}, not (0, 0, -9.81)")
    mass = sum(lk.inertial.mass or 0.0 for lk in robot.links if lk.inertial is not None)
    root = robot.root()
    if default_base(robot) != "floor" and root is not None:  # welded to the world: its mass is the world's
        mass -= sum(_mass(robot, name) for name in robot.body_of(root))
    if not _close(float(sum(model.body_mass)), mass):
        out.append(f"the bodies weigh {float(sum(model.body_mass)):g} kg in the MJCF, the links {mass:g} kg")
    frees = [i for i in range(model.njnt) if model.jnt_type[i] == free]
    if bool(frees) != (default_base(robot) == "floor"):
        out.append("a free base joint where the robot has a fixed base, or none on a mobile base")
    return out


def _actuators(model: Any, robot: Robot, jid: Any) -> list[str]:
    import mujoco

    out: list[str] = []
    rc = robot.ros2_control
    wanted = {}
    for cj in rc.joints if rc is not None else ():
        j = robot.joint(cj.name)
        if j is not None and j.mimic is None and cj.command:
            wanted[cj.name] = mjcf.actuator_kind(cj)
    names = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a): a for a in range(model.nu)}
    for name in sorted(set(names) - set(wanted)):
        out.append(f"actuator '{name}' drives no commanded ros2_control joint")
    for name, command in wanted.items():
        a = names.get(name)
        if a is None:
            out.append(f"ros2_control joint '{name}' ({command}) has no actuator of its name")
            continue
        if model.actuator_trntype[a] != mujoco.mjtTrn.mjTRN_JOINT or model.actuator_trnid[a][0] != jid(name):
            out.append(f"actuator '{name}' does not drive joint '{name}'")
        # as the plugin classifies an actuator (sif.cpp:128): a position bias, else a velocity one
        bias = model.actuator_biasprm[a]
        kind = "position" if bias[1] != 0 else "velocity" if bias[2] != 0 else "effort"
        if kind != command:
            out.append(f"actuator '{name}' is a {kind} actuator; the joint's most demanding command is {command}")
        if not _close(float(model.actuator_gear[a][0]), 1.0):
            out.append(f"actuator '{name}' has a gear of {float(model.actuator_gear[a][0]):g}, not 1")
        j = robot.joint(name)
        effort = j.limit.effort if j is not None and j.limit is not None and j.limit.effort else None
        low, high = (float(x) for x in model.actuator_forcerange[a])
        if effort and not (model.actuator_forcelimited[a] and _close(low, -effort) and _close(high, effort)):
            out.append(f"actuator '{name}' force range [{low:g}, {high:g}], the URDF's effort {effort:g}")
    return out


def _equalities(model: Any, robot: Robot, jid: Any) -> list[str]:
    import mujoco

    out: list[str] = []
    found = {
        (int(model.eq_obj1id[e]), int(model.eq_obj2id[e])): model.eq_data[e]
        for e in range(model.neq)
        if model.eq_type[e] == mujoco.mjtEq.mjEQ_JOINT
    }
    for j in robot.joints:
        if j.mimic is None or robot.joint(j.mimic.joint) is None:
            continue
        data = found.get((jid(j.name), jid(j.mimic.joint)))
        if data is None:
            out.append(f"mimic joint '{j.name}' has no joint equality with '{j.mimic.joint}'")
        elif not (_close(float(data[0]), j.mimic.offset) and _close(float(data[1]), j.mimic.multiplier)):
            out.append(f"mimic joint '{j.name}': the equality's offset and multiplier are not the URDF's")
    return out


def _kinematics(model: Any, robot: Robot) -> list[str]:
    """Every MJCF body where the robot puts its link (relative to the root, joints at zero), with
    the mass of the links fused into it, and every joint axis as the URDF gives it."""
    import mujoco
    import numpy as np

    from descgen.physics.kinematics import forward

    out: list[str] = []
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    root = robot.root()
    poses = forward(robot)
    base = np.eye(4)
    rid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, root) if root else -1
    if rid >= 0:
        base[:3, :3], base[:3, 3] = data.xmat[rid].reshape(3, 3), data.xpos[rid]
    inv = np.linalg.inv(base)
    for b in range(1, model.nbody):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)
        if name not in poses:
            continue
        pose = np.eye(4)
        pose[:3, :3], pose[:3, 3] = data.xmat[b].reshape(3, 3), data.xpos[b]
        got = inv @ pose
        if not np.allclose(got, poses[name], atol=TOLERANCE * 10):
            out.append(f"body '{name}' is not where the URDF puts link '{name}' (joints at zero)")
        fused = sum(_mass(robot, lk) for lk in robot.body_of(name))
        if not _close(float(model.body_mass[b]), fused):
            out.append(f"body '{name}' weighs {float(model.body_mass[b]):g} kg, its links {fused:g} kg")
        elif fused > 0:
            com, tensor = _combined(robot, name, poses)
            rot = np.zeros(9)
            mujoco.mju_quat2Mat(rot, model.body_iquat[b])
            r = rot.reshape(3, 3)
            theirs = r @ np.diag(model.body_inertia[b]) @ r.T
            scale = max(float(np.abs(tensor).max()), 1e-12)
            if not np.allclose(model.body_ipos[b], com, atol=TOLERANCE * 10):
                out.append(f"body '{name}' centre of mass {tuple(model.body_ipos[b])}, its links' {tuple(com)}")
            elif not np.allclose(theirs, tensor, atol=1e-4 * scale):
                out.append(f"body '{name}' inertia is not its links' (about their centre of mass)")
    for j in robot.joints:
        i = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, j.name)
        if i < 0 or j.axis is None or j.type not in KINDS:
            continue
        want = np.array(j.axis, dtype=float) / np.linalg.norm(j.axis)
        if not np.allclose(model.jnt_axis[i], want, atol=TOLERANCE * 10):
            out.append(f"joint '{j.name}' axis {tuple(float(x) for x in model.jnt_axis[i])}, the URDF's {tuple(want)}")
    return out


def _combined(robot: Robot, body: str, poses: dict[str, Any]) -> tuple[Any, Any]:
    """The centre of mass and inertia tensor (about it), in ``body``'s frame, of the links fused
    into it (each link's inertial moved by the links' poses: the parallel-axis theorem)."""
    import numpy as np

    from descgen.physics.transforms import rpy_matrix

    inv = np.linalg.inv(poses[body])
    parts = []
    for name in robot.body_of(body):
        lk = robot.link(name)
        if lk is None or lk.inertial is None or not lk.inertial.mass or name not in poses:
            continue
        i = lk.inertial
        frame = inv @ poses[name]
        r = frame[:3, :3] @ rpy_matrix(i.origin.rpy)
        com = frame[:3, :3] @ np.array(i.origin.xyz) + frame[:3, 3]
        t = i.inertia
        own = (
            np.zeros((3, 3))
            if t is None
            else np.array([[t.ixx, t.ixy, t.ixz], [t.ixy, t.iyy, t.iyz], [t.ixz, t.iyz, t.izz]])
        )
        parts.append((float(i.mass or 0.0), com, r @ own @ r.T))
    total = sum(m for m, _, _ in parts)
    centre = sum(m * c for m, c, _ in parts) / total
    tensor = np.zeros((3, 3))
    for m, c, own in parts:
        d = c - centre
        tensor += own + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return centre, tensor


def _mass(robot: Robot, link: str) -> float:
    lk = robot.link(link)
    return (lk.inertial.mass or 0.0) if lk is not None and lk.inertial is not None else 0.0


def _close(a: float, b: float) -> bool:
    return math.isclose(a, b, rel_tol=TOLERANCE, abs_tol=TOLERANCE)


def _differs(why: str, loc: Where) -> Finding:
    return GEN097.finding(
        f"hardware:=mujoco: {why}",
        "descgen's URDF-to-MJCF conversion is wrong here (descgen/render/mjcf.py); the file is not written",
        "file:" + loc.file,
        loc,
    )
