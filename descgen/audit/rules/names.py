"""NAME: unique and usable names."""

from __future__ import annotations

import re
from collections.abc import Iterator

from descgen.audit.located import Param
from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.launch_subst import unresolved
from descgen.core.model import Joint, Link, Robot
from descgen.core.naming import GLOBAL_FRAMES
from descgen.physics.control_claims import FRAME_LEAVES, FRAME_PARAMS, default_frames, joint_params, names

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@rule("NAME001", "duplicate-link-name", "error")
def duplicate_link_name(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds two links with the same name.
    ## Why is this bad?
    urdfdom refuses the file; tf would have two frames with one id.
    """
    seen: dict[str, object] = {}
    for lk in robot.links:
        if lk.name in seen:
            first = getattr(seen[lk.name], "where", None)
            yield at(
                "NAME001",
                lk,
                f"duplicate link name '{lk.name}' (first at {first})",
                "rename one of them; each rigid body needs one identity",
            )
        else:
            seen[lk.name] = lk


@rule("NAME002", "duplicate-joint-name", "error")
def duplicate_joint_name(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds two joints with the same name.
    ## Why is this bad?
    urdfdom refuses the file; joint_states and ros2_control address joints by name.
    """
    seen: dict[str, object] = {}
    for j in robot.joints:
        if j.name in seen:
            first = getattr(seen[j.name], "where", None)
            yield at("NAME002", j, f"duplicate joint name '{j.name}' (first at {first})", "rename one of them")
        else:
            seen[j.name] = j


@rule("NAME003", "unusable-name", "warning")
def unusable_name(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags movable joint names that are not plain identifiers ([A-Za-z][A-Za-z0-9_]*), and
    link names that cannot be tf frame ids (empty, a leading '/', blanks).
    ## Why is this bad?
    ros2_control builds `<joint>/<interface>` and parameter paths such as `gains.<joint>.p`
    from joint names (fixed joints never reach it); tf refuses frame ids starting with '/'.
    """
    for lk in robot.links:
        if not lk.name or lk.name.startswith("/") or any(c.isspace() for c in lk.name):
            yield at(
                "NAME003",
                lk,
                f"link name '{lk.name}' cannot be a tf frame id (empty, leading '/' or blank)",
                "use letters, digits and _, starting with a letter",
            )
    elems: list[Link | Joint] = [j for j in robot.joints if j.type != "fixed"]
    for elem in elems:
        if not _IDENT.match(elem.name):
            message = f"name '{elem.name}' is not a plain identifier"
            yield at("NAME003", elem, message, "use letters, digits and _, starting with a letter")


def _leaves(params: tuple[tuple[str, object], ...], at: str = "") -> Iterator[tuple[str, object]]:
    """Every parameter as (dotted name, value): a spec's nested namespaces (tf: {child_frame_id:})
    and a controllers file's dotted names alike."""
    for k, v in params:
        name = f"{at}.{k}" if at else k
        if isinstance(v, tuple) and v and all(isinstance(x, tuple) and len(x) == 2 for x in v):
            yield from _leaves(v, name)
        else:
            yield name, v


@rule("NAME014", "name-without-prefix", "error")
def name_without_prefix(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Where a robot declares a name prefix (a Xacro's `prefix` or `tf_prefix` argument, the
    convention of ros2_control_demos and the UR description), finds the names that lack it:
    frames robot_state_publisher publishes (every joint's child; the root is where the robot is
    mounted and may be shared), joints, ros2_control joints, sensors and GPIOs, and the joints
    and frame ids its controllers name.
    ## Why is this bad?
    ROS 2 has no tf_prefix: the prefix is the only thing that keeps two robots of one graph
    apart. One name without it is published by both robots (two parents for one frame on /tf)
    or commands the other robot's joint; `descgen audit A B --together` shows the collision.
    """
    p = robot.prefix
    if p is None or not p.value:
        return
    declared = f"{p.declared} = '{p.value}', {p.where}"

    def lacking(kind: str, name: str, elem: object, subject: str | None = None) -> Finding:
        return at(
            "NAME014",
            elem,
            f"{kind} '{name}' lacks the robot's prefix ({declared})",
            f"name it '{p.value}{name}': write the prefix argument before the name",
            subject=subject,
        )

    for j in robot.joints:
        if not j.name.startswith(p.value):
            yield lacking("joint", j.name, j)
        if j.child and not j.child.startswith(p.value) and j.child not in GLOBAL_FRAMES:
            lk = robot.link(j.child)
            yield lacking("frame", j.child, lk if lk is not None else j, f"link:{j.child}")
    rc = robot.ros2_control
    if rc is None:
        return
    for kind, elems in (("ros2_control joint", rc.joints), ("ros2_control sensor", rc.sensors), ("gpio", rc.gpios)):
        for e in elems:
            if not e.name.startswith(p.value):
                yield lacking(kind, e.name, e, f"ros2_control:{e.name}")
    for c in rc.controllers:
        for key, default in default_frames(c.type):
            if c.param(key) is None:  # unset: the controller publishes its default, unprefixed
                unset = f"controller '{c.name}' {key} (unset, so its default)"
                yield lacking(unset, default, c, f"controller:{c.name}")
        nested = [k for k, _ in _leaves(c.params) if "." in k and k.rsplit(".", 1)[-1] in FRAME_LEAVES]
        for key in dict.fromkeys((*joint_params(c), *FRAME_PARAMS, *nested)):
            value = c.param(key) if "." not in key else dict(_leaves(c.params)).get(key)
            for i, name in enumerate(names(value)):
                if not name.startswith(p.value) and name not in GLOBAL_FRAMES and not unresolved(name):
                    index = i if isinstance(value, tuple | list) else None
                    yield lacking(f"controller '{c.name}' {key}", name, Param(c, key, index))
