"""SRDF -> the model's semantic part (lxml, tolerant, with line numbers)."""

from __future__ import annotations

import math
from collections.abc import Sequence

from lxml import etree

from descgen.codes.read import READ011, READ042, READ047
from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.core.xmlcompare import line_of
from descgen.read.urdf import element_sources, parse_xml


def read_srdf_text(
    data: bytes, file: str, sources: Sequence[Where | None] | None = None
) -> tuple[m.Semantic, str, list[Finding]]:
    """The semantics, the SRDF's robot name, and what could not be read. InputError (READ047)
    for a file that is no SRDF: it would read as an empty one."""
    root = parse_xml(data, file)
    _refuse_non_srdf(root, file)
    found: list[Finding] = []

    # an expanded SRDF Xacro: each element where it was written (descgen/read/xacro_file.py)
    located = element_sources(root, sources) if sources is not None else {}

    def where(e: object) -> Where:
        return located.get(e) or Where(file, line_of(e))  # type: ignore[arg-type, call-overload]

    groups = tuple(
        m.Group(
            g.get("name", ""),
            tuple(x.get("name", "") for x in g.findall("link")),
            tuple(x.get("name", "") for x in g.findall("joint")),
            tuple((c.get("base_link", ""), c.get("tip_link", "")) for c in g.findall("chain")),
            tuple(x.get("name", "") for x in g.findall("group")),
            where(g),
        )
        for g in root.findall("group")
    )
    multi_dof = {v.get("name") for v in root.findall("virtual_joint") if v.get("type") in m.MULTI_DOF}
    states = []
    for s in root.findall("group_state"):
        values = []
        multi: list[tuple[str, tuple[float, ...]]] = []
        for j in s.findall("joint"):
            raw = j.get("value", "")
            try:
                numbers = [float(t) for t in raw.split()]
            except ValueError:
                numbers = []
            if not all(math.isfinite(v) for v in numbers):
                found.append(
                    READ042.finding(
                        f"group state '{s.get('name')}' joint '{j.get('name')}' value '{raw}' is not a finite number",
                        "write the joint position as a plain decimal number",
                        f"group_state:{s.get('name')}",
                        where(j),
                    )
                )
                values.append((j.get("name", ""), math.nan))  # treated as missing, like an unreadable value
                continue
            if len(numbers) != 1 and j.get("name") not in multi_dof:
                found.append(
                    READ011.finding(
                        f"group state '{s.get('name')}' joint '{j.get('name')}' value '{raw}' is not one number",
                        "multi-DOF values are not checked; write one number per 1-DOF joint",
                        f"group_state:{s.get('name')}",
                        where(j),
                        severity="warning" if numbers else "error",
                    )
                )
            if len(numbers) > 1 and j.get("name") in multi_dof:
                multi.append((j.get("name", ""), tuple(numbers)))  # every variable, in MoveIt's order
                continue
            values.append((j.get("name", ""), numbers[0] if len(numbers) == 1 else math.nan))
        states.append(m.GroupState(s.get("name", ""), s.get("group", ""), tuple(values), where(s), tuple(multi)))
    semantic = m.Semantic(
        groups,
        tuple(states),
        tuple(
            m.EndEffector(
                e.get("name", ""), e.get("group", ""), e.get("parent_link", ""), e.get("parent_group"), where(e)
            )
            for e in root.findall("end_effector")
        ),
        tuple(
            m.VirtualJoint(
                v.get("name", ""), v.get("type", ""), v.get("parent_frame", ""), v.get("child_link", ""), where(v)
            )
            for v in root.findall("virtual_joint")
        ),
        tuple(p.get("name", "") for p in root.findall("passive_joint")),
        tuple(
            m.DisabledPair(d.get("link1", ""), d.get("link2", ""), d.get("reason", ""), where(d))
            for d in root.findall("disable_collisions")
        ),
        where(root),
    )
    return semantic, root.get("name", ""), found


XACRO_NS = "http://www.ros.org/wiki/xacro"


def _refuse_non_srdf(root: etree._Element, file: str) -> None:
    tag = root.tag
    why = ""
    if tag != "robot":
        why = f"its root is <{tag}>, not <robot>"
    elif root.find("link") is not None or root.find("joint") is not None:
        why = "it has <link> and <joint> elements: it is a URDF"
    elif any(str(e.tag).startswith(f"{{{XACRO_NS}}}") for e in root.iter()):
        why = "it still holds Xacro elements (an .srdf.xacro is expanded when its name ends in .xacro)"
    if why:
        where = Where(file, line_of(root))
        raise InputError([READ047.finding(f"not an SRDF: {why}", "give the SRDF, or its .srdf.xacro", "srdf", where)])
