"""The proof inside ``descgen import``: spec -> model -> render -> re-read is the same robot.

Compared field by field (names, tree, every origin, axis, limit, dynamics, mimic, safety
controller, inertial, geometry, material; the SRDF's groups, states, end effectors, virtual
and passive joints, disabled pairs) within 1e-12, then the written URDF through yourdfpy
(checks/urdf_roundtrip, an independent parser), then every pass-through element as XML data.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from lxml import etree

from descgen.audit.spec import load_spec_text
from descgen.codes.importer import IMP001
from descgen.commands.importer import control
from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.prove.urdf_roundtrip import compare as yourdfpy_compare
from descgen.read.srdf import read_srdf_text
from descgen.read.urdf import read_urdf_text
from descgen.render import render_package
from descgen.spec import passthrough
from descgen.spec.models import CALIBRATABLE

TOL = 1e-12
_IGNORED = {"where", "source", "part", "description", "robot_name"}  # provenance, not robot data


def _diff(a: Any, b: Any, path: str, out: list[str]) -> None:
    if dataclasses.is_dataclass(a) and dataclasses.is_dataclass(b) and type(a) is type(b):
        for f in dataclasses.fields(a):
            if f.name not in _IGNORED:
                _diff(getattr(a, f.name), getattr(b, f.name), f"{path}/{f.name}", out)
    elif isinstance(a, tuple) and isinstance(b, tuple):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} items in the description, {len(b)} after the round trip")
            return
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _diff(x, y, f"{path}[{i}]", out)
    elif isinstance(a, float) and isinstance(b, float | int):
        if not (math.isnan(a) and math.isnan(b)) and not abs(a - b) <= TOL:
            out.append(f"{path}: {a!r} in the description, {b!r} after the round trip")
    elif a != b:
        out.append(f"{path}: {a!r} in the description, {b!r} after the round trip")


def _by_name(items: tuple[Any, ...]) -> dict[str, Any]:
    return {x.name: x for x in items}


def model_differences(ours: m.Robot, back: m.Robot) -> list[str]:
    out: list[str] = []
    if ours.name != back.name:
        out.append(f"robot name: {ours.name!r}, {back.name!r} after the round trip")
    for kind, a, b in (
        ("link", _by_name(ours.links), _by_name(back.links)),
        ("joint", _by_name(ours.joints), _by_name(back.joints)),
        ("material", _by_name(ours.materials), _by_name(back.materials)),
    ):
        for name in sorted(set(a) ^ set(b)):
            out.append(f"{kind}:{name}: {'only in the description' if name in a else 'only after the round trip'}")
        for name in a.keys() & b.keys():
            x, y = a[name], b[name]
            if kind == "joint" and x.type == "fixed":  # URDF readers ignore a fixed joint's limit
                x, y = dataclasses.replace(x, limit=None), dataclasses.replace(y, limit=None)
            _diff(x, y, f"{kind}:{name}", out)
    return out


def _finding(message: str, where: Where) -> Finding:
    return IMP001.finding(
        f"round trip differs: {message}",
        "the imported spec does not give back this robot; nothing was written (please report it)",
        "import",
        where,
    )


def prove(
    spec_text: str,
    ours: m.Robot,
    spec_file: str,
    ctl: control.Imported | None = None,
    variants: dict[str, tuple[str, ...]] | None = None,
) -> list[Finding]:
    """Differences between the description and what its spec generates (empty: proven).

    With ``ctl``, its ``<ros2_control>`` blocks are compared as ros2_control reads them
    (:func:`control.block_differences`) and the imported controllers with the generated
    config/ros2_controllers.yaml (:func:`control.controllers_differences`).

    With ``variants`` (hardware variant name -> that expansion's blocks), the generated Xacro
    expanded with ``hardware:=<name>`` must give each variant's blocks and the same robot.

    InputError when the spec does not load: the description's own defects (a missing
    limit, an unreadable value) make the spec fail validate at the same elements."""
    loaded = load_spec_text(spec_text, spec_file, rules=False)
    files = render_package(loaded.robot, spec_file)
    urdf_name = f"urdf/{loaded.robot.name}.urdf"
    urdf = files[urdf_name]
    where = Where(urdf_name)
    back, _ = read_urdf_text(urdf.encode("utf-8"), urdf_name)
    messages = model_differences(dataclasses.replace(ours, ros2_control=None), back)
    found = [_finding(msg, where) for msg in messages]
    # the proof's differences (GEN030, errors) re-coded as the import's round trip
    found += [IMP001.finding(f.message, f.hint, f.subject, f.where) for f in yourdfpy_compare(ours, urdf, urdf_name)]
    imported = ctl is not None and ctl.data is not None
    found += [_finding(msg, where) for msg in passthrough_differences(ours.passthrough, urdf, imported)]
    if ctl is not None and ctl.data is not None:
        found += [_finding(msg, where) for msg in _control_differences(ctl, ours, urdf)]
        if ctl.controllers is not None and ctl.controllers.names:
            found += [_finding(msg, Where("config/ros2_controllers.yaml")) for msg in _controllers(ctl, ours, files)]
    for name, blocks in (variants or {}).items():
        found += _variant_differences(files, loaded.robot, name, blocks, ours)
    if ours.semantic is not None:
        srdf_name = f"srdf/{loaded.robot.name}.srdf"
        if srdf_name not in files:
            found.append(_finding("the SRDF is not generated", where))
        else:
            sem, _, _ = read_srdf_text(files[srdf_name].encode("utf-8"), srdf_name)
            out: list[str] = []
            _diff(ours.semantic, _own_pairs(sem, len(ours.semantic.disabled_collisions)), "srdf", out)
            found += [_finding(msg, Where(srdf_name)) for msg in out]
    return found


def _variant_differences(
    files: dict[str, str], spec_robot: m.Robot, name: str, blocks: tuple[str, ...], ours: m.Robot
) -> list[Finding]:
    """The generated Xacro with ``hardware:=<name>`` against that variant's original expansion:
    the robot as the reader sees it, and the blocks as ros2_control reads them."""
    from descgen.prove.xacro_expand import expand_with
    from descgen.render.context import package_name

    xacro_path = f"urdf/{spec_robot.name}.urdf.xacro"
    where = Where(f"{xacro_path} (hardware:={name})")
    try:
        text, _ = expand_with(files, xacro_path, package_name(spec_robot), {"hardware": name})
    except InputError as exc:
        return [_finding(f"xacro hardware:={name} failed: {exc.findings[0].message}", where)]
    back, _ = read_urdf_text(text.encode("utf-8"), str(where))
    messages = model_differences(dataclasses.replace(ours, ros2_control=None), back)
    written = _parse(text).findall("ros2_control")
    messages += control.block_differences([_parse(x) for x in blocks], written, ours)
    return [_finding(f"hardware:={name}: {msg}", where) for msg in messages]


def _own_pairs(sem: m.Semantic, n: int) -> m.Semantic:
    """The generated SRDF lists derived "Adjacent" pairs first, then the description's own."""
    pairs = sem.disabled_collisions
    return dataclasses.replace(sem, disabled_collisions=pairs[len(pairs) - n :] if n else ())


def _parse(text: str) -> etree._Element:
    return etree.fromstring(text.encode("utf-8"), etree.XMLParser(resolve_entities=False, no_network=True))


def _control_differences(ctl: control.Imported, ours: m.Robot, urdf: str) -> list[str]:
    original = [_parse(x) for x in ctl.blocks]
    return control.block_differences(original, _parse(urdf).findall("ros2_control"), ours)


def _controllers(ctl: control.Imported, ours: m.Robot, files: dict[str, str]) -> list[str]:
    c = ctl.controllers
    assert c is not None
    written = files.get("config/ros2_controllers.yaml")
    if written is None:
        return ["config/ros2_controllers.yaml is not generated"]
    diff_drive = {x["name"] for x in c.data if x["type"] in CALIBRATABLE}
    return control.controllers_differences(c.text, written, c, diff_drive)


def passthrough_differences(kept: tuple[str, ...], urdf: str, control_imported: bool = False) -> list[str]:
    """Each kept element must come back, in order, as the same XML data (the spec's own
    ``<ros2_control>`` blocks, when imported, are not pass-through)."""
    root = _parse(urdf)
    own = passthrough.OWN_TAGS | ({"ros2_control"} if control_imported else set())
    back = [e for e in root if isinstance(e.tag, str) and e.tag not in own]
    if len(back) != len(kept):
        return [f"{len(kept)} pass-through elements in the description, {len(back)} in the written URDF"]
    return [
        f"pass-through <{etree.QName(e).localname}> (number {i + 1}) changed in the written URDF"
        for i, (xml, e) in enumerate(zip(kept, back, strict=True))
        if passthrough.canonical_text(xml) != passthrough.canonical(e)
    ]


__all__ = ["InputError", "model_differences", "passthrough_differences", "prove"]
