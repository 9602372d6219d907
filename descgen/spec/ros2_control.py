"""The spec's ``ros2_control`` block -> the model's: joints and their interfaces, hardware
parameters as ros2_control's parser reads them, controllers with their parameters (text
with a unit converted to SI) and calibrated values."""

from __future__ import annotations

import re
from collections.abc import Collection, Sequence

from descgen.codes.spec import (
    CTRL080,
    SPEC083,
    SPEC084,
    SPEC085,
    SPEC086,
    SPEC087,
    SPEC088,
    SPEC089,
    SPEC146,
    SPEC147,
    SPEC149,
)
from descgen.core import model as m
from descgen.core import units
from descgen.infra.yamlsource import Path_
from descgen.physics.control_claims import FT_INTERFACES, IMU_INTERFACES
from descgen.spec import models as s
from descgen.spec.convert import EFFORT, VELOCITY, Converter
from descgen.spec.quantity import Written

_NUMERIC_START = re.compile(r"^\s*[-+]?(\d|\.\d)")


Block = s.Ros2ControlSpec | s.Ros2ControlBlockSpec


def ros2_control(conv: Converter, rc: s.Ros2ControlSpec, links: Collection[str] = ()) -> m.Ros2Control:
    """Needs ``conv.joint_types``: an initial position is in its joint's unit; ``links``: the
    robot's link names, which a sensor's frame must be one of.

    The model keeps the first block's name, type and hardware in its own fields and every
    block's joints, sensors and gpios (each knows its block), as the URDF reader does; with
    ``blocks:`` in the spec, ``blocks`` holds every block's hardware."""
    base = ("ros2_control",)
    specs: list[tuple[Block, Path_]] = [(rc, base)] + [(b, (*base, "blocks", i)) for i, b in enumerate(rc.blocks)]
    joints: list[m.ControlJoint] = []
    sensors: list[m.ControlSensor] = []
    gpios: list[m.ControlGpio] = []
    hardware: list[m.HardwareBlock] = []
    for block, path in specs:
        joints += [_joint(conv, cj, (*path, "joints", i), block.name) for i, cj in enumerate(block.joints)]
        sensors += [_sensor(conv, sp, (*path, "sensors", i), links, block.name) for i, sp in enumerate(block.sensors)]
        gpios += [_gpio(conv, g, (*path, "gpios", i), block.name) for i, g in enumerate(block.gpios)]
        hw = tuple((k, _param_text(v)) for k, v in block.hardware.params.items())
        variants = _variants(conv, block.hardware, (*path, "hardware"))
        hardware.append(
            m.HardwareBlock(
                block.name,
                block.hardware.plugin,
                hw,
                conv.where(path),
                block.type,
                variants,
                block.is_async,
                _rw_rate(conv, block, path),
                _thread_priority(conv, block, path),
                block.hardware.group,
            )
        )
        _unique_components(conv, block, path)
        _sensor_block_commands(conv, block, path)
    _blocks_agree(conv, specs, hardware)
    if len(specs) > 1 and any(v.name == "mujoco" for v in hardware[0].variants):
        # each MujocoSystemInterface loads the whole model and runs its own physics and /clock
        conv.error(
            SPEC149,
            f"the mujoco variant with {len(specs)} <ros2_control> blocks: each block's MujocoSystemInterface would "
            "run its own simulation of the whole model",
            "put every joint of the robot in one block for hardware:=mujoco",
            "ros2_control",
            conv.where((*base, "hardware", "variants", "mujoco")),
        )
    controllers = []
    for i, c in enumerate(rc.controllers):
        p = (*base, "controllers", i)
        params = tuple((k, param(v, (*p, "params", k))) for k, v in c.params.items())
        calibrated = tuple(
            m.Calibrated(
                k,
                cal.value.si,
                None if cal.tolerance is None else cal.tolerance.si,
                cal.source,
                conv.where((*p, "calibrated", k)),
            )
            for k, cal in c.calibrated.items()
        )
        controllers.append(m.Controller(c.name, c.type, params, conv.where(p), calibrated))
    first = hardware[0]
    return m.Ros2Control(
        rc.name,
        rc.type,
        first.plugin,
        first.params,
        tuple(joints),
        rc.update_rate.si,
        tuple(controllers),
        conv.where(base),
        sensors=tuple(sensors),
        # one block: no ``blocks`` (as before, so a one-block spec's model is unchanged)
        blocks=tuple(hardware) if rc.blocks else (),
        variants=first.variants,
        gpios=tuple(gpios),
        is_async=first.is_async,
        rw_rate=first.rw_rate,
        thread_priority=first.thread_priority,
        group=first.group,
    )


def _rw_rate(conv: Converter, block: Block, path: Path_) -> int | None:
    """The block's rw_rate in whole Hz (ros2_control reads an integer), or None."""
    if block.rw_rate is None:
        return None
    hz = block.rw_rate.si
    if hz < 0 or abs(hz - round(hz)) > 1e-9:
        conv.error(
            SPEC146,
            f"rw_rate is {hz:g} Hz: ros2_control reads a whole, non-negative number of Hz",
            f"write {max(0, round(hz))} Hz, or leave rw_rate out (the controller manager's rate)",
            f"ros2_control:{block.name}",
            conv.where((*path, "rw_rate")),
        )
        return None
    return round(float(hz))


def _thread_priority(conv: Converter, block: Block, path: Path_) -> int | None:
    if block.thread_priority is not None and block.is_async is not True:
        conv.error(
            SPEC147,
            f"thread_priority {block.thread_priority} is set, but the block is not is_async: true",
            "set is_async: true, or leave thread_priority out (Jazzy reads it only for an async component)",
            f"ros2_control:{block.name}",
            conv.where((*path, "thread_priority")),
        )
        return None
    return block.thread_priority


# What a joint interface's value is, by interface and joint type (convert.py's tables).
_QUANTITY = {"velocity": VELOCITY, "effort": EFFORT}
_DEFAULT_QUANTITY = {"velocity": ("angular_velocity", "angular_velocity"), "effort": ("torque", "torque")}


def _joint_quantity(conv: Converter, joint: str, iface: str, w: Written | None, path: Path_) -> float | None:
    """A joint interface's min/max/initial value in SI: position in the joint's own unit,
    velocity and effort in the units of the joint type (rad/s or m/s, N*m or N)."""
    if w is None:
        return None
    if iface == "position":
        return conv.joint_value(joint, w, path)
    jt = conv.joint_types.get(joint, "revolute")
    kind, role = _QUANTITY[iface].get(jt, _DEFAULT_QUANTITY[iface])
    return conv.si(w, kind, role, path)


def _joint(conv: Converter, cj: s.ControlJointSpec, p: Path_, block: str) -> m.ControlJoint:
    commands = []
    for i, c in enumerate(cj.command):
        if isinstance(c, str):
            commands.append(m.Interface(c))
            continue
        cp = (*p, "command", i)
        lo = _joint_quantity(conv, cj.name, c.name, c.min, (*cp, "min"))
        hi = _joint_quantity(conv, cj.name, c.name, c.max, (*cp, "max"))
        commands.append(m.Interface(c.name, lo, hi, data_type=c.data_type))
    initial = None
    if cj.initial_position is not None:
        initial = conv.joint_value(cj.name, cj.initial_position, (*p, "initial_position"))
    states = []
    for i, st in enumerate(cj.state):
        if isinstance(st, str):
            states.append(m.Interface(st, initial_value=initial if st == "position" else None))
            continue
        sp = (*p, "state", i)
        value = _joint_quantity(conv, cj.name, st.name, st.initial_value, (*sp, "initial_value"))
        if st.name == "position" and initial is not None:
            if value is not None:
                conv.error(
                    CTRL080,
                    f"ros2_control joint '{cj.name}': the initial position is given twice "
                    "(initial_position and the position state's initial_value)",
                    "keep one of them",
                    f"ros2_control:{cj.name}",
                    conv.where((*sp, "initial_value")),
                )
            value = initial
        states.append(m.Interface(st.name, initial_value=value, data_type=st.data_type))
    mimic = None if cj.mimic is None else _param_text(cj.mimic)
    params = tuple((k, _param_text(v)) for k, v in cj.params.items())
    return m.ControlJoint(
        cj.name, tuple(commands), tuple(states), cj.on_limit, conv.where(p), mimic, params, block=block
    )


def _variants(conv: Converter, hw: s.HardwareSpec, path: Path_) -> tuple[m.HardwareVariant, ...]:
    """mock (the hardware itself), then gazebo and real as declared; none without variants."""
    if not hw.variants:
        return ()
    params = tuple((k, _param_text(v)) for k, v in hw.params.items())
    out = [m.HardwareVariant("mock", hw.plugin, params, conv.where(path))]
    for name in ("gazebo", "real", "mujoco"):
        v = hw.variants.get(name)
        if v is not None:
            plugin = v.plugin or (s.MUJOCO_PLUGIN if name == "mujoco" else s.GZ_PLUGIN)
            vparams = tuple((k, _param_text(x)) for k, x in v.params.items())
            out.append(m.HardwareVariant(name, plugin, vparams, conv.where((*path, "variants", name))))
    return tuple(out)


_KIND_STATES = {"imu": IMU_INTERFACES, "force_torque": FT_INTERFACES}


def _sensor(
    conv: Converter, sp: s.ControlSensorSpec, path: Path_, links: Collection[str], block: str
) -> m.ControlSensor:
    state = _interfaces(conv, sp.state, (*path, "state"), sp.name) or tuple(
        m.Interface(n) for n in _KIND_STATES.get(sp.kind, ())
    )
    params = tuple((k, _param_text(v)) for k, v in sp.params.items())
    if sp.frame is not None:
        if links and sp.frame not in links:
            conv.error(
                SPEC083,
                f"ros2_control sensor '{sp.name}': frame '{sp.frame}' is not a link of the robot",
                "name a link; a spec sensor's link is <name>_link",
                f"sensor:{sp.name}",
                conv.where((*path, "frame")),
            )
        if "frame_id" not in dict(params):
            params = (("frame_id", sp.frame), *params)
    return m.ControlSensor(sp.name, state, conv.where(path), params, sp.frame, block)


def _gpio(conv: Converter, g: s.GpioSpec, path: Path_, block: str) -> m.ControlGpio:
    return m.ControlGpio(
        g.name,
        _interfaces(conv, g.command, (*path, "command"), g.name),
        _interfaces(conv, g.state, (*path, "state"), g.name),
        conv.where(path),
        block,
        tuple((k, _param_text(v)) for k, v in g.params.items()),
    )


def _interfaces(
    conv: Converter, items: list[s.Iface] | list[s.GpioIface], path: Path_, owner: str
) -> tuple[m.Interface, ...]:
    out: list[m.Interface] = []
    for i, it in enumerate(items):
        iface = (
            m.Interface(it)
            if isinstance(it, str)
            else m.Interface(it.name, it.min, it.max, it.initial_value, it.data_type)
        )
        if any(o.name == iface.name for o in out):
            conv.error(
                SPEC084,
                f"'{owner}' lists interface '{iface.name}' twice",
                "list each interface once",
                f"component:{owner}",
                conv.where((*path, i)),
            )
            continue
        out.append(iface)
    return tuple(out)


def _unique_components(conv: Converter, rc: Block, path: Path_) -> None:
    """Joints, sensors and gpios share one namespace of ``<component>/<interface>`` names."""
    seen: dict[str, str] = {}
    groups: tuple[tuple[str, Sequence[s.ControlJointSpec | s.ControlSensorSpec | s.GpioSpec]], ...] = (
        ("joints", rc.joints),
        ("sensors", rc.sensors),
        ("gpios", rc.gpios),
    )
    for kind, items in groups:
        for i, item in enumerate(items):
            if item.name in seen:
                conv.error(
                    SPEC084,
                    f"ros2_control component '{item.name}' is declared twice ({seen[item.name]} and {kind})",
                    "give each joint, sensor and gpio its own name",
                    f"component:{item.name}",
                    conv.where((*path, kind, i)),
                )
            seen[item.name] = kind


def _components(block: Block) -> list[tuple[str, int, str]]:
    """(kind, index, name) of every joint, sensor and gpio of a block."""
    groups: tuple[tuple[str, Sequence[s.ControlJointSpec | s.ControlSensorSpec | s.GpioSpec]], ...] = (
        ("joints", block.joints),
        ("sensors", block.sensors),
        ("gpios", block.gpios),
    )
    return [(kind, i, item.name) for kind, items in groups for i, item in enumerate(items)]


def _sensor_block_commands(conv: Converter, block: Block, path: Path_) -> None:
    """A ``sensor`` component exports no command interfaces (hardware_interface
    sensor_interface.hpp: ``on_export_command_interfaces`` returns ``{}``), so a command
    declared in one would never exist and every controller claiming it fails to activate."""
    if block.type != "sensor":
        return
    owners: list[tuple[str, int, str, int]] = [
        ("joints", i, cj.name, len(cj.command)) for i, cj in enumerate(block.joints)
    ] + [("gpios", i, g.name, len(g.command)) for i, g in enumerate(block.gpios)]
    for kind, i, name, count in owners:
        if count:
            conv.error(
                SPEC087,
                f"ros2_control block '{block.name}' is a sensor, but '{name}' has command interfaces; "
                "a sensor component exports none",
                "remove the commands, or make the block type: system (or actuator)",
                f"component:{name}",
                conv.where((*path, kind, i, "command")),
            )


# Plugins registered only as hardware_interface::SystemInterface: pluginlib cannot load them
# for an actuator or sensor block (hardware_interface/mock_components_plugin_description.xml;
# gz_ros2_control's GazeboSimSystemInterface derives from SystemInterface).
SYSTEM_ONLY_PLUGINS = (s.MOCK_PLUGIN, s.GZ_PLUGIN)


def _blocks_agree(conv: Converter, specs: list[tuple[Block, Path_]], hardware: list[m.HardwareBlock]) -> None:
    """Across blocks: names unique, no component in two blocks, every block's plugins loadable
    for its type, and one set of hardware variants (a single ``hardware:=`` selects them all)."""
    names: dict[str, int] = {}
    owner: dict[str, str] = {}
    first_variants = [v.name for v in hardware[0].variants]
    for (block, path), hw in zip(specs, hardware, strict=True):
        if block.name in names:
            conv.error(
                SPEC086,
                f"two ros2_control blocks are named '{block.name}'; Jazzy's resource manager refuses "
                "a duplicated hardware name and loads no hardware",
                "give each block its own name",
                f"ros2_control:{block.name}",
                conv.where((*path, "name")),
            )
        names.setdefault(block.name, 0)
        for kind, i, name in _components(block):
            if name in owner and owner[name] != block.name:
                conv.error(
                    SPEC085,
                    f"'{name}' is in ros2_control blocks '{owner[name]}' and '{block.name}'; Jazzy's resource "
                    f"manager refuses the second '{name}/...' interface (already existing key) and loads no hardware",
                    "keep each joint, sensor and gpio in one block",
                    f"component:{name}",
                    conv.where((*path, kind, i)),
                )
            owner.setdefault(name, block.name)
        plugins = [("hardware", hw.plugin)] + [(f"variants.{v.name}", v.plugin) for v in hw.variants[1:]]
        for where_, plugin in plugins:
            if block.type != "system" and plugin in SYSTEM_ONLY_PLUGINS:
                at = (*path, "hardware") if where_ == "hardware" else (*path, "hardware", *where_.split("."))
                conv.error(
                    SPEC088,
                    f"ros2_control block '{block.name}' has type: {block.type}, but {plugin} is a system "
                    "plugin only: Jazzy cannot load it for an actuator or sensor",
                    "make the block type: system (mock and Gazebo hardware are systems), or name the vendor's plugin",
                    f"ros2_control:{block.name}",
                    conv.where(at),
                )
        if hw is not hardware[0] and [v.name for v in hw.variants] != first_variants:

            def listed(names: list[str]) -> str:
                return "variants " + ", ".join(names) if names else "no variants"

            conv.error(
                SPEC089,
                f"ros2_control block '{block.name}' declares {listed([v.name for v in hw.variants])}, the first "
                f"block {listed(first_variants)}; one Xacro argument hardware:= selects every block's variant",
                "declare the same variants (gazebo, real) under every block's hardware",
                f"ros2_control:{block.name}",
                conv.where((*path, "hardware")),
            )


def param(value: object, path: Path_) -> object:
    """Controller parameters pass through; text that starts with a number and has a
    unit (``"500 ms"``, ``"0.5 m/s"``, ``"90 deg/s"``) is converted to SI."""
    if isinstance(value, str) and _NUMERIC_START.match(value):
        try:
            q = units.parse(value)
        except units.QuantityError:
            return value
        if q.unitless:
            return value
        return float(q.to_base_units().magnitude) + 0.0
    if isinstance(value, list):
        return tuple(param(v, (*path, i)) for i, v in enumerate(value))
    if isinstance(value, dict):
        return tuple((str(k), param(v, (*path, str(k)))) for k, v in value.items())
    return value


def _param_text(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"  # ros2_control's parse_bool takes only true/false
    return str(v)
