"""``descgen sweep``: move each joint through its range, the others at a named state, and say
where it moves the robot and what collides on the way.

Per joint (``motion``): the links it moves, the displacement of each origin in the root frame
from the lower to the upper limit, and the axis in the root frame at the state, so that a
reviewer reads "positive elbow_joint moves tool_link -z 250 mm". Per joint (``contacts``,
pinocchio + coal, the ``collision`` extra): the pairs the SRDF does not disable that come
closer than the matrix's padding, with the joint values where each contact starts and ends.
A contact at a joint limit is SWEEP001, one inside the range SWEEP002.

Without pinocchio the directions are still reported, and SWEEP005 says the collisions were
not checked; links without collision geometry are listed, never silently absent.
``evidence`` renders the same result into the package (``evidence/sweep.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from descgen.codes import CODES
from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import NOWHERE, Robot
from descgen.core.record import record
from descgen.infra import keys
from descgen.physics import collision, derive, start_state
from descgen.physics.sweep.contacts import Run, available, runs, unresolved_meshes
from descgen.physics.sweep.motion import (
    JointMotion,
    NoRange,
    analyse,
    axis_text,
    direction,
    grid,
    sentence,
    sweepable,
    value_text,
)

ALGORITHM = "descgen-sweep-1"  # bump when results change: memoised and committed runs are then recomputed
# (tests/test_evidence_recompute.py sweeps the committed example again and fails on a forgotten bump)
DEFAULT_STEPS = 36
MIN_STEPS, MAX_STEPS = 1, 3600
# The sweep's bounds (SWEEP007, SWEEP008), so that a robot of 10,000 links is a finding in a
# second, not hours of work, gigabytes, or pinocchio's stack overflow (it recurses down the
# tree, and crashed past ~3,500 joints deep, exit 139). Each joint's forward kinematics at every grid step
# visits every link: joints x links x (steps + 1) link poses, ~20 us each in plain floats.
MAX_POSES = 500_000  # ~20 s; a 116-link chain at the default 36 steps, 500 links at --steps 1
# Collision tests: pairs checked x (steps + 1), ~4 us each (~8 s); what pinocchio may be given
# at all is collision.too_large's (shapes and depth).
MAX_CHECKS = 2_000_000


@dataclass(frozen=True)  # a frozen dataclass: ruff sees a default Settings() as immutable
class Settings:
    state: str | None = None  # a group state or known pose; None: the matrix's default state, else zero
    steps: int = DEFAULT_STEPS


@record
class Sweep:
    robot: Robot
    state: str  # "" = every joint at zero
    values: tuple[tuple[str, float], ...]
    steps: int
    padding: float
    disabled_by: str  # where the disabled pairs come from
    disabled: int
    motions: tuple[JointMotion, ...]
    no_range: tuple[NoRange, ...]
    runs: tuple[Run, ...] | None  # None: collisions not checked (``note`` says why)
    note: str
    skipped: tuple[str, ...]  # links without collision geometry
    unresolved: tuple[str, ...]  # links whose collision mesh the model could not resolve (left out)
    key: str  # the memo key ("" when not memoised)
    too_large: str = ""  # why nothing was swept: the robot is past MAX_POSES (SWEEP007)
    too_many_checks: bool = False  # collisions not checked: past MAX_CHECKS or MAX_SHAPE_PAIRS (SWEEP008)

    def motion(self, joint: str) -> JointMotion:
        return next(m for m in self.motions if m.joint.name == joint)


def finding(code: str, message: str, hint: str, subject: str = "", where: Where = NOWHERE) -> Finding:
    severity = CODES[code].severity
    assert severity != "varies", code  # every SWEEP code has one severity
    return Finding(code, severity, message, hint, subject, where)


# --- inputs: the state, the disabled pairs, the padding -------------------------------------------


def state_values(robot: Robot, name: str | None) -> tuple[str, dict[str, float]]:
    """The state's name and joint values: ``name`` (a group state, else a known pose), else
    the state the collision matrix used, else the SRDF's first state, else "" (no state); every
    joint the state does not name at MoveIt's default position (zero, or the middle of limits that
    exclude it: descgen/physics/start_state.py; zero is outside many real joints' limits, and a
    sweep from there finds collisions no robot has)."""
    sem = robot.semantic
    if name is None:
        if sem is not None and sem.matrix is not None:
            name = sem.matrix.state or None
        elif sem is not None and sem.collision_matrix is not None:
            name = sem.collision_matrix.default_state
        if name is None:
            return start_state.default_state(robot)
    base = start_state.inside_limits(robot)
    states = sem.states if sem else ()
    st = next((s for s in states if s.name == name), None)
    if st is not None:
        return name, {**base, **dict(st.values)}
    kp = next((p for p in robot.known_poses if p.name == name), None)
    if kp is not None:
        return name, {**base, **dict(kp.joints)}
    there = ", ".join(dict.fromkeys([s.name for s in states] + [p.name for p in robot.known_poses]))
    raise InputError(
        [
            finding(
                "SWEEP004",
                f"--state {name!a} is no group state or known pose of {robot.name}",
                f"states: {there}"
                if there
                else "the description has no group states or known poses: leave out --state",
                "option",
                Where("<command line>"),
            )
        ]
    )


def disabled_pairs(robot: Robot) -> tuple[set[frozenset[str]], str]:
    """The pairs MoveIt does not check, and where they come from: the sampled matrix and the
    spec's own pairs (as the generated SRDF), an SRDF's disable_collisions, or, with no SRDF,
    the adjacent pairs (one joint apart: they touch at the joint by design)."""
    sem = robot.semantic
    own = {frozenset((d.link1, d.link2)) for d in sem.disabled_collisions} if sem else set()
    if sem is not None and sem.matrix is not None:
        return {frozenset((d.link1, d.link2)) for d in sem.matrix.pairs} | own, "the collision matrix and the spec"
    if sem is not None and sem.robot_name is not None:
        return own, "the SRDF"
    if sem is not None:  # a spec without a matrix: its SRDF disables the adjacent pairs and its own
        return {frozenset(p) for p in derive.adjacent_pairs(robot)} | own, "the spec's SRDF (adjacent and listed pairs)"
    return collision.adjacent_pairs(robot), "adjacent pairs (no SRDF given)"


def padding(robot: Robot) -> float:
    sem = robot.semantic
    return sem.collision_matrix.padding if sem is not None and sem.collision_matrix is not None else 0.0


# --- the sweep ----------------------------------------------------------------------------------

# collision runs computed in this process (or read back from a committed evidence/sweep.md), by
# key: generate followed by check sweeps once, and check reuses what generate committed
_RUNS: dict[str, tuple[Run, ...]] = {}


def memo_key(robot: Robot, state: str, values: dict[str, float], steps: int, disabled: set[frozenset[str]]) -> str:
    """Only a robot with a sampled matrix is memoised: the matrix's input hash already covers
    its geometry, joints, meshes and padding, on any machine. The key (descgen/infra/keys.py)
    names :data:`ALGORITHM`, descgen's release and the libraries that computed the matrix
    (pinocchio and coal check the sweep's contacts as they checked the matrix's samples)."""
    sem = robot.semantic
    if sem is None or sem.matrix is None:
        return ""
    inputs = {
        "matrix": sem.matrix.input_hash,
        "state": state,
        "values": sorted(values.items()),
        "steps": steps,
        "disabled": sorted(sorted(p) for p in disabled),
    }
    return keys.key("sweep collision runs", ALGORITHM, inputs, dict(sem.matrix.libraries), keys.RELEASE)


def remember(key: str, found: Sequence[Run]) -> None:
    _RUNS[key] = tuple(found)


def remembered(key: str) -> tuple[Run, ...] | None:
    """The collision runs memoised under ``key`` (computed in this process or read back from a
    committed evidence/sweep.md), or None."""
    return _RUNS.get(key) if key else None


def compute(robot: Robot, settings: Settings = Settings(), progress: Callable[[str], None] | None = None) -> Sweep:
    """The sweep of every joint of ``robot``. InputError for an unknown state."""
    state, values = state_values(robot, settings.state)
    disabled, disabled_by = disabled_pairs(robot)
    geometry = [lk.name for lk in robot.links if lk.collisions]
    joints = sweepable(robot)
    poses = len(joints) * len(robot.links) * (settings.steps + 1)
    if poses > MAX_POSES:
        why = (
            f"sweeping {len(joints):,} joints of {len(robot.links):,} links through {settings.steps + 1} steps "
            f"computes {poses:,} link poses, more than the sweep's bound of {MAX_POSES:,}"
        )
        return Sweep(
            robot, state, tuple(sorted(values.items())), settings.steps, padding(robot), disabled_by,
            len(disabled), (), (), None, why, (), (), "", too_large=why,
        )  # fmt: skip
    motions, empty = [], []
    checks = 0  # collision tests so far (pairs x grid steps)
    for j in joints:
        g = grid(j, settings.steps)
        if isinstance(g, str):
            empty.append(NoRange(j, g))
            continue
        left = max(MAX_CHECKS - checks, 0) // len(g[0])
        motion = analyse(robot, j, g[0], g[1], values, geometry, disabled, left)
        if not all(math.isfinite(c * 1000.0) for m in motion.moved for c in m.displacement):
            # a link past the float range in millimetres, as it is printed (a joint offset near
            # 1e308 m): no direction to say
            empty.append(NoRange(j, "a link it moves lies beyond the float range (a joint offset near 1e308)"))
            continue
        motions.append(motion)
        checks += len(motion.pairs) * len(g[0])
    too_many = collision.too_large(robot)
    over = any(m.pairs_over for m in motions) or bool(too_many)
    key = "" if over else memo_key(robot, state, values, settings.steps, disabled)
    found: tuple[Run, ...] | None = _RUNS.get(key) if key else None
    note = ""
    if over:
        motions = [replace(m, pairs=(), pairs_over=True) for m in motions]
        note = too_many or f"the sweep would make more than {MAX_CHECKS:,} pair tests (pairs x steps), its bound"
    elif found is None:
        if not available():
            note = "pinocchio is not installed"
        else:
            try:
                found = tuple(runs(robot, motions, values, padding(robot), progress))
            except InputError as exc:
                note = exc.findings[0].message
            if found is not None and key:
                _RUNS[key] = found
    return Sweep(
        robot,
        state,
        tuple(sorted(values.items())),
        settings.steps,
        padding(robot),
        disabled_by,
        len(disabled),
        tuple(motions),
        tuple(empty),
        found,
        note,
        tuple(lk.name for lk in robot.links if not lk.collisions),
        tuple(unresolved_meshes(robot)),
        key,
        too_many_checks=over,
    )


def span_text(m: JointMotion, r: Run) -> str:
    """``from 72.2 deg to 100 deg``, or ``at 100 deg`` for a single grid step."""
    j = m.joint
    if r.first == r.last:
        return f"at {value_text(j, m.values[r.first])}"
    return f"from {value_text(j, m.values[r.first])} to {value_text(j, m.values[r.last])}"


def limit_of(m: JointMotion, r: Run) -> list[str]:
    """Which limits a run touches ("lower", "upper"); none for a continuous joint."""
    if m.continuous:
        return []
    return [side for side, k in (("lower", 0), ("upper", len(m.values) - 1)) if k in (r.first, r.last)]


def findings(sw: Sweep) -> list[Finding]:
    """What the sweep found, as findings (the report says the rest)."""
    out: list[Finding] = []
    robot = sw.robot
    at = f" (others at state {sw.state})" if sw.state else " (others at MoveIt's default position)"
    if sw.too_large:
        return [
            finding(
                "SWEEP007",
                f"{robot.name} is too large to sweep: {sw.too_large}",
                "sweep with fewer --steps, or a description with fewer links or joints (the bound keeps a sweep "
                "within about 20 s and its memory small; docs/security.md)",
                f"robot:{robot.name}",
                robot.where,
            )
        ]
    for nr in sw.no_range:
        out.append(
            finding(
                "SWEEP003",
                f"{nr.joint.name} is not swept: {nr.why}",
                "give the joint finite lower < upper limits (in radians or metres) to have its motion checked",
                f"joint:{nr.joint.name}",
                nr.joint.where,
            )
        )
    if sw.too_many_checks:
        out.append(
            finding(
                "SWEEP008",
                f"self-collisions were not checked: {sw.note}; directions only",
                "sweep with fewer --steps, disable pairs that cannot collide in the SRDF, or give fewer collision "
                "shapes (simpler collision geometry); a tree deeper than pinocchio takes is not checked",
                f"robot:{robot.name}",
                robot.where,
            )
        )
    elif sw.runs is None:
        out.append(
            finding(
                "SWEEP005",
                f"self-collisions were not checked: {sw.note}; directions only",
                "pip install 'descgen[collision]' (pinocchio with coal), then run the sweep again",
                f"robot:{robot.name}",
                robot.where,
            )
        )
    for link in sw.unresolved:
        out.append(
            finding(
                "SWEEP006",
                f"a collision mesh of {link} was not found, so that shape is left out of the collision check",
                "give --package-path for package:// meshes, or fix the mesh filename",
                f"link:{link}",
                lk.where if (lk := robot.link(link)) is not None else robot.where,
            )
        )
    for r in sw.runs or ():
        m = sw.motion(r.joint)
        j = m.joint
        span = span_text(m, r)
        sides = limit_of(m, r)
        for side in sides:
            value = value_text(j, m.values[0] if side == "lower" else m.values[-1])
            out.append(
                finding(
                    "SWEEP001",
                    f"{r.link1} and {r.link2} collide at the {side} limit of {j.name} ({value}){at}; in contact {span}",
                    "narrow the joint's limit so the motion stops before the contact, change the collision "
                    "shapes, or disable the pair in the SRDF if the contact is by design",
                    f"joint:{j.name}",
                    j.limit.where if j.limit is not None and j.limit.where.file else j.where,
                )
            )
        if not sides:
            out.append(
                finding(
                    "SWEEP002",
                    f"{r.link1} and {r.link2} collide while {j.name} moves {span}{at}",
                    "check the collision shapes and the joint's range; disable the pair in the SRDF only if "
                    "the contact is by design",
                    f"joint:{j.name}",
                    j.where,
                )
            )
    return out


# --- reports --------------------------------------------------------------------------------------


def as_dict(sw: Sweep) -> dict[str, Any]:
    """The sweep for ``--format json`` (SI values: metres and radians)."""
    joints = []
    for m in sw.motions:
        mine = [r for r in sw.runs or () if r.joint == m.joint.name]
        joints.append(
            {
                "joint": m.joint.name,
                "type": m.joint.type,
                "lower": m.values[0],
                "upper": m.values[-1],
                "followers": list(m.followers),
                "axis_root": list(m.axis) if m.axis else None,
                "direction": sentence(m),
                "displacement_between": list(m.span),
                "moving": [{"link": x.link, "displacement_m": list(x.displacement), "tip": x.tip} for x in m.moved],
                "pairs_checked": len(m.pairs) if sw.runs is not None else None,
                "collisions": [
                    {
                        "link1": r.link1,
                        "link2": r.link2,
                        "from": m.values[r.first],
                        "to": m.values[r.last],
                        "at_limit": limit_of(m, r),
                    }
                    for r in mine
                ],
            }
        )
    return {
        "robot": sw.robot.name,
        "state": sw.state or None,
        "steps": sw.steps,
        "padding_m": sw.padding,
        "disabled_pairs": {"count": sw.disabled, "from": sw.disabled_by},
        "collisions_checked": sw.runs is not None,
        "not_checked_because": sw.note or None,
        "links_without_collision_geometry": list(sw.skipped),
        "links_with_unresolved_meshes": list(sw.unresolved),
        "joints": joints,
        "not_swept": [{"joint": nr.joint.name, "why": nr.why} for nr in sw.no_range],
    }


def text(sw: Sweep) -> str:
    """The sweep for a terminal: per joint its direction, what moves and what collides."""
    state = f"state {sw.state}" if sw.state else "every joint at MoveIt's default position"
    lines = [
        f"{sw.robot.name}: each joint through its range, the others at {state} ({sw.steps} steps; "
        f"padding {sw.padding * 1000:g} mm; {sw.disabled} pairs disabled by {sw.disabled_by})"
    ]
    for m in sw.motions:
        j = m.joint
        axis = f", axis {axis_text(m.axis)} in the root frame" if m.axis else ""
        lines.append(f"{j.name} ({j.type}, {value_text(j, m.values[0])} to {value_text(j, m.values[-1])}{axis})")
        lines.append(f"  {sentence(m)}")
        for x in m.moved:
            lines.append(f"    {x.link}: {direction(x.displacement) or 'origin stays'}")
        if m.followers:
            lines.append(f"  moves with it: {', '.join(m.followers)}")
        if sw.runs is not None:
            mine = [r for r in sw.runs if r.joint == j.name]
            if not mine:
                lines.append(f"  no self-collision ({len(m.pairs)} pairs checked)")
            for r in mine:
                sides = limit_of(m, r)
                where = f" (at the {' and '.join(sides)} limit)" if sides else ""
                lines.append(f"  collision {r.link1} / {r.link2} {span_text(m, r)}{where}")
    for nr in sw.no_range:
        lines.append(f"{nr.joint.name}: not swept ({nr.why})")
    if sw.skipped:
        lines.append(f"no collision geometry, not checked: {', '.join(sw.skipped)}")
    if sw.runs is None:
        lines.append(f"self-collisions not checked: {sw.note}")
    return "\n".join(lines) + "\n"
