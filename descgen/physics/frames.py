"""Who publishes each transform of the running robot (derived from the model).

Facts encoded (docs/reference/robot_state_publisher.md, ros2_control.md, conventions.md):
- robot_state_publisher sends fixed joints once on /tf_static; movable joints on /tf, only
  when a /joint_states message names them (stamped with that message's stamp). KDL turns
  ``planar`` joints into fixed ones (published frozen at zero) and ``floating`` joints are
  skipped entirely: something else must publish them.
- With ros2_control, /joint_states comes from joint_state_broadcaster, which reads the
  hardware's *state* interfaces (position for the transform).
- diff_drive_controller publishes ``odom_frame_id -> base_frame_id`` on /tf when
  ``enable_odom_tf`` is true (its default), from the wheels' state interfaces.
- A mimic joint's transform follows its leader's /joint_states value
  (``q = multiplier * q_leader + offset``; robot_state_publisher, GenericSystem).
- Anything else (localisation's map -> odom, a calibrated sensor mount, a driver's own
  frames) is declared in the spec under ``frames.external``.
"""

from __future__ import annotations

from descgen.core.findings import Where
from descgen.core.model import NOWHERE, ONE_DOF, Robot
from descgen.core.record import record
from descgen.physics import mimic

RSP = "robot_state_publisher"


@record
class Edge:
    parent: str
    child: str
    owner: str
    topic: str  # /tf or /tf_static
    static: bool
    joint: str | None  # the URDF joint it comes from
    via: str  # what feeds the owner
    where: Where = NOWHERE

    @property
    def subject(self) -> str:
        return f"frame:{self.child}"


def _jsb(robot: Robot) -> str | None:
    rc = robot.ros2_control
    if rc is None:
        return None
    return next((c.name for c in rc.controllers if c.type.startswith("joint_state_broadcaster/")), None)


def joint_state_feed(robot: Robot, joint: str) -> str | None:
    """What puts ``joint`` on /joint_states (or drives it), or None when nothing does.

    A mimic joint is driven by its leader: robot_state_publisher adds
    ``multiplier * leader + offset`` for it whenever the leader is on /joint_states
    (GenericSystem and joint_state_publisher publish the same value), so its transform
    follows the leader's feed. A follower with no driving joint (JOINT007) falls back to
    its own feed."""
    rel = mimic.relation(robot, joint)
    if rel is not None:
        feed = _own_feed(robot, rel.leader)
        if feed is not None:
            return f"mimics {rel.leader} (q = {mimic.formula(robot, rel)}); {feed}"
    return _own_feed(robot, joint)


def _own_feed(robot: Robot, joint: str) -> str | None:
    declared = [s for s in robot.joint_state_sources if not s.joints or joint in s.joints]
    rc = robot.ros2_control
    feeds = [f"/joint_states from {s.node} ({s.kind})" for s in declared]
    if rc is not None:
        # without a controllers file (a URDF audited alone) joint_state_broadcaster is assumed
        jsb = _jsb(robot) or (None if rc.controllers else "joint_state_broadcaster (assumed)")
        cj = next((c for c in rc.joints if c.name == joint), None)
        if jsb is not None and cj is not None and any(i.name == "position" for i in cj.state):
            feeds.insert(0, f"/joint_states from {jsb} (position state interface of {rc.plugin or 'the hardware'})")
    elif not declared:
        feeds.append("/joint_states from joint_state_publisher (display only; no ros2_control)")
    return "; ".join(feeds) if feeds else None


def edges(robot: Robot) -> list[Edge]:
    out: list[Edge] = []
    for j in robot.joints:
        if j.parent is None or j.child is None:
            continue
        if j.type == "fixed":
            out.append(Edge(j.parent, j.child, RSP, "/tf_static", True, j.name, "the URDF", j.where))
        elif j.type == "planar":
            out.append(
                Edge(
                    j.parent,
                    j.child,
                    RSP,
                    "/tf_static",
                    True,
                    j.name,
                    "the URDF (KDL treats planar as fixed: frozen at zero)",
                    j.where,
                )
            )
        elif j.type in ONE_DOF:
            feed = joint_state_feed(robot, j.name)
            out.append(Edge(j.parent, j.child, RSP, "/tf", False, j.name, feed or "nothing", j.where))
        # floating: robot_state_publisher publishes nothing for it
    rc = robot.ros2_control
    for c in rc.controllers if rc else ():
        if c.type.startswith("diff_drive_controller/") and c.param("enable_odom_tf", True) is not False:
            odom = str(c.param("odom_frame_id", "odom"))
            base = str(c.param("base_frame_id", "base_link"))
            out.append(
                Edge(
                    odom,
                    base,
                    c.name,
                    "/tf",
                    False,
                    None,
                    "odometry integrated from the wheels' state interfaces",
                    c.where,
                )
            )
    for e in robot.external_frames:
        out.append(
            Edge(
                e.parent,
                e.child,
                e.owner,
                "/tf_static" if e.static else "/tf",
                e.static,
                None,
                "declared in the spec",
                e.where,
            )
        )
    return out
