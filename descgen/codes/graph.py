"""Codes of many robots in one ROS graph: ``descgen audit A B --together``.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py). The checks are descgen/audit/together.py."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("graph")


GRAPH001 = declare(
    "GRAPH001",
    "frame-published-by-two-robots",
    "error",
    "A frame is the child of a joint in two robots audited together: each robot's robot_state_publisher puts it "
    "on /tf, each with its own parent.",
    """ROS 2 has no tf_prefix: every robot_state_publisher of a graph publishes on the one /tf (and /tf_static).
      A frame with two parents makes tf2 take whichever message came last, so lookups through it jump between the
      robots. Prefix one robot's frames (the `prefix` Xacro argument of ros2_control_demos, `tf_prefix` of the UR
      description), or drop the frame from one description.""",
)

GRAPH002 = declare(
    "GRAPH002",
    "joint-in-two-robots",
    "error",
    "A moving joint has the same name in two robots audited together: in one namespace their joint_states mix.",
    """Both robots' joint_state_broadcasters publish on /joint_states when they share a namespace, and each
      robot_state_publisher moves its joint of that name with whichever robot's position came last. Prefix the
      joints, or run each robot in its own namespace: two specs with different namespace: are not compared; for
      descriptions, whose namespace is the launch file's, accept the finding with --baseline.""",
)

GRAPH003 = declare(
    "GRAPH003",
    "controller-claims-other-robots-joint",
    "error",
    "A controller or a ros2_control joint of one robot names a joint that only the other robot has.",
    """The controller would command (or the hardware would claim) the other robot's joint: in one
      controller_manager it fails to configure; across two it moves the wrong arm. Usually a prefix left out or
      written twice. Name the robot's own joint.""",
)

GRAPH004 = declare(
    "GRAPH004",
    "robots-joined",
    "info",
    "One robot's root frame is a frame of the other robot audited together: the two trees are one on /tf.",
    """This is how a robot mounted on another is composed (an arm whose root is a frame of the base); the message
      names the frame. Where the trees should stay apart, prefix one of them.""",
)

GRAPH010 = declare(
    "GRAPH010",
    "per-robot-files-mismatch",
    "error",
    "--controllers or --srdf is given more than once, but not once per URDF or Xacro audited with --together; or "
    "--moveit-config is given with --together.",
    """With --together, each URDF or Xacro given is one robot, and a controllers YAML or SRDF given for it is
      matched by order: the first --controllers to the first URDF or Xacro, and so on (a spec brings its own).
      Without --together, give each option once.""",
)
