"""Check 2b: the SRDF, the ``<ros2_control>`` block and the controllers YAML, read back
with lxml and pyyaml, say what the model says."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import yaml
from lxml import etree

from .. import derive
from ..findings import Finding, Where
from ..model import Robot
from ..xmlcompare import line_of, parse


def _f(text: str | None) -> float | None:
    try:
        return None if text is None else float(text)
    except ValueError:
        return math.nan


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
    def __init__(self, file: str, code: str, what: str) -> None:
        self.file, self.code, self.what = file, code, what
        self.found: list[Finding] = []

    def eq(self, path: str, model: Any, written: Any, line: int = 0) -> None:
        if not _same(model, written):
            self.found.append(
                Finding(
                    self.code,
                    "error",
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
    d = _Diffs(str(where / rel), "GEN031", "SRDF")
    try:
        root = parse(files[rel])
    except etree.XMLSyntaxError as exc:
        return [
            Finding("GEN031", "error", f"SRDF does not parse: {exc}", "check the SRDF template", "file", Where(d.file))
        ]
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
                dict(s.values),
                {j.get("name"): _f(j.get("value")) for j in e.findall("joint")},
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
    expected = {frozenset(p): "Adjacent" for p in derive.adjacent_pairs(robot)}
    expected.update(explicit)
    written = {frozenset((x.get("link1"), x.get("link2"))): x.get("reason") for x in root.findall("disable_collisions")}
    d.eq(
        "disable_collisions",
        {tuple(sorted(k)): v for k, v in expected.items()},
        {tuple(sorted(str(n) for n in k)): v for k, v in written.items()},
    )
    return d.found


def ros2_control_roundtrip(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    rel = f"urdf/{robot.name}.urdf"
    rc = robot.ros2_control
    if rc is None:
        return []
    d = _Diffs(str(where / rel), "GEN032", "ros2_control block")
    root = parse(files[rel])
    blocks = root.findall("ros2_control")
    if len(blocks) != 1:
        d.eq("ros2_control/count", 1, len(blocks))
        return d.found
    b = blocks[0]
    line = line_of(b)
    d.eq("ros2_control/name", rc.name, b.get("name"), line)
    d.eq("ros2_control/type", rc.type, b.get("type"), line)
    d.eq("ros2_control/plugin", rc.plugin, (b.findtext("hardware/plugin") or "").strip(), line)
    d.eq(
        "ros2_control/params", dict(rc.params), {p.get("name"): p.text or "" for p in b.findall("hardware/param")}, line
    )
    joints = {j.get("name"): j for j in b.findall("joint")}
    d.eq("ros2_control/joints", [cj.name for cj in rc.joints], list(joints), line)
    for name, commands, states in derive.interfaces_with_limits(robot):
        e = joints.get(name)
        if e is None:
            continue
        jl = line_of(e)

        def params(iface: Any) -> dict[str, float | None]:
            return {p.get("name"): _f(p.text) for p in iface.findall("param")}

        d.eq(
            f"joint:{name}/command_interfaces",
            [(i.name, {k: v for k, v in (("min", i.min), ("max", i.max)) if v is not None}) for i in commands],
            [(c.get("name"), params(c)) for c in e.findall("command_interface")],
            jl,
        )
        d.eq(
            f"joint:{name}/state_interfaces",
            [(i.name, {} if i.initial_value is None else {"initial_value": i.initial_value}) for i in states],
            [(s.get("name"), params(s)) for s in e.findall("state_interface")],
            jl,
        )
    return d.found


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
    d = _Diffs(str(where / rel), "GEN033", "controllers YAML")
    doc = yaml.safe_load(files[rel]) or {}
    cm = doc.get("controller_manager", {}).get("ros__parameters", {})
    d.eq("controller_manager/update_rate", rc.update_rate, cm.get("update_rate"))
    for c in rc.controllers:
        d.eq(f"controller:{c.name}/type", c.type, (cm.get(c.name) or {}).get("type"))
        written = (doc.get(c.name) or {}).get("ros__parameters", {})
        expected = {k: _plain(v) for k, v in c.params}
        if c.type.startswith("diff_drive_controller/"):
            geo = derive.diff_drive_geometry(robot, c)
            expected["wheel_separation"] = geo.wheel_separation
            expected["wheel_radius"] = geo.wheel_radius
            expected.update(derive.wheel_params(robot, c))  # a calibrated value wins
        d.eq(f"controller:{c.name}/params", expected, written)
    d.eq("controllers", [c.name for c in rc.controllers], [k for k in cm if k != "update_rate"])
    return d.found
