"""The short gravity run: joints held by PD position servos at a pose, base fixed or free on a floor.

Each one-DOF joint gets MuJoCo's position servo (PD, ``set_to_position``; consumers.md §1.5),
its force clamped to the joint's effort limit as the real motor is, under the ``implicitfast``
integrator; then step and watch: finite state, no MuJoCo warning, every joint within its
tolerance of the pose and at rest at the end, a free base upright.

``kp = effort / HOLD`` (full effort at HOLD rad or m of error) comes from the joint's effort,
not from the masses, so a mass that is wrong shows as sag instead of being tuned away. ``kv``
damps the servo critically for the joint-space inertia the description states (MuJoCo's mass
matrix at the pose). The damping is integrated implicitly, the stiffness is not: a step of
``dt`` is stable while ``omega * dt`` stays below about 4 (``omega = sqrt(kp / I)``), which
every real link meets at TIMESTEP (a UR5e wrist: about 1.7) and an inertia a million times too
small breaks by orders of magnitude, as it would in any simulator.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from descgen.codes.simulate import SIM010, SIM011, SIM012, SIM013
from descgen.core.findings import Finding
from descgen.core.model import ONE_DOF, ROTATING, Joint, Robot

# error at which a servo gives its full effort: below the tolerance, so a joint whose effort
# can carry its gravity load stays within it, and one that cannot saturates and falls
HOLD_RAD, HOLD_M = 0.04, 0.008
ZETA = 1.0  # damping ratio of each servo against its joint's inertia
DEFAULT_KP_RAD, DEFAULT_KP_M = 200.0, 2000.0  # a joint without an effort limit: a stiff hobby servo
TOL_RAD, TOL_M = 0.05, 0.01  # allowed drift from the pose under gravity
REST_RAD_S, REST_M_S = 0.05, 0.01  # "at rest" at the end of the run
TIP_DEG = 10.0  # a free base tilted further has tipped over
FLOOR_CLEARANCE = 0.002  # m between the lowest collision shape and the floor at the start
TIMESTEP = 0.001  # s: half MuJoCo's default, for small real links (see above)
KICK = 1e-3  # rad/s or m/s given to every held joint at the start
# MuJoCo's warnings that mean the run cannot be trusted (mjtWarning; pybind11 enums do not iterate)
WARNINGS = (
    "mjWARN_INERTIA",
    "mjWARN_CONTACTFULL",
    "mjWARN_CNSTRFULL",
    "mjWARN_BADQPOS",
    "mjWARN_BADQVEL",
    "mjWARN_BADQACC",
    "mjWARN_BADCTRL",
)


@dataclass(frozen=True)
class Servo:
    joint: str
    kp: float
    kv: float | None  # None: critical for the joint's inertia, set by :func:`damped`
    effort: float | None  # N or N*m; None: unlimited
    target: float
    rotating: bool

    @property
    def tolerance(self) -> float:
        return TOL_RAD if self.rotating else TOL_M


@dataclass(frozen=True)
class Setup:
    """How the run is set up; a planted fault may change it (see :mod:`.faults`)."""

    base: str  # fixed | floor
    seconds: float
    targets: tuple[tuple[str, float], ...]  # the pose: joint -> value
    gear: float = 1.0  # actuator gear (a planted fault makes it huge)
    damping: float | None = None  # None: the servo's kv; else this kv (a planted fault: 0)


@dataclass
class Trace:
    """What the run showed, for the report."""

    steps: int = 0
    drift: dict[str, float] = field(default_factory=dict)  # joint -> max |q - q0|
    end_speed: dict[str, float] = field(default_factory=dict)
    tilt_deg: float = 0.0
    warnings: dict[str, int] = field(default_factory=dict)
    finite: bool = True


def held_joints(robot: Robot, passive: tuple[str, ...] = ()) -> list[Joint]:
    """Joints a servo holds: one-DOF, not mimicking another (MuJoCo couples those), not passive."""
    return [j for j in robot.joints if j.type in ONE_DOF and j.mimic is None and j.name not in passive]


def servos(robot: Robot, setup: Setup) -> list[Servo]:
    targets = dict(setup.targets)
    passive = robot.semantic.passive_joints if robot.semantic else ()
    out = []
    for j in held_joints(robot, passive):
        rotating = j.type in ROTATING
        effort = j.limit.effort if j.limit is not None and j.limit.effort else None
        hold = HOLD_RAD if rotating else HOLD_M
        kp = effort / hold if effort else (DEFAULT_KP_RAD if rotating else DEFAULT_KP_M)
        out.append(Servo(j.name, kp, setup.damping, effort, targets.get(j.name, 0.0), rotating))
    return out


def damped(model: Any, data: Any, held: list[Servo]) -> list[Servo]:
    """Each servo without a given kv, critically damped for its joint's inertia at the pose
    (from MuJoCo's joint-space mass matrix, after place()); the kv is set on ``model``."""
    import mujoco

    full = np.zeros((model.nv, model.nv))
    if hasattr(data, "qM"):  # MuJoCo 3.x: mj_fullM(model, dst, qM)
        mujoco.mj_fullM(model, full, data.qM)
    else:  # 4.x: mj_fullM(model, data, dst)
        mujoco.mj_fullM(model, data, full)
    # the inertia a joint's servo feels with every other joint free: 1 / (M^-1)_jj, never more
    # than M_jj (every other joint locked); damping against M_jj lets coupled modes ring
    if np.isfinite(full).all():
        apparent = 1.0 / np.maximum(np.diag(np.linalg.pinv(full)), 1e-300)
    else:  # a pose past the floats (a joint offset of 1e308 m): no damping; the run shows SIM010
        apparent = np.zeros(model.nv)
    out = []
    for s in held:
        inertia = float(apparent[_joint_addr(model, s.joint)[1]])
        kv = 2.0 * ZETA * math.sqrt(s.kp * max(inertia, 0.0)) if s.kv is None else s.kv
        act = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"descgen_servo_{s.joint}")
        model.actuator_biasprm[act, 2] = -kv  # a position servo's force: kp * (ctrl - q) - kv * qdot
        out.append(dataclasses.replace(s, kv=kv))
    return out


def add_servos(spec: Any, held: list[Servo], gear: float) -> None:
    """A position servo per held joint, its force clamped to the joint's effort; its damping is
    set on the compiled model by :func:`damped` (it needs the mass matrix)."""
    import mujoco

    for s in held:
        act = spec.add_actuator()
        act.name = f"descgen_servo_{s.joint}"
        act.trntype = mujoco.mjtTrn.mjTRN_JOINT
        act.target = s.joint
        act.set_to_position(kp=s.kp, kv=0.0)
        act.gear[0] = gear
        if s.effort is not None:
            act.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            act.forcerange = [-s.effort, s.effort]


def add_floor(spec: Any, root: str) -> None:
    """A ground plane and a free joint on the root body (placed on the floor later)."""
    import mujoco

    spec.worldbody.add_geom(name="descgen_floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05])
    body = spec.body(root)
    body.add_freejoint(name="descgen_free_base")


def set_integrator(spec: Any) -> None:
    import mujoco

    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.timestep = TIMESTEP


# -- the run on a compiled model ----------------------------------------------------------------


def _joint_addr(model: Any, name: str) -> tuple[int, int]:
    import mujoco

    jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
    return int(model.jnt_qposadr[jid]), int(model.jnt_dofadr[jid])


def place(model: Any, data: Any, pose: dict[str, float], free: bool) -> None:
    """Every joint at ``pose`` (mimic joints included), each servo's target there, and a free base
    standing FLOOR_CLEARANCE above the floor."""
    import mujoco

    mujoco.mj_resetData(model, data)
    for name, value in pose.items():
        if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name) >= 0:
            data.qpos[_joint_addr(model, name)[0]] = value
    for a in range(model.nu):  # each servo's set point: its joint's value in the pose
        data.ctrl[a] = model.actuator_gear[a, 0] * data.qpos[model.jnt_qposadr[model.actuator_trnid[a, 0]]]
    mujoco.mj_forward(model, data)
    if free:
        adr = _joint_addr(model, "descgen_free_base")[0]
        data.qpos[adr + 2] += FLOOR_CLEARANCE - _lowest_point(model, data)
        mujoco.mj_forward(model, data)


def _lowest_point(model: Any, data: Any) -> float:
    """The lowest z of any robot collision shape (its bounding box turned into the world)."""
    import mujoco

    low = math.inf
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == 0 or model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        rot = data.geom_xmat[g].reshape(3, 3)
        corners = data.geom_xpos[g] + (centre + signs * half) @ rot.T
        low = min(low, float(corners[:, 2].min()))
    return 0.0 if low == math.inf else low


def touching(model: Any, data: Any) -> list[tuple[str, str]]:
    """Pairs of robot bodies in contact (the floor excluded), by name, each once."""
    import mujoco

    pairs: set[tuple[str, str]] = set()
    for c in data.contact[: data.ncon]:
        names = []
        for g in (c.geom1, c.geom2):
            if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE:
                break
            names.append(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[g]) or "world")
        if len(names) == 2 and names[0] != names[1]:
            a, b = sorted(names)
            pairs.add((a, b))
    return sorted(pairs)


def step(model: Any, data: Any, held: list[Servo], seconds: float, free: bool) -> Trace:
    """Step ``seconds`` of simulated time and record what the checks need."""
    import mujoco

    trace = Trace()
    addr = {s.joint: _joint_addr(model, s.joint) for s in held}
    target = np.array([data.qpos[addr[s.joint][0]] for s in held])
    qadr = np.array([addr[s.joint][0] for s in held], dtype=int)
    vadr = np.array([addr[s.joint][1] for s in held], dtype=int)
    drift = np.zeros(len(held))
    data.qvel[vadr] += KICK  # a stable hold shrugs off a nudge; an unstable one needs one to show
    base = _joint_addr(model, "descgen_free_base")[0] if free else None
    steps = max(1, round(seconds / model.opt.timestep))
    for _ in range(steps):
        mujoco.mj_step(model, data)
        trace.steps += 1
        if not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            trace.finite = False
            break
        if len(held):
            drift = np.maximum(drift, np.abs(data.qpos[qadr] - target))
        if base is not None:
            trace.tilt_deg = max(trace.tilt_deg, _tilt_deg(data.qpos[base + 3 : base + 7]))
    trace.drift = {s.joint: float(d) for s, d in zip(held, drift, strict=True)}
    trace.end_speed = {s.joint: float(abs(data.qvel[v])) for s, v in zip(held, vadr, strict=True)}
    trace.warnings = {
        name: int(data.warning[int(getattr(mujoco.mjtWarning, name))].number)
        for name in WARNINGS
        if data.warning[int(getattr(mujoco.mjtWarning, name))].number
    }
    return trace


def _tilt_deg(quat: Any) -> float:
    """Angle between the body's z axis and the world's, from its quaternion (w, x, y, z)."""
    w, x, y, z = (float(v) for v in quat)
    norm = w * w + x * x + y * y + z * z
    if not math.isfinite(norm) or norm == 0:
        return 180.0
    cos = 1.0 - 2.0 * (x * x + y * y) / norm  # R[2][2]
    return math.degrees(math.acos(max(-1.0, min(1.0, cos))))


def verdict(robot: Robot, held: list[Servo], trace: Trace, seconds: float) -> list[Finding]:
    """The trace as findings: each failed check once, on the element it is about."""
    out: list[Finding] = []
    subject, where = f"robot:{robot.name}", robot.where
    if not trace.finite:
        out.append(
            SIM010.finding(
                f"the state became NaN or infinite after {trace.steps * TIMESTEP:.3g} s of the gravity run",
                "check the masses and inertias of the moving links, and the joints' damping",
                subject,
                where,
            )
        )
    if trace.warnings:
        said = ", ".join(f"{k} ×{n}" for k, n in sorted(trace.warnings.items()))
        out.append(
            SIM011.finding(
                f"MuJoCo warned during the gravity run: {said}",
                "a bad acceleration means the simulation blew up and was reset; check masses, inertias and damping",
                subject,
                where,
            )
        )
    if trace.finite:
        out += _drifts(robot, held, trace)
    if trace.tilt_deg > TIP_DEG:
        out.append(
            SIM013.finding(
                f"the free base tilted {trace.tilt_deg:.3g} deg (limit {TIP_DEG:g} deg) within {seconds:g} s: "
                "the robot tips over",
                "the centre of mass must stay over the support of wheels and casters; check masses and their origins",
                subject,
                where,
            )
        )
    return out


def _drifts(robot: Robot, held: list[Servo], trace: Trace) -> list[Finding]:
    out = []
    for s in held:
        j = robot.joint(s.joint)
        assert j is not None
        drift, speed = trace.drift[s.joint], trace.end_speed[s.joint]
        rest = REST_RAD_S if s.rotating else REST_M_S
        if drift <= s.tolerance and speed <= rest:
            continue
        unit = "rad" if s.rotating else "m"
        what = (
            f"drifted {drift:.3g} {unit} from the pose (tolerance {s.tolerance:g} {unit})"
            if drift > s.tolerance
            else f"was still moving at {speed:.3g} {unit}/s at the end (at rest: below {rest:g})"
        )
        held_by = f"effort {s.effort:g}" if s.effort is not None else "no effort limit"
        out.append(
            SIM012.finding(
                f"joint {s.joint} {what} under gravity, held by a PD servo (kp {s.kp:.4g}, {held_by})",
                "check the masses this joint carries and its effort limit",
                j.subject,
                j.where,
            )
        )
    return out
