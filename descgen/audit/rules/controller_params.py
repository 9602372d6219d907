"""CTRL060–CTRL065: a controller's parameters against Jazzy's own definitions of its type
(descgen/physics/controller_params.py; docs/controller_params.md)."""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.located import Param
from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.launch_subst import unresolved
from descgen.core.model import Controller, Robot
from descgen.physics import controller_params as cp
from descgen.physics.control_claims import claims_of

_DIFF_DRIVE = "diff_drive_controller/DiffDriveController"
_WHEELS = ("left_wheel_names", "right_wheel_names")  # CTRL006 says when they are missing
_DERIVED = ("wheel_separation", "wheel_radius")  # a spec's: descgen writes them from the URDF


def _checked(robot: Robot) -> Iterator[tuple[Controller, dict[str, object], cp.Definitions]]:
    """Each controller whose type descgen has Jazzy's definitions of, with its parameters
    under ROS's dotted names. Other types are skipped (CTRL049 names the unknown ones)."""
    rc = robot.ros2_control
    for c in rc.controllers if rc is not None else ():
        if cp.known(c.type):
            given = dict(cp.flatten(c.params))
            yield c, given, cp.Definitions(c.type, given)


def _elsewhere(robot: Robot, c: Controller, name: str) -> bool:
    """Whether another rule already reports parameter ``name`` of ``c`` as missing or empty:
    CTRL050 (its ``'name' is empty`` problems), CTRL006 (diff-drive wheels), or descgen
    writes it itself (a spec's diff-drive wheel_separation/wheel_radius)."""
    if any(f"'{name}'" in p for p in claims_of(c).problems):
        return True
    if c.type == _DIFF_DRIVE:
        return name in _WHEELS or (robot.spec_hash is not None and name in _DERIVED)
    return False


def _subject(c: Controller) -> str:
    return f"controller:{c.name}"


def _shown(value: object) -> str:
    if isinstance(value, tuple | list):
        return "[" + ", ".join(_shown(x) for x in value) + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f"'{value}'"
    return repr(value)


@rule("CTRL060", "controller-param-unknown", "warning")
def controller_param_unknown(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller parameter that Jazzy's definition of the controller's type does not
    declare (its generate_parameter_library file in ros2_controllers, jazzy branch, plus
    what every controller node has: `use_sim_time`, `update_rate`, `is_async`, ...), and
    names the closest declared one. Names removed or renamed before Jazzy are CTRL063's.
    ## Why is this bad?
    A controller node accepts any parameter and reads only those it declares: a misspelt
    `wheel_seperation` or a gain under a joint the controller does not have is kept and
    silently ignored, so the controller runs with the default instead.
    ## Example
    `linear.x.max_velocty: 1.0` for diff_drive_controller/DiffDriveController.
    ## Use instead
    The declared name: `linear.x.max_velocity: 1.0`.
    """
    for c, given, defs in _checked(robot):
        for name, value in given.items():
            if unresolved(name) or defs.lookup(name) is not None or cp.retired_match(c.type, name, value):
                continue
            near = defs.nearest(name)
            yield at(
                "CTRL060",
                Param(c, name),
                f"controller '{c.name}' sets '{name}', which Jazzy's {c.type} does not declare: it is ignored",
                f"did you mean '{near}'?"
                if near
                else "remove it, or check the name against the controller's "
                "parameter list (ros2_controllers, jazzy branch)",
                subject=_subject(c),
            )


def _type_hint(want: str, value: object) -> str:
    if want == "double" and type(value) is int:
        return f"write {value}.0: a double needs a decimal point"
    if want == "double_array" and isinstance(value, tuple) and all(isinstance(x, int | float) for x in value):
        return f"write every item with a decimal point: [{', '.join(f'{float(x)!r}' for x in value)}]"
    if want == "integer" and isinstance(value, float) and value.is_integer():
        return f"write {int(value)}: an integer has no decimal point"
    if want.endswith("_array") and not isinstance(value, tuple | list):
        return f"write a list: [{_shown(value)}]"
    if want == "bool" and isinstance(value, str) and value.lower() in ("true", "false"):
        return f"write {value.lower()} unquoted: quoted, it is a string"
    if want == "string":
        return "quote the value: a string"
    return f"write a {want}"


@rule("CTRL061", "controller-param-wrong-type", "error")
def controller_param_wrong_type(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares each controller parameter's type, as ROS reads the controllers file (an
    unquoted `40` is an integer, `40.0` a double, `true` a bool, a list of integers an
    integer array), with the type Jazzy's definition of the controller declares.
    ## Why is this bad?
    The controller node declares each value with the type the file gives it, and
    generate_parameter_library then reads it as the declared type: rclcpp throws
    ("expected [double] got [integer]"), the controller fails to initialize and never
    loads.
    ## Example
    `wheel_radius: 1` or `pose_covariance_diagonal: [0, 0, 0, 0, 0, 0]` for
    diff_drive_controller/DiffDriveController.
    ## Use instead
    `wheel_radius: 1.0`, `[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]`.
    """
    for c, given, defs in _checked(robot):
        for name, value in given.items():
            d = defs.lookup(name)
            if d is None or cp.type_ok(d.type, value):
                continue
            want, got = cp.type_name(d.type), cp.value_type(value)
            yield at(
                "CTRL061",
                Param(c, name),
                f"controller '{c.name}' {name} is {got} {_shown(value)}, but Jazzy's {c.type} declares it {want}: "
                f"rclcpp refuses it (expected [{want}] got [{got}]) and the controller fails to initialize",
                _type_hint(want, value),
                subject=_subject(c),
            )


@rule("CTRL062", "controller-param-invalid-value", "error")
def controller_param_invalid_value(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks each controller parameter of the right type against the validators of Jazzy's
    definition: bounds (`gt`, `gt_eq`, `bounds`, `element_bounds`, the NaN-tolerant limits),
    allowed values (`one_of`, `subset_of`), sizes (`fixed_size`, `size_gt`, `size_lt`,
    `not_empty`), `unique`, and the joint_trajectory_controller's interface combinations.
    An empty parameter CTRL050 reports is left to it, and so is an empty list (`[]`): rcl
    gives it no value and rclcpp refuses the file before any controller sees it
    ("No parameter value set", ros2/rclcpp#1955).
    ## Why is this bad?
    generate_parameter_library validates every value when the controller declares its
    parameters and throws "Invalid value set during initialization": the controller never
    loads.
    ## Example
    `interpolation_method: spline` or `command_interfaces: [velocity, effort]` for
    joint_trajectory_controller/JointTrajectoryController; `wheel_radius: -0.05`.
    ## Use instead
    `interpolation_method: splines`; `command_interfaces: [position, velocity]`;
    `wheel_radius: 0.05`.
    """
    for c, given, defs in _checked(robot):
        for name, value in given.items():
            d = defs.lookup(name)
            if d is None or value == () or not cp.type_ok(d.type, value) or _elsewhere(robot, c, name):
                continue  # an empty list never reaches the controller: rclcpp refuses [] in a parameter file
            for v in cp.violations(d, value):
                yield at(
                    "CTRL062",
                    Param(c, name, v.index),
                    f"controller '{c.name}' {name} {v.message}: Jazzy's {c.type} refuses it and fails to initialize",
                    "fix the value (see the parameter's validation in ros2_controllers, jazzy branch)",
                    subject=_subject(c),
                )


@rule("CTRL063", "controller-param-removed", "warning")
def controller_param_removed(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller parameter that Jazzy's controller no longer reads: removed before
    Jazzy (diff_drive_controller `use_stamped_vel` and `wheels_per_side`, the JTC's
    `state_publish_rate`, `start_with_holding` and `gains.<joint>.angle_wraparound`, ...),
    still declared but never read (diff_drive_controller `*.min_acceleration`, renamed
    `max_deceleration`), or overwritten by the controller (a JointGroup controller's
    `interface_name`). The finding names what to use instead.
    ## Why is this bad?
    The controller ignores it without a word: a Humble-era config keeps its look but loses
    its effect (no deceleration limit, no angle wrapping, an unstamped cmd_vel publisher
    that nothing hears).
    ## Example
    `use_stamped_vel: false` for diff_drive_controller/DiffDriveController.
    ## Use instead
    Remove it, and publish geometry_msgs/msg/TwistStamped on ~/cmd_vel.
    """
    for c, given, _ in _checked(robot):
        for name, value in given.items():
            r = cp.retired_match(c.type, name, value)
            if r is None or r.kind == "deprecated":
                continue
            yield at(
                "CTRL063",
                Param(c, name),
                f"controller '{c.name}' sets '{name}', which Jazzy's {c.type} ignores: {r.since}",
                f"use instead: {r.use}",
                subject=_subject(c),
            )


@rule("CTRL064", "controller-param-required", "error")
def controller_param_required(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller that does not set a parameter Jazzy's definition requires: one with
    no default (the admittance controller's `kinematics.*`, the omni-wheel drive's
    `wheel_names`, ...) or whose default fails its own validation
    (diff_drive_controller `wheel_separation` and `wheel_radius`: default 0.0, must be > 0).
    Parameters CTRL050 and CTRL006 already report, and the diff-drive wheel values descgen
    writes from a spec's URDF, are left to them.
    ## Why is this bad?
    generate_parameter_library refuses an unset required parameter when the controller
    declares its parameters: the controller never loads.
    ## Example
    A diff_drive_controller/DiffDriveController with wheel names but no `wheel_separation`.
    ## Use instead
    Set it: `wheel_separation: 0.42` (the distance between the wheels, in metres).
    """
    for c, given, defs in _checked(robot):
        missing = [(n, d) for n, d in defs.missing(given) if not _elsewhere(robot, c, n)]
        if not missing:
            continue
        parts = []
        for name, d in missing:
            if d.default is cp.REQUIRED:
                parts.append(f"'{name}' (no default)")
            else:
                why = cp.violations(d, d.default)[0].want
                parts.append(f"'{name}' (default {_shown(d.default)}, but it {why})")
        yield at(
            "CTRL064",
            c,
            f"controller '{c.name}' does not set {', '.join(parts)}: Jazzy's {c.type} refuses to initialize",
            f"set {', '.join(n for n, _ in missing)} in the controller's parameters",
            subject=_subject(c),
        )


@rule("CTRL065", "controller-param-deprecated", "info")
def controller_param_deprecated(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller parameter that Jazzy still reads but has deprecated (most log a
    warning at configure), and names its replacement: diff_drive_controller
    `has_velocity_limits` and the like, the JTC's `open_loop_control` and
    `gains.<joint>.i_clamp`, the steering controllers' `front_steering` and
    `front_wheels_names`, pid_controller's `antiwindup`, ...
    ## Why is this bad?
    It works today, but the next distribution drops it (most are gone in Kilted), and the
    config then silently loses its effect (CTRL063).
    ## Example
    `open_loop_control: true` for joint_trajectory_controller/JointTrajectoryController.
    ## Use instead
    `interpolate_from_desired_state: true` with the feedback gains set to zero.
    """
    for c, given, _ in _checked(robot):
        for name, value in given.items():
            r = cp.retired_match(c.type, name, value)
            if r is None or r.kind != "deprecated":
                continue
            yield at(
                "CTRL065",
                Param(c, name),
                f"controller '{c.name}' sets '{name}': Jazzy's {c.type} still reads it, but it is {r.since}",
                f"use instead: {r.use}",
                subject=_subject(c),
            )
