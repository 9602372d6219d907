"""Many robots in one ROS graph (``descgen audit A B --together``): what each robot's files are
fine with alone and wrong beside the other's.

ROS 2 has no tf_prefix. Every robot_state_publisher publishes on the one /tf, and robots in one
namespace share /joint_states and their controllers' joint names, so two descriptions that are
each correct collide by name. The checks compare every pair of robots, in the order given; a
finding sits in the second robot's file and names the first. Codes: descgen/codes/graph.py.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from descgen.codes.graph import GRAPH001, GRAPH002, GRAPH003, GRAPH004
from descgen.core.findings import Finding
from descgen.core.model import Joint, Robot
from descgen.physics.control_claims import command_pairs, joint_params, names

Labelled = tuple[str, Robot]  # the path as the user gave it, and its model


def findings(robots: Sequence[Labelled]) -> list[Finding]:
    """Every cross-robot finding of ``robots``, pair by pair in the order given."""
    out: list[Finding] = []
    for i, first in enumerate(robots):
        for second in robots[i + 1 :]:
            out += _frames(first, second)
            out += _joints(first, second)
            out += _claims(first, second)
            out += _claims(second, first)
            out += _joined(first, second)
            out += _joined(second, first)
    return out


def _publishing(robot: Robot) -> dict[str, Joint]:
    """Each frame robot_state_publisher puts on /tf or /tf_static: the child of every joint."""
    return {j.child: j for j in robot.joints if j.child}


def _roots(robot: Robot) -> list[str]:
    children = {j.child for j in robot.joints}
    return [lk.name for lk in robot.links if lk.name not in children]


def _frames(first: Labelled, second: Labelled) -> Iterator[Finding]:
    (a_label, a), (_, b) = first, second
    theirs = _publishing(a)
    for frame, joint in _publishing(b).items():
        other = theirs.get(frame)
        if other is None:
            continue
        yield GRAPH001.finding(
            f"frame '{frame}' is published by {b.name} (joint '{joint.name}', parent '{joint.parent}') and by "
            f"{a.name} in {a_label} (joint '{other.name}', parent '{other.parent}'): two parents on one /tf",
            f"prefix one robot's frames (a prefix Xacro argument), or remove '{frame}' from one of them",
            f"frame:{frame}",
            joint.where,
        )


def _joints(first: Labelled, second: Labelled) -> Iterator[Finding]:
    (a_label, a), (_, b) = first, second
    if a.namespace and b.namespace and a.namespace.strip("/") != b.namespace.strip("/"):
        return  # two specs in two namespaces: each robot's /joint_states is its own
    moving = {j.name for j in a.joints if j.type != "fixed"}
    for j in b.joints:
        if j.type != "fixed" and j.name in moving:
            yield GRAPH002.finding(
                f"joint '{j.name}' moves in both {b.name} and {a.name} ({a_label}): in one namespace both robots' "
                "joint_states carry it, and each robot_state_publisher takes the other's position",
                "prefix the joints of one robot, or run each in its own namespace (a spec's namespace:; for "
                "descriptions, accept it with --baseline)",
                f"joint:{j.name}",
                j.where,
            )


def _claims(first: Labelled, second: Labelled) -> Iterator[Finding]:
    """Names in ``second``'s ros2_control and controllers that are ``first``'s joints, not its own."""
    (a_label, a), (_, b) = first, second
    rc = b.ros2_control
    if rc is None:
        return
    own = {j.name for j in b.joints}
    other = {j.name for j in a.joints} - own

    def foreign(name: str) -> bool:
        return name in other

    for cj in rc.joints:
        if foreign(cj.name):
            yield GRAPH003.finding(
                f"ros2_control joint '{cj.name}' of {b.name} is a joint of {a.name} ({a_label}), not of {b.name}",
                f"name {b.name}'s own joint (a prefix left out or doubled?)",
                f"ros2_control:{cj.name}",
                cj.where,
            )
    for c in rc.controllers:
        seen: set[str] = set()
        for key in joint_params(c):
            value = c.param(key)
            for i, name in enumerate(names(value)):
                if foreign(name) and name not in seen:
                    seen.add(name)
                    yield GRAPH003.finding(
                        f"controller '{c.name}' of {b.name} names '{name}' in {key}, a joint of {a.name} "
                        f"({a_label}), not of {b.name}",
                        f"name {b.name}'s own joint (a prefix left out or doubled?)",
                        f"controller:{c.name}",
                        c.where_of(key, i if isinstance(value, tuple | list) else None),
                    )
        for component, _ in command_pairs(c):
            if foreign(component) and component not in seen:
                seen.add(component)
                yield GRAPH003.finding(
                    f"controller '{c.name}' of {b.name} claims '{component}', a joint of {a.name} ({a_label})",
                    f"name {b.name}'s own joint (a prefix left out or doubled?)",
                    f"controller:{c.name}",
                    c.where,
                )


def _joined(first: Labelled, second: Labelled) -> Iterator[Finding]:
    """``second`` hangs from a frame ``first`` publishes."""
    (a_label, a), (_, b) = first, second
    published = _publishing(a)
    for root in _roots(b):
        joint = published.get(root)
        if joint is not None:
            lk = b.link(root)
            yield GRAPH004.finding(
                f"{b.name}'s root '{root}' is a frame of {a.name} ({a_label}, child of joint '{joint.name}'): "
                f"{b.name} hangs from {a.name} on /tf",
                "",
                f"frame:{root}",
                lk.where if lk is not None else b.where,
            )
