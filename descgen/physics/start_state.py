"""The state a command starts a robot in when none is named (``sweep``, ``simulate``, the
collision matrix's default state): inside every joint's limits. "Every joint at zero" is outside
the limits of many real arms (a wrist whose range is 10 to 350 degrees, a gripper that opens from
5 mm), and a sweep or a simulation started there reports collisions and forces no real robot can
have.

The SRDF's first group state is taken (the Setup Assistant's "home" or "ready", what a MoveIt
demo starts at); every joint it does not name is at MoveIt's default position: zero when the
limits hold it, else the middle of the limits (moveit_core RevoluteJointModel and
PrismaticJointModel ``getVariableDefaultPositions``, what ``RobotState::setToDefaultValues`` and
so the Setup Assistant's default state use).
"""

from __future__ import annotations

from descgen.core.model import MULTI_DOF, WITH_LIMITS, Joint, Robot

WHEELED_BASE_CONTROLLERS = frozenset(
    {  # controllers of a wheeled base: the robot drives on a floor (ros2_controllers jazzy plugin names)
        "diff_drive_controller/DiffDriveController",
        "tricycle_controller/TricycleController",
        "mecanum_drive_controller/MecanumDriveController",
        "omni_wheel_drive_controller/OmniWheelDriveController",
        "ackermann_steering_controller/AckermannSteeringController",
        "bicycle_steering_controller/BicycleSteeringController",
        "tricycle_steering_controller/TricycleSteeringController",
    }
)


def default_position(j: Joint) -> float:
    """MoveIt's default position of a joint: zero when [lower, upper] holds it, else the middle."""
    lm = j.limit
    if j.type not in WITH_LIMITS or lm is None or lm.lower is None or lm.upper is None or lm.lower > lm.upper:
        return 0.0
    return 0.0 if lm.lower <= 0.0 <= lm.upper else float((lm.lower + lm.upper) / 2)


def inside_limits(robot: Robot) -> dict[str, float]:
    """Every joint with limits at MoveIt's default position."""
    return {j.name: default_position(j) for j in robot.joints if j.type in WITH_LIMITS}


def default_state(robot: Robot) -> tuple[str, dict[str, float]]:
    """(the SRDF's first group state, or "" without one; joint values): that state's values over
    :func:`inside_limits`."""
    values = inside_limits(robot)
    states = robot.semantic.states if robot.semantic is not None else ()
    if not states:
        return "", values
    return states[0].name, {**values, **dict(states[0].values)}


def wheeled(robot: Robot) -> bool:
    """A wheeled base: its ros2_control runs a drive controller."""
    rc = robot.ros2_control
    return rc is not None and any(c.type in WHEELED_BASE_CONTROLLERS for c in rc.controllers)


def default_base(robot: Robot) -> str:
    """floor for a mobile robot (an SRDF virtual joint that is planar or floating, a root link
    named base_footprint, or a drive controller: a wheeled base held in the air shows nothing
    of how it stands), else fixed. A root named world is fixed by definition."""
    root = robot.root()
    if root is None or root == "world":
        return "fixed"
    virtual = robot.semantic.virtual_joints if robot.semantic else ()
    if any(v.type in MULTI_DOF and v.child_link == root for v in virtual) or root == "base_footprint":
        return "floor"
    return "floor" if wheeled(robot) else "fixed"
