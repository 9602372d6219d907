"""Mimic joints: the one place that turns leader values into follower values.

A URDF ``<mimic joint="L" multiplier="m" offset="o"/>`` on joint F means
``q_F = m * q_L + o`` (docs/reference/urdf.md). robot_state_publisher, MoveIt, yourdfpy,
pinocchio and ros2_control's GenericSystem all compute the follower from its leader, so
every forward kinematics here must too: a follower left at zero puts a gripper finger at
the wrong place by its offset plus its travel.

Chains (F mimics G mimics L) are resolved leader-first into one relation on the driving
joint, as MoveIt does (JOINT007 still reports them as errors: robot_state_publisher and
pinocchio do not follow chains). A follower whose chain never reaches a driving joint
(a dangling leader, a cycle, itself) has no relation: :func:`problems` names it, and
:func:`resolve` leaves its value alone rather than loop or guess.
"""

from __future__ import annotations

import functools
import weakref
from collections.abc import Mapping

from descgen.core.model import ONE_DOF, Joint, Robot
from descgen.core.record import record


@record
class Relation:
    """``q_follower = multiplier * q_leader + offset``, with ``leader`` a driving joint."""

    follower: str
    leader: str
    multiplier: float
    offset: float
    direct: str = ""  # the joint its <mimic> names: another follower on a chain, else the leader

    def value(self, leader_value: float) -> float:
        return self.multiplier * leader_value + self.offset


@record
class Problem:
    """A follower whose chain does not reach a driving joint."""

    joint: Joint
    message: str


def _followers(robot: Robot) -> dict[str, Joint]:
    """One-degree-of-freedom joints with a ``<mimic>`` (first of a repeated name)."""
    out: dict[str, Joint] = {}
    for j in robot.joints:
        if j.mimic is not None and j.type in ONE_DOF:
            out.setdefault(j.name, j)
    return out


def _walk(
    robot: Robot, followers: Mapping[str, Joint], done: Mapping[str, Relation | str], name: str
) -> tuple[list[Joint], Relation | str]:
    """Follow ``name``'s mimic chain until a driving joint or an already resolved follower:
    (the new followers on it, the relation where it ends, or why it has none)."""
    chain: list[Joint] = []
    seen: set[str] = set()
    cur = name
    while cur in followers:
        if cur in done:
            return chain, done[cur]
        if cur in seen:
            return chain, f"'{cur}' is on a mimic cycle"
        seen.add(cur)
        j = followers[cur]
        chain.append(j)
        assert j.mimic is not None
        cur = j.mimic.joint
    if robot.joint(cur) is None:
        return chain, f"'{cur}' is not a joint of the robot"
    return chain, Relation(cur, cur, 1.0, 0.0, cur)  # the driving joint follows itself


@record
class Mimics:
    """Every follower's relation to its driving joint, and the followers that have none."""

    relations: dict[str, Relation]
    problems: tuple[Problem, ...]

    def problem(self, joint: str) -> Problem | None:
        """Why no joint drives ``joint`` (None: it is driven, or not a follower)."""
        return self._index.get(joint)

    @functools.cached_property
    def _index(self) -> dict[str, Problem]:
        return {p.joint.name: p for p in reversed(self.problems)}


# analyse() per robot, kept while the robot lives: frames and rules ask per joint, and a
# rescan per joint would be quadratic on long chains. Robots are immutable, so the entry
# never goes stale (and a changed copy from ``dataclasses.replace`` is a new robot).
_CACHE: dict[int, tuple[weakref.ref[Robot], Mimics]] = {}


def _forget(key: int) -> None:
    _CACHE.pop(key, None)


def analyse(robot: Robot) -> Mimics:
    """Every follower's relation, and the followers without one (cached per robot)."""
    hit = _CACHE.get(id(robot))
    if hit is not None and hit[0]() is robot:
        return hit[1]
    out = _analyse(robot)
    key = id(robot)
    _CACHE[key] = (weakref.ref(robot, lambda _ref: _forget(key)), out)
    return out


def _analyse(robot: Robot) -> Mimics:
    """Resolve every mimic chain; each follower is composed once (linear in the joints)."""
    followers = _followers(robot)
    done: dict[str, Relation | str] = {}
    problems: list[Problem] = []
    for name in followers:
        if name in done:
            continue
        chain, end = _walk(robot, followers, done, name)
        for k, link in reversed(list(enumerate(chain))):  # leader side first
            assert link.mimic is not None
            if isinstance(end, str):
                done[link.name] = end
                problems.append(Problem(link, _problem_text(chain, k, end)))
                continue
            mm, off = link.mimic.multiplier, link.mimic.offset
            end = Relation(link.name, end.leader, mm * end.multiplier, mm * end.offset + off, link.mimic.joint)
            done[link.name] = end
    relations = {n: r for n, r in done.items() if isinstance(r, Relation)}
    order = {j.name: i for i, j in enumerate(robot.joints)}
    problems.sort(key=lambda p: order.get(p.joint.name, 0))
    return Mimics(relations, tuple(problems))


def _problem_text(chain: list[Joint], k: int, why: str) -> str:
    """The message for ``chain[k]``: its first few hops (a hostile chain may be long)."""
    hops = chain[k : k + 4]
    names = [x.name for x in hops]
    last = hops[-1].mimic.joint if hops[-1].mimic else "?"
    names.append(last if k + 4 >= len(chain) else "...")
    return f"no joint drives mimic joint '{chain[k].name}' ({' -> '.join(names)}): {why}"


def relation(robot: Robot, joint: str) -> Relation | None:
    """How ``joint`` follows its driving joint, or None (not a follower, or no driver)."""
    return analyse(robot).relations.get(joint)


def problems(robot: Robot) -> tuple[Problem, ...]:
    """Every follower no joint drives (a cycle, or a chain ending at a missing joint)."""
    return analyse(robot).problems


def problem(robot: Robot, joint: str) -> Problem | None:
    return analyse(robot).problem(joint)


def resolve(robot: Robot, positions: Mapping[str, float], default: float = 0.0) -> dict[str, float]:
    """``positions`` with every follower set from its driving joint.

    A driving joint not in ``positions`` counts as ``default`` (known poses leave unlisted
    joints at zero). A follower's own entry is replaced, as yourdfpy, pinocchio and MoveIt
    do: it is not a free variable (a known pose that contradicts it is POSE020). Followers
    without a driver keep their entry, if any. This is what the control model's measured
    state calls to make mimic joints follow (GenericSystem does the same)."""
    out = dict(positions)
    for name, rel in analyse(robot).relations.items():
        out[name] = rel.value(positions.get(rel.leader, default))
    return out


def formula(robot: Robot, rel: Relation) -> str:
    """``-1 * q(finger_left) + 0.01 m`` for people, in the follower's units."""
    j = robot.joint(rel.follower)
    unit = "m" if j is not None and j.type == "prismatic" else "rad"
    text = f"{rel.multiplier:.6g} * q({rel.leader})"
    if rel.offset:
        text += f" {'-' if rel.offset < 0 else '+'} {abs(rel.offset):.6g} {unit}"
    if rel.direct != rel.leader:
        text += f" (through {rel.direct})"
    return text


def unactuated(robot: Robot) -> set[str]:
    """Joints no actuator of their own drives: the SRDF's passive joints (a spring, a free
    caster, an underactuated finger) and mimic followers (robot_state_publisher computes them
    from their leader; MoveIt treats them as passive). A zero effort or velocity limit is what
    such a joint has, and its load rests on a spring, a linkage or its leader's motor."""
    declared = set(robot.semantic.passive_joints) if robot.semantic is not None else set()
    return declared | {j.name for j in robot.joints if j.mimic is not None}
