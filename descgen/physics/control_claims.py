"""Which interfaces a controller claims, per controller type, read from its parameters.

The one place that says it: the audit rules (CTRL002, CTRL004, CTRL049, CTRL050), the
generate check and the control model all ask here. Each entry follows the controller's
``command_interface_configuration()`` / ``state_interface_configuration()`` and its
parameter definitions at ros-controls/ros2_controllers ``jazzy`` (docs/ros2_control_jazzy.md §8):

- joint_state_broadcaster: ALL state interfaces when ``joints`` and ``interfaces`` are both
  empty, else each joint x interface (joint_state_broadcaster/src/joint_state_broadcaster.cpp);
- joint_trajectory_controller: ``command_joints`` (default ``joints``) x ``command_interfaces``,
  ``joints`` x ``state_interfaces`` (joint_trajectory_controller_parameters.yaml);
- diff_drive_controller: ``<wheel>/velocity``; states ``<wheel>/position`` (``velocity`` when
  ``position_feedback: false``, none when ``open_loop``) (diff_drive_controller.cpp);
- forward_command_controller: ``joints`` x ``interface_name``; the multi-interface one
  ``joint`` x ``interface_names``; the JointGroup{Position,Velocity,Effort}Controllers fix
  the interface;
- position_/effort_controllers GripperActionController: ``<joint>/position`` (``effort``),
  states ``<joint>/position`` and ``<joint>/velocity`` (gripper_action_controller_impl.hpp);
- parallel_gripper_action_controller: ``<joint>/position`` plus the optional full names
  ``max_effort_interface``/``max_velocity_interface``, states ``<joint>/<state_interfaces>``
  (default position, velocity) (parallel_gripper_action_controller_impl.hpp);
- imu_sensor_broadcaster: the ten IMU interfaces of ``sensor_name``
  (ros2_control controller_interface/include/semantic_components/imu_sensor.hpp);
- force_torque_sensor_broadcaster: the six ``force.*``/``torque.*`` of ``sensor_name``, or
  the non-empty ``interface_names.{force,torque}.{x,y,z}``; both or neither is refused at
  configure (force_torque_sensor_broadcaster.cpp).
"""

from __future__ import annotations

from collections.abc import Callable

from descgen.core.model import Controller
from descgen.core.record import record

IMU_INTERFACES = (
    "orientation.x",
    "orientation.y",
    "orientation.z",
    "orientation.w",
    "angular_velocity.x",
    "angular_velocity.y",
    "angular_velocity.z",
    "linear_acceleration.x",
    "linear_acceleration.y",
    "linear_acceleration.z",
)
FT_INTERFACES = ("force.x", "force.y", "force.z", "torque.x", "torque.y", "torque.z")
# parameters that name URDF joints, per the controllers above
JOINT_PARAMS = ("joints", "command_joints", "joint", "left_wheel_names", "right_wheel_names")
# parameters that name a frame or a ros2_control sensor of the robot
FRAME_PARAMS = ("base_frame_id", "odom_frame_id", "frame_id", "sensor_name")
# the last name of a (nested) parameter that holds a frame id: pose_broadcaster's tf.child_frame_id
FRAME_LEAVES = ("frame_id", "child_frame_id", "base_frame_id", "odom_frame_id")
ODOMETRY_FRAMES = ("odom_frame_id", "base_frame_id")


def default_frames(ctype: str) -> tuple[tuple[str, str], ...]:
    """(parameter, Jazzy's default) for each odometry frame id ``ctype`` declares with a frame
    name as its default (descgen/physics/controller_params.py: diff drive, mecanum, omni,
    tricycle, the steering controllers): left unset, the controller publishes that frame."""
    from descgen.physics.controller_params import definitions

    return tuple(
        (d.name, d.default)
        for d in definitions(ctype)
        if d.name in ODOMETRY_FRAMES and isinstance(d.default, str) and d.default
    )


def prefixes_tf_frames(ctype: str) -> bool:
    """Whether ``ctype`` declares ``tf_frame_prefix_enable`` (default true: in a namespace it
    writes the namespace before its frame ids)."""
    from descgen.physics.controller_params import definitions

    return any(d.name == "tf_frame_prefix_enable" for d in definitions(ctype))


@record
class Claims:
    """Full interface names (``<component>/<interface>``) a controller needs when active."""

    known: bool  # False: the type is not in the table; nothing could be checked
    command: tuple[str, ...] = ()
    state: tuple[str, ...] = ()
    all_states: bool = False  # joint_state_broadcaster with neither joints nor interfaces
    problems: tuple[str, ...] = ()  # parameters the controller refuses at configure


def names(value: object) -> list[str]:
    """A parameter that is a list of names (or one name) as a list of strings."""
    if isinstance(value, list | tuple):
        return [str(v) for v in value if not isinstance(v, tuple)]
    return [] if value is None or value == "" else [str(value)]


def nested(c: Controller, path: str) -> object:
    """A parameter by dotted path: ``a.b.c`` nested (YAML mappings) or written flat."""
    params = dict(c.params)
    if path in params:
        return params[path]
    value: object = params
    for part in path.split("."):
        if isinstance(value, dict):
            value = value.get(part)
        elif isinstance(value, tuple) and all(isinstance(x, tuple) and len(x) == 2 for x in value):
            value = dict(value).get(part)
        else:
            return None
    return value


def _product(components: list[str], interfaces: list[str]) -> tuple[str, ...]:
    return tuple(f"{c}/{i}" for c in components for i in interfaces)


def _required(c: Controller, *keys: str) -> tuple[str, ...]:
    return tuple(f"'{k}' is empty: the controller refuses to configure" for k in keys if not names(c.param(k)))


def _jsb(c: Controller) -> Claims:
    joints, ifaces = names(c.param("joints")), names(c.param("interfaces"))
    if not joints and not ifaces:
        return Claims(True, all_states=True)
    return Claims(True, state=_product(joints, ifaces))


def _jtc(c: Controller) -> Claims:
    joints = names(c.param("joints"))
    cmd_joints = names(c.param("command_joints")) or joints
    return Claims(
        True,
        _product(cmd_joints, names(c.param("command_interfaces"))),
        _product(joints, names(c.param("state_interfaces"))),
        problems=_required(c, "joints", "command_interfaces", "state_interfaces"),
    )


def _diff_drive(c: Controller) -> Claims:
    wheels = names(c.param("left_wheel_names")) + names(c.param("right_wheel_names"))
    if c.param("open_loop") is True:
        state: tuple[str, ...] = ()
    else:
        state = _product(wheels, ["velocity" if c.param("position_feedback") is False else "position"])
    return Claims(True, _product(wheels, ["velocity"]), state)  # missing wheels: CTRL006 says so


def _forward(c: Controller) -> Claims:
    return Claims(
        True,
        _product(names(c.param("joints")), names(c.param("interface_name"))),
        problems=_required(c, "joints", "interface_name"),
    )


def _multi_forward(c: Controller) -> Claims:
    return Claims(
        True,
        _product(names(c.param("joint")), names(c.param("interface_names"))),
        problems=_required(c, "joint", "interface_names"),
    )


def _group(interface: str) -> Callable[[Controller], Claims]:
    def claims(c: Controller) -> Claims:
        return Claims(True, _product(names(c.param("joints")), [interface]), problems=_required(c, "joints"))

    return claims


def _gripper(interface: str) -> Callable[[Controller], Claims]:
    def claims(c: Controller) -> Claims:
        joint = names(c.param("joint"))
        return Claims(
            True,
            _product(joint, [interface]),
            _product(joint, ["position", "velocity"]),
            problems=_required(c, "joint"),
        )

    return claims


def _parallel_gripper(c: Controller) -> Claims:
    joint = names(c.param("joint"))
    extra = [*names(c.param("max_effort_interface")), *names(c.param("max_velocity_interface"))]
    raw = c.param("state_interfaces")
    states = ["position", "velocity"] if raw is None else names(raw)
    return Claims(
        True, (*_product(joint, ["position"]), *extra), _product(joint, states), problems=_required(c, "joint")
    )


def _imu(c: Controller) -> Claims:
    return Claims(
        True,
        state=_product(names(c.param("sensor_name")), list(IMU_INTERFACES)),
        problems=_required(c, "sensor_name", "frame_id"),
    )


def _force_torque(c: Controller) -> Claims:
    sensor = names(c.param("sensor_name"))
    axes = [str(v) for v in (nested(c, f"interface_names.{k}") for k in FT_INTERFACES) if v]
    problems = list(_required(c, "frame_id"))
    if sensor and axes:
        problems.append("both 'sensor_name' and 'interface_names' are set: the controller refuses to configure")
    elif not sensor and not axes:
        problems.append("neither 'sensor_name' nor 'interface_names' is set: the controller refuses to configure")
    return Claims(True, state=(*_product(sensor, list(FT_INTERFACES)), *axes), problems=tuple(problems))


TABLE: dict[str, Callable[[Controller], Claims]] = {
    "joint_state_broadcaster/JointStateBroadcaster": _jsb,
    "joint_trajectory_controller/JointTrajectoryController": _jtc,
    "diff_drive_controller/DiffDriveController": _diff_drive,
    "forward_command_controller/ForwardCommandController": _forward,
    "forward_command_controller/MultiInterfaceForwardCommandController": _multi_forward,
    "position_controllers/JointGroupPositionController": _group("position"),
    "velocity_controllers/JointGroupVelocityController": _group("velocity"),
    "effort_controllers/JointGroupEffortController": _group("effort"),
    "position_controllers/GripperActionController": _gripper("position"),
    "effort_controllers/GripperActionController": _gripper("effort"),
    "parallel_gripper_action_controller/GripperActionController": _parallel_gripper,
    "imu_sensor_broadcaster/IMUSensorBroadcaster": _imu,
    "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster": _force_torque,
}


def claims_of(c: Controller) -> Claims:
    fn = TABLE.get(c.type)
    return fn(c) if fn is not None else Claims(False)


def joint_params(c: Controller) -> tuple[str, ...]:
    """The parameters of ``c`` that name URDF joints: an unknown type's ``joint`` may mean
    something else, its joint lists are still joints."""
    return JOINT_PARAMS if claims_of(c).known else ("joints", "left_wheel_names", "right_wheel_names")


def split(full: str) -> tuple[str, str]:
    """``joint/interface`` -> (joint, interface); interface names carry no slash."""
    component, _, iface = full.rpartition("/")
    return component, iface


def command_pairs(c: Controller) -> list[tuple[str, str]]:
    """(component, command interface) pairs a controller claims when active."""
    return [split(k) for k in claims_of(c).command]


def state_pairs(c: Controller) -> list[tuple[str, str]]:
    """(component, state interface) pairs a controller reads when active."""
    return [split(k) for k in claims_of(c).state]
