"""SRDF: the semantic description names real links, joints and groups."""

from __future__ import annotations

from collections.abc import Iterator

from ...findings import Finding
from ...model import Robot
from ..registry import at, rule


def _is_ancestor(robot: Robot, anc: str, desc: str) -> bool:
    return anc == desc or any(j.parent == anc for j in robot.path_to_root(desc))


@rule("SRDF001", "group-bad-reference", "error")
def group_bad_reference(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds planning groups naming unknown links, joints or subgroups, and chains whose
    base is not an ancestor of the tip.
    ## Why is this bad?
    srdfdom only logs these and drops the element; MoveIt then lacks the group.
    """
    sem = robot.semantic
    if sem is None:
        return
    links = {lk.name for lk in robot.links}
    joints = {j.name for j in robot.joints} | {v.name for v in sem.virtual_joints}
    groups = {g.name for g in sem.groups}
    for g in sem.groups:
        s = f"group:{g.name}"
        for name in g.links:
            if name not in links:
                yield at("SRDF001", g, f"group '{g.name}' names unknown link '{name}'", "fix the link name", subject=s)
        for name in g.joints:
            if name not in joints:
                yield at(
                    "SRDF001", g, f"group '{g.name}' names unknown joint '{name}'", "fix the joint name", subject=s
                )
        for name in g.subgroups:
            if name not in groups or name == g.name:
                yield at(
                    "SRDF001",
                    g,
                    f"group '{g.name}' names unknown or self subgroup '{name}'",
                    "fix the group name",
                    subject=s,
                )
        for base, tip in g.chains:
            bad = [x for x in (base, tip) if x not in links]
            if bad:
                yield at(
                    "SRDF001",
                    g,
                    f"group '{g.name}' chain names unknown link '{bad[0]}'",
                    "fix the link name",
                    subject=s,
                )
            elif not _is_ancestor(robot, base, tip):
                yield at(
                    "SRDF001",
                    g,
                    f"group '{g.name}' chain: '{base}' is not an ancestor of '{tip}'",
                    "swap base and tip, or pick links on one branch",
                    subject=s,
                )
        if not (g.links or g.joints or g.chains or g.subgroups):
            yield at("SRDF001", g, f"group '{g.name}' is empty", "add a chain, links or joints", "warning", s)


@rule("SRDF002", "group-state-bad", "error")
def group_state_bad(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds named states whose group or joints are unknown, or whose values break limits.
    ## Why is this bad?
    srdfdom checks neither membership nor limits; MoveIt refuses to plan to such a state.
    """
    sem = robot.semantic
    if sem is None:
        return
    groups = {g.name for g in sem.groups}
    for st in sem.states:
        s = f"group_state:{st.name}"
        if st.group not in groups:
            yield at(
                "SRDF002", st, f"state '{st.name}' names unknown group '{st.group}'", "fix the group name", subject=s
            )
        for name, value in st.values:
            j = robot.joint(name)
            if j is None:
                yield at(
                    "SRDF002", st, f"state '{st.name}' names unknown joint '{name}'", "fix the joint name", subject=s
                )
            elif j.outside_limits(value):
                message = f"state '{st.name}' sets '{name}' to {j.show(value)}, outside {j.range_text()}"
                yield at("SRDF002", st, message, "fix the value or the limits", subject=s)


@rule("SRDF003", "semantic-bad-reference", "error")
def semantic_bad_reference(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks end effectors, virtual joints, passive joints and disabled collision pairs name
    existing links, joints and groups.
    ## Why is this bad?
    srdfdom skips the element with a log line; the robot then plans without it.
    """
    sem = robot.semantic
    if sem is None:
        return
    links = {lk.name for lk in robot.links}
    joints = {j.name for j in robot.joints} | {v.name for v in sem.virtual_joints}
    groups = {g.name for g in sem.groups}
    for e in sem.end_effectors:
        for what, name, pool in (
            ("group", e.group, groups),
            ("parent link", e.parent_link, links),
            ("parent group", e.parent_group, groups),
        ):
            if name is not None and name not in pool:
                yield at(
                    "SRDF003",
                    e,
                    f"end effector '{e.name}' names unknown {what} '{name}'",
                    "fix the name",
                    subject=f"end_effector:{e.name}",
                )
    for v in sem.virtual_joints:
        if v.child_link not in links:
            yield at(
                "SRDF003",
                v,
                f"virtual joint '{v.name}' child '{v.child_link}' is not a link",
                "fix the name",
                subject=f"virtual_joint:{v.name}",
            )
    for name in sem.passive_joints:
        if name not in joints:
            yield at(
                "SRDF003",
                sem,
                f"passive joint '{name}' is not a joint",
                "fix the name",
                subject=f"passive_joint:{name}",
            )
    for d in sem.disabled_collisions:
        for name in (d.link1, d.link2):
            if name not in links:
                yield at(
                    "SRDF003",
                    d,
                    f"disabled collision pair names unknown link '{name}'",
                    "fix the name",
                    subject=f"disable_collisions:{d.link1}:{d.link2}",
                )
