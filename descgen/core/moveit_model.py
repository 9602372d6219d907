"""A MoveIt config package as data: what its YAML files say, each value with its location.

``descgen/read/moveit_config.py`` fills it from a folder; the MOVEIT rules
(``descgen/audit/rules/moveit.py``) read it from ``Robot.moveit``. Values of the wrong type
are recorded as :class:`TypeProblem` and read as missing (an integer where MoveIt declares a
double is the exception: it is kept, since that is what the user meant, and reported).
"""

from __future__ import annotations

from descgen.core.findings import Where
from descgen.core.record import record

NOWHERE = Where("<unknown>")

# moveit_simple_controller_manager's action types (moveit_simple_controller_manager.cpp, jazzy)
CONTROLLER_TYPES = ("FollowJointTrajectory", "GripperCommand", "ParallelGripperCommand")


@record
class TypeProblem:
    """A value whose YAML type is not the ROS parameter type MoveIt declares for it."""

    path: str  # dotted, as the parameter is named: joint_limits.j1.max_velocity
    expected: str  # double | bool | string | string array | mapping | number
    got: str  # integer | string | boolean | list | mapping | null | float
    value: str  # the value as written, for the message
    where: Where


@record
class JointLimits:
    """One ``joint_limits.<joint>`` entry; None: the key is absent (or of the wrong type)."""

    joint: str
    where: Where  # the joint's key
    has_velocity: bool | None = None
    max_velocity: float | None = None
    has_acceleration: bool | None = None
    max_acceleration: float | None = None
    min_position: float | None = None
    max_position: float | None = None
    marks: tuple[tuple[str, Where], ...] = ()  # key -> where its value is written

    def at(self, key: str) -> Where:
        """Where ``key``'s value is written, else the joint's key."""
        return dict(self.marks).get(key, self.where)


@record
class MoveItController:
    """One controller of ``moveit_simple_controller_manager``."""

    name: str
    where: Where  # its section's key, or its entry in controller_names when it has no section
    listed: bool  # named in controller_names (MoveIt loads only those)
    has_section: bool
    action_ns: str | None = None
    type: str | None = None
    default: bool | None = None
    joints: tuple[str, ...] | None = None
    marks: tuple[tuple[str, Where], ...] = ()

    @property
    def subject(self) -> str:
        return f"controller:{self.name}"

    def at(self, key: str) -> Where:
        return dict(self.marks).get(key, self.where)


@record
class KinematicsGroup:
    group: str
    where: Where  # the group's key
    solver: str | None = None
    solver_where: Where = NOWHERE


@record
class InitialPosition:
    joint: str
    value: float | None  # None: not a number (a TypeProblem says so)
    where: Where


@record
class MoveItConfig:
    """The files of one MoveIt config package; a tuple is None when its file is absent."""

    folder: str  # the config folder as shown in messages
    where: Where  # the folder itself, for findings about a missing file
    joint_limits_file: str | None = None
    joint_limits: tuple[JointLimits, ...] | None = None
    joint_limits_where: Where = NOWHERE  # the ``joint_limits:`` key (or the file)
    controllers_file: str | None = None
    controllers: tuple[MoveItController, ...] | None = None
    controller_names_where: Where | None = None  # None: no controller_names key
    kinematics_file: str | None = None
    kinematics: tuple[KinematicsGroup, ...] | None = None
    initial_positions_file: str | None = None
    initial_positions: tuple[InitialPosition, ...] | None = None
    pilz_cartesian_limits_file: str | None = None
    type_problems: tuple[TypeProblem, ...] = ()
    srdf_file: str | None = None  # the SRDF read from the folder (None: --srdf, or none there)
    ros2_controllers_file: str | None = None  # likewise for the ros2_control controllers YAML
