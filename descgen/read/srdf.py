"""SRDF -> the model's semantic part (lxml, tolerant, with line numbers)."""

from __future__ import annotations

import math

from descgen.core import model as m
from descgen.core.findings import Finding, Where
from descgen.core.xmlcompare import line_of
from descgen.read.urdf import parse_xml


def read_srdf_text(data: bytes, file: str) -> tuple[m.Semantic, str, list[Finding]]:
    """The semantics, the SRDF's robot name, and what could not be read."""
    root = parse_xml(data, file)
    found: list[Finding] = []

    def where(e: object) -> Where:
        return Where(file, line_of(e))  # type: ignore[arg-type]

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
                    Finding(
                        "READ042",
                        "error",
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
                    Finding(
                        "READ011",
                        "warning" if numbers else "error",
                        f"group state '{s.get('name')}' joint '{j.get('name')}' value '{raw}' is not one number",
                        "multi-DOF values are not checked; write one number per 1-DOF joint",
                        f"group_state:{s.get('name')}",
                        where(j),
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
