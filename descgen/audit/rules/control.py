"""CTRL: the ros2_control block and controllers agree with the joints."""

from __future__ import annotations

import dataclasses
from collections import defaultdict
from collections.abc import Iterator
from typing import cast

from descgen.audit.located import Param
from descgen.audit.registry import at, rule
from descgen.core.findings import Finding, Where
from descgen.core.launch_subst import unresolved
from descgen.core.model import WITH_LIMITS, Controller, HardwareBlock, Robot
from descgen.physics.control_claims import JOINT_PARAMS, claims_of, command_pairs, joint_params, state_pairs
from descgen.physics.hardware_info import active_mimic, mimic_attribute, valid_mimic_attribute

_SENSOR_BROADCASTERS = ("imu_sensor_broadcaster/", "force_torque_sensor_broadcaster/")


def _list(v: object) -> list[object]:
    if isinstance(v, list | tuple):
        return list(v)
    return [] if v is None else [v]


def _naming(c: Controller, joint: str) -> object:
    """Where ``c`` names ``joint`` (the first joint parameter that lists it), else ``c``."""
    for key in JOINT_PARAMS:
        value = c.param(key)
        for i, name in enumerate(_list(value)):
            if str(name) == joint:
                return Param(c, key, i if isinstance(value, tuple | list) else None)
    return c


def _placed(f: Finding, where: Where) -> Finding:
    """``f`` at ``where`` (a parameter's value in a controllers file) when that is known."""
    return dataclasses.replace(f, where=where) if where.line else f


@rule("CTRL001", "control-joint-not-in-urdf", "error")
def control_joint_not_in_urdf(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a ros2_control joint that is not a moving URDF joint.
    ## Why is this bad?
    ros2_control fails to load: "Joint 'x' not found in URDF" / "Fixed joints do not make
    sense in ros2_control".
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is None:
            yield at(
                "CTRL001",
                cj,
                f"ros2_control joint '{cj.name}' is not a URDF joint",
                "fix the name",
                subject=f"ros2_control:{cj.name}",
            )
        elif j.type == "fixed":
            yield at(
                "CTRL001",
                cj,
                f"ros2_control joint '{cj.name}' is fixed",
                "remove it from ros2_control",
                subject=f"ros2_control:{cj.name}",
            )


@rule("CTRL002", "controller-interface-missing", "error")
def controller_interface_missing(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller that claims a command interface or reads a state interface the
    hardware does not export.
    ## Why is this bad?
    The controller fails to activate; on the robot nothing moves and nothing says why
    until someone reads the controller_manager log.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    cmd = {(cj.name, i.name) for cj in rc.joints for i in cj.command}
    state = {(cj.name, i.name) for cj in rc.joints for i in cj.state}
    state |= {(s.name, i.name) for s in rc.sensors for i in s.state}
    sensors = {s.name for s in rc.sensors}
    for c in rc.controllers:
        for joint, iface in command_pairs(c):
            if (joint, iface) not in cmd and not unresolved(joint) and not unresolved(iface):  # CTRL052/053
                yield at(
                    "CTRL002",
                    _naming(c, joint),
                    f"controller '{c.name}' claims '{joint}/{iface}', which the hardware does not export",
                    f"add command: [{iface}] to ros2_control joint '{joint}', or fix the controller",
                    subject=f"controller:{c.name}",
                )
        missing_sensor = set()
        for comp, iface in state_pairs(c):
            if (comp, iface) in state or unresolved(comp) or unresolved(iface):  # CTRL052/053 stand for it
                continue
            if c.type.startswith(_SENSOR_BROADCASTERS) and comp not in sensors:
                missing_sensor.add(comp)  # one finding per absent sensor, not ten per interface
                continue
            yield at(
                "CTRL002",
                _naming(c, comp),
                f"controller '{c.name}' reads state '{comp}/{iface}', which the hardware does not export",
                f"add state: [{iface}] to ros2_control {'sensor' if comp in sensors else 'joint'} '{comp}'",
                subject=f"controller:{c.name}",
            )
        for comp in sorted(missing_sensor):
            yield at(
                "CTRL002",
                c,
                f"controller '{c.name}' reads sensor '{comp}', which is not a <sensor> of ros2_control",
                "fix sensor_name, or add the <sensor> with its state interfaces to the ros2_control block"
                + (f" (sensors: {', '.join(sorted(sensors))})" if sensors else ""),
                subject=f"controller:{c.name}",
            )


@rule("CTRL003", "no-joint-state-broadcaster", "warning")
def no_joint_state_broadcaster(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a ros2_control setup with controllers but no joint_state_broadcaster.
    ## Why is this bad?
    Nothing publishes measured joint states, so robot_state_publisher shows no motion,
    or something else fills /joint_states with commands.
    """
    rc = robot.ros2_control
    if rc is None or not rc.controllers:
        return
    if not any(c.type.startswith("joint_state_broadcaster/") for c in rc.controllers):
        yield at(
            "CTRL003",
            rc,
            "no joint_state_broadcaster among the controllers",
            "add joint_state_broadcaster/JointStateBroadcaster",
            subject="ros2_control",
        )


@rule("CTRL004", "interface-claimed-twice", "warning")
def interface_claimed_twice(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a command interface that two controllers claim.
    ## Why is this bad?
    Command interfaces are exclusive: the second controller fails to activate
    ("Resource conflict"). Fine only when they are alternatives never active together.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    owners: dict[tuple[str, str], list[str]] = defaultdict(list)
    for c in rc.controllers:
        for key in command_pairs(c):
            owners[key].append(c.name)
    for (joint, iface), names in owners.items():
        if len(names) > 1:
            c = next(x for x in rc.controllers if x.name == names[1])
            yield at(
                "CTRL004",
                c,
                f"'{joint}/{iface}' is claimed by {', '.join(names)}",
                "give each command interface one controller, or activate them exclusively",
                subject=f"controller:{c.name}",
            )


@rule("CTRL005", "control-joint-listed-twice", "error")
def control_joint_listed_twice(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a joint listed twice in the ros2_control block.
    ## Why is this bad?
    Interfaces get exported twice and the resource manager refuses the duplicate keys.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    seen: set[str] = set()
    for cj in rc.joints:
        if cj.name in seen:
            yield at(
                "CTRL005",
                cj,
                f"joint '{cj.name}' is listed twice in ros2_control",
                "merge the entries",
                subject=f"ros2_control:{cj.name}",
            )
        seen.add(cj.name)


# A calibrated wheel_separation/wheel_radius differs from the CAD by tyre squash and wear:
# millimetres. Beyond this (or the stated tolerance) it is worth a look, not an error.
DEFAULT_CALIBRATION_TOLERANCE = 0.005  # m
# factors a value typed in the wrong unit is off by: mm, cm or dm taken as m, or the reverse
UNIT_SLIPS = (1000.0, 100.0, 10.0, 0.1, 0.01, 0.001)


def unit_slip(value: float, derived: float) -> float | None:
    """The unit-slip factor (within 10 %) that turns ``derived`` into ``value``, if any."""
    if derived <= 0 or value <= 0:
        return None
    return next((f for f in UNIT_SLIPS if abs(value / (derived * f) - 1.0) <= 0.1), None)


@rule("CTRL006", "diff-drive-geometry-disagrees", "error")
def diff_drive_geometry_disagrees(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Derives `wheel_separation` and `wheel_radius` from the wheel joints and wheel
    geometry, and flags a diff_drive_controller whose wheels cannot give them, a spec that
    repeats them as plain parameters, or a value (a spec's `calibrated:` entry or an
    audited controllers file's parameter) off by a unit slip (x10, x100, x1000 or the
    inverse) from the URDF. A difference beyond the tolerance that is not a unit slip is
    CTRL051.
    ## Why is this bad?
    Odometry scales with both: a radius typed in millimetres as metres makes the robot
    believe it drove a thousand times further than it did, and the map smears.
    ## Example
    `wheel_radius: 100` for a 0.1 m wheel.
    ## Use instead
    `calibrated: {wheel_radius: {value: "0.0985 m", source: "odometry calibration 2024-05"}}`
    in the spec, or the value in metres in the controllers file.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for c in rc.controllers:
        if not c.type.startswith("diff_drive_controller/"):
            continue
        if any(unresolved(n) for k in ("left_wheel_names", "right_wheel_names") for n in _list(c.param(k))):
            continue  # the wheels are named by a launch substitution: CTRL052/053 stand for it
        from descgen.physics.derive import diff_drive_geometry  # numpy: only for a diff-drive controller

        geo = diff_drive_geometry(robot, c)
        for problem in geo.problems:
            yield at(
                "CTRL006",
                c,
                f"controller '{c.name}': {problem}",
                "fix the wheel joints or their collision geometry",
                subject=f"controller:{c.name}",
            )
    yield from (f for f in _wheel_values(robot) if f.code == "CTRL006")


def _wheel_values(robot: Robot) -> Iterator[Finding]:
    """CTRL006 (unit slip, repeated in a spec) and CTRL051 (beyond tolerance) findings."""
    rc = robot.ros2_control
    for c in rc.controllers if rc is not None else ():
        if not c.type.startswith("diff_drive_controller/"):
            continue
        from descgen.physics.derive import diff_drive_geometry  # numpy: only for a diff-drive controller

        geo = diff_drive_geometry(robot, c)
        for key, derived in (("wheel_separation", geo.wheel_separation), ("wheel_radius", geo.wheel_radius)):
            if derived is not None:
                yield from _wheel_value(robot, c, key, derived)


def _wheel_value(robot: Robot, c: Controller, key: str, derived: float) -> Iterator[Finding]:
    """One wheel parameter against the URDF: a spec's calibrated value, a spec's plain
    parameter (descgen derives it), or an audited file's parameter."""
    spec = robot.spec_hash is not None
    cal = next((x for x in c.calibrated if x.param == key), None)
    given = c.param(key)
    subject = f"controller:{c.name}"
    if cal is None and given is None:
        return
    if cal is None and spec:
        yield at(
            "CTRL006",
            c,
            f"controller '{c.name}' {key} is {given} but the URDF gives {derived:.9g} m",
            f"remove {key} from params: descgen derives it from the URDF; a measured value goes under "
            f"calibrated: {{{key}: {{value: ..., source: ...}}}}",
            subject=subject,
        )
        return
    if cal is not None:
        value, tol, elem = cal.value, cal.tolerance or DEFAULT_CALIBRATION_TOLERANCE, cast(object, cal)
        fix = f"fix calibrated.{key} of controller '{c.name}' in the spec (a length, e.g. \"{derived:.4g} m\")"
    elif isinstance(given, int | float) and not isinstance(given, bool):
        value, tol, elem = float(given), DEFAULT_CALIBRATION_TOLERANCE, cast(object, Param(c, key))
        fix = f"set {key} in {c.where.file} to the robot's value in metres (the URDF gives {derived:.6g} m)"
    else:
        yield at(
            "CTRL006",
            Param(c, key),
            f"controller '{c.name}' {key} is {given!a}, not a number",
            "write metres",
            subject=subject,
        )
        return
    if abs(value - derived) <= tol + 1e-12:
        return
    slip = unit_slip(value, derived)
    shown = f"controller '{c.name}' {key} is {value:.6g} m but the URDF gives {derived:.6g} m"
    if slip is not None:
        yield at(
            "CTRL006", elem, f"{shown}: {slip:g} times it, a unit slip (mm, cm or dm for m?)", fix, subject=subject
        )
    else:
        yield at(
            "CTRL051",
            elem,
            f"{shown}: {abs(value - derived) * 1000:.3g} mm apart, beyond the {tol * 1000:.3g} mm tolerance",
            f"recheck the calibration and the wheel geometry in the URDF; {fix}"
            if cal is not None
            else f"recheck the calibration and the wheel geometry in the URDF, or {fix}",
            subject=subject,
        )


@rule("CTRL051", "calibrated-wheel-value-off", "warning")
def calibrated_wheel_value_off(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Reported by CTRL006's check: a diff_drive_controller `wheel_separation`/`wheel_radius`
    (calibrated in the spec, or set in an audited controllers file) differs from the URDF
    value by more than the tolerance (default 5 mm), but not by a unit slip.
    ## Why is this bad?
    Calibration moves these by millimetres (tyre squash, wear, contact patch). Centimetres
    mean the calibration or the URDF's wheel placement is wrong, and odometry or the
    displayed robot is off by as much.
    ## Example
    URDF wheels 0.40 m apart, `wheel_separation: 0.43`.
    ## Use instead
    A value within the tolerance, or a stated `tolerance:` with the calibration's source.
    """
    yield from (f for f in _wheel_values(robot) if f.code == "CTRL051")


@rule("CTRL007", "update-rate-not-whole", "error")
def update_rate_not_whole(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks the controller_manager update rate is a whole number of Hz.
    ## Why is this bad?
    `update_rate` is an integer parameter; a fractional value fails to load.
    """
    rc = robot.ros2_control
    if rc is not None and rc.update_rate is not None and not float(rc.update_rate).is_integer():
        found = at(
            "CTRL007",
            rc,
            f"update_rate {rc.update_rate:g} Hz is not a whole number",
            "write e.g. 100 Hz",
            subject="ros2_control",
        )
        yield _placed(found, rc.update_rate_where)  # the value in the controllers file, when read from one


@rule("CTRL008", "command-limit-beyond-urdf", "error")
def command_limit_beyond_urdf(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares each command interface's `min`/`max` with the joint's URDF limits (position
    with lower/upper, velocity and effort with their limits).
    ## Why is this bad?
    ros2_control uses them to tighten the URDF limits; wider values are ignored on new
    releases and trusted on older ones, so a command beyond the joint's range reaches the
    hardware.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is None or j.limit is None:
            continue
        lm = j.limit
        for iface in cj.command:
            if iface.name == "position" and j.type in WITH_LIMITS:
                lo, hi = lm.lower, lm.upper
            elif iface.name == "velocity" and lm.velocity is not None:
                lo, hi = -abs(lm.velocity), abs(lm.velocity)
            elif iface.name == "effort" and lm.effort is not None:
                lo, hi = -abs(lm.effort), abs(lm.effort)
            else:
                continue
            tol = 1e-9
            if iface.max is not None and hi is not None and iface.max > hi + tol:
                yield at(
                    "CTRL008",
                    cj,
                    f"'{cj.name}/{iface.name}' command max {iface.max:.6g} is beyond the URDF limit {hi:.6g}",
                    "make the command limit equal to or inside the joint limit",
                    subject=f"ros2_control:{cj.name}",
                )
            if iface.min is not None and lo is not None and iface.min < lo - tol:
                yield at(
                    "CTRL008",
                    cj,
                    f"'{cj.name}/{iface.name}' command min {iface.min:.6g} is beyond the URDF limit {lo:.6g}",
                    "make the command limit equal to or inside the joint limit",
                    subject=f"ros2_control:{cj.name}",
                )


@rule("CTRL009", "controller-names-unknown-joint", "error")
def controller_names_unknown_joint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds controllers whose joint parameters (`joints`, `command_joints`, a gripper's
    `joint`, `left_wheel_names`, `right_wheel_names`) name joints the URDF does not have.
    ## Why is this bad?
    The controller fails to configure on the robot; nothing moves.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for c in rc.controllers:
        for key in joint_params(c):
            value = c.param(key)
            for i, name in enumerate(_list(value)):
                # a controllers file's launch substitution left as written: CTRL052/053 stand for it
                # (a spec's value is never substituted: there it is a name like any other)
                if robot.joint(str(name)) is None and (_in_spec(robot) or not unresolved(name)):
                    yield at(
                        "CTRL009",
                        Param(c, key, i if isinstance(value, tuple | list) else None),
                        f"controller '{c.name}' {key} names '{name}', which is not a URDF joint",
                        "fix the joint name",
                        subject=f"controller:{c.name}",
                    )


@rule("CTRL010", "broadcaster-fed-from-commands", "error")
def broadcaster_fed_from_commands(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a joint_state_broadcaster whose `interfaces` or `map_interface_to_joint_state`
    names an interface the hardware exports only as a command interface.
    ## Why is this bad?
    /joint_states then carries what was commanded, robot_state_publisher turns it into tf,
    and the operator display animates commands as if they were measured motion.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    commands = {i.name for cj in rc.joints for i in cj.command}
    states = {i.name for cj in rc.joints for i in cj.state}
    for c in rc.controllers:
        if not c.type.startswith("joint_state_broadcaster/"):
            continue
        interfaces = c.param("interfaces")
        named = [(str(x), Param(c, "interfaces", i)) for i, x in enumerate(_list(interfaces))]
        mapping = c.param("map_interface_to_joint_state")
        if isinstance(mapping, tuple):
            named += [(str(v), Param(c, "map_interface_to_joint_state")) for _, v in mapping]
        for iface, elem in named:
            if iface in commands and iface not in states:
                yield at(
                    "CTRL010",
                    elem,
                    f"'{c.name}' publishes '{iface}', which the hardware exports only as a command interface",
                    "broadcast state interfaces only; publish desired values on their own topic",
                    subject=f"controller:{c.name}",
                )


# -- Jazzy's ros2_control rules (docs/ros2_control_jazzy.md; hardware_interface/src/component_parser.cpp
#    at the jazzy branch, parse_control_resources_from_urdf and parse_component_from_xml) ------------


def _in_spec(robot: Robot) -> bool:
    """A spec's model (hints say what to edit in the spec) or a read file (hints name its XML)."""
    return robot.spec_hash is not None


@rule("CTRL040", "mimic-joint-commanded", "error")
def mimic_joint_commanded(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a ros2_control joint that is a URDF `<mimic>` joint (its `mimic` attribute not
    `false`) and has command interfaces.
    ## Why is this bad?
    Jazzy's parser refuses the whole description: "Joint 'j' has mimic attribute not set to
    false: Activated mimic joints cannot have command interfaces." The controller_manager
    loads no hardware and nothing moves. ros2_control sets a mimic joint's state from its
    leader (`multiplier * leader + offset`); only the leader is commanded.
    ## Example
    `<joint name="finger_left_joint"><command_interface name="position"/>...` where the URDF
    joint has `<mimic joint="finger_right_joint"/>`.
    ## Use instead
    State interfaces only on the mimic joint, or `mimic="false"` on the ros2_control joint to
    drive it as an ordinary joint.
    """
    rc = robot.ros2_control
    for cj in rc.joints if rc is not None else ():
        if not cj.command or not active_mimic(robot, cj):
            continue
        leader = robot.joint(cj.name).mimic.joint  # type: ignore[union-attr]
        commands = ", ".join(i.name for i in cj.command)
        hint = (
            f"remove command: [{commands}] from ros2_control joint '{cj.name}' (its state follows '{leader}'), "
            "or set mimic: false on it to command it on its own"
            if _in_spec(robot)
            else f"remove its <command_interface>s (ros2_control sets its state from '{leader}'), "
            'or add mimic="false" to the ros2_control <joint> to command it on its own'
        )
        yield at(
            "CTRL040",
            cj,
            f"mimic joint '{cj.name}' has command interfaces ({commands}); Jazzy refuses it: "
            "Activated mimic joints cannot have command interfaces",
            hint,
            subject=f"ros2_control:{cj.name}",
        )


@rule("CTRL041", "mimic-attribute-without-urdf-mimic", "error")
def mimic_attribute_without_urdf_mimic(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a ros2_control joint with `mimic="true"` whose URDF joint has no `<mimic>`.
    ## Why is this bad?
    Jazzy's parser refuses the description: "Joint 'j' has no mimic information in the URDF".
    Since hardware_interface 4.13 the relation comes only from the URDF `<mimic>` element.
    ## Example
    `<joint name="finger_left_joint" mimic="true">` and a URDF joint without `<mimic>`.
    ## Use instead
    Add `<mimic joint="leader" multiplier="..." offset="..."/>` to the URDF joint, or drop the
    attribute.
    """
    rc = robot.ros2_control
    for cj in rc.joints if rc is not None else ():
        j = robot.joint(cj.name)
        if j is not None and j.mimic is None and valid_mimic_attribute(cj) and mimic_attribute(cj) is True:
            yield at(
                "CTRL041",
                cj,
                f"ros2_control joint '{cj.name}' says mimic=\"true\" but URDF joint '{cj.name}' has no <mimic>; "
                "Jazzy refuses it: no mimic information in the URDF",
                'add <mimic joint="LEADER" multiplier="..." offset="..."/> to the URDF joint, '
                "or remove the mimic attribute",
                subject=f"ros2_control:{cj.name}",
            )


@rule("CTRL042", "mimic-leader-outside-block", "error")
def mimic_leader_outside_block(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a mimic joint under ros2_control whose leader (the `<mimic joint=...>`) is not a
    joint of the same `<ros2_control>` block.
    ## Why is this bad?
    Jazzy's parser refuses the description: "Mimic joint 'leader' not found in <ros2_control>
    tag". The hardware copies the leader's state, so it must own the leader.
    ## Example
    `finger_left_joint` (mimics `finger_right_joint`) under ros2_control, `finger_right_joint`
    not, or in another block.
    ## Use instead
    Put the leader in the same block (with its command interface), or set `mimic="false"`
    and give the follower its own hardware.
    """
    rc = robot.ros2_control
    for cj in rc.joints if rc is not None else ():
        if not active_mimic(robot, cj):
            continue
        leader = robot.joint(cj.name).mimic.joint  # type: ignore[union-attr]
        if any(o.name == leader and o.block == cj.block for o in rc.joints):  # type: ignore[union-attr]
            continue
        yield at(
            "CTRL042",
            cj,
            f"mimic joint '{cj.name}' follows '{leader}', which is not a joint of the same <ros2_control> block; "
            f"Jazzy refuses it: Mimic joint '{leader}' not found in <ros2_control> tag",
            f"add '{leader}' to the ros2_control joints"
            + ("" if _in_spec(robot) else " of the same block")
            + (" or set mimic: false" if _in_spec(robot) else ', or set mimic="false" on this joint'),
            subject=f"ros2_control:{cj.name}",
        )


@rule("CTRL043", "mimic-attribute-invalid", "error")
def mimic_attribute_invalid(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a ros2_control `<joint mimic="...">` whose value is not `true` or `false`.
    ## Why is this bad?
    Jazzy strips the value of blanks and reads it with parse_bool, which accepts only
    true/false (any case) and throws std::invalid_argument otherwise; the parser does not
    catch it, so loading fails.
    ## Example
    `mimic="1"`, `mimic="yes"`.
    ## Use instead
    `mimic="true"` or `mimic="false"`, or no attribute.
    """
    rc = robot.ros2_control
    for cj in rc.joints if rc is not None else ():
        if not valid_mimic_attribute(cj):
            yield at(
                "CTRL043",
                cj,
                f"ros2_control joint '{cj.name}' has mimic={cj.mimic!a}; Jazzy accepts only true or false",
                'write mimic="true" or mimic="false" (or leave it out: a URDF <mimic> joint is then a mimic joint)',
                subject=f"ros2_control:{cj.name}",
            )


@rule("CTRL044", "pre-jazzy-mimic-params", "error")
def pre_jazzy_mimic_params(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds `<param name="mimic">` or `<param name="multiplier">` inside a ros2_control `<joint>`.
    ## Why is this bad?
    That syntax was removed in hardware_interface 4.13.0 (ros2_control #1553, before Jazzy):
    Jazzy keeps the params but no longer makes the joint a mimic joint, so its state never
    follows the leader (a gripper finger stays at zero in RViz and MoveIt).
    ## Example
    `<joint name="left_finger"><param name="mimic">right_finger</param>...`
    ## Use instead
    The URDF `<mimic joint="right_finger" multiplier="1" offset="0"/>` on the URDF joint, and
    no command interface on the ros2_control joint.
    """
    rc = robot.ros2_control
    for cj in rc.joints if rc is not None else ():
        names = [k for k, _ in cj.params if k in ("mimic", "multiplier")]
        if names:
            leader = dict(cj.params).get("mimic", "LEADER")
            yield at(
                "CTRL044",
                cj,
                f"ros2_control joint '{cj.name}' has <param name=\"{names[0]}\">, which Jazzy no longer reads "
                "(removed in hardware_interface 4.13): the joint does not follow its leader",
                f'remove the mimic/multiplier/offset params and add <mimic joint="{leader}" multiplier="..." '
                'offset="..."/> to the URDF joint',
                subject=f"ros2_control:{cj.name}",
            )


def _blocks(robot: Robot) -> tuple[HardwareBlock, ...]:
    rc = robot.ros2_control
    if rc is None:
        return ()
    return rc.blocks or (HardwareBlock(rc.name, rc.plugin, rc.params, rc.where),)


# plugin -> Jazzy replacement, for hardware plugins Jazzy no longer has
REMOVED_PLUGINS = {
    "fake_components/GenericSystem": "mock_components/GenericSystem",
    "gazebo_ros2_control/GazeboSystem": "gz_ros2_control/GazeboSimSystem",
}
REMOVED_HW_PARAMS = {"fake_sensor_commands": "mock_sensor_commands", "fake_gpio_commands": "mock_gpio_commands"}
CLASSIC_SIM_PLUGINS = ("libgazebo_ros2_control.so", "gazebo_ros2_control")


@rule("CTRL045", "hardware-plugin-not-in-jazzy", "error")
def hardware_plugin_not_in_jazzy(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a `<hardware><plugin>` that Jazzy does not have: `fake_components/GenericSystem`
    (removed in hardware_interface 4.0.0, #1150) or Gazebo Classic's
    `gazebo_ros2_control/GazeboSystem` (gazebo_ros2_control is not released for Jazzy).
    ## Why is this bad?
    The resource manager cannot load the plugin, so no hardware component starts and every
    controller fails to activate.
    ## Example
    `<plugin>fake_components/GenericSystem</plugin>`
    ## Use instead
    `mock_components/GenericSystem`; for simulation `gz_ros2_control/GazeboSimSystem` with
    the `gz_ros2_control-system` Gazebo plugin.
    """
    for b in _blocks(robot):
        new = REMOVED_PLUGINS.get(b.plugin)
        if new is None:
            continue
        where = "hardware: plugin in the spec" if _in_spec(robot) else "<hardware><plugin>"
        yield at(
            "CTRL045",
            b,
            f"ros2_control '{b.name}' uses the plugin {b.plugin}, which Jazzy does not have",
            f"write {new} as the {where}"
            + (" and load gz_ros2_control-system in <gazebo>" if new.startswith("gz_") else ""),
            subject=f"ros2_control:{b.name}",
        )


@rule("CTRL046", "generic-system-param-renamed", "warning")
def generic_system_param_renamed(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds GenericSystem parameters renamed before Jazzy: hardware params
    `fake_sensor_commands`/`fake_gpio_commands`, and joint-level `initial_<interface>` params.
    ## Why is this bad?
    GenericSystem looks up only the names it knows, so these are silently ignored (4.0.0,
    #1150): the sensor gets no mock command interface, the joint starts at 0 instead of the
    intended position.
    ## Example
    `<param name="fake_sensor_commands">true</param>`, `<param name="initial_position">0.5</param>`
    in a `<joint>`.
    ## Use instead
    `mock_sensor_commands`/`mock_gpio_commands`; `<param name="initial_value">` inside the
    `<state_interface>`.
    """
    for b in _blocks(robot):
        for k, _ in b.params:
            if k in REMOVED_HW_PARAMS:
                yield at(
                    "CTRL046",
                    b,
                    f"ros2_control '{b.name}' sets {k}, which Jazzy's GenericSystem ignores",
                    f"rename it {REMOVED_HW_PARAMS[k]}",
                    subject=f"ros2_control:{b.name}",
                )
    rc = robot.ros2_control
    for cj in rc.joints if rc is not None else ():
        for k, _ in cj.params:
            if k.startswith("initial_") and k != "initial_value":
                iface = k.removeprefix("initial_")
                yield at(
                    "CTRL046",
                    cj,
                    f"ros2_control joint '{cj.name}' sets <param name=\"{k}\">, which Jazzy's GenericSystem ignores",
                    f'move it into <state_interface name="{iface}"> as <param name="initial_value">',
                    subject=f"ros2_control:{cj.name}",
                )


@rule("CTRL047", "gazebo-classic-plugin", "warning")
def gazebo_classic_plugin(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a `<gazebo><plugin filename="libgazebo_ros2_control.so">` (Gazebo Classic's
    gazebo_ros2_control) in a description with ros2_control.
    ## Why is this bad?
    Jazzy pairs with Gazebo Harmonic; gazebo_ros2_control is not released for Jazzy, so in
    simulation no controller_manager starts and the robot never moves.
    ## Example
    `<plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control">`
    ## Use instead
    `<plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">`
    with `<parameters>` naming the controllers file.
    """
    rc = robot.ros2_control
    for filename, where in rc.sim_plugins if rc is not None else ():
        if filename.rsplit("/", 1)[-1] in CLASSIC_SIM_PLUGINS:
            yield Finding(
                "CTRL047",
                "warning",
                f"<gazebo> loads {filename} (Gazebo Classic), which Jazzy does not have",
                'use <plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">',
                "gazebo",
                where,
            )


@rule("CTRL049", "controller-claims-unchecked", "warning")
def controller_claims_unchecked(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Names a controller whose type descgen does not know, so the interfaces it claims could
    not be checked against the hardware.
    ## Why is this bad?
    A typo in its joint or interface names would only show when the controller fails to
    activate on the robot. (A misspelt type is also unknown to pluginlib.)
    ## Example
    `type: my_controllers/WristController`, or `position_controller/GripperActionController`.
    ## Use instead
    Check the type against the plugin XMLs of ros2_controllers; for your own controller,
    check its joints and interfaces by hand.
    """
    rc = robot.ros2_control
    for c in rc.controllers if rc is not None else ():
        if not claims_of(c).known:
            yield at(
                "CTRL049",
                Param(c, "type"),
                f"controller '{c.name}' has type {c.type}, whose claims descgen does not know: "
                "its joints and interfaces were not checked",
                "check the type's spelling (plugin XMLs of ros2_controllers) and its interfaces by hand",
                subject=f"controller:{c.name}",
            )


@rule("CTRL050", "controller-params-refused", "error")
def controller_params_refused(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller missing a parameter its type requires (JTC `joints`,
    `command_interfaces`, `state_interfaces`; a gripper's `joint`; the IMU and
    force-torque broadcasters' `sensor_name`/`frame_id`), or a force-torque broadcaster with
    both or neither of `sensor_name` and `interface_names`.
    ## Why is this bad?
    The controller refuses to configure (generate_parameter_library validation or its
    on_configure), so it never claims anything and never runs.
    ## Example
    `position_controllers/GripperActionController` without `joint`.
    ## Use instead
    Set the parameter (see the type's `*_parameters.yaml` in ros2_controllers, jazzy branch).
    """
    rc = robot.ros2_control
    for c in rc.controllers if rc is not None else ():
        for problem in claims_of(c).problems:
            yield at(
                "CTRL050",
                c,
                f"controller '{c.name}' ({c.type}): {problem}",
                "set it in the controller's params",
                subject=f"controller:{c.name}",
            )


@rule("CTRL066", "ros2-control-parser-throws", "error")
def ros2_control_parser_throws(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Reads each `<ros2_control>` block as Jazzy's component parser does
    (hardware_interface/src/component_parser.cpp, jazzy) and reports every place it throws,
    in the parser's own words: a required attribute missing (`name`, `type` on the block;
    `name` on joints, sensors, gpios, interfaces and transmissions; `enable` on `<limits>`;
    `role` on a transmission's joints and actuators), a `<param>` without a name, a
    `<hardware>` or `<transmission>` without `<plugin>`, a child of `<ros2_control>` other than
    hardware, properties, joint, sensor, gpio or transmission, and a boolean attribute that is
    not true or false (after stripping blanks).
    ## Why is this bad?
    The parser stops at the first throw, and the controller manager does not start: no
    controller runs. xacro and check_urdf accept the file (it is valid XML and valid URDF).
    ## Example
    `<ros2_control name="arm">` (no `type`), `<param>1.0</param>`, `<hardware/>`.
    ## Use instead
    `<ros2_control name="arm" type="system">`, `<param name="gain">1.0</param>`,
    `<hardware><plugin>mock_components/GenericSystem</plugin></hardware>`.
    """
    for block, message, where in robot.control_refusals:
        yield Finding(
            "CTRL066",
            "error",
            f"Jazzy's ros2_control parser throws: {message}",
            "fix the element as the message says (docs/ros2_control_parser_jazzy.md lists each case)",
            f"ros2_control:{block}",
            where,
        )


@rule("CTRL067", "rw-rate-above-update-rate", "warning")
def rw_rate_above_update_rate(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a `<ros2_control>` block whose `rw_rate` is above the controller manager's
    `update_rate`.
    ## Why is this bad?
    A component is read and written from the controller manager's loop, so it cannot run
    faster: Jazzy's resource manager replaces such an rw_rate (and 0) with the update rate
    (resource_manager.cpp, jazzy). The value written is not the rate the hardware gets.
    """
    rc = robot.ros2_control
    if rc is None or rc.update_rate is None:
        return
    for b in rc.hardware_blocks():
        if b.rw_rate is not None and b.rw_rate > rc.update_rate:
            yield at(
                "CTRL067",
                b,
                f"ros2_control block '{b.name}' has rw_rate {b.rw_rate} Hz, above the controller manager's "
                f"update_rate {rc.update_rate:g} Hz: it runs at {rc.update_rate:g} Hz",
                f"write rw_rate {rc.update_rate:g} Hz or less, or raise update_rate",
                subject=f"ros2_control:{b.name}",
            )
