"""``descgen simulate``: MuJoCo as a consumer of the description.

MuJoCo compiles the robot from its URDF (``descgen/render/mujoco_urdf.py``), which shows what it refuses and
what it changes silently (``compile``); then a short gravity run holds the joints at a pose
with PD servos, on a fixed base or free on a floor (``gravity``). ``faults`` plants the
mistakes the run must catch.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from descgen.codes.simulate import SIM009, SIM014, SIM015, SIM016, SIM017
from descgen.commands.simulate import gravity
from descgen.commands.simulate.compile import compile_robot, silent_changes
from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import Robot
from descgen.physics import start_state
from descgen.physics.mimic import resolve
from descgen.render.mujoco_urdf import emit

BASES = ("fixed", "floor")
MIN_SECONDS, MAX_SECONDS = 0.01, 10.0
DEFAULT_SECONDS = 2.0
# What MuJoCo is given (SIM017, exit 2, before anything is compiled), so that a robot of 10,000
# links is a finding in a second, not minutes. MuJoCo's compiler and the servos' pseudo-inverse
# grow with the cube of the degrees of freedom (a 1,000-joint chain: 22 s to compile, 3 s of SVD);
# a step factorises the mass matrix, sum(depth^2) over the degrees of freedom (depth: how many
# of them are above it, itself included; a chain's N^3 / 3), ~1e-9 s per unit here.
MAX_LINKS = 2_000
MAX_DOFS = 500
MAX_WORK = 15_000_000_000  # steps x sum(depth^2): a 250-joint chain for 2 s (2,000 steps), ~15 s
_NV = {"revolute": 1, "continuous": 1, "prismatic": 1, "planar": 3, "floating": 6}


@dataclass(frozen=True)
class Settings:
    seconds: float = DEFAULT_SECONDS
    pose: str | None = None  # None: the SRDF's first state, others at MoveIt's default position
    base: str | None = None  # None: floor for a mobile robot, else fixed (see default_base)
    gear: float = 1.0  # planted faults only
    damping: float | None = None  # planted faults only: the servos' kv instead of the default


@dataclass
class Outcome:
    findings: list[Finding]
    report: dict[str, Any] = field(default_factory=dict)

    @property
    def failed(self) -> bool:
        return any(f.severity == "error" for f in self.findings)


def require_mujoco() -> None:
    try:
        import mujoco  # noqa: F401
    except ImportError:
        raise InputError(
            [
                SIM009.finding(
                    "descgen simulate needs the mujoco package, which is not installed",
                    "pip install 'descgen[sim]' (or pip install 'mujoco>=3')",
                )
            ]
        ) from None


def pose_values(robot: Robot, name: str | None) -> dict[str, float]:
    """Joint values of the named pose (a known pose, else an SRDF group state), else of the
    SRDF's first state; every joint it does not name at MoveIt's default position (zero, or the
    middle of limits that exclude it: descgen/physics/start_state.py), mimic joints set from their
    leaders."""
    if name is None:
        values = start_state.default_state(robot)[1]
    elif (kp := next((p for p in robot.known_poses if p.name == name), None)) is not None:
        values = {**start_state.inside_limits(robot), **dict(kp.joints)}
    elif robot.semantic and (st := next((s for s in robot.semantic.states if s.name == name), None)) is not None:
        values = {**start_state.inside_limits(robot), **dict(st.values)}
    else:
        names = [p.name for p in robot.known_poses] + [
            s.name for s in (robot.semantic.states if robot.semantic else ())
        ]
        there = ", ".join(dict.fromkeys(names)) or "none (the description has no known poses or SRDF states)"
        raise InputError(
            [
                SIM014.finding(
                    f"--pose {name!a} is no known pose or SRDF group state",
                    f"poses: {there}",
                    where=Where("<command line>"),
                )
            ]
        )
    return resolve(robot, values)


def too_large(robot: Robot, seconds: float, free: bool) -> str:
    """Why ``robot`` is past the bounds MuJoCo is given (:data:`MAX_LINKS`, :data:`MAX_DOFS`,
    :data:`MAX_WORK`), or "". Linear in the model."""
    if len(robot.links) > MAX_LINKS:
        return f"{len(robot.links):,} links, more than the {MAX_LINKS:,} descgen simulates"
    parent = {j.child: j for j in robot.joints if j.child is not None and j.parent is not None}
    above: dict[str, int] = {}  # link -> degrees of freedom from the root to it

    def dofs_to(link: str) -> int:
        path: list[str] = []
        n = link
        while n in parent and n not in above and len(path) <= len(parent):  # a cycle ends the walk
            path.append(n)
            n = parent[n].parent or ""
        d = above.get(n, 6 if free else 0)
        for m in reversed(path):
            d += _NV.get(parent[m].type, 0)
            above[m] = d
        return above.get(link, d)

    work = sum(d * d for d in range(1, 7)) if free else 0
    nv = 6 if free else 0
    for child, j in parent.items():
        k = _NV.get(j.type, 0)
        if k:
            below = dofs_to(child)  # this joint's degrees of freedom are the last k of the path
            nv += k
            work += sum(d * d for d in range(below - k + 1, below + 1))
    if nv > MAX_DOFS:
        return f"{nv:,} degrees of freedom, more than the {MAX_DOFS:,} descgen simulates"
    steps = max(1, round(seconds / gravity.TIMESTEP))
    if steps * work > MAX_WORK:
        return (
            f"{steps:,} steps of a mass matrix costing {work:,} (the sum of each degree of freedom's depth "
            f"squared) are {steps * work:,}, more than the {MAX_WORK:,} descgen simulates"
        )
    return ""


def simulate(robot: Robot, settings: Settings) -> Outcome:
    """Compile ``robot`` with MuJoCo, report its refusals and silent changes, run gravity.
    InputError (SIM017) for a robot past the bounds (:func:`too_large`), before MuJoCo sees it."""
    require_mujoco()
    import mujoco

    started = time.perf_counter()
    base = settings.base or start_state.default_base(robot)
    root = robot.root()
    if base == "floor" and (root is None or root == "world"):
        base = "fixed"  # no single root to set free; reported in the report's "base"
    why = too_large(robot, settings.seconds, base == "floor")
    if why:
        raise InputError(
            [
                SIM017.finding(
                    f"{robot.name} is too large to simulate: {why}",
                    "simulate a smaller description (fewer links or moving joints), or fewer --seconds when the "
                    "run's work is past its bound (the bounds keep a run within about 15 s; docs/security.md)",
                    f"robot:{robot.name}",
                    robot.where,
                )
            ]
        )
    pose = pose_values(robot, settings.pose)
    setup = gravity.Setup(base, settings.seconds, tuple(pose.items()), settings.gear, settings.damping)
    held = gravity.servos(robot, setup)
    free = base == "floor"

    def customise(spec: Any) -> None:
        gravity.set_integrator(spec)
        gravity.add_servos(spec, held, setup.gear)
        if free:
            assert root is not None
            gravity.add_floor(spec, root)

    compiled = compile_robot(robot, emit, customise)
    held_at = settings.pose or start_state.default_state(robot)[0] or "MoveIt's default position"
    report: dict[str, Any] = {"base": base, "pose": held_at, "seconds": settings.seconds}
    if compiled.spec is None:
        return Outcome(compiled.findings, report | {"compiled": False})
    found = [*compiled.findings, *silent_changes(robot, compiled.model)]
    model = compiled.model
    data = mujoco.MjData(model)
    gravity.place(model, data, pose, free)
    excluded = gravity.touching(model, data)
    if excluded:  # shapes touching at rest would push the pose away: leave those contacts out
        for a, b in excluded:
            compiled.spec.add_exclude(bodyname1=a, bodyname2=b)
        model = compiled.spec.compile()
        data = mujoco.MjData(model)
        gravity.place(model, data, pose, free)
        found.append(_excluded(robot, excluded))
    held = gravity.damped(model, data, held)
    if not held and not free:
        found.append(
            SIM016.finding(
                "nothing moves: no one-DOF joint to hold and a fixed base",
                "use --base floor for a mobile robot",
                f"robot:{robot.name}",
                robot.where,
            )
        )
    trace = gravity.step(model, data, held, settings.seconds, free)
    found += gravity.verdict(robot, held, trace, settings.seconds)
    report |= {
        "compiled": True,
        "bodies": int(model.nbody),
        "servos": [dataclasses.asdict(s) | {"tolerance": s.tolerance} for s in held],
        "drift": trace.drift,
        "end_speed": trace.end_speed,
        "tilt_deg": trace.tilt_deg,
        "warnings": trace.warnings,
        "steps": trace.steps,
        "excluded_contacts": [list(p) for p in excluded],
        "wall_s": time.perf_counter() - started,
    }
    return Outcome(found, report)


def _excluded(robot: Robot, pairs: list[tuple[str, str]]) -> Finding:
    said = ", ".join(f"{a}/{b}" for a, b in pairs)
    return SIM015.finding(
        f"{len(pairs)} pair(s) of bodies touch at the pose and are excluded from contact: {said}",
        "a MuJoCo consumer needs the same <contact><exclude> pairs (or smaller collision shapes)",
        f"robot:{robot.name}",
        robot.where,
    )


def simulate_description(path: Path, options: Any, settings: Settings) -> Outcome:
    """``descgen simulate``: read a spec, URDF or Xacro (``options``: audit.inputs.Options) and
    simulate it; what its readers reported comes first."""
    from descgen.read.description import load_description

    require_mujoco()  # before reading: a missing optional package is the first thing to say
    robot, read = load_description(path, options)
    outcome = simulate(robot, settings)
    outcome.findings[:0] = read
    return outcome
