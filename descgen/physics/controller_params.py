"""The parameters Jazzy's controllers declare, as data, and the lookups the CTRL060–CTRL065
audit rules make with it (docs/controller_params.md has the sources and the facts).

Each controller of ros-controls/ros2_controllers declares its parameters with
generate_parameter_library (GPL) from a YAML file (``<pkg>/src/*.yaml``). The table
``PARAMETER_FILES`` below holds, for each such file on the ``jazzy`` branch, every
parameter's dotted name, type, default (``REQUIRED``: none), whether it is read-only, and
its validators; ``scripts/extract_controller_params.py`` re-makes it from a checkout. Names
with a ``__map_<key>`` segment expand over the values of parameter ``<key>``
(``gains.__map_joints.p`` is ``gains.<joint>.p`` for each joint in ``joints``); a ``none``
type is a namespace GPL leaves open (a filter chain's parameters).

What ROS does with a controller's parameters (ros2_control ``jazzy``,
controller_interface/include/controller_interface/controller_interface_base.hpp
``get_node_options``; GPL's generated ``declare_params``):

- the controller node allows undeclared parameters and declares every override from the
  file, so a parameter no one reads is kept and silently ignored;
- GPL then reads each declared one with ``as_<type>()``: a value of another rcl type (``40``
  for a double, ``[0, 0]`` for a double array, ``"true"`` for a bool) throws, and the
  controller fails to initialize;
- GPL runs the validators on the value (the default too): a failing one throws "Invalid value
  set during initialization", so a parameter whose default fails (``wheel_separation: 0.0``
  with ``gt<>: [0.0]``) or that has no default must be set.

The rest is written by hand below, each fact with its source: parameters outside the GPL files
(every controller node's own, the effort gripper's gains, PidROS's extra), which GPL file(s)
each controller type reads, parameters a type's code requires although GPL does not, and the
retired (removed, ignored, deprecated) names with what to use instead.

Imports only the standard library and descgen.core: pure data plus lookups.
"""

from __future__ import annotations

import difflib
import itertools
import math
import re
from collections.abc import Iterable, Iterator, Mapping
from typing import Literal, TypeGuard

from descgen.core.launch_subst import unresolved
from descgen.core.record import record

REPO = "ros-controls/ros2_controllers"
BRANCH = "jazzy"
COMMIT = "ed360c97d6e9e74cb884e3e39a949d987cd15c11"  # 4.42.1 plus one test-only commit
RELEASE = "4.42.1"

NAN = math.nan
INF = math.inf


class _Required:
    """The default of a parameter that has none: it must be set."""

    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: object = _Required()
RO, RW = True, False

Check = tuple[str, tuple[object, ...]]  # (validator, its arguments)
Entry = tuple[str, str, object, bool, tuple[Check, ...]]  # name, type, default, read_only, checks
Defs = tuple[Entry, ...]

# --- BEGIN GENERATED (scripts/extract_controller_params.py) ---
# ros-controls/ros2_controllers jazzy @ ed360c97d6e9e74cb884e3e39a949d987cd15c11
PARAMETER_FILES: dict[str, Defs] = {
    # ackermann_steering_controller/src/ackermann_steering_controller.yaml
    "ackermann_steering_controller": (
        ("front_wheel_track", "double", 0.0, RW, ()),
        ("steering_track_width", "double", 0.0, RW, ()),
        ("rear_wheel_track", "double", 0.0, RW, ()),
        ("traction_track_width", "double", 0.0, RW, ()),
        ("wheelbase", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("traction_wheels_radius", "double", 0.0, RW, ()),
        ("front_wheels_radius", "double", 0.0, RW, ()),
        ("rear_wheels_radius", "double", 0.0, RW, ()),
    ),
    # admittance_controller/src/admittance_controller_parameters.yaml
    "admittance_controller": (
        ("joints", "string_array", REQUIRED, RO, ()),
        ("command_joints", "string_array", (), RO, ()),
        ("command_interfaces", "string_array", REQUIRED, RO, ()),
        ("state_interfaces", "string_array", REQUIRED, RO, ()),
        ("chainable_command_interfaces", "string_array", ("position", "velocity"), RO, ()),
        ("kinematics.plugin_name", "string", REQUIRED, RW, ()),
        ("kinematics.plugin_package", "string", REQUIRED, RW, ()),
        ("kinematics.base", "string", REQUIRED, RW, ()),
        ("kinematics.tip", "string", REQUIRED, RW, ()),
        ("kinematics.alpha", "double", 0.01, RW, ()),
        ("ft_sensor.name", "string", REQUIRED, RW, ()),
        ("ft_sensor.frame.id", "string", REQUIRED, RW, ()),
        ("ft_sensor.filter_coefficient", "double", 0.05, RW, ()),
        ("control.frame.id", "string", REQUIRED, RW, ()),
        ("fixed_world_frame.frame.id", "string", REQUIRED, RW, ()),
        ("gravity_compensation.frame.id", "string", REQUIRED, RW, ()),
        ("gravity_compensation.CoG.pos", "double_array", REQUIRED, RW, (("fixed_size", (3,)),)),
        ("gravity_compensation.CoG.force", "double", 0.0, RW, ()),
        ("admittance.selected_axes", "bool_array", REQUIRED, RW, (("fixed_size", (6,)),)),
        (
            "admittance.mass",
            "double_array",
            REQUIRED,
            RW,
            (("fixed_size", (6,)), ("element_bounds", (0.0001, 1000000.0))),
        ),
        ("admittance.damping_ratio", "double_array", REQUIRED, RW, (("fixed_size", (6,)),)),
        (
            "admittance.stiffness",
            "double_array",
            REQUIRED,
            RW,
            (("fixed_size", (6,)), ("element_bounds", (0.0, 100000000.0))),
        ),
        ("admittance.joint_damping", "double", 5, RW, (("gt_eq", (0.0,)),)),
        ("enable_parameter_update_without_reactivation", "bool", True, RW, ()),
    ),
    # battery_state_broadcaster/src/battery_state_broadcaster_parameters.yaml
    "battery_state_broadcaster": (
        ("batteries", "string_array", REQUIRED, RO, (("unique", ()),)),
        ("interfaces.__map_batteries.battery_temperature", "bool", False, RO, ()),
        ("interfaces.__map_batteries.battery_current", "bool", False, RO, ()),
        ("interfaces.__map_batteries.battery_charge", "bool", False, RO, ()),
        ("interfaces.__map_batteries.battery_percentage", "bool", False, RO, ()),
        ("interfaces.__map_batteries.battery_power_supply_status", "bool", False, RO, ()),
        ("interfaces.__map_batteries.battery_power_supply_health", "bool", False, RO, ()),
        ("interfaces.__map_batteries.battery_present", "bool", False, RO, ()),
        ("__map_batteries.minimum_voltage", "double", NAN, RO, ()),
        ("__map_batteries.maximum_voltage", "double", NAN, RO, ()),
        ("__map_batteries.capacity", "double", NAN, RO, ()),
        ("__map_batteries.design_capacity", "double", NAN, RO, ()),
        ("__map_batteries.power_supply_technology", "int", 0, RO, (("bounds", (0, 8)),)),
        ("__map_batteries.location", "string", "", RO, ()),
        ("__map_batteries.serial_number", "string", "", RO, ()),
        ("sensor_name", "string", "", RO, ()),
        ("design_capacity", "double", NAN, RO, ()),
        ("power_supply_technology", "int", 0, RO, (("bounds", (0, 8)),)),
    ),
    # bicycle_steering_controller/src/bicycle_steering_controller.yaml
    "bicycle_steering_controller": (
        ("wheelbase", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("traction_wheel_radius", "double", 0.0, RW, ()),
        ("front_wheel_radius", "double", 0.0, RO, ()),
        ("rear_wheel_radius", "double", 0.0, RO, ()),
    ),
    # chained_filter_controller/src/chained_filter_parameters.yaml
    "chained_filter": (
        ("input_interfaces", "string_array", (), RO, (("not_empty", ()),)),
        ("output_interfaces", "string_array", (), RO, (("not_empty", ()),)),
        ("filter_chain", "none", REQUIRED, RW, ()),
        ("__map_input_interfaces.filter_chain", "none", REQUIRED, RW, ()),
    ),
    # diff_drive_controller/src/diff_drive_controller_parameter.yaml
    "diff_drive_controller": (
        ("left_wheel_names", "string_array", (), RW, (("not_empty", ()),)),
        ("right_wheel_names", "string_array", (), RW, (("not_empty", ()),)),
        ("wheel_separation", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("wheel_radius", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("wheel_separation_multiplier", "double", 1.0, RW, ()),
        ("left_wheel_radius_multiplier", "double", 1.0, RW, ()),
        ("right_wheel_radius_multiplier", "double", 1.0, RW, ()),
        ("tf_frame_prefix_enable", "bool", True, RW, ()),
        ("tf_frame_prefix", "string", "", RW, ()),
        ("odom_frame_id", "string", "odom", RW, ()),
        ("base_frame_id", "string", "base_link", RW, ()),
        ("pose_covariance_diagonal", "double_array", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), RW, ()),
        ("twist_covariance_diagonal", "double_array", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), RW, ()),
        ("open_loop", "bool", False, RW, ()),
        ("position_feedback", "bool", True, RW, ()),
        ("enable_odom_tf", "bool", True, RW, ()),
        ("cmd_vel_timeout", "double", 0.5, RW, ()),
        ("publish_limited_velocity", "bool", False, RW, ()),
        ("velocity_rolling_window_size", "int", 10, RW, ()),
        ("publish_rate", "double", 50.0, RW, ()),
        ("linear.x.has_velocity_limits", "bool", True, RW, ()),
        ("linear.x.has_acceleration_limits", "bool", True, RW, ()),
        ("linear.x.has_jerk_limits", "bool", True, RW, ()),
        ("linear.x.max_velocity", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.min_velocity", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_acceleration", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_deceleration", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.x.min_acceleration", "double", NAN, RW, ()),
        ("linear.x.max_acceleration_reverse", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_deceleration_reverse", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_jerk", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.min_jerk", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.has_velocity_limits", "bool", True, RW, ()),
        ("angular.z.has_acceleration_limits", "bool", True, RW, ()),
        ("angular.z.has_jerk_limits", "bool", True, RW, ()),
        ("angular.z.max_velocity", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.min_velocity", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_acceleration", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_deceleration", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.min_acceleration", "double", NAN, RW, ()),
        ("angular.z.max_acceleration_reverse", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_deceleration_reverse", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_jerk", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.min_jerk", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
    ),
    # force_torque_sensor_broadcaster/src/force_torque_sensor_broadcaster_parameters.yaml
    "force_torque_sensor_broadcaster": (
        ("frame_id", "string", "", RW, (("not_empty", ()),)),
        ("sensor_name", "string", "", RW, ()),
        ("interface_names.force.x", "string", "", RW, ()),
        ("interface_names.force.y", "string", "", RW, ()),
        ("interface_names.force.z", "string", "", RW, ()),
        ("interface_names.torque.x", "string", "", RW, ()),
        ("interface_names.torque.y", "string", "", RW, ()),
        ("interface_names.torque.z", "string", "", RW, ()),
        ("offset.force.x", "double", 0.0, RW, ()),
        ("offset.force.y", "double", 0.0, RW, ()),
        ("offset.force.z", "double", 0.0, RW, ()),
        ("offset.torque.x", "double", 0.0, RW, ()),
        ("offset.torque.y", "double", 0.0, RW, ()),
        ("offset.torque.z", "double", 0.0, RW, ()),
        ("multiplier.force.x", "double", 1.0, RW, ()),
        ("multiplier.force.y", "double", 1.0, RW, ()),
        ("multiplier.force.z", "double", 1.0, RW, ()),
        ("multiplier.torque.x", "double", 1.0, RW, ()),
        ("multiplier.torque.y", "double", 1.0, RW, ()),
        ("multiplier.torque.z", "double", 1.0, RW, ()),
        ("sensor_filter_chain", "none", REQUIRED, RW, ()),
    ),
    # forward_command_controller/src/forward_command_controller_parameters.yaml
    "forward_command_controller": (
        ("joints", "string_array", (), RW, ()),
        ("interface_name", "string", "", RW, ()),
    ),
    # forward_command_controller/src/multi_interface_forward_command_controller_parameters.yaml
    "multi_interface_forward_command_controller": (
        ("joint", "string", "", RW, ()),
        ("interface_names", "string_array", (), RW, ()),
    ),
    # gpio_controllers/src/gpio_command_controller_parameters.yaml
    "gpio_command_controller_parameters": (
        ("gpios", "string_array", REQUIRED, RO, (("size_gt", (0,)), ("unique", ()))),
        ("command_interfaces.__map_gpios.interfaces", "string_array", (), RO, (("unique", ()),)),
        ("state_interfaces.__map_gpios.interfaces", "string_array", (), RO, (("unique", ()),)),
    ),
    # gps_sensor_broadcaster/src/gps_sensor_broadcaster_parameters.yaml
    "gps_sensor_broadcaster": (
        ("sensor_name", "string", "", RW, (("not_empty", ()),)),
        ("frame_id", "string", "", RW, (("not_empty", ()),)),
        (
            "static_position_covariance",
            "double_array",
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            RW,
            (("fixed_size", (9,)),),
        ),
        ("read_covariance_from_interface", "bool", False, RW, ()),
    ),
    # gripper_controllers/src/gripper_action_controller_parameters.yaml
    "gripper_action_controller": (
        ("action_monitor_rate", "double", 20.0, RW, (("gt_eq", (0.1,)),)),
        ("joint", "string", "", RW, ()),
        ("goal_tolerance", "double", 0.01, RW, (("gt_eq", (0.0,)),)),
        ("max_effort", "double", 0.0, RW, (("gt_eq", (0.0,)),)),
        ("allow_stalling", "bool", False, RW, ()),
        ("stall_velocity_threshold", "double", 0.001, RW, ()),
        ("stall_timeout", "double", 1.0, RW, ()),
    ),
    # imu_sensor_broadcaster/src/imu_sensor_broadcaster_parameters.yaml
    "imu_sensor_broadcaster": (
        ("sensor_name", "string", "", RW, (("not_empty", ()),)),
        ("frame_id", "string", "", RW, (("not_empty", ()),)),
        (
            "static_covariance_orientation",
            "double_array",
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            RW,
            (("fixed_size", (9,)),),
        ),
        (
            "static_covariance_angular_velocity",
            "double_array",
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            RW,
            (("fixed_size", (9,)),),
        ),
        (
            "static_covariance_linear_acceleration",
            "double_array",
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            RW,
            (("fixed_size", (9,)),),
        ),
    ),
    # joint_state_broadcaster/src/joint_state_broadcaster_parameters.yaml
    "joint_state_broadcaster": (
        ("use_local_topics", "bool", False, RO, ()),
        ("joints", "string_array", (), RO, ()),
        ("extra_joints", "string_array", (), RO, ()),
        ("interfaces", "string_array", (), RO, ()),
        ("map_interface_to_joint_state.position", "string", "position", RO, ()),
        ("map_interface_to_joint_state.velocity", "string", "velocity", RO, ()),
        ("map_interface_to_joint_state.effort", "string", "effort", RO, ()),
        ("use_urdf_to_filter", "bool", True, RO, ()),
        ("frame_id", "string", "base_link", RO, ()),
        ("publish_dynamic_joint_states", "bool", True, RO, ()),
    ),
    # joint_trajectory_controller/src/joint_trajectory_controller_parameters.yaml
    "joint_trajectory_controller": (
        ("joints", "string_array", (), RO, (("unique", ()), ("size_gt", (0,)))),
        ("command_joints", "string_array", (), RO, (("unique", ()),)),
        (
            "command_interfaces",
            "string_array",
            (),
            RO,
            (
                ("unique", ()),
                ("size_gt", (0,)),
                ("subset_of", (("position", "velocity", "acceleration", "effort"),)),
                ("joint_trajectory_controller::command_interface_type_combinations", ()),
            ),
        ),
        (
            "state_interfaces",
            "string_array",
            (),
            RO,
            (
                ("unique", ()),
                ("size_gt", (0,)),
                ("subset_of", (("position", "velocity", "acceleration"),)),
                ("joint_trajectory_controller::state_interface_type_combinations", ()),
            ),
        ),
        ("speed_scaling.initial_scaling_factor", "double", 1.0, RO, (("gt_eq", (0.0,)),)),
        ("speed_scaling.state_interface", "string", "", RO, ()),
        ("speed_scaling.command_interface", "string", "", RO, ()),
        ("allow_partial_joints_goal", "bool", False, RW, ()),
        ("open_loop_control", "bool", False, RO, ()),
        ("interpolate_from_desired_state", "bool", False, RO, ()),
        ("allow_integration_in_goal_trajectories", "bool", False, RW, ()),
        ("set_last_command_interface_value_as_state_on_activation", "bool", True, RW, ()),
        ("action_monitor_rate", "double", 20.0, RO, (("gt_eq", (0.1,)),)),
        ("interpolation_method", "string", "splines", RO, (("one_of", (("splines", "none"),)),)),
        ("allow_nonzero_velocity_at_trajectory_end", "bool", False, RW, ()),
        ("cmd_timeout", "double", 0.0, RW, ()),
        ("gains.__map_joints.p", "double", 0.0, RW, ()),
        ("gains.__map_joints.i", "double", 0.0, RW, ()),
        ("gains.__map_joints.d", "double", 0.0, RW, ()),
        ("gains.__map_joints.i_clamp", "double", INF, RW, ()),
        ("gains.__map_joints.i_clamp_max", "double", INF, RW, ()),
        ("gains.__map_joints.i_clamp_min", "double", -INF, RW, ()),
        ("gains.__map_joints.ff_velocity_scale", "double", 0.0, RW, ()),
        ("gains.__map_joints.u_clamp_max", "double", INF, RW, ()),
        ("gains.__map_joints.u_clamp_min", "double", -INF, RW, ()),
        (
            "gains.__map_joints.antiwindup_strategy",
            "string",
            "legacy",
            RO,
            (("one_of", (("back_calculation", "conditional_integration", "legacy", "none"),)),),
        ),
        ("gains.__map_joints.tracking_time_constant", "double", 0.0, RW, ()),
        ("gains.__map_joints.error_deadband", "double", 0.0, RW, ()),
        ("constraints.stopped_velocity_tolerance", "double", 0.01, RW, ()),
        ("constraints.goal_time", "double", 0.0, RW, (("gt_eq", (0.0,)),)),
        ("constraints.decelerate_on_cancel", "bool", False, RO, ()),
        ("constraints.__map_joints.trajectory", "double", 0.0, RW, ()),
        ("constraints.__map_joints.goal", "double", 0.0, RW, ()),
        ("constraints.__map_joints.max_deceleration_on_cancel", "double", 0.0, RO, (("gt_eq", (0.0,)),)),
    ),
    # magnetometer_broadcaster/src/magnetometer_broadcaster_parameters.yaml
    "magnetometer_broadcaster": (
        ("sensor_name", "string", "", RO, (("not_empty", ()),)),
        ("frame_id", "string", "", RO, (("not_empty", ()),)),
        (
            "static_covariance",
            "double_array",
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            RO,
            (("fixed_size", (9,)),),
        ),
    ),
    # mecanum_drive_controller/src/mecanum_drive_controller.yaml
    "mecanum_drive_controller": (
        ("reference_timeout", "double", 0.0, RW, ()),
        ("front_left_wheel_command_joint_name", "string", "", RO, (("not_empty", ()),)),
        ("front_right_wheel_command_joint_name", "string", "", RO, (("not_empty", ()),)),
        ("rear_right_wheel_command_joint_name", "string", "", RO, (("not_empty", ()),)),
        ("rear_left_wheel_command_joint_name", "string", "", RO, (("not_empty", ()),)),
        ("front_left_wheel_state_joint_name", "string", "", RO, ()),
        ("front_right_wheel_state_joint_name", "string", "", RO, ()),
        ("rear_right_wheel_state_joint_name", "string", "", RO, ()),
        ("rear_left_wheel_state_joint_name", "string", "", RO, ()),
        ("kinematics.base_frame_offset.x", "double", 0.0, RO, ()),
        ("kinematics.base_frame_offset.y", "double", 0.0, RO, ()),
        ("kinematics.base_frame_offset.theta", "double", 0.0, RO, ()),
        ("kinematics.wheels_radius", "double", 0.0, RO, (("gt", (0.0,)),)),
        ("kinematics.sum_of_robot_center_projection_on_X_Y_axis", "double", 0.0, RO, ()),
        ("tf_frame_prefix_enable", "bool", True, RW, ()),
        ("tf_frame_prefix", "string", "", RO, ()),
        ("base_frame_id", "string", "base_link", RO, ()),
        ("odom_frame_id", "string", "odom", RO, ()),
        ("enable_odom_tf", "bool", True, RW, ()),
        ("twist_covariance_diagonal", "double_array", (0.1, 0.1, 0.1, 0.1, 0.1, 0.1), RO, ()),
        ("pose_covariance_diagonal", "double_array", (0.1, 0.1, 0.1, 0.1, 0.1, 0.1), RO, ()),
        ("linear.x.max_velocity", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.min_velocity", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_acceleration", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_deceleration", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_acceleration_reverse", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_deceleration_reverse", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.max_jerk", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.x.min_jerk", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.y.max_velocity", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.y.min_velocity", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.y.max_acceleration", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.y.max_deceleration", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.y.max_acceleration_reverse", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("linear.y.max_deceleration_reverse", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.y.max_jerk", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("linear.y.min_jerk", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_velocity", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.min_velocity", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_acceleration", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_deceleration", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_acceleration_reverse", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_deceleration_reverse", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.max_jerk", "double", NAN, RW, (("gt_eq_or_nan", (0.0,)),)),
        ("angular.z.min_jerk", "double", NAN, RW, (("lt_eq_or_nan", (0.0,)),)),
    ),
    # motion_primitives_controllers/src/motion_primitives_forward_controller_parameter.yaml
    "motion_primitives_forward_controller": (("tf_prefix", "string", "", RO, ()),),
    # omni_wheel_drive_controller/src/omni_wheel_drive_controller_parameters.yaml
    "omni_wheel_drive_controller": (
        ("wheel_offset", "double", REQUIRED, RO, ()),
        ("wheel_names", "string_array", REQUIRED, RO, (("not_empty", ()),)),
        ("robot_radius", "double", REQUIRED, RO, (("gt", (0.0,)),)),
        ("wheel_radius", "double", REQUIRED, RO, (("gt", (0.0,)),)),
        ("tf_frame_prefix_enable", "bool", True, RO, ()),
        ("tf_frame_prefix", "string", "", RO, ()),
        ("odom_frame_id", "string", "odom", RO, ()),
        ("base_frame_id", "string", "base_link", RO, ()),
        ("diagonal_covariance.pose", "double_array", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), RO, ()),
        ("diagonal_covariance.twist", "double_array", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), RO, ()),
        ("open_loop", "bool", False, RO, ()),
        ("position_feedback", "bool", True, RO, ()),
        ("enable_odom_tf", "bool", True, RO, ()),
        ("cmd_vel_timeout", "double", 0.5, RO, ()),
    ),
    # parallel_gripper_controller/src/gripper_action_controller_parameters.yaml
    "parallel_gripper_action_controller": (
        ("action_monitor_rate", "double", 20.0, RO, (("gt_eq", (0.1,)),)),
        ("joint", "string", REQUIRED, RO, (("not_empty", ()),)),
        ("state_interfaces", "string_array", ("position", "velocity"), RW, ()),
        ("goal_tolerance", "double", 0.01, RW, (("gt_eq", (0.0,)),)),
        ("allow_stalling", "bool", False, RW, ()),
        ("stall_velocity_threshold", "double", 0.001, RW, ()),
        ("stall_timeout", "double", 1.0, RW, (("gt_eq", (0.0,)),)),
        ("max_effort_interface", "string", "", RW, ()),
        ("max_effort", "double", 10.0, RW, (("gt_eq", (0.0,)),)),
        ("max_velocity_interface", "string", "", RW, ()),
        ("max_velocity", "double", 0.1, RW, (("gt_eq", (0.0,)),)),
    ),
    # pid_controller/src/pid_controller.yaml
    "pid_controller": (
        ("dof_names", "string_array", (), RO, (("unique", ()), ("not_empty", ()))),
        ("reference_and_state_dof_names", "string_array", (), RO, (("unique", ()),)),
        ("command_interface", "string", "", RO, (("not_empty", ()),)),
        (
            "reference_and_state_interfaces",
            "string_array",
            (),
            RO,
            (("not_empty", ()), ("size_gt", (0,)), ("size_lt", (3,))),
        ),
        ("set_current_state_as_first_setpoint", "bool", True, RO, ()),
        ("use_external_measured_states", "bool", False, RW, ()),
        ("enable_feedforward", "bool", False, RW, ()),
        ("gains.__map_dof_names.p", "double", 0.0, RW, ()),
        ("gains.__map_dof_names.i", "double", 0.0, RW, ()),
        ("gains.__map_dof_names.d", "double", 0.0, RW, ()),
        ("gains.__map_dof_names.u_clamp_max", "double", INF, RW, ()),
        ("gains.__map_dof_names.u_clamp_min", "double", -INF, RW, ()),
        ("gains.__map_dof_names.antiwindup", "bool", False, RW, ()),
        ("gains.__map_dof_names.i_clamp_max", "double", INF, RW, ()),
        ("gains.__map_dof_names.i_clamp_min", "double", -INF, RW, ()),
        (
            "gains.__map_dof_names.antiwindup_strategy",
            "string",
            "legacy",
            RW,
            (("one_of", (("back_calculation", "conditional_integration", "legacy", "none"),)),),
        ),
        ("gains.__map_dof_names.tracking_time_constant", "double", 0.0, RW, ()),
        ("gains.__map_dof_names.error_deadband", "double", 1e-16, RW, ()),
        ("gains.__map_dof_names.feedforward_gain", "double", 0.0, RW, ()),
        ("gains.__map_dof_names.angle_wraparound", "bool", False, RW, ()),
        ("gains.__map_dof_names.save_i_term", "bool", True, RW, ()),
        ("gains.__map_dof_names.activate_state_publisher", "bool", False, RW, ()),
    ),
    # pose_broadcaster/src/pose_broadcaster_parameters.yaml
    "pose_broadcaster": (
        ("frame_id", "string", "", RW, (("not_empty", ()),)),
        ("pose_name", "string", "", RW, (("not_empty", ()),)),
        ("tf.enable", "bool", True, RW, ()),
        ("tf.child_frame_id", "string", "", RW, ()),
        ("tf.publish_rate", "double", 0.0, RW, (("gt_eq", (0.0,)),)),
    ),
    # range_sensor_broadcaster/src/range_sensor_broadcaster_parameters.yaml
    "range_sensor_broadcaster": (
        ("sensor_name", "string", "", RW, ()),
        ("frame_id", "string", "", RW, ()),
        ("radiation_type", "int", 0, RW, ()),
        ("field_of_view", "double", 0.52, RW, ()),
        ("min_range", "double", 0.52, RW, ()),
        ("max_range", "double", 4.0, RW, ()),
        ("variance", "double", 0.0, RW, ()),
    ),
    # state_interfaces_broadcaster/src/state_interfaces_broadcaster_parameters.yaml
    "state_interfaces_broadcaster": (("interfaces", "string_array", (), RO, (("not_empty", ()),)),),
    # steering_controllers_library/src/steering_controllers_library.yaml
    "steering_controllers_library": (
        ("reference_timeout", "double", 1.0, RW, ()),
        ("front_steering", "bool", True, RO, ()),
        ("rear_wheels_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("traction_joints_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("front_wheels_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("steering_joints_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("traction_joints_state_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("rear_wheels_state_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("steering_joints_state_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("front_wheels_state_names", "string_array", (), RO, (("size_lt", (5,)), ("unique", ()))),
        ("open_loop", "bool", False, RW, ()),
        ("reduce_wheel_speed_until_steering_reached", "bool", False, RW, ()),
        ("velocity_rolling_window_size", "int", 10, RW, ()),
        ("base_frame_id", "string", "base_link", RW, ()),
        ("odom_frame_id", "string", "odom", RW, ()),
        ("enable_odom_tf", "bool", True, RW, ()),
        ("twist_covariance_diagonal", "double_array", (0.0, 7.0, 14.0, 21.0, 28.0, 35.0), RW, ()),
        ("pose_covariance_diagonal", "double_array", (0.0, 7.0, 14.0, 21.0, 28.0, 35.0), RW, ()),
        ("position_feedback", "bool", False, RW, ()),
    ),
    # tricycle_controller/src/tricycle_controller_parameter.yaml
    "tricycle_controller": (
        ("traction_joint_name", "string", "", RW, (("not_empty", ()),)),
        ("steering_joint_name", "string", "", RW, (("not_empty", ()),)),
        ("wheelbase", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("wheel_radius", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("odom_frame_id", "string", "odom", RW, ()),
        ("base_frame_id", "string", "base_link", RW, ()),
        ("pose_covariance_diagonal", "double_array", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), RW, ()),
        ("twist_covariance_diagonal", "double_array", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), RW, ()),
        ("open_loop", "bool", False, RW, ()),
        ("enable_odom_tf", "bool", False, RW, ()),
        ("odom_only_twist", "bool", False, RW, ()),
        ("cmd_vel_timeout", "int", 500, RW, ()),
        ("publish_ackermann_command", "bool", False, RW, ()),
        ("velocity_rolling_window_size", "int", 10, RW, (("gt", (0,)),)),
        ("traction.max_velocity", "double", NAN, RW, ()),
        ("traction.min_velocity", "double", NAN, RW, ()),
        ("traction.max_acceleration", "double", NAN, RW, ()),
        ("traction.min_acceleration", "double", NAN, RW, ()),
        ("traction.max_deceleration", "double", NAN, RW, ()),
        ("traction.min_deceleration", "double", NAN, RW, ()),
        ("traction.max_jerk", "double", NAN, RW, ()),
        ("traction.min_jerk", "double", NAN, RW, ()),
        ("steering.max_position", "double", NAN, RW, ()),
        ("steering.min_position", "double", NAN, RW, ()),
        ("steering.max_velocity", "double", NAN, RW, ()),
        ("steering.min_velocity", "double", NAN, RW, ()),
        ("steering.max_acceleration", "double", NAN, RW, ()),
        ("steering.min_acceleration", "double", NAN, RW, ()),
    ),
    # tricycle_steering_controller/src/tricycle_steering_controller.yaml
    "tricycle_steering_controller": (
        ("wheel_track", "double", 0.0, RW, ()),
        ("traction_track_width", "double", 0.0, RW, ()),
        ("wheelbase", "double", 0.0, RW, (("gt", (0.0,)),)),
        ("traction_wheels_radius", "double", 0.0, RW, ()),
        ("front_wheels_radius", "double", 0.0, RW, ()),
        ("rear_wheels_radius", "double", 0.0, RW, ()),
    ),
}
# namespace -> (package, file under its src/)
SOURCES: dict[str, tuple[str, str]] = {
    "ackermann_steering_controller": ("ackermann_steering_controller", "ackermann_steering_controller.yaml"),
    "admittance_controller": ("admittance_controller", "admittance_controller_parameters.yaml"),
    "battery_state_broadcaster": ("battery_state_broadcaster", "battery_state_broadcaster_parameters.yaml"),
    "bicycle_steering_controller": ("bicycle_steering_controller", "bicycle_steering_controller.yaml"),
    "chained_filter": ("chained_filter_controller", "chained_filter_parameters.yaml"),
    "diff_drive_controller": ("diff_drive_controller", "diff_drive_controller_parameter.yaml"),
    "force_torque_sensor_broadcaster": (
        "force_torque_sensor_broadcaster",
        "force_torque_sensor_broadcaster_parameters.yaml",
    ),
    "forward_command_controller": ("forward_command_controller", "forward_command_controller_parameters.yaml"),
    "multi_interface_forward_command_controller": (
        "forward_command_controller",
        "multi_interface_forward_command_controller_parameters.yaml",
    ),
    "gpio_command_controller_parameters": ("gpio_controllers", "gpio_command_controller_parameters.yaml"),
    "gps_sensor_broadcaster": ("gps_sensor_broadcaster", "gps_sensor_broadcaster_parameters.yaml"),
    "gripper_action_controller": ("gripper_controllers", "gripper_action_controller_parameters.yaml"),
    "imu_sensor_broadcaster": ("imu_sensor_broadcaster", "imu_sensor_broadcaster_parameters.yaml"),
    "joint_state_broadcaster": ("joint_state_broadcaster", "joint_state_broadcaster_parameters.yaml"),
    "joint_trajectory_controller": ("joint_trajectory_controller", "joint_trajectory_controller_parameters.yaml"),
    "magnetometer_broadcaster": ("magnetometer_broadcaster", "magnetometer_broadcaster_parameters.yaml"),
    "mecanum_drive_controller": ("mecanum_drive_controller", "mecanum_drive_controller.yaml"),
    "motion_primitives_forward_controller": (
        "motion_primitives_controllers",
        "motion_primitives_forward_controller_parameter.yaml",
    ),
    "omni_wheel_drive_controller": ("omni_wheel_drive_controller", "omni_wheel_drive_controller_parameters.yaml"),
    "parallel_gripper_action_controller": ("parallel_gripper_controller", "gripper_action_controller_parameters.yaml"),
    "pid_controller": ("pid_controller", "pid_controller.yaml"),
    "pose_broadcaster": ("pose_broadcaster", "pose_broadcaster_parameters.yaml"),
    "range_sensor_broadcaster": ("range_sensor_broadcaster", "range_sensor_broadcaster_parameters.yaml"),
    "state_interfaces_broadcaster": ("state_interfaces_broadcaster", "state_interfaces_broadcaster_parameters.yaml"),
    "steering_controllers_library": ("steering_controllers_library", "steering_controllers_library.yaml"),
    "tricycle_controller": ("tricycle_controller", "tricycle_controller_parameter.yaml"),
    "tricycle_steering_controller": ("tricycle_steering_controller", "tricycle_steering_controller.yaml"),
}
# --- END GENERATED ---

# -- written by hand ---------------------------------------------------------------------------

# Parameters every controller node has besides its GPL file's.
NODE_PARAMS: Defs = (
    # rclcpp (jazzy) Node: TimeSource and the type description service
    ("use_sim_time", "bool", False, RW, ()),
    ("start_type_description_service", "bool", True, RO, ()),
    ("qos_overrides", "none", REQUIRED, RW, ()),  # rclcpp QoS overrides: qos_overrides./topic.publisher.depth ...
    # ros2_control jazzy controller_interface/src/controller_interface_base.cpp, init(): auto_declare
    # update_rate (default: the controller manager's; "Update rate cannot be a negative value!" at configure),
    # is_async, thread_priority; realtime_tools' AsyncFunctionHandlerParams read "async_parameters.*"
    ("update_rate", "int", 0, RW, (("gt_eq", (0,)),)),
    ("is_async", "bool", False, RW, ()),
    ("thread_priority", "int", -100, RW, ()),
    ("async_parameters", "none", REQUIRED, RW, ()),
    # ros2_control jazzy controller_manager/controller_manager/controller_manager_services.py,
    # set_controller_parameters_from_param_files: the spawner reads these from the controller's own entry
    ("type", "string", "", RO, ()),
    ("fallback_controllers", "string_array", (), RO, ()),
)

EXTRA: dict[str, Defs] = {
    # gripper_controllers/include/gripper_controllers/hardware_interface_adapter.hpp (jazzy), the effort
    # adapter's init(): declare_parameter<double>("gains.<joint>.p" ...) for its PID
    "effort_gripper_gains": (
        ("gains.__map_joint.p", "double", 0.0, RW, ()),
        ("gains.__map_joint.i", "double", 0.0, RW, ()),
        ("gains.__map_joint.d", "double", 0.0, RW, ()),
        ("gains.__map_joint.i_clamp", "double", 0.0, RW, ()),
    ),
    # ros-controls/control_toolbox jazzy @05de3c67 control_toolbox/src/pid_ros.cpp: PidROS (which
    # pid_controller makes per dof with prefix "gains.<dof>") also reads "saturation"
    "pid_ros": (("gains.__map_dof_names.saturation", "bool", True, RW, ()),),
}

# controller type (as a controllers YAML names it) -> the GPL files (namespaces above) it reads.
# The plugin names are those of each package's plugin XML on jazzy.
TYPES: dict[str, tuple[str, ...]] = {
    "joint_state_broadcaster/JointStateBroadcaster": ("joint_state_broadcaster",),
    "joint_trajectory_controller/JointTrajectoryController": ("joint_trajectory_controller",),
    "diff_drive_controller/DiffDriveController": ("diff_drive_controller",),
    "forward_command_controller/ForwardCommandController": ("forward_command_controller",),
    "forward_command_controller/MultiInterfaceForwardCommandController": (
        "multi_interface_forward_command_controller",
    ),
    # JointGroup*Controller are ForwardCommandControllers that set interface_name themselves
    "position_controllers/JointGroupPositionController": ("forward_command_controller",),
    "velocity_controllers/JointGroupVelocityController": ("forward_command_controller",),
    "effort_controllers/JointGroupEffortController": ("forward_command_controller",),
    "position_controllers/GripperActionController": ("gripper_action_controller",),
    "effort_controllers/GripperActionController": ("gripper_action_controller", "effort_gripper_gains"),
    "parallel_gripper_action_controller/GripperActionController": ("parallel_gripper_action_controller",),
    "imu_sensor_broadcaster/IMUSensorBroadcaster": ("imu_sensor_broadcaster",),
    "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster": ("force_torque_sensor_broadcaster",),
    "ackermann_steering_controller/AckermannSteeringController": (
        "steering_controllers_library",
        "ackermann_steering_controller",
    ),
    "bicycle_steering_controller/BicycleSteeringController": (
        "steering_controllers_library",
        "bicycle_steering_controller",
    ),
    "tricycle_steering_controller/TricycleSteeringController": (
        "steering_controllers_library",
        "tricycle_steering_controller",
    ),
    "tricycle_controller/TricycleController": ("tricycle_controller",),
    "mecanum_drive_controller/MecanumDriveController": ("mecanum_drive_controller",),
    "omni_wheel_drive_controller/OmniWheelDriveController": ("omni_wheel_drive_controller",),
    "admittance_controller/AdmittanceController": ("admittance_controller",),
    "pid_controller/PidController": ("pid_controller", "pid_ros"),
    "chained_filter_controller/ChainedFilter": ("chained_filter",),
    "gpio_controllers/GpioCommandController": ("gpio_command_controller_parameters",),
    "battery_state_broadcaster/BatteryStateBroadcaster": ("battery_state_broadcaster",),
    "gps_sensor_broadcaster/GPSSensorBroadcaster": ("gps_sensor_broadcaster",),
    "magnetometer_broadcaster/MagnetometerBroadcaster": ("magnetometer_broadcaster",),
    "pose_broadcaster/PoseBroadcaster": ("pose_broadcaster",),
    "range_sensor_broadcaster/RangeSensorBroadcaster": ("range_sensor_broadcaster",),
    "state_interfaces_broadcaster/StateInterfacesBroadcaster": ("state_interfaces_broadcaster",),
    "motion_primitives_controllers/MotionPrimitivesForwardController": ("motion_primitives_forward_controller",),
}

RetiredKind = Literal["removed", "ignored", "deprecated"]


@record
class Retired:
    """A parameter name a controller no longer reads as written (``removed``: Jazzy does not
    declare it; ``ignored``: declared but never read, or overwritten by the controller) or
    reads with a deprecation warning (``deprecated``: gone in Kilted)."""

    name: str  # dotted; a "__map_<key>" segment stands for any one name
    kind: RetiredKind
    since: str  # when (release, PR) and how: "removed in 4.0.0 (#812)", "deprecated since ...", why it is ignored
    use: str  # what to write instead
    source: str  # where the fact is written (paths at ros2_controllers jazzy unless said)
    value: object = None  # "ignored" only when the value is not this one (None: any value)


_MIGRATION = "doc/migration.rst"
_NOTES = "doc/release_notes.rst"
_NAN_LIMIT = "leave it out: Jazzy disables a limit whose value is .nan (the default)"

# keyed by a GPL namespace of PARAMETER_FILES (every type reading that file) or by a controller type
RETIRED: dict[str, tuple[Retired, ...]] = {
    "diff_drive_controller": (
        Retired(
            "use_stamped_vel",
            "removed",
            "removed in 4.0.0 (#812)",
            "nothing: ~/cmd_vel takes geometry_msgs/msg/TwistStamped only; publish stamped twists",
            f"{_MIGRATION} diff_drive_controller; diff_drive_controller/CHANGELOG.rst 4.0.0",
        ),
        Retired(
            "wheels_per_side",
            "removed",
            "removed in 4.5.0 (#958)",
            "nothing: the wheels are those listed in left_wheel_names and right_wheel_names",
            f"{_NOTES} diff_drive_controller; diff_drive_controller/CHANGELOG.rst 4.5.0",
        ),
        *(
            Retired(
                f"{axis}.min_acceleration",
                "ignored",
                "declared but never read since 4.18.0 (#1315)",
                f"{axis}.max_deceleration (a value <= 0, as min_acceleration was)",
                "diff_drive_controller/src/diff_drive_controller_parameter.yaml ('deprecated, use "
                "max_deceleration'); diff_drive_controller.cpp never reads it",
            )
            for axis in ("linear.x", "angular.z")
        ),
        *(
            Retired(
                f"{axis}.{flag}",
                "deprecated",
                "deprecated since 4.18.0 (#1315)",
                _NAN_LIMIT,
                f"{_MIGRATION} diff_drive_controller (says removed; Jazzy still declares it and warns: "
                "diff_drive_controller.cpp on_configure)",
            )
            for axis in ("linear.x", "angular.z")
            for flag in ("has_velocity_limits", "has_acceleration_limits", "has_jerk_limits")
        ),
    ),
    "joint_trajectory_controller": (
        Retired(
            "state_publish_rate",
            "removed",
            "removed in 3.3.0 (#520)",
            "nothing: the state is published every update (the controller's update_rate)",
            "joint_trajectory_controller/CHANGELOG.rst 3.3.0",
        ),
        Retired(
            "start_with_holding",
            "removed",
            "removed in 4.1.0 (#839)",
            "nothing: Jazzy's JTC always holds the position at activation",
            f"{_MIGRATION} joint_trajectory_controller; joint_trajectory_controller/CHANGELOG.rst 4.1.0",
        ),
        Retired(
            "gains.__map_joints.normalize_error",
            "removed",
            "removed in 4.0.0 (#834)",
            "nothing: make the joint continuous in the URDF and the JTC wraps its angle",
            "joint_trajectory_controller/CHANGELOG.rst 4.0.0",
        ),
        Retired(
            "gains.__map_joints.angle_wraparound",
            "removed",
            "removed in 4.10.0 (#1152)",
            "make the joint continuous in the URDF: the JTC wraps the angles of continuous joints itself (#949)",
            f"{_MIGRATION} and {_NOTES} joint_trajectory_controller",
        ),
        Retired(
            "open_loop_control",
            "deprecated",
            "deprecated since 4.22.0 (#1525)",
            "interpolate_from_desired_state: true, with the feedback gains set to zero",
            f"{_MIGRATION} joint_trajectory_controller; joint_trajectory_controller.cpp on_configure",
        ),
        Retired(
            "gains.__map_joints.i_clamp",
            "deprecated",
            "deprecated since 4.33.1 (#1959)",
            "gains.<joint>.i_clamp_max and i_clamp_min",
            "joint_trajectory_controller_parameters.yaml; joint_trajectory_controller.cpp update_pids",
        ),
    ),
    "steering_controllers_library": (
        Retired(
            "use_stamped_vel",
            "removed",
            "removed in 4.10.0 (#1151)",
            "nothing: ~/reference takes geometry_msgs/msg/TwistStamped only",
            "steering_controllers_library/CHANGELOG.rst 4.10.0",
        ),
        Retired(
            "front_steering",
            "deprecated",
            "deprecated since 4.24.0 (#1166)",
            "traction_joints_names and steering_joints_names",
            f"{_MIGRATION} steering_controllers_library (says removed; Jazzy still reads it and warns: "
            "steering_controllers_library.cpp on_configure)",
        ),
        *(
            Retired(
                f"{end}_wheels{state}_names",
                "deprecated",
                "deprecated since 4.24.0 (#1166)",
                f"traction_joints{state}_names or steering_joints{state}_names",
                f"{_MIGRATION} steering_controllers_library; steering_controllers_library.cpp on_configure",
            )
            for end in ("front", "rear")
            for state in ("", "_state")
        ),
    ),
    "ackermann_steering_controller": (
        *(
            Retired(
                f"{end}_wheel_track",
                "deprecated",
                "deprecated since 4.24.0 (#1166)",
                "traction_track_width (and steering_track_width when it differs)",
                f"{_MIGRATION} steering_controllers_library; ackermann_steering_controller.cpp",
            )
            for end in ("front", "rear")
        ),
        *(
            Retired(
                f"{end}_wheels_radius",
                "deprecated",
                "deprecated since 4.24.0 (#1166)",
                "traction_wheels_radius",
                f"{_MIGRATION} steering_controllers_library; ackermann_steering_controller.cpp",
            )
            for end in ("front", "rear")
        ),
    ),
    "bicycle_steering_controller": tuple(
        Retired(
            f"{end}_wheel_radius",
            "deprecated",
            "deprecated since 4.24.0 (#1166)",
            "traction_wheel_radius",
            f"{_MIGRATION} steering_controllers_library; bicycle_steering_controller.cpp",
        )
        for end in ("front", "rear")
    ),
    "tricycle_steering_controller": (
        Retired(
            "wheel_track",
            "deprecated",
            "deprecated since 4.24.0 (#1166)",
            "traction_track_width",
            "tricycle_steering_controller.yaml; tricycle_steering_controller.cpp",
        ),
        *(
            Retired(
                f"{end}_wheels_radius",
                "deprecated",
                "deprecated since 4.24.0 (#1166)",
                "traction_wheels_radius",
                f"{_MIGRATION} steering_controllers_library; tricycle_steering_controller.cpp",
            )
            for end in ("front", "rear")
        ),
    ),
    "tricycle_controller": (
        Retired(
            "use_stamped_vel",
            "removed",
            "removed in 4.10.0 (#1151)",
            "nothing: ~/cmd_vel takes geometry_msgs/msg/TwistStamped only",
            "tricycle_controller/CHANGELOG.rst 4.10.0",
        ),
    ),
    "mecanum_drive_controller": (
        Retired(
            "use_stamped_vel",
            "removed",
            "not in Jazzy's version of the controller (Humble's backport has it)",
            "nothing: ~/reference takes geometry_msgs/msg/TwistStamped only",
            "mecanum_drive_controller/src/mecanum_drive_controller.yaml, humble vs jazzy",
        ),
    ),
    "admittance_controller": (
        Retired(
            "robot_description",
            "removed",
            "removed in 4.3.0 (#963)",
            "nothing: the controller manager hands the controller the URDF",
            f"{_NOTES} admittance_controller",
        ),
    ),
    "pid_controller": (
        Retired(
            "enable_feedforward",
            "deprecated",
            "deprecated since 4.25.0 (#1553)",
            "gains.<dof>.feedforward_gain (zero or not)",
            f"{_MIGRATION} pid_controller",
        ),
        # the jazzy file also calls gains.<dof>.i_clamp_max/i_clamp_min deprecated, but PidROS (control_toolbox
        # jazzy, pid_ros.cpp) uses them as every anti-windup strategy's integral limits, and kilted's file
        # no longer says deprecated: not listed
        Retired(
            "gains.__map_dof_names.antiwindup",
            "deprecated",
            "deprecated since 4.27.0 (#1585)",
            "gains.<dof>.antiwindup_strategy (with i_clamp_max/i_clamp_min as its limits)",
            f"{_MIGRATION} pid_controller",
        ),
    ),
    "pose_broadcaster": (
        Retired(
            "tf.publish_rate",
            "deprecated",
            "deprecated since 4.24.0 (#1614)",
            "leave it out (0.0): tf is not to be rate-limited",
            "pose_broadcaster/src/pose_broadcaster.cpp on_configure",
        ),
    ),
    "battery_state_broadcaster": (
        Retired(
            "sensor_name",
            "deprecated",
            "deprecated since 4.42.0 (#2086)",
            "batteries and interfaces.<battery>.*",
            "battery_state_broadcaster/src/battery_state_broadcaster.cpp on_configure",
        ),
    ),
    **{
        f"{group}_controllers/JointGroup{group.title()}Controller": (
            Retired(
                "interface_name",
                "ignored",
                f"the controller sets it to '{group}' itself at on_init",
                f"leave it out: JointGroup{group.title()}Controller commands '{group}' whatever the file says",
                f"{group}_controllers/src/joint_group_{group}_controller.cpp on_init (set_parameter)",
                value=group,
            ),
        )
        for group in ("position", "velocity", "effort")
    },
}


# -- the definitions of one controller type ---------------------------------------------------


@record
class ParamDef:
    name: str  # concrete, or a pattern with "__map_<key>" segments
    type: str  # GPL's: bool, int, double, string, *_array, none (an open namespace)
    default: object  # REQUIRED: none
    read_only: bool
    checks: tuple[Check, ...]
    source: str  # the GPL file, or what declares it

    @property
    def required(self) -> bool:
        """GPL refuses the controller when this is not set: no default, or a default that
        fails its own validators (``not_empty`` with ``""``, ``gt 0`` with ``0.0``)."""
        if self.type == "none":
            return False
        return self.default is REQUIRED or bool(violations(self, self.default))


def known(ctype: str) -> bool:
    """Whether descgen has Jazzy's parameter definitions of this controller type."""
    return ctype in TYPES


def _defs(ctype: str) -> tuple[ParamDef, ...]:
    out = [ParamDef(*e, source="controller node") for e in NODE_PARAMS]
    for key in TYPES.get(ctype, ()):
        package, file = SOURCES.get(key, (key, ""))
        source = f"{package}/src/{file}" if file else key
        out += [ParamDef(*e, source=source) for e in PARAMETER_FILES.get(key, EXTRA.get(key, ()))]
    return tuple(out)


_DEFS: dict[str, tuple[ParamDef, ...]] = {}


def definitions(ctype: str) -> tuple[ParamDef, ...]:
    """Every parameter ``ctype`` declares (its node's own first); () for an unknown type."""
    if ctype not in TYPES:
        return ()
    if ctype not in _DEFS:
        _DEFS[ctype] = _defs(ctype)
    return _DEFS[ctype]


def retired(ctype: str) -> tuple[Retired, ...]:
    keys = (*TYPES.get(ctype, ()), ctype)
    return tuple(r for k in keys for r in RETIRED.get(k, ()))


# -- parameters as ROS names them ---------------------------------------------------------------


def _pairs(value: object) -> TypeGuard[tuple[tuple[str, object], ...]]:
    """A nested mapping as the model keeps it: a tuple of (name, value) pairs."""
    return (
        isinstance(value, tuple)
        and bool(value)
        and all(isinstance(x, tuple) and len(x) == 2 and isinstance(x[0], str) for x in value)
    )


def flatten(params: Iterable[tuple[str, object]]) -> tuple[tuple[str, object], ...]:
    """A controller's parameters with ROS's dotted names: nested mappings (``linear: {x:
    {max_velocity: 1.0}}``) and names written with dots (``linear.x.max_velocity: 1.0``) give
    the same name. Values stay as they are (a list is a tuple)."""
    out: list[tuple[str, object]] = []

    def walk(name: str, value: object) -> None:
        if isinstance(value, Mapping):
            for k, v in value.items():
                walk(f"{name}.{k}", v)
        elif _pairs(value):
            for k, v in value:
                walk(f"{name}.{k}", v)
        else:
            out.append((name, value))

    for k, v in params:
        walk(str(k), v)
    return tuple(out)


def _names(value: object) -> list[str]:
    """A map's keys: the values of its key parameter (a list, or one name)."""
    items = value if isinstance(value, tuple | list) else () if value in (None, "") else (value,)
    return [str(x) for x in items if isinstance(x, str) and not unresolved(x)]


class Definitions:
    """One controller's parameter definitions with its ``__map_`` names expanded over the
    values it is given (its defaults else)."""

    def __init__(self, ctype: str, given: Mapping[str, object]) -> None:
        self.ctype = ctype
        self.defs = definitions(ctype)
        plain = {d.name: d for d in self.defs if "__map_" not in d.name}
        self.concrete: dict[str, ParamDef] = {}
        self.wild: list[tuple[re.Pattern[str], ParamDef]] = []  # a map whose keys are not known
        self.open: list[re.Pattern[str]] = []  # "none" namespaces
        for d in self.defs:
            parts = d.name.split(".")
            keys = [p.removeprefix("__map_") for p in parts if p.startswith("__map_")]
            values, partial = [], False
            for key in keys:
                raw = given.get(key, plain[key].default if key in plain else None)
                values.append(_names(raw))
                partial |= any(unresolved(x) for x in (raw if isinstance(raw, tuple | list) else (raw,)))
            if all(values):
                for combo in itertools.product(*values):
                    it = iter(combo)
                    name = ".".join(next(it) if p.startswith("__map_") else p for p in parts)
                    self._add(name, d)
            if partial or not all(values):  # a key not known (or written as a launch substitution): any name
                self.wild.append((_pattern(parts), d))
                if d.type == "none":
                    self.open.append(_pattern(parts, namespace=True))

    def _add(self, name: str, d: ParamDef) -> None:
        if d.type == "none":
            self.open.append(re.compile(re.escape(name) + r"(\..+)?"))
        else:
            self.concrete.setdefault(name, d)

    def lookup(self, name: str) -> ParamDef | None:
        """The definition of a given parameter name; None when the type does not declare it
        (a name in an open namespace is declared, with type ``none``)."""
        d = self.concrete.get(name)
        if d is not None:
            return d
        for rx, wd in self.wild:
            if rx.fullmatch(name):
                return wd
        if any(rx.fullmatch(name) for rx in self.open):
            return ParamDef(name, "none", REQUIRED, RW, (), "open namespace")
        return None

    def nearest(self, name: str) -> str | None:
        """The declared name closest to ``name`` (a typo's intent), if any is close."""
        close = difflib.get_close_matches(name, list(self.concrete), n=1, cutoff=0.75)
        return close[0] if close else None

    def missing(self, given: Mapping[str, object]) -> list[tuple[str, ParamDef]]:
        """Required parameters (``ParamDef.required``) that are not given."""
        return [(n, d) for n, d in self.concrete.items() if n not in given and d.required]


def _pattern(parts: list[str], namespace: bool = False) -> re.Pattern[str]:
    body = r"\.".join(r"[^.]+" if p.startswith("__map_") else re.escape(p) for p in parts)
    return re.compile(body + (r"(\..+)?" if namespace else ""))


def retired_match(ctype: str, name: str, value: object) -> Retired | None:
    """The retired-name fact that applies to parameter ``name`` given ``value``, if any."""
    for r in retired(ctype):
        if not _pattern(r.name.split(".")).fullmatch(name):
            continue
        if r.kind == "ignored" and r.value is not None and value == r.value:
            continue  # overwritten with the value the file gives: harmless
        return r
    return None


# -- types and values -----------------------------------------------------------------------

_SCALARS: dict[str, type] = {"bool": bool, "int": int, "double": float, "string": str}
ROS_TYPE = {"bool": "bool", "int": "integer", "double": "double", "string": "string"}
_PY_TYPE = {bool: "bool", int: "integer", float: "double", str: "string"}


def _base(gpl_type: str) -> str:
    return re.sub(r"_fixed_\d+$", "", gpl_type)


def type_name(gpl_type: str) -> str:
    """A GPL type as rclcpp names it ("int" -> "integer", "double_array")."""
    base = _base(gpl_type)
    if base.endswith("_array"):
        return f"{ROS_TYPE.get(base.removesuffix('_array'), base)}_array"
    return ROS_TYPE.get(base, base)


def value_type(value: object) -> str:
    """The rcl type of a value as read from a parameter file ("integer", "double_array")."""
    if isinstance(value, tuple | list):
        kinds = {_PY_TYPE.get(type(x), type(x).__name__) for x in value}
        return f"{kinds.pop()}_array" if len(kinds) == 1 else "empty list" if not kinds else "mixed list"
    return _PY_TYPE.get(type(value), type(value).__name__)


def type_ok(gpl_type: str, value: object) -> bool:
    """Whether rclcpp gives GPL this value as the declared type: rcl's types must agree
    exactly (an integer is not a double); an empty list fits any array; a value that is
    still a launch substitution is not judged."""
    base = _base(gpl_type)
    if base == "none" or unresolved(value):
        return True
    if base.endswith("_array"):
        want = _SCALARS.get(base.removesuffix("_array"))
        if not isinstance(value, tuple | list):
            return False
        return want is None or all(type(x) is want or unresolved(x) for x in value)
    want = _SCALARS.get(base)
    return want is None or type(value) is want


def _num(v: object) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None


def _len(v: object) -> int | None:
    return len(v) if isinstance(v, str | tuple | list) else None


def _fmt(v: object) -> str:
    if isinstance(v, tuple | list):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    if isinstance(v, float):
        return f"{v:g}"
    return str(v)


@record
class Violation:
    want: str  # what the validator asks, e.g. "must be > 0"
    found: str = ""  # what the value is instead, e.g. "it is 0"
    index: int | None = None  # the list item that fails, when one does

    @property
    def message(self) -> str:
        return f"{self.want} ({self.found})" if self.found else self.want


def _compare(check: str, value: float, bound: float) -> bool:
    return {
        "gt": value > bound,
        "gt_eq": value >= bound,
        "lt": value < bound,
        "lt_eq": value <= bound,
    }[check]


_OPS = {"gt": ">", "gt_eq": ">=", "lt": "<", "lt_eq": "<="}


def _check(name: str, args: tuple[object, ...], value: object) -> Iterator[Violation]:
    n = _num(value)
    size = _len(value)
    items = list(value) if isinstance(value, tuple | list) else []
    base = name.removesuffix("_or_nan")
    if base in _OPS and args and n is not None and _num(args[0]) is not None:
        if name.endswith("_or_nan") and math.isnan(n):
            return
        if not _compare(base, n, float(args[0])):  # type: ignore[arg-type]
            nan = " or .nan" if name.endswith("_or_nan") else ""
            yield Violation(f"must be {_OPS[base]} {_fmt(args[0])}{nan}", f"it is {_fmt(value)}")
    elif name == "bounds" and len(args) == 2 and n is not None:
        if not float(args[0]) <= n <= float(args[1]):  # type: ignore[arg-type]
            yield Violation(f"must be within [{_fmt(args[0])}, {_fmt(args[1])}]", f"it is {_fmt(value)}")
    elif name in ("element_bounds", "lower_element_bounds", "upper_element_bounds") and args:
        lo = float(args[0]) if name != "upper_element_bounds" else -INF  # type: ignore[arg-type]
        hi = float(args[-1]) if name != "lower_element_bounds" else INF  # type: ignore[arg-type]
        for i, x in enumerate(items):
            xn = _num(x)
            if xn is not None and not lo <= xn <= hi:
                yield Violation(f"item {_fmt(x)} must be within [{_fmt(lo)}, {_fmt(hi)}]", index=i)
    elif name == "one_of" and args and isinstance(args[0], tuple) and not isinstance(value, tuple | list):
        if value not in args[0] and not unresolved(value):
            yield Violation(f"must be one of {', '.join(map(str, args[0]))}", f"it is {_fmt(value)}")
    elif name == "subset_of" and args and isinstance(args[0], tuple):
        for i, x in enumerate(items):
            if x not in args[0] and not unresolved(x):
                yield Violation(f"item '{x}' is not one of {', '.join(map(str, args[0]))}", index=i)
    elif name == "fixed_size" and args and size is not None and size != args[0]:
        yield Violation(f"must have {_fmt(args[0])} items", f"it has {size}")
    elif name == "size_gt" and args and size is not None and not size > args[0]:  # type: ignore[operator]
        yield Violation(f"must have more than {_fmt(args[0])} items", f"it has {size}")
    elif name == "size_lt" and args and size is not None and not size < args[0]:  # type: ignore[operator]
        yield Violation(f"must have fewer than {_fmt(args[0])} items", f"it has {size}")
    elif name == "not_empty" and size == 0:
        yield Violation("must not be empty")
    elif name == "unique":
        seen: set[object] = set()
        for i, x in enumerate(items):
            if x in seen:
                yield Violation(f"lists '{x}' twice", index=i)
            seen.add(x)
    elif name == "joint_trajectory_controller::command_interface_type_combinations":
        yield from (Violation(m) for m in _jtc_commands([str(x) for x in items]))
    elif name == "joint_trajectory_controller::state_interface_type_combinations":
        yield from (Violation(m) for m in _jtc_states([str(x) for x in items]))


def _jtc_commands(ifaces: list[str]) -> list[str]:
    """joint_trajectory_controller/include/joint_trajectory_controller/validate_jtc_parameters.hpp
    (jazzy): velocity alone or with position; acceleration needs velocity or position; effort
    alone or with position only."""
    out = []
    if "velocity" in ifaces and len(ifaces) > 1 and "position" not in ifaces:
        out.append("'velocity' must be alone or with 'position'")
    if "acceleration" in ifaces and "velocity" not in ifaces and "position" not in ifaces:
        out.append("'acceleration' needs 'position' and 'velocity'")
    if "effort" in ifaces and not (len(ifaces) == 1 or (len(ifaces) == 2 and "position" in ifaces)):
        out.append("'effort' must be alone or with 'position' only")
    return out


def _jtc_states(ifaces: list[str]) -> list[str]:
    """Same file: velocity needs position; acceleration needs position and velocity."""
    out = []
    if "velocity" in ifaces and "position" not in ifaces:
        out.append("'velocity' needs 'position'")
    if "acceleration" in ifaces and ("position" not in ifaces or "velocity" not in ifaces):
        out.append("'acceleration' needs 'position' and 'velocity'")
    return out


def violations(d: ParamDef, value: object) -> list[Violation]:
    """The validators of ``d`` that ``value`` fails (value of the declared type)."""
    if value is REQUIRED or unresolved(value):
        return []
    return [v for name, args in d.checks for v in _check(name, args, value)]
