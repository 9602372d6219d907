"""``<ros2_control>`` blocks and a controller_manager YAML -> the spec's ``ros2_control:``.

A block goes into the spec only when every part of it has a spec field (hardware plugin and
params, joints with command/state interfaces and their min/max/initial_value, sensors, gpios,
the ``mimic`` attribute); otherwise all blocks stay verbatim in pass-through (IMP021 says why),
so nothing is lost and one block is never written twice.

generate adds what the description leaves to ros2_control's defaults: command ``min``/``max``
from the URDF joint limits (Jazzy only tightens limits with them, so equal values change
nothing: docs/reference/ros2_control.md section 3) and a state ``initial_value`` (0, GenericSystem's
default for a NaN joint state). Those additions are listed (IMP022) and the round trip allows
exactly them, nothing else (:func:`block_differences`).
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lxml import etree

from descgen.codes.importer import IMP020, IMP021, IMP022, IMP023, IMP024, IMP025, IMP031, IMP032
from descgen.commands.importer.spec import SpecWriter, number
from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.core.xmlcompare import line_of
from descgen.infra.safeio import read_bounded
from descgen.physics import component_parser, derive
from descgen.physics.hardware_info import parsed_bool
from descgen.read import params
from descgen.read.controllers import Parsed, manager_view, parse_substituted
from descgen.spec.convert import EFFORT, POSITION, VELOCITY
from descgen.spec.models import (
    CALIBRATABLE,
    GPIO_INTERFACE_PATTERN,
    GPIO_NAME_PATTERN,
    INTERFACE_PATTERN,
    NAME_PATTERN,
    PARAM_NAME_PATTERN,
)

Data = dict[str, Any]
Locate = Callable[[etree._Element], Where | None]

_NAME = re.compile(NAME_PATTERN)
_PARAM_NAME = re.compile(PARAM_NAME_PATTERN)
_GPIO_NAME = re.compile(GPIO_NAME_PATTERN)
_GPIO_IFACE = re.compile(GPIO_INTERFACE_PATTERN)
_IFACE = re.compile(INTERFACE_PATTERN)
_PLUGIN = re.compile(r"^[A-Za-z0-9_/:]+$")
_CONTROLLER_TYPE = re.compile(r"^[A-Za-z0-9_]+/[A-Za-z0-9_]+$")
_ONE_LINE = re.compile(r"[\x00-\x1f\x7f-\x9f\u2028\u2029]")
_JOINT_IFACES = ("position", "velocity", "acceleration", "effort")
_PARAM_IFACES = ("position", "velocity", "effort")  # the spec knows their units per joint type
_DATA_TYPES = ("double", "bool", "float32", "uint8", "int8", "uint16", "int16", "uint32", "int32")
DEFAULT_UPDATE_RATE = 100  # Hz, controller_manager's default (docs/reference/ros2_control.md section 4)


def _elements(e: etree._Element) -> list[etree._Element]:
    return [c for c in e if isinstance(c.tag, str)]


def _number(text: str | None) -> float | None:
    try:
        v = float((text or "").strip())
    except ValueError:
        return None
    return v if math.isfinite(v) else None


# -- what the spec can express ------------------------------------------------------------------


def _iface_problem(
    e: etree._Element,
    owner: str,
    names: tuple[str, ...] | None,
    params: tuple[str, ...],
    pattern: re.Pattern[str] | None = None,
) -> str | None:
    name = e.get("name", "")
    if set(e.attrib) - {"name", "data_type"}:
        return f"{owner} interface '{name}' has attributes {sorted(set(e.attrib) - {'name', 'data_type'})}"
    if (names is not None and name not in names) or (names is None and not (pattern or _IFACE).fullmatch(name)):
        return f"{owner} has interface '{name}', which the spec does not name"
    if e.get("data_type") is not None and e.get("data_type") not in _DATA_TYPES:
        return f"{owner} interface '{name}' has data_type '{e.get('data_type')}'"
    seen = set()
    for p in _elements(e):
        key = p.get("name", "")
        if p.tag != "param" or set(p.attrib) != {"name"} or _elements(p) or key not in params or key in seen:
            return f"{owner} interface '{name}' holds <{p.tag} name='{key}'>, which the spec has no field for"
        seen.add(key)
        if _number(p.text) is None:
            return f"{owner} interface '{name}' param {key} is '{(p.text or '').strip()}', not a finite number"
    return None


def _params_problem(e: etree._Element, owner: str) -> str | None:
    seen = set()
    for p in e.findall("param"):
        key = p.get("name", "")
        text = (p.text or "").strip()
        if (
            set(p.attrib) != {"name"}
            or _elements(p)
            or not _PARAM_NAME.fullmatch(key)
            or key in seen
            or _ONE_LINE.search(text)
        ):
            return f"{owner} param '{key}' is not a plain name=value parameter the spec can hold"
        seen.add(key)
    return None


def _not_plain_bool(text: str | None) -> bool:
    """A boolean attribute the spec's true/false cannot give back as written: one Jazzy
    refuses, or one it reads only after stripping whitespace (kept verbatim in pass-through)."""
    return text is not None and (parsed_bool(text) is None or text != text.strip())


def _joint_problem(je: etree._Element, robot: m.Robot) -> str | None:
    name = je.get("name", "")
    owner = f"joint '{name}'"
    if set(je.attrib) - {"name", "mimic"}:
        return f"{owner} has attributes {sorted(set(je.attrib) - {'name', 'mimic'})}"
    if _not_plain_bool(je.get("mimic")):
        return f"{owner} has mimic='{je.get('mimic')}' (ros2_control reads only true/false)"
    if (p := _params_problem(je, owner)) is not None:
        return p
    for c in _elements(je):
        if c.tag == "param":
            continue  # the joint's own params: params: of the spec's joint
        if c.tag == "command_interface":
            allowed: tuple[str, ...] = ("min", "max")
        elif c.tag == "state_interface":
            allowed = ("initial_value",)
        else:
            return f"{owner} holds <{c.tag}>, which the spec has no field for"
        if c.get("name", "") not in _JOINT_IFACES and not _elements(c) and set(c.attrib) == {"name"}:
            names: tuple[str, ...] | None = None  # any other name the hardware exports (kp, kd), bare
        else:
            names = _PARAM_IFACES if _elements(c) else _JOINT_IFACES
        problem = _iface_problem(c, owner, names, allowed)
        if problem:
            return problem
    return None


# the <ros2_control> attributes the spec holds (rw_rate and thread_priority as written canonically)
_BLOCK_ATTRIBUTES = ("name", "type", "is_async", "rw_rate", "thread_priority")


def _number_problem(block: etree._Element) -> str | None:
    """rw_rate or thread_priority as the spec cannot give it back: not the plain decimal the
    parser reads (std::stoi takes "50abc" as 50), or a thread_priority the parser ignores."""
    rate, priority = block.get("rw_rate"), block.get("thread_priority")
    if rate is not None and (component_parser.rw_rate(rate) is None or rate != str(component_parser.rw_rate(rate))):
        return f"the block has rw_rate='{rate}', not a plain whole number of Hz"
    if priority is not None:
        value = component_parser.thread_priority(priority)
        if value is None or priority != str(value) or block.get("is_async") != "true":
            return f"the block has thread_priority='{priority}' (the spec holds one only for is_async=\"true\")"
    return None


def problem(block: etree._Element, robot: m.Robot) -> str | None:
    """Why ``block`` cannot be written in the spec's ``ros2_control:`` (None: it can)."""
    name = block.get("name", "")
    if set(block.attrib) - set(_BLOCK_ATTRIBUTES):
        return f"the block has attributes {sorted(set(block.attrib) - set(_BLOCK_ATTRIBUTES))}"
    if _not_plain_bool(block.get("is_async")):
        return f"the block has is_async='{block.get('is_async')}' (ros2_control reads only true/false)"
    if (p := _number_problem(block)) is not None:
        return p
    if not _NAME.fullmatch(name):
        return f"the block name '{name}' is not a plain identifier"
    if block.get("type", "system") not in ("system", "actuator", "sensor"):
        return f"the block type is '{block.get('type')}'"
    hw = block.findall("hardware")
    if len(hw) != 1:
        return f"the block has {len(hw)} <hardware> elements"
    plugins = hw[0].findall("plugin")
    if len(plugins) != 1 or not _PLUGIN.fullmatch((plugins[0].text or "").strip()):
        return "the hardware plugin is missing, repeated or not a plugin name"
    if any(c.tag not in ("plugin", "param", "group") for c in _elements(hw[0])):
        return "the hardware holds elements other than <plugin>, <param> and <group>"
    groups = hw[0].findall("group")
    if len(groups) > 1 or any(not _NAME.fullmatch(g.text or "") or _elements(g) or g.attrib for g in groups):
        return "the hardware's <group> is repeated or not a plain name"
    if (p := _params_problem(hw[0], "hardware")) is not None:
        return p
    for c in _elements(block):
        cname = c.get("name", "")
        if c.tag == "hardware":
            continue
        if c.tag == "joint":
            p = _joint_problem(c, robot)
        elif c.tag in ("sensor", "gpio"):
            kinds = (
                ("state_interface", "param") if c.tag == "sensor" else ("command_interface", "state_interface", "param")
            )
            if set(c.attrib) != {"name"} or not (_GPIO_NAME if c.tag == "gpio" else _NAME).fullmatch(cname):
                p = f"{c.tag} '{cname}' has a name or attributes the spec cannot hold"
            elif any(x.tag not in kinds for x in _elements(c)):
                p = f"{c.tag} '{cname}' holds elements other than {', '.join(kinds)}"
            else:
                p = _params_problem(c, f"{c.tag} '{cname}'") or next(
                    (
                        q
                        for x in _elements(c)
                        if x.tag != "param"
                        and (
                            q := _iface_problem(
                                x,
                                f"{c.tag} '{cname}'",
                                None,
                                ("min", "max", "initial_value"),
                                _GPIO_IFACE if c.tag == "gpio" else None,
                            )
                        )
                    ),
                    None,
                )
        else:
            p = f"the block holds <{c.tag}>, which the spec has no field for"
        if p is not None:
            return p
    return None


# -- spec data -----------------------------------------------------------------------------------


def _params(e: etree._Element) -> dict[str, str]:
    return {p.get("name", ""): (p.text or "").strip() for p in e.findall("param")}


def _joint_kind(robot: m.Robot, joint: str, iface: str) -> str:
    j = robot.joint(joint)
    jt = j.type if j is not None else "revolute"
    table = {"position": POSITION, "velocity": VELOCITY, "effort": EFFORT}[iface]
    default = {"position": "angle", "velocity": "angular_velocity", "effort": "torque"}[iface]
    return table.get(jt, (default, ""))[0]


def _joint_iface(w: SpecWriter, robot: m.Robot, joint: str, e: etree._Element) -> str | Data:
    """A joint's interface: its min/max/initial_value as quantities of the joint's kind."""
    kind = _joint_kind(robot, joint, e.get("name", "")) if _params(e) else ""
    return _iface(e, lambda v: w.q(v, kind), ("min", "max", "initial_value"))


def _interfaces(
    e: etree._Element,
    read: Callable[[etree._Element], str | Data],
    kinds: tuple[str, ...] = ("command", "state"),
) -> Data:
    """``command:``/``state:`` lists of an element's interfaces, each kind only when it has one."""
    out: Data = {}
    for kind in kinds:
        if found := [read(c) for c in e.findall(f"{kind}_interface")]:
            out[kind] = found
    return out


def _iface(
    e: etree._Element,
    value: Callable[[float], object] = number,
    keys: tuple[str, ...] = ("initial_value", "min", "max"),
) -> str | Data:
    """An interface as the spec writes it: the bare name, or name, data_type and ``keys``
    (each through ``value``) for one that has parameters or a data type."""
    params = _params(e)
    if not params and e.get("data_type") is None:
        return e.get("name", "")
    out: Data = {"name": e.get("name", "")}
    if e.get("data_type") is not None:
        out["data_type"] = e.get("data_type")
    for key in keys:
        if key in params:
            out[key] = value(float(params[key]))
    return out


def block_data(block: etree._Element, robot: m.Robot, w: SpecWriter, source: Callable[[etree._Element], str]) -> Data:
    """One block as the spec writes it (name, type, hardware, joints, sensors, gpios)."""
    hw = block.find("hardware")
    assert hw is not None  # problem() said so
    hardware: Data = {"plugin": (hw.findtext("plugin") or "").strip()}
    if params := _params(hw):
        hardware["params"] = params
    if (group := hw.findtext("group")) is not None:
        hardware["group"] = group
    out: Data = {"name": block.get("name", ""), "type": block.get("type", "system")}
    if block.get("is_async") is not None:
        out["is_async"] = block.get("is_async", "").lower() == "true"
    if block.get("rw_rate") is not None:
        out["rw_rate"] = f"{block.get('rw_rate')} Hz"
    if block.get("thread_priority") is not None:
        out["thread_priority"] = int(block.get("thread_priority", ""))
    out["hardware"] = hardware
    joints = []
    for je in block.findall("joint"):
        name = je.get("name", "")
        j: Data = {"name": name, **_interfaces(je, functools.partial(_joint_iface, w, robot, name))}
        if je.get("mimic") is not None:
            j["mimic"] = je.get("mimic", "").lower() == "true"
        if params := _params(je):
            j["params"] = params
        j["source"] = source(je)
        joints.append(j)
    sensors = []
    for se in block.findall("sensor"):
        s: Data = {"name": se.get("name", ""), **_interfaces(se, _iface, kinds=("state",))}
        if params := _params(se):
            s["params"] = params
        s["source"] = source(se)
        sensors.append(s)
    gpios = []
    for ge in block.findall("gpio"):
        g: Data = {"name": ge.get("name", ""), **_interfaces(ge, _iface)}
        if params := _params(ge):
            g["params"] = params
        g["source"] = source(ge)
        gpios.append(g)
    for key, items in (("joints", joints), ("sensors", sensors), ("gpios", gpios)):
        if items:
            out[key] = items
    out["source"] = source(block)
    return out


def additions(block: etree._Element, robot: m.Robot) -> list[str]:
    """The params generate will write that ``block`` leaves to ros2_control's defaults."""
    out = []
    for je in block.findall("joint"):
        j = robot.joint(je.get("name", ""))
        for c in je.findall("command_interface"):
            lo, hi = derive.command_limits(j, c.get("name", ""))
            params = _params(c)
            out += [
                f"{je.get('name')}/{c.get('name')} {k}"
                for k, v in (("min", lo), ("max", hi))
                if v is not None and k not in params
            ]
        for c in je.findall("state_interface"):
            if "initial_value" not in _params(c):
                out.append(f"{je.get('name')}/{c.get('name')} initial_value")
    return out


# -- the round trip of the blocks ----------------------------------------------------------------


def _ifaces(e: etree._Element, tag: str) -> list[tuple[str, str | None, dict[str, float | str]]]:
    out = []
    for i in e.findall(tag):
        params: dict[str, float | str] = {}
        for k, v in _params(i).items():
            f = _number(v)
            params[k] = v if f is None else f
        out.append((i.get("name", ""), i.get("data_type"), params))
    return out


def _derived(robot: m.Robot, joint: str, kind: str, iface: str, key: str) -> float | None:
    """What generate writes for a param the description left out (None: nothing)."""
    j = robot.joint(joint)
    if kind == "command_interface":
        lo, hi = derive.command_limits(j, iface)
        return {"min": lo, "max": hi}.get(key)
    if key == "initial_value":
        return derive.initial_position(j, None) if iface == "position" else 0.0
    return None


def block_differences(original: list[etree._Element], written: list[etree._Element], robot: m.Robot) -> list[str]:
    """The blocks as ros2_control's parser reads them, original against written: names, types,
    plugin, params (text), each joint's mimic and interfaces (params as numbers), sensors and
    gpios. A param only in the written block must be exactly what generate derives for a
    missing one (:func:`additions`); comments and layout are not data."""
    out: list[str] = []
    if [b.get("name") for b in original] != [b.get("name") for b in written]:
        names = [b.get("name") for b in original], [b.get("name") for b in written]
        return [f"ros2_control blocks {names[0]}, after the round trip {names[1]}"]
    for a, b in zip(original, written, strict=True):
        at = f"ros2_control:{a.get('name')}"

        def eq(what: str, x: object, y: object, at: str = at) -> None:
            if x != y:
                out.append(f"{at}/{what}: {x!r} in the description, {y!r} after the round trip")

        eq("type", a.get("type", "system"), b.get("type", "system"))
        eq("is_async", (a.get("is_async") or "false").lower(), (b.get("is_async") or "false").lower())
        eq("rw_rate", a.get("rw_rate"), b.get("rw_rate"))
        eq("thread_priority", a.get("thread_priority"), b.get("thread_priority"))
        eq("group", a.findtext("hardware/group"), b.findtext("hardware/group"))
        eq("plugin", (a.findtext("hardware/plugin") or "").strip(), (b.findtext("hardware/plugin") or "").strip())
        ha, hb = a.find("hardware"), b.find("hardware")
        eq("hardware params", _params(ha) if ha is not None else {}, _params(hb) if hb is not None else {})
        ja, jb = a.findall("joint"), b.findall("joint")
        eq("joints", [j.get("name") for j in ja], [j.get("name") for j in jb])
        for x, y in zip(ja, jb, strict=False):
            name = x.get("name", "")
            eq(f"joint:{name}/mimic", (x.get("mimic") or "").lower() or None, y.get("mimic"))
            eq(f"joint:{name}/params", _params(x), _params(y))
            for kind in ("command_interface", "state_interface"):
                mine, back = _ifaces(x, kind), _ifaces(y, kind)
                if [i[:2] for i in mine] != [i[:2] for i in back]:
                    eq(f"joint:{name}/{kind}s", [i[:2] for i in mine], [i[:2] for i in back])
                    continue
                for (iname, _, pa), (_, _, pb) in zip(mine, back, strict=True):
                    extra = {k: v for k, v in pb.items() if k not in pa and v == _derived(robot, name, kind, iname, k)}
                    eq(f"joint:{name}/{kind}:{iname}", pa, {k: v for k, v in pb.items() if k not in extra})
        for tag, kinds in (("sensor", ("state_interface",)), ("gpio", ("command_interface", "state_interface"))):
            sa, sb = a.findall(tag), b.findall(tag)
            eq(f"{tag}s", [s.get("name") for s in sa], [s.get("name") for s in sb])
            for x, y in zip(sa, sb, strict=False):
                for kind in kinds:
                    eq(f"{tag}:{x.get('name')}/{kind}s", _ifaces(x, kind), _ifaces(y, kind))
                eq(f"{tag}:{x.get('name')}/params", _params(x), _params(y))
        eq(
            "elements",
            sorted(str(c.tag) for c in _elements(a)),
            sorted(str(c.tag) for c in _elements(b)),
        )
    return out


# -- the controllers YAML ------------------------------------------------------------------------


@dataclass
class Controllers:
    data: list[Data] = field(default_factory=list)  # the spec's controllers
    update_rate: float | None = None  # as the file gives it; None: not given (100 Hz written)
    names: tuple[str, ...] = ()  # the controllers imported (what the round trip compares)
    report: list[Finding] = field(default_factory=list)
    text: str = ""  # the file as read (the round trip loads it again with yaml.safe_load)


def _not_imported(what: str, where: Where, subject: str) -> Finding:
    return IMP024.finding(
        f"{what} is not imported from the controllers file (the spec has no field for it)",
        "the generated config/ros2_controllers.yaml lacks it; keep it in a file of your own if the robot needs it",
        subject,
        where,
    )


def _parsed(text: str, shown: str, launch_args: Mapping[str, str] | None) -> tuple[Parsed, list[Finding]]:
    """The controllers file as ROS loads it (descgen/read/params.py), after its ``$(var NAME)``
    launch substitutions (core/launch_subst.py), and an IMP031 per substitution; InputError
    (IMP032) when one has no value or is not evaluated: the spec's joint names must be real
    joints, never the ``$(var ...)`` text; InputError (READ045) for a file ROS refuses."""
    parsed = parse_substituted(text, shown, launch_args)
    unresolved = [f for f in parsed.found if f.code in ("CTRL052", "CTRL053")]
    if unresolved:
        raise InputError(
            [
                IMP032.finding(
                    f"cannot import the controllers: {f.message}",
                    f.hint if f.code == "CTRL052" else "write the value into the file, or import without --controllers",
                    "controllers",
                    f.where,
                )
                for f in unresolved
            ]
        )
    refused = [f for f in parsed.found if f.code == "READ045"]
    if refused:
        raise InputError(refused)
    report = [
        IMP031.finding(
            f"launch substitution '{site.text}' is imported as {site.value!r}",
            "the spec holds the substituted names; import again with other --launch-arg values for another launch",
            "controllers",
            site.where,
        )
        for site in parsed.sites
    ]
    return parsed, report + [f for f in parsed.found if f.code != "READ045"]


def _plain(value: object) -> object:
    """A parameter value as the spec writes it: a list for a list."""
    return list(value) if isinstance(value, tuple) else value


def read_controllers(path: Path, w: SpecWriter, launch_args: Mapping[str, str] | None = None) -> Controllers:
    """The controller_manager YAML as the spec's controllers, read as ROS loads it (any form rcl
    accepts: classic, ``/**:`` blocks, namespaced): each controller's type (classic
    ``controller_manager.ros__parameters.<name>.type`` or ``<name>.ros__parameters.type``) and
    parameters, the update rate; diff_drive's wheel_separation/wheel_radius as ``calibrated``
    values (the file's, with its line: generate writes them instead of the URDF-derived ones)."""
    shown = str(path)
    text = read_bounded(path, "controllers YAML", display=shown).decode("utf-8", "replace")
    parsed, report = _parsed(text, shown, launch_args)
    out = Controllers(text=parsed.text, report=report)  # the round trip loads the substituted text again
    view = manager_view(parsed.params)

    def src(where: Where) -> str:
        return f"{Path(where.file).name}:{where.line}"

    declared = {d.name for d in view.controllers}
    # an entry for every node (/**: ros__parameters:) reaches the controller manager too: said once, below
    everyone = {
        (p.name, p.key_where) for n in parsed.params.nodes if "*" in n.name.rsplit("/", 1)[-1] for p in n.params
    }
    for key, p in view.params.items():
        if (p.name, p.key_where) in everyone:
            continue
        head, dot, tail = key.partition(".")
        value = p.value
        if (
            key == "update_rate"
            and isinstance(value, int | float)
            and not isinstance(value, bool)
            and math.isfinite(value)
        ):
            out.update_rate = value
            continue
        if dot and tail == "type" and head in declared:
            continue
        out.report.append(_not_imported(f"controller_manager parameter '{key}'", p.key_where, "controllers"))
    for node in parsed.params.nodes:
        last = node.name.rsplit("/", 1)[-1]
        if "*" in last:  # an entry for every node (/**: ros__parameters:): the spec has no place for it
            for p in node.params:
                out.report.append(
                    _not_imported(
                        f"parameter '{p.name}' of every node ({node.name})", p.key_where, f"controller:{node.name}"
                    )
                )
    for name, where in view.untyped:
        out.report.append(_not_imported(f"'{name}' (no controller type names it)", where, f"controller:{name}"))
    names = []
    for d in view.controllers:
        if not _NAME.fullmatch(d.name) or not _CONTROLLER_TYPE.fullmatch(d.type):
            out.report.append(
                _not_imported(
                    f"controller '{d.name}' of type '{d.type}' (not a plain name/type)", d.where, f"controller:{d.name}"
                )
            )
            continue
        c: Data = {"name": d.name, "type": d.type}
        own = params.nested(d.params, d.spaces)
        calibrated: Data = {}
        for key in CALIBRATABLE.get(d.type, ()):
            v = own.get(key)
            if isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) and v > 0:
                calibrated[key] = {"value": w.q(float(v), "length"), "source": src(d.params[key].key_where)}
                del own[key]
        if own:
            c["params"] = own
        if calibrated:
            c["calibrated"] = calibrated
        c["source"] = src(d.where)
        out.data.append(c)
        names.append(d.name)
    out.names = tuple(names)
    return out


def _controllers_view(text: str, file: str, names: tuple[str, ...]) -> dict[str, Any]:
    """A controllers file as ROS loads it -> {update_rate, name: (type, params)} for the named
    controllers: whichever form declares them, key order not data."""
    view = manager_view(parse_substituted(text, file).params)
    rate = view.params.get("update_rate")
    out: dict[str, Any] = {"update_rate": rate.value if rate is not None else None}
    by_name = {d.name: d for d in view.controllers}
    for n in names:
        d = by_name.get(n)
        out[n] = (d.type, {k: p.value for k, p in d.params.items()}) if d is not None else (None, {})
    return out


def controllers_differences(
    original_text: str, written_text: str, imported: Controllers, diff_drive: set[str]
) -> list[str]:
    """The imported parts of the original file against the generated one, both read as ROS loads
    them (rcl's parser, rclcpp's node matching). Normalised: where ``type`` stands, which form
    declares the controllers, key order, 0.1 = 0.10; allowed additions: update_rate 100 when the
    file has none, and diff_drive's wheel_separation/wheel_radius (derived from the URDF) when
    the file has none."""
    a = _controllers_view(original_text, "controllers (imported)", imported.names)
    b = _controllers_view(written_text, "controllers (generated)", imported.names)
    out = []
    rate = a["update_rate"] if a["update_rate"] is not None else DEFAULT_UPDATE_RATE
    if rate != b["update_rate"]:
        out.append(
            f"controllers update_rate: {a['update_rate']!r} in the file, {b['update_rate']!r} after the round trip"
        )
    for n in imported.names:
        (ta, pa), (tb, pb) = a[n], b[n]
        if n in diff_drive:
            pb = {k: v for k, v in pb.items() if k in pa or k not in ("wheel_separation", "wheel_radius")}
        if (ta, pa) != (tb, pb):
            keys = sorted({*pa, *pb}, key=str)
            changed = [k for k in keys if pa.get(k, "<absent>") != pb.get(k, "<absent>")] or ["type"]
            out.append(f"controller:{n}: {', '.join(map(str, changed))} differ after the round trip")
    return out


def locate_source(locate: Locate, shown: str, source_name: Callable[[Where], str]) -> Callable[[etree._Element], str]:
    return lambda e: source_name(locate(e) or Where(shown, line_of(e)))


@dataclass
class Imported:
    data: Data | None = None  # the spec's ros2_control section; None: the blocks stay pass-through
    blocks: tuple[str, ...] = ()  # the imported blocks' XML, for the round trip
    controllers: Controllers | None = None
    report: list[Finding] = field(default_factory=list)


def import_control(
    root: etree._Element,
    robot: m.Robot,
    w: SpecWriter,
    source: Callable[[etree._Element], str],
    where: Callable[[etree._Element], Where],
    controllers: Path | None,
    xacro_args: dict[str, str],
    launch_args: Mapping[str, str] | None = None,
) -> Imported:
    """The spec's ros2_control section for ``root``'s blocks and ``controllers`` (or why not)."""
    blocks = root.findall("ros2_control")
    if not blocks:
        return Imported()
    problems = [(b, p) for b in blocks if (p := problem(b, robot)) is not None]
    if problems:
        return Imported(
            report=[
                IMP021.finding(
                    f"ros2_control block '{b.get('name', '')}' stays in passthrough: {p}",
                    "generate writes it back unchanged; move it into ros2_control: by hand once the spec can say it",
                    f"ros2_control:{b.get('name', '')}",
                    where(b),
                )
                for b, p in problems
            ]
        )
    first, *rest = [block_data(b, robot, w, source) for b in blocks]
    out = Imported(blocks=tuple(etree.tostring(b, encoding="unicode", with_tail=False) for b in blocks))
    data: Data = {k: v for k, v in first.items() if k != "source"}
    ctl = read_controllers(controllers, w, launch_args) if controllers is not None else None
    rate = ctl.update_rate if ctl is not None and ctl.update_rate is not None else None
    data["update_rate"] = f"{number(float(rate if rate is not None else DEFAULT_UPDATE_RATE))} Hz"
    if rest:
        data["blocks"] = rest
    if ctl is not None and ctl.data:
        data["controllers"] = ctl.data
    data["source"] = first["source"]
    out.data, out.controllers = data, ctl
    args = ", ".join(f"{k}:={v}" for k, v in sorted(xacro_args.items())) or "no --xacro-arg"
    for b in blocks:
        out.report.append(
            IMP020.finding(
                f"ros2_control block '{b.get('name', '')}' is imported with hardware "
                f"{(b.findtext('hardware/plugin') or '').strip()}: the variant the description expands to with {args}",
                "a Xacro that chooses its hardware by an argument has other variants; import with those "
                "arguments to see them, and add them under hardware.variants by hand",
                f"ros2_control:{b.get('name', '')}",
                where(b),
            )
        )
        if added := additions(b, robot):
            out.report.append(
                IMP022.finding(
                    f"generate writes {len(added)} interface param(s) that block '{b.get('name', '')}' leaves to "
                    f"ros2_control's defaults: {', '.join(added[:6])}{' ...' if len(added) > 6 else ''}",
                    "command min/max equal the URDF limits (Jazzy only tightens with them); initial_value is 0 "
                    "(or the middle of a range without 0); check they suit your hardware",
                    f"ros2_control:{b.get('name', '')}",
                    where(b),
                )
            )
    if rate is None:
        out.report.append(
            IMP023.finding(
                f"the controller manager's update_rate is not given; the spec says {DEFAULT_UPDATE_RATE} Hz, "
                "controller_manager's default",
                "write the rate your hardware runs at in ros2_control.update_rate",
                "ros2_control",
                Where(str(controllers)) if controllers is not None else where(blocks[0]),
            )
        )
    if ctl is not None:
        out.report += ctl.report
        for c in ctl.data:
            missing = [k for k in CALIBRATABLE.get(c["type"], ()) if k not in c.get("calibrated", {})]
            if missing:
                out.report.append(
                    IMP025.finding(
                        f"controller '{c['name']}': the file gives no {'/'.join(missing)}; generate writes "
                        "the values derived from the URDF",
                        "state measured values under calibrated: if the robot has them",
                        f"controller:{c['name']}",
                        Where(str(controllers)),
                    )
                )
    return out
