"""What the MoveIt config package says about the robot, derived from the model (SI).

The Setup Assistant's rules, as read on moveit2 jazzy: joint_limits.yaml covers the
single-variable joints of every group (srdf_config.cpp ``GeneratedJointLimits``); a MoveIt
controller is a ros2_controllers action server (moveit_simple_controller_manager).
"""

from __future__ import annotations

from descgen.core import model as m
from descgen.core.record import record

# ros2_controllers (jazzy) plugin -> (MoveIt controller type, action namespace it serves):
# JTC serves ~/follow_joint_trajectory, both gripper action controllers ~/gripper_cmd
# (docs/reference/ros2_control_jazzy.md §8, moveit_config.md §5).
ACTION_SERVERS: dict[str, tuple[str, str]] = {
    "joint_trajectory_controller/JointTrajectoryController": ("FollowJointTrajectory", "follow_joint_trajectory"),
    "position_controllers/GripperActionController": ("GripperCommand", "gripper_cmd"),
    "effort_controllers/GripperActionController": ("GripperCommand", "gripper_cmd"),
    "parallel_gripper_action_controller/GripperActionController": ("ParallelGripperCommand", "gripper_cmd"),
}


@record
class MoveItController:
    name: str
    type: str  # FollowJointTrajectory | GripperCommand | ParallelGripperCommand
    action_ns: str
    joints: tuple[str, ...]


def group_joints(robot: m.Robot, group: str) -> list[m.Joint]:
    """The joints of ``group`` that MoveIt plans for: one variable, not fixed, not a mimic
    follower (its value follows its leader), not passive (MoveIt never moves it)."""
    passive = set(robot.semantic.passive_joints) if robot.semantic else set()
    return [j for j in robot.group_joints(group) if j.type in m.ONE_DOF and j.mimic is None and j.name not in passive]


def planning_joints(robot: m.Robot) -> list[m.Joint]:
    """The union over all groups, sorted by name as the Setup Assistant writes joint_limits.yaml."""
    found: dict[str, m.Joint] = {}
    for g in robot.semantic.groups if robot.semantic else ():
        for j in group_joints(robot, g.name):
            found.setdefault(j.name, j)
    return [found[n] for n in sorted(found)]


def controller_joints(c: m.Controller) -> tuple[str, ...]:
    """The joints a controller commands: ``joints`` (JTC) or ``joint`` (gripper controllers)."""
    joints = c.param("joints")
    if isinstance(joints, list | tuple):
        return tuple(str(j) for j in joints)
    joint = c.param("joint")
    return (str(joint),) if isinstance(joint, str) else ()


def controllers(robot: m.Robot) -> list[MoveItController]:
    """The spec's action-server controllers whose joints all belong to one planning group,
    in spec order: those MoveIt executes trajectories with."""
    rc = robot.ros2_control
    if rc is None or robot.semantic is None:
        return []
    groups = [{j.name for j in group_joints(robot, g.name)} for g in robot.semantic.groups]
    out = []
    for c in rc.controllers:
        server = ACTION_SERVERS.get(c.type)
        joints = controller_joints(c)
        if server is not None and joints and any(set(joints) <= g for g in groups):
            out.append(MoveItController(c.name, server[0], server[1], joints))
    return out


def unserved(robot: m.Robot) -> list[tuple[m.Group, list[str]]]:
    """Groups with joints that no MoveIt controller commands, with those joints."""
    covered = {j for c in controllers(robot) for j in c.joints}
    out = []
    for g in robot.semantic.groups if robot.semantic else ():
        missing = [j.name for j in group_joints(robot, g.name) if j.name not in covered]
        if missing:
            out.append((g, missing))
    return out


def default_value(j: m.Joint) -> float:
    """MoveIt's default joint value: 0, or the middle of the bounds when 0 is outside them
    (moveit_core revolute_joint_model.cpp ``getVariableDefaultPositions``, jazzy)."""
    lm = j.limit
    if j.type not in m.WITH_LIMITS or lm is None or lm.lower is None or lm.upper is None:
        return 0.0
    return 0.0 if lm.lower <= 0.0 <= lm.upper else (lm.lower + lm.upper) / 2


def initial_state(robot: m.Robot) -> m.GroupState | None:
    """The group state initial_positions.yaml is written from: moveit.initial_state, else
    the collision matrix's default state."""
    sem = robot.semantic
    if sem is None or robot.moveit is None:
        return None
    name = robot.moveit.initial_state or (sem.collision_matrix.default_state if sem.collision_matrix else None)
    return next((s for s in sem.states if s.name == name), None)


def initial_positions(robot: m.Robot) -> list[tuple[str, float]]:
    """Every planning joint at the initial state's value, or MoveIt's default value."""
    state = initial_state(robot)
    values = dict(state.values) if state is not None else {}
    return [(j.name, values.get(j.name, default_value(j))) for j in planning_joints(robot)]
