"""MoveIt config package: joint_limits.yaml, moveit_controllers.yaml, kinematics.yaml and
initial_positions.yaml against the URDF, the SRDF and the ros2_control controllers.

Facts from moveit/moveit2 ``jazzy`` (docs/reference/moveit_config.md): robot_model_loader.cpp
(how joint_limits.yaml overrides the URDF), time_optimal_trajectory_generation.cpp (TOTG's
refusals), moveit_simple_controller_manager.cpp (what a controller entry needs), robot_model.cpp
and joint_model_group.cpp (group joints, chains), kdl_kinematics_plugin.cpp. The rules stay
silent when no MoveIt config was read (``Robot.moveit_config`` is None).
"""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.registry import RULES, rule
from descgen.core.findings import Finding, Where
from descgen.core.model import ONE_DOF, WITH_LIMITS, Joint, Robot
from descgen.core.moveit_model import (
    CONTROLLER_TYPES,
    JointLimits,
    MoveItConfig,
    MoveItController,
    TypeProblem,
)

EPS = 2.220446049250313e-16  # robot_model.cpp: a URDF velocity is a bound when > DBL_EPSILON
KDL = "kdl_kinematics_plugin/KDLKinematicsPlugin"
JTC = "joint_trajectory_controller/JointTrajectoryController"
# which ros2_controllers type serves which MoveIt action type, and under which action name
SERVES: dict[str, tuple[str, ...]] = {
    "FollowJointTrajectory": (JTC,),
    "GripperCommand": ("position_controllers/GripperActionController", "effort_controllers/GripperActionController"),
    "ParallelGripperCommand": ("parallel_gripper_action_controller/GripperActionController",),
}
ACTION_NS = {"FollowJointTrajectory": "follow_joint_trajectory", "GripperCommand": "gripper_cmd"}
ACTION_NS["ParallelGripperCommand"] = "gripper_cmd"


def _f(code: str, where: Where, subject: str, message: str, hint: str) -> Finding:
    return Finding(code, RULES[code].severity, message, hint, subject, where)


def _planned(robot: Robot) -> dict[str, list[str]]:
    """joint -> the groups that plan it: 1-DOF, not a mimic follower, not passive (SRDF020's
    business), through chains, joints, links and subgroups as robot_model.cpp resolves them."""
    sem = robot.semantic
    out: dict[str, list[str]] = {}
    if sem is None:
        return out
    passive = set(sem.passive_joints)
    for g in sem.groups:
        for j in robot.group_joints(g.name):
            if j.type in ONE_DOF and j.mimic is None and j.name not in passive:
                out.setdefault(j.name, []).append(g.name)
    return out


def _group_sets(robot: Robot) -> dict[str, frozenset[str]]:
    sem = robot.semantic
    if sem is None:
        return {}
    passive = set(sem.passive_joints)
    return {
        g.name: frozenset(
            j.name
            for j in robot.group_joints(g.name)
            if j.type in ONE_DOF and j.mimic is None and j.name not in passive
        )
        for g in sem.groups
    }


def _limits(cfg: MoveItConfig) -> dict[str, JointLimits]:
    return {e.joint: e for e in cfg.joint_limits or ()}


def _groups_text(groups: list[str]) -> str:
    return ", ".join(f"'{g}'" for g in groups)


def _unit(j: Joint | None, per: str) -> str:
    return f"m/{per}" if j is not None and j.type == "prismatic" else f"rad/{per}"


@rule("MOVEIT001", "moveit-no-acceleration-limit", "error")
def no_acceleration_limit(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a joint of an SRDF planning group (chains resolved through the URDF; fixed joints,
    mimic followers and passive joints left out) without `has_acceleration_limits: true` and a
    positive `max_acceleration` in joint_limits.yaml.
    ## Why is this bad?
    A URDF has no acceleration attribute, so joint_limits.yaml is MoveIt's only source. Since
    Jazzy the time parameterisation (TOTG) refuses the whole trajectory: "No acceleration limit
    was defined for joint ...! You have to define acceleration limits in the URDF or
    joint_limits.yaml", and Pilz throws "acceleration limit not set". A fresh Setup Assistant
    package writes `has_acceleration_limits: false`, so it cannot plan until edited.
    ## Example
    `panda_joint1: {has_velocity_limits: true, max_velocity: 2.175}`
    ## Use instead
    `has_acceleration_limits: true` and `max_acceleration: 3.75` (measured, as a float).
    """
    cfg = robot.moveit_config
    if cfg is None or cfg.joint_limits is None:
        return
    limits = _limits(cfg)
    for name, groups in _planned(robot).items():
        e = limits.get(name)
        unit = _unit(robot.joint(name), "s^2")
        write = f"write 'has_acceleration_limits: true' and 'max_acceleration: <measured {unit}, e.g. 5.0>'"
        if e is None:
            yield _f(
                "MOVEIT001",
                cfg.joint_limits_where,
                f"joint:{name}",
                f"joint '{name}' of group {_groups_text(groups)} has no entry in joint_limits.yaml: without an "
                "acceleration limit Jazzy's time parameterisation refuses every trajectory of the group",
                f"add '{name}:' under joint_limits: and {write}",
            )
        elif e.has_acceleration is not True:
            said = "false" if e.has_acceleration is False else "absent"
            yield _f(
                "MOVEIT001",
                e.at("has_acceleration_limits"),
                f"joint:{name}",
                f"joint '{name}' of group {_groups_text(groups)}: has_acceleration_limits is {said}; the URDF "
                'has no acceleration limit, so TOTG refuses to plan ("No acceleration limit was defined")',
                write,
            )
        elif e.max_acceleration is None or e.max_acceleration <= 0:
            said = "missing" if e.max_acceleration is None else f"{e.max_acceleration:g}"
            yield _f(
                "MOVEIT001",
                e.at("max_acceleration"),
                f"joint:{name}",
                f"joint '{name}' of group {_groups_text(groups)}: max_acceleration is {said}; TOTG needs a "
                "positive acceleration limit",
                f"write 'max_acceleration: <measured {unit}, e.g. 5.0>'",
            )


@rule("MOVEIT002", "moveit-no-velocity-limit", "error")
def no_velocity_limit(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a planning-group joint (as MOVEIT001 selects them) whose velocity is not bounded
    after joint_limits.yaml is applied to the URDF: the URDF's `velocity` is missing or 0 and
    the file gives none, or the file says `has_velocity_limits: false`, or its
    `max_velocity` is not positive.
    ## Why is this bad?
    robot_model_loader starts from the URDF limit and lets joint_limits.yaml override it: a
    key that is absent keeps the URDF value, but an explicit `has_velocity_limits: false`
    removes it. TOTG then refuses the trajectory ("No velocity limit was defined for joint")
    or rejects it ("Invalid max_velocity ... must be greater than 0.0").
    ## Example
    `elbow: {has_velocity_limits: false}`
    ## Use instead
    `has_velocity_limits: true` and `max_velocity: 2.0` (at most the URDF's `velocity`).
    """
    cfg = robot.moveit_config
    if cfg is None or cfg.joint_limits is None:
        return
    limits = _limits(cfg)
    for name, groups in _planned(robot).items():
        j = robot.joint(name)
        urdf = j.limit.velocity if j is not None and j.limit is not None else None
        e = limits.get(name)
        unit = _unit(j, "s")
        write = f"write 'has_velocity_limits: true' and 'max_velocity: <{unit}, e.g. 2.0>'"
        where: Where | None = None
        why = ""
        if e is None or e.has_velocity is None:
            if urdf is None or urdf <= EPS:
                where = cfg.joint_limits_where if e is None else e.where
                why = "the URDF gives no velocity limit and joint_limits.yaml none either"
        elif e.has_velocity is False:
            where, why = e.at("has_velocity_limits"), "has_velocity_limits: false removes the URDF's velocity limit"
        else:
            value = e.max_velocity if e.max_velocity is not None else urdf
            if value is None or value <= 0:
                where = e.at("max_velocity")
                why = "max_velocity is " + ("missing and the URDF has none" if value is None else f"{value:g}")
        if where is not None:
            yield _f(
                "MOVEIT002",
                where,
                f"joint:{name}",
                f"joint '{name}' of group {_groups_text(groups)}: {why}; TOTG refuses to plan "
                '("No velocity limit was defined")',
                write,
            )


def _int_why(p: TypeProblem) -> str:
    if p.path.startswith("joint_limits."):
        return (
            "robot_model_loader logs 'expected [double] got [integer]' and drops the joint's remaining "
            "limits, and Pilz's limit reader does not catch it, so move_group exits"
        )
    return "rclcpp refuses an integer for a parameter declared double (ParameterTypeException)"


@rule("MOVEIT003", "moveit-integer-for-double", "error")
def integer_for_double(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags an integer (`1`) where MoveIt reads a double (`1.0`): joint limits it reads
    (`max_velocity` under `has_velocity_limits: true`, `max_acceleration`, positions, ...),
    the default scaling factors, kinematics timeouts and resolutions, gripper efforts.
    ## Why is this bad?
    ROS parameters are typed by how the YAML is written, and rclcpp's `get_parameter` into a
    double throws `ParameterTypeException: expected [double] got [integer]`. In joint limits
    robot_model_loader catches it and silently loses the rest of that joint's limits; Pilz
    does not catch it and move_group terminates (moveit/moveit2#2776). The Setup Assistant's
    YAML emitter writes the double 1.0 as `1`, so generated files hit this.
    ## Example
    `max_velocity: 1`
    ## Use instead
    `max_velocity: 1.0`
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for p in cfg.type_problems:
        if p.expected == "double" and p.got == "integer":
            yield _f(
                "MOVEIT003",
                p.where,
                f"param:{p.path}",
                f"'{p.path}' is the integer {p.value}; MoveIt reads a double: {_int_why(p)}",
                f"write {p.value}.0",
            )


_TYPE_HINT = {
    "bool": "write true or false",
    "string": "write a name (a string)",
    "string array": "write a list of names, e.g. [joint_1, joint_2]",
    "mapping": "write 'key: value' lines indented below it",
    "double": "write a decimal number, e.g. 1.0",
    "number": "write a number, e.g. 0.0",
}


@rule("MOVEIT004", "moveit-value-wrong-type", "error")
def value_wrong_type(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a MoveIt config value of the wrong type (other than an integer for a double,
    MOVEIT003): a flag that is not `true`/`false`, `joints` or `controller_names` that is not a
    list of names, a section that is not a mapping, an initial position that is not a number,
    an initial_positions.yaml without its `initial_positions:` key.
    ## Why is this bad?
    MoveIt reads each as a typed ROS parameter. A mistyped value throws, and the reader
    skips what it was reading: moveit_simple_controller_manager drops the controller
    ("Parameter controller_names should be specified as a string array" drops all of them),
    and the Setup Assistant's ros2_control xacro fails with "No such key: 'initial_positions'".
    ## Example
    `default: "yes"`, `joints: panda_joint1`
    ## Use instead
    `default: true`, `joints: [panda_joint1]`
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for p in cfg.type_problems:
        if p.expected == "double" and p.got == "integer":
            continue
        if p.got == "absent":
            message = f"no '{p.path}:' key; the ros2_control xacro reads load_yaml(file)['{p.path}']"
        else:
            message = (
                f"'{p.path}' is {'an' if p.got[0] in 'aeiou' else 'a'} {p.got} ({p.value}); MoveIt reads a {p.expected}"
            )
        yield _f("MOVEIT004", p.where, f"param:{p.path}", message, _TYPE_HINT.get(p.expected, "fix the value"))


@rule("MOVEIT005", "moveit-limits-unknown-joint", "warning")
def limits_unknown_joint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a `joint_limits:` entry that names no joint of the URDF.
    ## Why is this bad?
    robot_model_loader reads limits only for the robot's own joints, so the entry is ignored
    without a word; usually it is a typo or a renamed joint, and the real joint runs without
    the limits written for it.
    ## Example
    `joint_limits: {elbow_jiont: ...}`
    ## Use instead
    The URDF joint's exact name, or remove the entry.
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for e in cfg.joint_limits or ():
        if robot.joint(e.joint) is None:
            yield _f(
                "MOVEIT005",
                e.where,
                f"joint:{e.joint}",
                f"joint_limits.yaml names '{e.joint}', which is not a joint of the URDF; MoveIt ignores the entry",
                "use the URDF joint's name, or remove the entry",
            )


@rule("MOVEIT006", "moveit-limits-looser-than-urdf", "warning")
def limits_looser_than_urdf(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a joint_limits.yaml `max_velocity` above the URDF's `velocity`, or a
    `min_position`/`max_position` outside the URDF's `lower`/`upper`.
    ## Why is this bad?
    joint_limits.yaml is meant to tighten the URDF for planning. robot_model_loader replaces
    the URDF bound with the file's, so MoveIt plans motions the description (and the
    ros2_control limits taken from it) does not allow; the controller or the driver then
    clips or rejects them mid-motion.
    ## Example
    URDF `velocity="2.0"`, joint_limits.yaml `max_velocity: 3.0`
    ## Use instead
    `max_velocity: 2.0` or less; positions inside the URDF range.
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for e in cfg.joint_limits or ():
        j = robot.joint(e.joint)
        if j is None or j.limit is None:
            continue
        lim = j.limit
        looser = e.has_velocity is True and e.max_velocity is not None and lim.velocity is not None
        if (
            looser
            and lim.velocity is not None
            and lim.velocity > EPS
            and (e.max_velocity or 0) > lim.velocity * (1 + 1e-9)
        ):
            yield _f(
                "MOVEIT006",
                e.at("max_velocity"),
                f"joint:{e.joint}",
                f"joint '{e.joint}': max_velocity {e.max_velocity:g} is above the URDF's velocity "
                f"{lim.velocity:g}; MoveIt plans with the looser limit",
                f"write 'max_velocity: {lim.velocity:g}' or less",
            )
        if j.type not in WITH_LIMITS:
            continue
        low = e.min_position is not None and lim.lower is not None and e.min_position < lim.lower - 1e-9
        high = e.max_position is not None and lim.upper is not None and e.max_position > lim.upper + 1e-9
        for key, value, outside in (("min_position", e.min_position, low), ("max_position", e.max_position, high)):
            if outside and value is not None:
                yield _f(
                    "MOVEIT006",
                    e.at(key),
                    f"joint:{e.joint}",
                    f"joint '{e.joint}': {key} {value:g} is outside the URDF range {j.range_text()}",
                    f"write a {key} inside the URDF range, or remove it to keep the URDF's",
                )


def _listed(cfg: MoveItConfig) -> Iterator[MoveItController]:
    return (c for c in cfg.controllers or () if c.listed and c.has_section)


@rule("MOVEIT007", "moveit-controller-without-action-ns", "error")
def controller_without_action_ns(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a controller named in `controller_names` whose entry has no `action_ns` (or that
    has no entry at all).
    ## Why is this bad?
    moveit_simple_controller_manager logs "No action namespace specified for controller" and
    skips it (`continue`); execution then fails with "Unable to identify any set of
    controllers that can actuate the specified joints". The Setup Assistant's "Auto Add"
    button writes controllers without it (moveit/moveit2#3796).
    ## Example
    `arm_controller: {type: FollowJointTrajectory, joints: [...]}`
    ## Use instead
    `action_ns: follow_joint_trajectory` (JTC) or `action_ns: gripper_cmd` (gripper controllers).
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for c in cfg.controllers or ():
        if not c.listed or (c.action_ns is not None or "action_ns" in dict(c.marks)):
            continue
        ns = ACTION_NS.get(c.type or "", "follow_joint_trajectory")
        what = "has no action_ns" if c.has_section else "is listed in controller_names but has no entry"
        yield _f(
            "MOVEIT007",
            c.where,
            c.subject,
            f"controller '{c.name}' {what}; MoveIt skips it, so it never executes a trajectory",
            f"write 'action_ns: {ns}' in its entry under moveit_simple_controller_manager",
        )


@rule("MOVEIT008", "moveit-controller-unknown-type", "error")
def controller_unknown_type(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a listed controller whose `type` is missing or is not one of
    FollowJointTrajectory, GripperCommand, ParallelGripperCommand.
    ## Why is this bad?
    moveit_simple_controller_manager knows only these action types; for anything else it
    logs "Unknown controller type" (or "No type specified") and skips the controller.
    A ros2_controllers type such as `joint_trajectory_controller/JointTrajectoryController`
    written here is the usual mistake.
    ## Example
    `type: joint_trajectory_controller/JointTrajectoryController`
    ## Use instead
    `type: FollowJointTrajectory`
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for c in _listed(cfg):
        if c.type is None and "type" not in dict(c.marks):
            yield _f(
                "MOVEIT008",
                c.where,
                c.subject,
                f"controller '{c.name}' has no type; MoveIt skips it",
                "write 'type: FollowJointTrajectory' (or GripperCommand for a gripper)",
            )
        elif c.type is not None and c.type not in CONTROLLER_TYPES:
            yield _f(
                "MOVEIT008",
                c.at("type"),
                c.subject,
                f"controller '{c.name}' has type '{c.type}', which MoveIt does not know; it skips the controller",
                f"write one of {', '.join(CONTROLLER_TYPES)}",
            )


@rule("MOVEIT009", "moveit-controller-bad-joints", "error")
def controller_bad_joints(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a listed controller whose `joints` are missing or empty, or name joints that are
    not in the URDF.
    ## Why is this bad?
    MoveIt skips a controller without joints ("No joints specified for controller"), and a
    joint that is not in the robot can never be in a trajectory, so the controller is never
    chosen for the joints it was meant for.
    ## Example
    `joints: [panda_joint1, panda_joint_8]`
    ## Use instead
    The URDF joints the controller drives.
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for c in _listed(cfg):
        if c.joints is None and "joints" in dict(c.marks):
            continue  # of the wrong type: MOVEIT004
        if not c.joints:
            yield _f(
                "MOVEIT009",
                c.at("joints"),
                c.subject,
                f"controller '{c.name}' has no joints; MoveIt skips it",
                "write 'joints: [<the joints it drives>]'",
            )
            continue
        unknown = [n for n in c.joints if robot.joint(n) is None]
        if unknown:
            yield _f(
                "MOVEIT009",
                c.at("joints"),
                c.subject,
                f"controller '{c.name}' names joints that are not in the URDF: {', '.join(unknown)}",
                "use the URDF joint names",
            )


@rule("MOVEIT010", "moveit-controller-not-a-group", "warning")
def controller_not_a_group(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a listed controller whose joints are not exactly the planned joints (1-DOF, not
    mimic, not passive) of any SRDF planning group.
    ## Why is this bad?
    MoveIt sends a trajectory to the controllers whose joints cover the group's joints. A
    controller that drives a few joints more or less than every group is either never used
    alone or needs another controller beside it; most often a joint was added to the group
    and not to the controller (or the other way round).
    ## Example
    group `arm` = j1, j2, j3; controller joints = j1, j2
    ## Use instead
    The controller's joints equal to one group's joints.
    """
    cfg = robot.moveit_config
    groups = _group_sets(robot)
    if cfg is None or not groups:
        return
    for c in _listed(cfg):
        if not c.joints or any(robot.joint(n) is None for n in c.joints):
            continue  # MOVEIT009
        if frozenset(c.joints) not in groups.values():
            yield _f(
                "MOVEIT010",
                c.at("joints"),
                c.subject,
                f"controller '{c.name}' drives {', '.join(c.joints)}, which are not the joints of any planning group",
                "make its joints those of one group (e.g. "
                + ", ".join(f"{g}: [{', '.join(sorted(s))}]" for g, s in list(groups.items())[:2])
                + ")",
            )


def _ros2(robot: Robot) -> dict[str, object] | None:
    rc = robot.ros2_control
    if rc is None or not rc.controllers:
        return None
    return {c.name: c for c in rc.controllers}


@rule("MOVEIT011", "moveit-controller-not-in-ros2-control", "error")
def controller_not_in_ros2_control(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a listed MoveIt controller that the ros2_control controllers YAML does not define
    (checked when a controllers YAML was read: `--controllers`, or the package's
    config/ros2_controllers.yaml).
    ## Why is this bad?
    MoveIt only talks to an action server `<name>/<action_ns>` that a ros2_control controller
    of that name provides; the Setup Assistant's demo.launch.py also spawns each name. With
    no such controller the spawner fails and execution waits for an action server that
    never comes.
    ## Example
    moveit_controllers.yaml `arm_controller`; ros2_controllers.yaml only `joint_trajectory_controller`.
    ## Use instead
    The same controller name in both files.
    """
    cfg, ros2 = robot.moveit_config, _ros2(robot)
    if cfg is None or ros2 is None:
        return
    for c in _listed(cfg):
        if c.name not in ros2:
            known = ", ".join(n for n in ros2 if n != "joint_state_broadcaster") or "none"
            yield _f(
                "MOVEIT011",
                c.where,
                c.subject,
                f"controller '{c.name}' is not a controller of the ros2_control controllers YAML (it has: {known})",
                "name the ros2_control controller that serves it, or add it to ros2_controllers.yaml",
            )


@rule("MOVEIT012", "moveit-controller-action-mismatch", "error")
def controller_action_mismatch(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a listed MoveIt controller whose ros2_control controller of the same name does not
    serve its action: FollowJointTrajectory needs a joint_trajectory_controller (action
    `follow_joint_trajectory`), GripperCommand a position_/effort_controllers
    GripperActionController and ParallelGripperCommand a parallel_gripper_action_controller
    (both `gripper_cmd`); and an `action_ns` other than the one that controller serves.
    ## Why is this bad?
    MoveIt connects an action client of its type to `<name>/<action_ns>`; a server of
    another type or at another name never answers, and execution fails after the
    action-server wait.
    ## Example
    `type: FollowJointTrajectory` for a `forward_command_controller/ForwardCommandController`.
    ## Use instead
    A joint_trajectory_controller for FollowJointTrajectory, with `action_ns: follow_joint_trajectory`.
    """
    cfg, ros2 = robot.moveit_config, _ros2(robot)
    if cfg is None or ros2 is None:
        return
    for c in _listed(cfg):
        other = ros2.get(c.name)
        if other is None or c.type not in SERVES:
            continue
        rtype = getattr(other, "type", "")
        if rtype not in SERVES[c.type]:
            yield _f(
                "MOVEIT012",
                c.at("type"),
                c.subject,
                f"controller '{c.name}' is a {c.type} controller for MoveIt, but ros2_control runs it as "
                f"'{rtype}', which does not serve that action",
                f"make it a {' or '.join(SERVES[c.type])} in ros2_controllers.yaml, or fix the type here",
            )
        elif c.action_ns is not None and c.action_ns != ACTION_NS[c.type]:
            yield _f(
                "MOVEIT012",
                c.at("action_ns"),
                c.subject,
                f"controller '{c.name}': action_ns '{c.action_ns}', but {rtype} serves '{c.name}/{ACTION_NS[c.type]}'",
                f"write 'action_ns: {ACTION_NS[c.type]}'",
            )


def _ros2_joints(controller: object) -> list[str]:
    param = getattr(controller, "param", None)
    if param is None:
        return []
    value = param("joints")
    if value is None:
        value = param("joint")
    if isinstance(value, list | tuple):
        return [str(v) for v in value]
    return [] if value is None else [str(value)]


@rule("MOVEIT013", "moveit-controller-joints-differ", "error")
def controller_joints_differ(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a listed MoveIt controller whose `joints` differ from those of the ros2_control
    controller of the same name (`joints`, or `joint` for a gripper action controller).
    ## Why is this bad?
    MoveIt sends the trajectory of the joints it believes the controller drives. The
    joint_trajectory_controller rejects a goal whose joints it does not have, and joints it
    has but is not sent are held, so the motion that was checked for collisions is not the
    one executed.
    ## Example
    MoveIt `joints: [j1, j2, j3]`; ros2_controllers.yaml `joints: [j1, j2]`.
    ## Use instead
    The same joints in both files.
    """
    cfg, ros2 = robot.moveit_config, _ros2(robot)
    if cfg is None or ros2 is None:
        return
    for c in _listed(cfg):
        other = ros2.get(c.name)
        if other is None or not c.joints or getattr(other, "type", "") not in (t for ts in SERVES.values() for t in ts):
            continue  # MOVEIT011 / MOVEIT009 / MOVEIT012
        theirs = _ros2_joints(other)
        if set(theirs) != set(c.joints):
            yield _f(
                "MOVEIT013",
                c.at("joints"),
                c.subject,
                f"controller '{c.name}' has joints {', '.join(c.joints)} for MoveIt, but "
                f"{', '.join(theirs) or 'none'} in the ros2_control controllers YAML",
                "write the same joints in moveit_controllers.yaml and ros2_controllers.yaml",
            )


@rule("MOVEIT014", "moveit-default-controllers-overlap", "warning")
def default_controllers_overlap(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags two listed controllers marked `default: true` that share a joint.
    ## Why is this bad?
    MoveIt prefers default controllers when several can execute a trajectory; two defaults
    for the same joint leave the choice to the order in which it searches, so which
    controller moves the joint is not stated anywhere.
    ## Example
    `arm_controller` and `arm_servo_controller`, both `default: true` on j1..j6.
    ## Use instead
    `default: true` on one of them only.
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    seen: list[MoveItController] = []
    for c in _listed(cfg):
        if c.default is not True or not c.joints:
            continue
        for prev in seen:
            shared = [n for n in c.joints if n in (prev.joints or ())]
            if shared:
                yield _f(
                    "MOVEIT014",
                    c.at("default"),
                    c.subject,
                    f"controllers '{prev.name}' and '{c.name}' are both default for {', '.join(shared)}",
                    f"keep 'default: true' on one of them; write 'default: false' for '{c.name}'",
                )
                break
        seen.append(c)


@rule("MOVEIT015", "moveit-controller-not-listed", "error")
def controller_not_listed(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a controller entry under `moveit_simple_controller_manager` that `controller_names`
    does not list (including when `controller_names` is missing).
    ## Why is this bad?
    moveit_simple_controller_manager loads only the names in `controller_names` ("No
    controller_names specified." loads none); an entry outside the list is ignored without
    a word, and its joints have no controller.
    ## Example
    `controller_names: [arm_controller]` and an entry `hand_controller:`.
    ## Use instead
    `controller_names: [arm_controller, hand_controller]`
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for c in cfg.controllers or ():
        if c.has_section and not c.listed:
            missing = cfg.controller_names_where is None
            yield _f(
                "MOVEIT015",
                c.where,
                c.subject,
                f"controller '{c.name}' is not in controller_names"
                + (" (there is no controller_names list)" if missing else "")
                + "; MoveIt never loads it",
                f"add '{c.name}' to moveit_simple_controller_manager.controller_names",
            )


@rule("MOVEIT016", "moveit-kinematics-group-not-in-srdf", "warning")
def kinematics_unknown_group(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a kinematics.yaml entry that names no SRDF planning group.
    ## Why is this bad?
    MoveIt loads an IK solver per SRDF group and looks its settings up by the group's name;
    an entry under another name is never read, and the group it was meant for has no IK
    solver (no Cartesian goals, no interactive marker in RViz).
    ## Example
    `manipulator:` in kinematics.yaml, group `arm` in the SRDF.
    ## Use instead
    The SRDF group's name.
    """
    cfg = robot.moveit_config
    if cfg is None or robot.semantic is None:
        return
    groups = {g.name for g in robot.semantic.groups}
    for k in cfg.kinematics or ():
        if k.group not in groups:
            yield _f(
                "MOVEIT016",
                k.where,
                f"group:{k.group}",
                f"kinematics.yaml configures '{k.group}', which is not a planning group of the SRDF; "
                "MoveIt never reads it",
                f"use one of the SRDF groups: {', '.join(sorted(groups)) or 'none'}",
            )


def _is_chain(robot: Robot, group: str) -> bool:
    """joint_model_group.cpp: one root, and each joint an ancestor of the next (one path)."""
    joints = [j for j in robot.group_joints(group) if j.child is not None]
    if not joints:
        return False
    deepest = max(joints, key=lambda j: len(robot.path_to_root(j.child or "")))
    path = {id(j) for j in robot.path_to_root(deepest.child or "")}
    return all(id(j) in path for j in joints)


@rule("MOVEIT017", "moveit-kdl-not-a-chain", "warning")
def kdl_not_a_chain(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a kinematics.yaml group with the KDL solver whose joints do not lie on one path of
    the tree (MoveIt's `isChain()`), e.g. a group of two arms or a gripper's fingers.
    ## Why is this bad?
    kdl_kinematics_plugin refuses to initialise ("Group '...' is not a chain"), so the group
    has no IK at all.
    ## Example
    `both_arms: {kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin}`
    ## Use instead
    KDL on single chains only; remove the entry (or use a solver for trees) for the others.
    """
    cfg = robot.moveit_config
    if cfg is None or robot.semantic is None:
        return
    groups = {g.name for g in robot.semantic.groups}
    for k in cfg.kinematics or ():
        if k.solver == KDL and k.group in groups and not _is_chain(robot, k.group):
            yield _f(
                "MOVEIT017",
                k.solver_where,
                f"group:{k.group}",
                f"group '{k.group}' is not a chain; the KDL solver refuses it and the group has no IK",
                "configure KDL only for single-chain groups, or remove this entry",
            )


@rule("MOVEIT018", "moveit-initial-position-bad", "error")
def initial_position_bad(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags an initial_positions.yaml entry for a joint that is not in the URDF, or whose value
    is outside the joint's limits.
    ## Why is this bad?
    The mock hardware starts the joint at this value; MoveIt then sees a start state outside
    the bounds and refuses to plan from it, and an unknown name is silently unused (the real
    joint starts at 0).
    ## Example
    `elbow: 3.5` for an elbow limited to [-2.6, 2.6].
    ## Use instead
    A value inside the limits, for a URDF joint.
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for p in cfg.initial_positions or ():
        j = robot.joint(p.joint)
        if j is None:
            yield _f(
                "MOVEIT018",
                p.where,
                f"joint:{p.joint}",
                f"initial_positions.yaml names '{p.joint}', which is not a joint of the URDF",
                "use the URDF joint's name",
            )
        elif p.value is not None and j.outside_limits(p.value):
            yield _f(
                "MOVEIT018",
                p.where,
                f"joint:{p.joint}",
                f"initial position of '{p.joint}' is {j.show(p.value)}, outside its limits {j.range_text()}",
                "write a value inside the joint's limits",
            )


@rule("MOVEIT019", "moveit-config-file-missing", "error")
def config_file_missing(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a MoveIt config folder without `joint_limits.yaml`, `kinematics.yaml` or
    `pilz_cartesian_limits.yaml`.
    ## Why is this bad?
    `MoveItConfigsBuilder(...).to_moveit_configs()` raises when one is missing (it loads the
    Pilz limits by default; the old name `cartesian_limits.yaml` only draws a warning and is
    not read), so no launch file of the package starts.
    ## Example
    A config/ folder with only the SRDF and moveit_controllers.yaml.
    ## Use instead
    Write config/joint_limits.yaml (velocity and acceleration per group joint) and
    config/kinematics.yaml (a solver per arm group).
    """
    cfg = robot.moveit_config
    if cfg is None:
        return
    for name, present in (
        ("joint_limits.yaml", cfg.joint_limits),
        ("kinematics.yaml", cfg.kinematics),
        ("pilz_cartesian_limits.yaml", cfg.pilz_cartesian_limits_file),
    ):
        if present is None:
            yield _f(
                "MOVEIT019",
                cfg.where,
                "file",
                f"no {name} in {cfg.folder}; MoveItConfigsBuilder raises without it",
                f"write config/{name}",
            )
