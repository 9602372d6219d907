"""FRAME: every transform of the running robot has exactly one publisher."""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Iterator

from descgen.audit.located import Param
from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.launch_subst import unresolved
from descgen.core.model import ONE_DOF, Robot
from descgen.physics.frames import RSP, edges


@rule("FRAME001", "frame-with-two-owners", "error")
def frame_with_two_owners(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a frame that two publishers claim as child (e.g. the diff-drive controller and a
    declared odometry node both publishing `odom -> base_footprint`).
    ## Why is this bad?
    tf keeps one parent per frame: the two publishers overwrite each other and the robot
    jumps between two poses many times a second.
    """
    owners = defaultdict(list)
    for e in edges(robot):
        owners[e.child].append(e)
    for child, es in owners.items():
        if len(es) > 1:
            names = ", ".join(f"{e.owner} ({e.parent} -> {child})" for e in es)
            yield at(
                "FRAME001",
                es[1],
                f"frame '{child}' is published by {len(es)} owners: {names}",
                "keep one publisher per frame: disable one (e.g. enable_odom_tf: false)",
            )


@rule("FRAME002", "moving-joint-without-state", "error")
def moving_joint_without_state(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a movable joint that nothing puts on /joint_states (with ros2_control: no
    joint_state_broadcaster, or no position state interface for the joint).
    ## Why is this bad?
    robot_state_publisher publishes a movable joint only when /joint_states names it: its
    child frame and everything below are never in tf ("frame does not exist").
    """
    for e in edges(robot):
        if e.owner == RSP and not e.static and e.via == "nothing":
            j = robot.joint(e.joint or "")
            yield at(
                "FRAME002",
                j or e,
                f"nothing publishes joint '{e.joint}' on /joint_states, so '{e.child}' never appears in tf",
                "give the joint a position state interface and run joint_state_broadcaster",
                subject=f"joint:{e.joint}",
            )


@rule("FRAME003", "joint-not-published-by-rsp", "error")
def joint_not_published_by_rsp(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags floating joints (robot_state_publisher skips them) unless the spec declares who
    publishes them, and planar joints (published frozen at zero).
    ## Why is this bad?
    The subtree below a floating joint is disconnected in tf; a planar joint never moves
    in tf however the robot moves.
    """
    external = {(e.parent, e.child) for e in robot.external_frames}
    for j in robot.joints:
        if j.type == "floating" and (j.parent, j.child) not in external:
            yield at(
                "FRAME003",
                j,
                f"floating joint '{j.name}': robot_state_publisher publishes nothing for it",
                "declare its publisher under frames.external (e.g. the localisation node)",
            )
        elif j.type == "planar":
            yield at(
                "FRAME003",
                j,
                f"planar joint '{j.name}' is published frozen at zero (KDL treats it as fixed)",
                "publish the planar motion from another node, or model it as two prismatic joints and a revolute",
                severity="warning",
            )


@rule("FRAME004", "frame-not-in-tree", "error")
def frame_not_in_tree(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds frames that publishers or controllers name but that nothing connects to the
    robot's tree: the diff-drive `base_frame_id`, a declared external edge whose child is
    not a link and whose parent is unknown, a joint_state_broadcaster `frame_id`.
    ## Why is this bad?
    Odometry or sensor data arrives in a frame tf cannot relate to the robot; every lookup
    fails with "not part of the same tree".
    """
    links = {lk.name for lk in robot.links}
    all_edges = edges(robot)
    known = links | {e.parent for e in all_edges} | {e.child for e in all_edges}
    # Only declared edges are checked as edges: a diff-drive controller's odom -> base edge
    # joins the tree exactly when its base_frame_id is a link, which the controller check
    # below reports at that parameter (a second finding for the same name would be a double
    # report; an unresolved $(var ...) there is CTRL052/053's).
    declared = {(x.parent, x.child, x.owner) for x in robot.external_frames}
    parents = {x.parent for x in all_edges}  # one set, not a scan of every edge per edge
    for e in all_edges:
        joined = e.child in links or e.parent in links or e.child in parents
        if e.owner != RSP and (e.parent, e.child, e.owner) in declared and not joined:
            yield at(
                "FRAME004",
                e,
                f"{e.owner} publishes '{e.parent} -> {e.child}', which connects to no link",
                "fix the frame names so the edge joins the robot's tree",
            )
    rc = robot.ros2_control
    for c in rc.controllers if rc else ():
        if c.type.startswith("diff_drive_controller/"):
            base = str(c.param("base_frame_id", "base_link"))
            if base not in links and not unresolved(base):  # CTRL052/053 stand for a $(var ...)
                yield at(
                    "FRAME004",
                    Param(c, "base_frame_id"),  # not given: the controller's own key
                    f"controller '{c.name}' base_frame_id '{base}' is not a link of the robot",
                    "set base_frame_id to the base's frame (base_footprint or base_link)",
                    subject=f"controller:{c.name}",
                )
        if c.type.startswith("joint_state_broadcaster/"):
            frame = c.param("frame_id")
            if frame is not None and str(frame) not in known and not unresolved(frame):
                yield at(
                    "FRAME004",
                    Param(c, "frame_id"),
                    f"controller '{c.name}' frame_id '{frame}' is not a frame of the robot",
                    "use a link name",
                    subject=f"controller:{c.name}",
                )


@rule("FRAME005", "desired-on-joint-states", "error")
def desired_on_joint_states(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds /joint_states publishers that publish desired commands (declared `kind: desired`),
    and joints that two publishers put on /joint_states.
    ## Why is this bad?
    robot_state_publisher turns /joint_states into tf: the operator display then animates
    what was commanded, not what the robot did, and shows motion that never happened.
    """
    for s in robot.joint_state_sources:
        if s.kind == "desired":
            yield at(
                "FRAME005",
                s,
                f"'{s.node}' publishes desired commands on /joint_states",
                "publish desired states on their own topic (e.g. ~/controller_state); keep /joint_states "
                "for measured state",
                subject=f"node:{s.node}",
            )
    for j in robot.joints:
        if j.type in ONE_DOF:
            from descgen.physics.frames import joint_state_feed

            feed = joint_state_feed(robot, j.name) or ""
            if feed.count("/joint_states from") > 1:
                yield at(
                    "FRAME005",
                    j,
                    f"joint '{j.name}' has several /joint_states publishers: {feed}",
                    "keep one publisher per joint (joint_state_broadcaster on a ros2_control robot)",
                )


# -- where frames sit against the body ---------------------------------------------------------

Box = tuple[tuple[float, float, float], tuple[float, float, float]]
FAR = 0.5  # a frame farther outside the body than this share of its largest side is reported
SLIPS = ((10.0, "10"), (100.0, "100"), (1000.0, "1000"), (25.4, "25.4 (mm written as inches)"))


def _union(a: Box | None, b: Box) -> Box:
    if a is None:
        return b
    return (
        (min(a[0][0], b[0][0]), min(a[0][1], b[0][1]), min(a[0][2], b[0][2])),
        (max(a[1][0], b[1][0]), max(a[1][1], b[1][1]), max(a[1][2], b[1][2])),
    )


def _link_boxes(robot: Robot) -> dict[str, Box]:
    """Each link's shapes (primitives and measured meshes) as one axis-aligned box in the root
    frame, with every joint at zero."""
    from descgen.meshes.load import box_in_metres, mesh_shapes
    from descgen.physics.extent import extent, shape_hull
    from descgen.physics.rigid import compose, frame, placed_box
    from descgen.physics.zero_pose import at_zero

    poses = at_zero(robot)
    out: dict[str, Box] = {}
    for lk in robot.links:
        at_link = poses.get(lk.name)
        if at_link is None:
            continue
        for shape in lk.shapes():
            hull = shape_hull(shape)
            if hull is not None:
                lo, hi = extent(hull, at_link)
                pad = hull.pad
                box: Box = ((lo[0] - pad, lo[1] - pad, lo[2] - pad), (hi[0] + pad, hi[1] + pad, hi[2] + pad))
                out[lk.name] = _union(out.get(lk.name), box)
    for lk, shape, mesh, facts in mesh_shapes(robot):
        at_link = poses.get(lk.name)
        corners = box_in_metres(facts, mesh.scale)
        if at_link is None or corners is None:
            continue
        low = tuple(min(a, b) for a, b in zip(*corners, strict=True))
        high = tuple(max(a, b) for a, b in zip(*corners, strict=True))
        placed = placed_box(low, high, compose(at_link, frame(shape.origin.xyz, shape.origin.rpy)))
        out[lk.name] = _union(out.get(lk.name), placed)
    return out


def _outside(box: Box, p: tuple[float, float, float]) -> float:
    """How far ``p`` is from ``box`` (0 inside)."""
    d = [max(box[0][i] - p[i], 0.0, p[i] - box[1][i]) for i in range(3)]
    return float((d[0] ** 2 + d[1] ** 2 + d[2] ** 2) ** 0.5)


def _welded_leaf(robot: Robot, link: str) -> list[str] | None:
    """``link`` and everything below it when only fixed joints hang there (a sensor mount, a
    frame); None when something below moves."""
    below = [link, *robot.descendants(link)]
    for name in below[1:]:
        j = robot.parent_joint(name)
        if j is None or j.type != "fixed":
            return None
    return below


@rule("FRAME006", "frame-far-outside-body", "warning")
def frame_far_outside_body(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Places the robot at zero and boxes its geometry (primitives and meshes). A frame on a
    fixed joint (a sensor, a button, a tool point; with anything welded below it) that lies
    outside the box of everything else by more than half the box's largest side is reported,
    with the factor (10, 100, 1000, 25.4) that would bring its joint's offset inside when one
    does.
    ## Why is this bad?
    A sensor frame twice the body's radius from its centre is a unit slip (millimetres
    written as centimetres), not a mount: every measurement in that frame lands in the wrong
    place, and no parser can tell.
    """
    from descgen.physics.rigid import apply
    from descgen.physics.zero_pose import at_zero

    boxes = _link_boxes(robot)
    if not boxes:
        return
    root = robot.root()
    poses = at_zero(robot)
    for j in robot.joints:
        if j.type != "fixed" or j.child is None or j.parent is None or j.child == root:
            continue
        leaf = _welded_leaf(robot, j.child)
        if leaf is None or j.child not in poses or j.parent not in poses:
            continue
        body: Box | None = None
        for name, box in boxes.items():
            if name not in leaf:
                body = _union(body, box)
        if body is None:
            continue
        side = max(body[1][i] - body[0][i] for i in range(3))
        where = poses[j.child][1]
        away = _outside(body, where)
        if side <= 0 or away <= FAR * side:
            continue
        hint = "check the joint's origin (its unit, its sign), or the body's geometry"
        for factor, said in SLIPS:
            nearer = apply(poses[j.parent], tuple(c / factor for c in j.origin.xyz))
            if _outside(body, nearer) <= 0.05 * side:
                shown = ", ".join(f"{c / factor * 1000:.4g}" for c in j.origin.xyz)
                hint = (
                    f"the origin looks {said} times too large: ({shown}) mm would put it on the body; "
                    "fix the unit of the joint's xyz"
                )
                break
        yield at(
            "FRAME006",
            j,
            f"frame '{j.child}' (joint '{j.name}') is {away * 1000:.0f} mm outside the robot's body, whose "
            f"largest side is {side * 1000:.0f} mm",
            hint,
        )


_SIDE = {
    "left": "right",
    "right": "left",
    "front": "back",
    "back": "front",
    "rear": "front",
    "top": "bottom",
    "bottom": "top",
}
# REP 103 (x forward, y left, z up): the axis a side word names, and its sign
_AXIS = {
    "left": (1, 1.0),
    "right": (1, -1.0),
    "front": (0, 1.0),
    "back": (0, -1.0),
    "rear": (0, -1.0),
    "top": (2, 1.0),
    "bottom": (2, -1.0),
}
_TOKEN = re.compile(r"[A-Za-z]+|[0-9]+|[^A-Za-z0-9]+")


def _mirrors(name: str) -> Iterator[tuple[str, str]]:
    """(the name with one of its side words swapped, that word), for each side word in it:
    ``bump_front_left`` pairs with ``bump_front_right`` and with ``bump_back_left``."""
    tokens = _TOKEN.findall(name)
    for i, t in enumerate(tokens):
        word = t.lower()
        if word not in _SIDE:
            continue
        other = _SIDE[word]  # rear pairs with front from its side; front pairs with back
        swapped = other.upper() if t.isupper() else other.capitalize() if t[0].isupper() else other
        yield "".join([*tokens[:i], swapped, *tokens[i + 1 :]]), word


@rule("FRAME007", "side-name-against-rep103", "warning")
def side_name_against_rep103(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Pairs links whose names differ only by a side word (left/right, front/back or rear,
    top/bottom) that both belong to the robot's body (the link they share is welded to the
    root by fixed joints) and compares where they sit, with every joint at zero, in the root
    link's frame: REP 103 has y to the left, x forward and z up, so the "left" one should have
    the larger y, the "front" one the larger x, the "top" one the larger z. Pairs past a
    moving joint (a gripper's fingers) follow the part's own convention and are not judged.
    The pair is reported when they sit the other way round.
    ## Why is this bad?
    A left bumper at the right is a swapped sign or a mirrored mount: the robot reacts to a
    bump on the wrong side, and the frame tree looks right to every parser.
    """
    from descgen.physics.zero_pose import at_zero, relative

    names = {lk.name for lk in robot.links}
    poses = at_zero(robot)
    done: set[frozenset[str]] = set()
    pairs = [(lk.name, other, word) for lk in robot.links for other, word in _mirrors(lk.name) if other in names]
    for name, other, word in pairs:
        if frozenset((name, other)) in done:
            continue
        done.add(frozenset((name, other)))
        lk = robot.link(name)
        assert lk is not None
        # nearest first (path_to_root runs from the root down)
        up = [lk.name, *(j.parent for j in reversed(robot.path_to_root(lk.name)) if j.parent)]
        theirs = {other, *(j.parent for j in robot.path_to_root(other) if j.parent)}
        common = next((x for x in up if x in theirs), None)
        if common is None or lk.name not in poses or other not in poses:
            continue
        # REP 103's sides are the body's: compare in the root link, when the link they share is
        # welded to it. Past a moving joint (a gripper's fingers) the words follow the part's own
        # convention, which varies by vendor: not judged.
        while (j := robot.parent_joint(common)) is not None and j.type == "fixed" and j.parent is not None:
            common = j.parent
        if robot.parent_joint(common) is not None:
            continue
        a, b = relative(poses, lk.name, common), relative(poses, other, common)
        if a is None or b is None:
            continue
        axis, sign = _AXIS[word]
        gap = (a[1][axis] - b[1][axis]) * sign  # > 0 when this one is on its own side of the other
        if gap < -1e-3:
            letter = "xyz"[axis]
            yield at(
                "FRAME007",
                robot.parent_joint(lk.name) or lk,
                f"'{lk.name}' is {-gap * 1000:.0f} mm to the {_SIDE[word]} of '{other}' in '{common}' "
                f"({letter} {a[1][axis] * 1000:.0f} mm against {b[1][axis] * 1000:.0f} mm): REP 103 puts "
                f"{word} at {'+' if sign > 0 else '-'}{letter}",
                "swap the two names, or the sign of the joint's offset (REP 103: x forward, y left, z up)",
                subject=f"link:{lk.name}",
            )
