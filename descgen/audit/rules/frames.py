"""FRAME: every transform of the running robot has exactly one publisher."""

from __future__ import annotations

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
