"""SRDF: the semantic description names real links, joints and groups."""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import ONE_DOF, Group, Robot


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
    virtual = {v.name for v in sem.virtual_joints}
    for st in sem.states:
        s = f"group_state:{st.name}"
        if st.group not in groups:
            yield at(
                "SRDF002", st, f"state '{st.name}' names unknown group '{st.group}'", "fix the group name", subject=s
            )
        for name, value in st.values:
            j = robot.joint(name)
            if j is None and name not in virtual:
                yield at(
                    "SRDF002", st, f"state '{st.name}' names unknown joint '{name}'", "fix the joint name", subject=s
                )
            elif j is not None and j.outside_limits(value):
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


@rule("SRDF004", "passive-joint-commanded", "error")
def passive_joint_commanded(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a joint the SRDF declares passive that has a ros2_control command interface.
    ## Why is this bad?
    MoveIt will not plan for a passive joint, yet the hardware accepts commands for it:
    one of the two descriptions is wrong.
    """
    sem, rc = robot.semantic, robot.ros2_control
    if sem is None or rc is None:
        return
    commanded = {cj.name for cj in rc.joints if cj.command}
    for name in sem.passive_joints:
        if name in commanded:
            yield at(
                "SRDF004",
                sem,
                f"passive joint '{name}' has command interfaces",
                "drop one of the two",
                subject=f"passive_joint:{name}",
            )


@rule("SRDF005", "srdf-robot-name-mismatch", "warning")
def srdf_robot_name_mismatch(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares the SRDF's robot name with the URDF's.
    ## Why is this bad?
    srdfdom only logs "Semantic description is not specified for the same robot".
    """
    name = robot.semantic.robot_name if robot.semantic is not None else None
    if name is not None and robot.semantic is not None and name != robot.name:
        yield at(
            "SRDF005",
            robot.semantic,
            f"SRDF robot name '{name}' differs from the URDF's '{robot.name}'",
            "use the same name in both",
            subject="srdf",
        )


@rule("SRDF006", "group-state-joint-outside-group", "warning")
def group_state_joint_outside_group(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a named state that sets a joint outside its group, or leaves a group joint out.
    A mimic joint needs no value: MoveIt sets it from its leader.
    ## Why is this bad?
    srdfdom does not check it; MoveIt then fills the missing joint with whatever it has.
    """
    sem = robot.semantic
    if sem is None:
        return
    names = {g.name for g in sem.groups}
    virtual = {v.name for v in sem.virtual_joints}
    for st in sem.states:
        if st.group not in names:
            continue
        in_group = [j for j in robot.group_joints(st.group) if j.type in ONE_DOF]
        # a mimic follower is set from its leader (RobotState::updateMimicJoints): it needs no value
        members = {j.name for j in in_group if j.mimic is None}
        followers = {j.name for j in in_group if j.mimic is not None}
        given = {n for n, _ in st.values}
        extra = sorted(given - members - followers - virtual)
        missing = sorted(members - given)
        if extra:
            yield at(
                "SRDF006",
                st,
                f"state '{st.name}' sets joints outside group '{st.group}': {', '.join(extra)}",
                "remove them or add them to the group",
                subject=f"group_state:{st.name}",
            )
        if missing:
            yield at(
                "SRDF006",
                st,
                f"state '{st.name}' leaves out joints of group '{st.group}': {', '.join(missing)}",
                "give a value for every joint of the group",
                subject=f"group_state:{st.name}",
            )


def _own_joints(robot: Robot, g: Group) -> list[str]:
    """The joints a group names itself (joint list, chains, links' parent joints), not its subgroups'."""
    names = list(g.joints)
    for base, tip in g.chains:
        names += [j.name for j in robot.chain_joints(base, tip)]
    names += [j.name for n in g.links if (j := robot.parent_joint(n)) is not None]
    return list(dict.fromkeys(names))


@rule("SRDF020", "passive-joint-in-group", "warning")
def passive_joint_in_group(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a planning group that contains a joint the SRDF declares passive (in its joint
    list, or through one of its chains or links).
    ## Why is this bad?
    MoveIt's JointModelGroup treats every non-mimic joint of a group as a variable to
    plan, so the planner moves the passive joint; the TrajectoryExecutionManager then drops
    passive joints from what it sends to the controllers. The robot executes a different
    motion from the one that was checked for collisions, or the group cannot be executed
    at all.
    ## Example
    `<passive_joint name="caster_joint"/>` and `<group name="base"><joint name="caster_joint"/></group>`.
    ## Use instead
    Leave passive joints out of planning groups (a chain that passes through one needs
    its tip moved), or drop the `<passive_joint>` if the joint is actuated.
    """
    sem = robot.semantic
    if sem is None or not sem.passive_joints:
        return
    # a mimic joint is no planning variable (MoveIt sets it from its leader), so a passive one in a
    # group changes nothing: Kinova's Robotiq 2F-85 declares its four-bar's mimic joints passive
    passive = {n for n in sem.passive_joints if (j := robot.joint(n)) is None or j.mimic is None}
    for g in sem.groups:
        found = [name for name in _own_joints(robot, g) if name in passive]
        if found:
            yield at(
                "SRDF020",
                g,
                f"group '{g.name}' contains passive joint(s) {', '.join(found)}: MoveIt plans them "
                "but never sends them to a controller",
                "remove them from the group, or drop the <passive_joint> if they are actuated",
                subject=f"group:{g.name}",
            )
