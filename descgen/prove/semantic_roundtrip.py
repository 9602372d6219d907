"""Check 2b: the SRDF, the ``<ros2_control>`` block and the controllers YAML, read back
with lxml and pyyaml, say what the model says."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from lxml import etree

from descgen.codes import Code
from descgen.codes.generate import GEN031, GEN032, GEN033
from descgen.core.findings import Finding, Where
from descgen.core.model import Interface, Robot
from descgen.core.xmlcompare import line_of, parse
from descgen.physics import derive
from descgen.prove.controllers import safe_load
from descgen.render.context import node_key


def _f(text: str | None) -> float | None:
    try:
        return None if text is None else float(text)
    except ValueError:
        return math.nan


def _values(text: str | None) -> float | list[float] | None:
    """One number, or the list a planar/floating joint's value is (srdfdom splits on space)."""
    parts = (text or "").split()
    if len(parts) < 2:
        return _f(text)
    return [v if (v := _f(p)) is not None else math.nan for p in parts]


def _same(a: Any, b: Any) -> bool:
    if (
        isinstance(a, float | int)
        and isinstance(b, float | int)
        and not isinstance(a, bool)
        and not isinstance(b, bool)
    ):
        return math.isclose(float(a), float(b), rel_tol=0, abs_tol=1e-9)
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list | tuple) and isinstance(b, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(a == b)


class _Diffs:
    def __init__(self, file: str, code: Code, what: str) -> None:
        self.file, self.code, self.what = file, code, what
        self.found: list[Finding] = []

    def eq(self, path: str, model: Any, written: Any, line: int = 0) -> None:
        if not _same(model, written):
            self.found.append(
                self.code.finding(
                    f"{self.what} read back differs at {path}: model {model!r}, file {written!r}",
                    "the template writes this wrong (or the file was edited)",
                    path.split("/")[0],
                    Where(self.file, line),
                )
            )


def srdf_roundtrip(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    rel = f"srdf/{robot.name}.srdf"
    sem = robot.semantic
    if sem is None or rel not in files:
        return []
    d = _Diffs(str(where / rel), GEN031, "SRDF")
    try:
        root = parse(files[rel])
    except etree.XMLSyntaxError as exc:
        return [GEN031.finding(f"SRDF does not parse: {exc}", "check the SRDF template", "file", Where(d.file))]
    d.eq("robot/name", robot.name, root.get("name"), line_of(root))
    groups = {g.get("name"): g for g in root.findall("group")}
    d.eq("groups", [g.name for g in sem.groups], list(groups))
    for g in sem.groups:
        e = groups.get(g.name)
        if e is None:
            continue
        line = line_of(e)
        d.eq(
            f"group:{g.name}/chains",
            [list(c) for c in g.chains],
            [[c.get("base_link"), c.get("tip_link")] for c in e.findall("chain")],
            line,
        )
        d.eq(f"group:{g.name}/links", list(g.links), [x.get("name") for x in e.findall("link")], line)
        d.eq(f"group:{g.name}/joints", list(g.joints), [x.get("name") for x in e.findall("joint")], line)
        d.eq(f"group:{g.name}/subgroups", list(g.subgroups), [x.get("name") for x in e.findall("group")], line)
    states = {(s.get("name"), s.get("group")): s for s in root.findall("group_state")}
    d.eq("group_states", [(s.name, s.group) for s in sem.states], list(states))
    for s in sem.states:
        e = states.get((s.name, s.group))
        if e is not None:
            d.eq(
                f"group_state:{s.name}/values",
                dict(s.values) | {n: list(v) for n, v in s.multi},
                {j.get("name"): _values(j.get("value")) for j in e.findall("joint")},
                line_of(e),
            )
    d.eq(
        "virtual_joints",
        [(v.name, v.type, v.parent_frame, v.child_link) for v in sem.virtual_joints],
        [
            (v.get("name"), v.get("type"), v.get("parent_frame"), v.get("child_link"))
            for v in root.findall("virtual_joint")
        ],
    )
    d.eq(
        "end_effectors",
        [(e.name, e.group, e.parent_link, e.parent_group) for e in sem.end_effectors],
        [
            (e.get("name"), e.get("group"), e.get("parent_link"), e.get("parent_group"))
            for e in root.findall("end_effector")
        ],
    )
    d.eq("passive_joints", list(sem.passive_joints), [p.get("name") for p in root.findall("passive_joint")])
    explicit = {frozenset((x.link1, x.link2)): x.reason for x in sem.disabled_collisions}
    expected = (
        {frozenset((x.link1, x.link2)): x.reason for x in sem.matrix.pairs}  # the sampled matrix
        if sem.matrix is not None
        else {frozenset(p): "Adjacent" for p in derive.adjacent_pairs(robot)}
    )
    expected.update(explicit)
    written = {frozenset((x.get("link1"), x.get("link2"))): x.get("reason") for x in root.findall("disable_collisions")}
    d.eq(
        "disable_collisions",
        {tuple(sorted(k)): v for k, v in expected.items()},
        {tuple(sorted(str(n) for n in k)): v for k, v in written.items()},
    )
    return d.found


def ros2_control_roundtrip(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    """Every ``<ros2_control>`` block of the URDF (the default hardware variant) against the
    model: name, type, hardware, and each joint, sensor and gpio with its interfaces, their
    data types and params; the other variants are proven by ``xacro_variants_match``."""
    from descgen.render.control_blocks import in_block

    rel = f"urdf/{robot.name}.urdf"
    rc = robot.ros2_control
    if rc is None:
        return []
    d = _Diffs(str(where / rel), GEN032, "ros2_control block")
    root = parse(files[rel])
    expected = rc.hardware_blocks()
    found = root.findall("ros2_control")
    d.eq("ros2_control/blocks", [(b.name, b.type) for b in expected], [(e.get("name"), e.get("type")) for e in found])
    written = dict(zip([e.get("name") for e in found], found, strict=True))
    joints = derive.interfaces_with_limits(robot)
    block_of = {cj.name: cj.block for cj in rc.joints}
    mimic = {cj.name: cj.mimic for cj in rc.joints}
    joint_params = {cj.name: dict(cj.params) for cj in rc.joints}
    for hb in expected:
        b = written.get(hb.name)
        if b is None:
            continue
        line = line_of(b)
        at = "ros2_control" if len(expected) == 1 else f"ros2_control:{hb.name}"
        d.eq(f"{at}/plugin", hb.plugin, (b.findtext("hardware/plugin") or "").strip(), line)
        shown_async = None if hb.is_async is None else ("true" if hb.is_async else "false")
        d.eq(f"{at}/is_async", shown_async, b.get("is_async"), line)
        for attr in ("rw_rate", "thread_priority"):
            value = getattr(hb, attr)
            d.eq(f"{at}/{attr}", None if value is None else str(value), b.get(attr), line)
        d.eq(f"{at}/group", hb.group, b.findtext("hardware/group"), line)
        d.eq(f"{at}/params", dict(hb.params), {p.get("name"): p.text or "" for p in b.findall("hardware/param")}, line)
        mine = [jt for jt in joints if in_block(rc, hb, block_of.get(jt[0], ""))]
        elements = {j.get("name"): j for j in b.findall("joint")}
        d.eq(f"{at}/joints", [name for name, _, _ in mine], [j.get("name") for j in b.findall("joint")], line)
        for name, commands, states in mine:
            e = elements.get(name)
            if e is None:
                continue
            jl = line_of(e)
            d.eq(f"joint:{name}/mimic", mimic.get(name), e.get("mimic"), jl)
            d.eq(
                f"joint:{name}/params",
                joint_params.get(name, {}),
                {p.get("name"): p.text or "" for p in e.findall("param")},
                jl,
            )
            d.eq(f"joint:{name}/command_interfaces", [_iface(i) for i in commands], _ifaces(e, "command"), jl)
            d.eq(f"joint:{name}/state_interfaces", [_iface(i) for i in states], _ifaces(e, "state"), jl)
        sensors = [c for c in rc.sensors if in_block(rc, hb, c.block)]
        d.eq(
            f"{at}/sensors",
            [(c.name, [_iface(i) for i in c.state], dict(c.params)) for c in sensors],
            [
                (s.get("name"), _ifaces(s, "state"), {p.get("name"): p.text or "" for p in s.findall("param")})
                for s in b.findall("sensor")
            ],
            line,
        )
        gpios = [g for g in rc.gpios if in_block(rc, hb, g.block)]
        d.eq(
            f"{at}/gpios",
            [(g.name, [_iface(i) for i in g.command], [_iface(i) for i in g.state], dict(g.params)) for g in gpios],
            [
                (
                    g.get("name"),
                    _ifaces(g, "command"),
                    _ifaces(g, "state"),
                    {p.get("name"): p.text or "" for p in g.findall("param")},
                )
                for g in b.findall("gpio")
            ],
            line,
        )
        # nothing else: an element the model does not know (a stray <joint>, a <sensor> typo)
        d.eq(
            f"{at}/elements",
            ["hardware"] + ["joint"] * len(mine) + ["sensor"] * len(sensors) + ["gpio"] * len(gpios),
            [str(c.tag) for c in b if isinstance(c.tag, str)],
            line,
        )
    return d.found


def _iface(i: Interface) -> tuple[str, str | None, dict[str, float]]:
    """An interface of the model as (name, data_type, params) for comparison."""
    params = (("min", i.min), ("max", i.max), ("initial_value", i.initial_value))
    return i.name, i.data_type, {k: v for k, v in params if v is not None}


def _ifaces(e: etree._Element, kind: str) -> list[tuple[str | None, str | None, dict[str | None, float | None]]]:
    """The ``<{kind}_interface>`` children of ``e`` as written, in the shape of ``_iface``."""
    return [
        (i.get("name"), i.get("data_type"), {p.get("name"): _f(p.text) for p in i.findall("param")})
        for i in e.findall(f"{kind}_interface")
    ]


def _plain(v: Any) -> Any:
    if isinstance(v, tuple) and v and all(isinstance(x, tuple) and len(x) == 2 for x in v):
        return {str(k): _plain(x) for k, x in v}
    if isinstance(v, tuple | list):
        return [_plain(x) for x in v]
    return v


def controllers_roundtrip(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    rel = "config/ros2_controllers.yaml"
    rc = robot.ros2_control
    if rc is None or rel not in files:
        return []
    d = _Diffs(str(where / rel), GEN033, "controllers YAML")
    doc = safe_load(files[rel]) or {}
    cm = doc.get(node_key(robot, "controller_manager"), {}).get("ros__parameters", {})
    d.eq("controller_manager/update_rate", rc.update_rate, cm.get("update_rate"))
    for c in rc.controllers:
        d.eq(f"controller:{c.name}/type", c.type, (cm.get(c.name) or {}).get("type"))
        written = (doc.get(node_key(robot, c.name)) or {}).get("ros__parameters", {})
        expected = {k: _plain(v) for k, v in c.params}
        if c.type.startswith("diff_drive_controller/"):
            geo = derive.diff_drive_geometry(robot, c)
            expected["wheel_separation"] = geo.wheel_separation
            expected["wheel_radius"] = geo.wheel_radius
            expected.update(derive.wheel_params(robot, c))  # a calibrated value wins
        d.eq(f"controller:{c.name}/params", expected, written)
    d.eq("controllers", [c.name for c in rc.controllers], [k for k in cm if k != "update_rate"])
    return d.found
