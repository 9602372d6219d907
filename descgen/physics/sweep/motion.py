"""Where each joint moves the robot: the sweep grid, the links that move, and their direction.

Pure forward kinematics in plain floats (``descgen.physics.zero_pose``, held to ``descgen.physics.kinematics``
by the tests), so a ``check`` that computes the sweep does not import numpy (~60 ms); no
pinocchio. A joint is swept from
its lower to its upper limit in ``steps`` equal steps, both limits exactly; a continuous
joint through one turn. Mimic followers are not swept: they move with their leader
(``descgen.physics.mimic`` sets them at every step), and the links they carry count as moving.

The direction a reviewer reads is the displacement of a link's origin in the root frame from
the lower to the upper limit ("positive elbow_joint moves tool_link -z 250 mm"); for a
continuous joint, whose limits are the same configuration, and for a revolute joint whose range
is more than half a turn (UR's -360 to 360 deg: both limits are one pose, and over most of a turn
the chord points anywhere), it is the displacement over a quarter turn from the state value (kept
inside the limits).
"""

from __future__ import annotations

import bisect
import math
import operator
from collections.abc import Mapping, Sequence
from itertools import chain

from descgen.core.model import ONE_DOF, ROTATING, Joint, Robot
from descgen.core.record import record
from descgen.physics import mimic
from descgen.physics.rigid import Frame, compose, inverse, norm, rotate

MOVES = 1e-9  # a pose change below this (metres, rotation-matrix entries) is no motion


@record
class Moved:
    """One moving link: the displacement of its origin in the root frame (metres)."""

    link: str
    displacement: tuple[float, float, float]
    tip: str  # "group": a group's chain tip; "end": the end of a chain (no moving child); else ""


@record
class JointMotion:
    joint: Joint
    values: tuple[float, ...]  # the grid, lower to upper (both exact)
    continuous: bool
    followers: tuple[str, ...]  # mimic joints that move with it
    moved: tuple[Moved, ...]  # model order
    axis: tuple[float, float, float] | None  # revolute/prismatic axis in the root frame at the state
    span: tuple[float, float]  # the two values the displacement is measured between
    pairs: tuple[tuple[str, str], ...]  # link pairs (with geometry, not disabled) whose relative pose changes
    pairs_over: bool = False  # more pairs than the sweep's bound on collision checks: none listed

    @property
    def quarter_turn(self) -> bool:
        """The direction is measured over a quarter turn, not from limit to limit."""
        return quarter_turn(self.joint, self.values, self.continuous)

    @property
    def moving(self) -> tuple[str, ...]:
        return tuple(m.link for m in self.moved)

    def headline(self) -> Moved | None:
        """The link the one-line direction names: the first tip that moves its origin."""
        tips = sorted((m for m in self.moved if m.tip), key=lambda m: m.tip != "group")
        shown = [m for m in tips if direction(m.displacement)] or [m for m in self.moved if direction(m.displacement)]
        return shown[0] if shown else (tips[0] if tips else None)


@record
class NoRange:
    """A joint with nothing to sweep: no limits, or lower >= upper."""

    joint: Joint
    why: str


def sweepable(robot: Robot) -> list[Joint]:
    """One-degree-of-freedom joints that are not mimic followers (those move with their leader)."""
    return [j for j in robot.joints if j.type in ONE_DOF and mimic.relation(robot, j.name) is None]


def grid(j: Joint, steps: int) -> tuple[tuple[float, ...], bool] | str:
    """The values to visit, and whether the joint is continuous; or why there are none."""
    if j.type == "continuous":
        lo, hi = -math.pi, math.pi
    else:
        lm = j.limit
        if lm is None or lm.lower is None or lm.upper is None:
            return "it has no lower and upper limit"
        lo, hi = float(lm.lower), float(lm.upper)
        if not hi > lo:
            return f"its range is empty (lower {lo:g}, upper {hi:g})"
        if not math.isfinite((hi - lo) * steps):  # the grid's products below stay finite
            return f"its range is too large to sweep (lower {lo:g}, upper {hi:g})"
    values = [lo + (hi - lo) * k / steps for k in range(steps)] + [hi]
    return tuple(values), j.type == "continuous"


def followers(robot: Robot, leader: str) -> tuple[str, ...]:
    return tuple(r.follower for r in mimic.analyse(robot).relations.values() if r.leader == leader)


def joint_values(robot: Robot, state: Mapping[str, float], joint: str, value: float) -> dict[str, float]:
    """Every joint's value: the state, ``joint`` at ``value``, followers from their leaders."""
    return mimic.resolve(robot, {**state, joint: value})


def analyse(
    robot: Robot,
    j: Joint,
    values: Sequence[float],
    continuous: bool,
    state: Mapping[str, float],
    geometry: Sequence[str],
    disabled: set[frozenset[str]],
    limit: int | None = None,
) -> JointMotion:
    """Which links ``j`` moves over ``values``, how far, and which pairs could collide (none
    listed, ``pairs_over`` set, when there are more than ``limit``)."""
    from descgen.physics.zero_pose import forward, forward_from

    base = forward(robot, state)

    def at_value(v: float) -> dict[str, Frame]:
        return forward_from(robot, joint_values(robot, state, j.name, v), base, state)

    poses = [at_value(v) for v in values]
    first = poses[0]
    # a link above the joint keeps the very frame object in every pose (zero_pose.forward_from)
    moving = {n for p in poses[1:] for n, m in p.items() if n in first and m is not first[n] and _apart(m, first[n])}
    q0 = state.get(j.name, 0.0)
    quarter = quarter_turn(j, values, continuous)
    if continuous:
        span = (q0, q0 + math.pi / 2)
    elif quarter:  # a quarter turn from the state, inside the limits
        start = min(max(q0, values[0]), values[-1] - math.pi / 2)
        span = (start, start + math.pi / 2)
    else:
        span = (values[0], values[-1])
    at = [at_value(v) for v in span] if quarter else [poses[0], poses[-1]]
    pairs = _pairs(poses, geometry, disabled, limit)
    tips = _group_tips(robot)
    parents = {jj.parent for jj in robot.joints if jj.child in moving}
    moved = tuple(
        Moved(
            lk.name,
            _minus(at[1][lk.name][1], at[0][lk.name][1]),
            "group" if lk.name in tips else "" if lk.name in parents else "end",
        )
        for lk in robot.links
        if lk.name in moving
    )
    return JointMotion(
        j,
        tuple(values),
        continuous,
        followers(robot, j.name),
        moved,
        _axis_at_state(robot, j, state),
        span,
        pairs or (),
        pairs is None,
    )


def quarter_turn(j: Joint, values: Sequence[float], continuous: bool) -> bool:
    """Whether ``j``'s direction is measured over a quarter turn: continuous, or a revolute
    range of more than half a turn (its limit-to-limit chord says little about the direction)."""
    return continuous or (j.type in ROTATING and values[-1] - values[0] > math.pi)


def _entries(f: Frame) -> tuple[float, ...]:
    """The 12 entries of the frame's 4x4 matrix that can change (its last row cannot)."""
    r, t = f
    return r[0] + r[1] + r[2] + t


def _gap(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    """The largest ``|a_i - b_i|``, nan when any is nan, as ``np.max(np.abs(a - b))`` gives it
    (a pose past the float range, 1e308 + 1e308, has inf - inf = nan entries: no motion is
    read from them). map, sum and max keep the loop in C; the sum of non-negative terms is
    nan exactly when one of them is."""
    diffs = tuple(map(abs, map(operator.sub, a, b)))
    return math.nan if math.isnan(sum(diffs)) else float(max(diffs))


def _apart(a: Frame, b: Frame) -> bool:
    """Some entry of the two poses differs by more than :data:`MOVES`."""
    return _gap(_entries(a), _entries(b)) > MOVES


def _pairs(
    poses: Sequence[Mapping[str, Frame]],
    geometry: Sequence[str],
    disabled: set[frozenset[str]],
    limit: int | None = None,
) -> tuple[tuple[str, str], ...] | None:
    """Pairs of links with geometry, not disabled, whose relative pose changes in the sweep
    (two links both fixed, or moving together, collide at every step or at none: not this joint's).

    Each link's pose relative to its pose at the first step, over every step (a pair's relative
    pose changes exactly when these differ: A0^-1 B0 = A^-1 B <=> A A0^-1 = B B0^-1). One joint
    moves, so these fall into a few groups that move alike; a link joins the first group whose
    first member it is within MOVES/2 of at every entry. Two members of a group are then within
    MOVES of each other (triangle inequality), and two groups whose first members are more than
    2 MOVES apart somewhere hold no pair within MOVES: pairs are decided group by group, and only
    a pair of groups nearer than that is compared member by member. None when there are more
    than ``limit`` pairs (the sweep's bound on collision checks: they are not all listed)."""
    names = [n for n in geometry if n in poses[0]]
    seq = {n: _relative(poses, n) for n in names}
    firsts: list[tuple[float, ...]] = []
    group: dict[str, int] = {}
    for n in names:
        group[n] = next((k for k, f in enumerate(firsts) if _gap(seq[n], f) <= MOVES / 2), len(firsts))
        if group[n] == len(firsts):
            firsts.append(seq[n])
    far = {(g, h): _gap(firsts[g], firsts[h]) > 2 * MOVES for g in range(len(firsts)) for h in range(len(firsts))}
    # each link meets only the later links of the other groups (a link's own group holds no pair),
    # so the work follows the pairs found, not every pair of links: a joint that moves one link
    # of 10,000 compares that link with the rest, not 50 million pairs
    members: list[list[int]] = [[] for _ in firsts]
    for i, n in enumerate(names):
        members[group[n]].append(i)
    out: list[tuple[str, str]] = []
    for i, a in enumerate(names):
        ga = group[a]
        later = sorted(k for h, idx in enumerate(members) if h != ga for k in idx[bisect.bisect_right(idx, i) :])
        for k in later:
            b = names[k]
            if frozenset((a, b)) in disabled:
                continue
            if far[ga, group[b]] or _gap(seq[a], seq[b]) > MOVES:
                out.append((a, b))
                if limit is not None and len(out) > limit:
                    return None
    return tuple(out)


def _relative(poses: Sequence[Mapping[str, Frame]], name: str) -> tuple[float, ...]:
    """The entries of ``name``'s pose relative to its first one, step after step (a step whose
    frame is the first's own object gives the first step's entries: the same floats)."""
    first = poses[0][name]
    back = inverse(first)
    still = _entries(compose(first, back))
    return tuple(chain.from_iterable(still if p[name] is first else _entries(compose(p[name], back)) for p in poses))


def _group_tips(robot: Robot) -> set[str]:
    groups = robot.semantic.groups if robot.semantic else ()
    return {tip for g in groups for _, tip in g.chains}


def _axis_at_state(robot: Robot, j: Joint, state: Mapping[str, float]) -> tuple[float, float, float] | None:
    """The joint axis in the root frame with every joint at the state."""
    if j.axis is None or j.parent is None or j.type not in (*ROTATING, "prismatic"):
        return None
    from descgen.physics.zero_pose import forward, joint_frame

    poses = forward(robot, joint_values(robot, state, j.name, state.get(j.name, 0.0)))
    if j.parent not in poses:
        return None
    # the joint's fixed frame (its origin): the axis is written in it, and turning about the
    # axis does not move the axis
    rot = compose(poses[j.parent], joint_frame(j))[0]
    axis = rotate(rot, j.axis)
    n = norm(axis)
    return (axis[0] / n, axis[1] / n, axis[2] / n) if n > 0 else None


def _minus(a: Sequence[float], b: Sequence[float]) -> tuple[float, float, float]:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


# --- words for people ------------------------------------------------------------------------------


def direction(d: Sequence[float]) -> str:
    """``+z 312 mm, -x 40 mm``: components of at least 1 mm (as rounded), largest first."""
    parts = sorted(
        ((abs(c), "xyz"[i], c) for i, c in enumerate(d)), key=lambda t: (-round(t[0] * 1000), "xyz".index(t[1]))
    )
    words = [
        f"{'+' if c > 0 else '-'}{axis} {round(mag * 1000)} mm" for mag, axis, c in parts if round(mag * 1000) >= 1
    ]
    return ", ".join(words)


def axis_text(a: Sequence[float] | None) -> str:
    """``+y`` for a principal axis, else the unit vector to three decimals."""
    if a is None:
        return ""
    for i, c in enumerate(a):
        if abs(abs(c) - 1.0) < 1e-9:
            return f"{'+' if c > 0 else '-'}{'xyz'[i]}"
    return "(" + ", ".join(_short(c, 3) for c in a) + ")"


def value_text(j: Joint, v: float) -> str:
    """A joint value for display: degrees for angles, millimetres for lengths, one decimal."""
    if j.type in ROTATING:
        return f"{_short(math.degrees(v), 1)} deg"
    return f"{_short(v * 1000, 1)} mm"


def _short(x: float, digits: int) -> str:
    text = f"{x:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def sentence(m: JointMotion) -> str:
    """``positive elbow_joint moves tool_link -z 250 mm`` (or what moves when no origin does)."""
    name = m.joint.name
    head = m.headline()
    over = " over a quarter turn" if m.quarter_turn else ""
    if head is None:
        return f"positive {name} moves no link"
    words = direction(head.displacement)
    if not words:
        return f"positive {name} turns {head.link} in place{over}"
    return f"positive {name} moves {head.link} {words}{over}"
