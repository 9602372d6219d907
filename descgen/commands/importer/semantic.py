"""SRDF semantics of a read description -> the spec's ``semantic:`` section, and the known
poses the import adds (zero, and one per group state, with tip positions by forward kinematics)."""

from __future__ import annotations

import math
from typing import Any

from descgen.commands.importer.spec import SpecWriter
from descgen.core import model as m
from descgen.spec.convert import POSITION
from descgen.spec.semantic import VARIABLES


def _value(robot: m.Robot, joint: str, value: float, w: SpecWriter) -> str | int:
    j = robot.joint(joint)
    kind = POSITION.get(j.type, ("angle", ""))[0] if j is not None else "angle"
    return w.q(value, kind)


def _type(sem: m.Semantic, joint: str) -> str:
    return next((v.type for v in sem.virtual_joints if v.name == joint), "")


def _values(jtype: str, values: tuple[float, ...], w: SpecWriter) -> list[str | int | float]:
    """A planar/floating joint's variables in MoveIt's order: lengths and theta with units,
    the quaternion as plain numbers (a count that fits no type is written as the SRDF has it,
    and validate reports it: SPEC125)."""
    kinds = [k for _, k in VARIABLES.get(jtype, ())]
    if len(kinds) != len(values):
        kinds = ["" for _ in values]
    return [w.q(v, k) if k else _plain(v) for v, k in zip(values, kinds, strict=True)]


def _plain(v: float) -> int | float:
    return int(v) if v.is_integer() and abs(v) < 2**53 else v


def semantic_data(robot: m.Robot, w: SpecWriter) -> dict[str, Any]:
    sem = robot.semantic
    assert sem is not None
    out: dict[str, Any] = {}
    if sem.virtual_joints:
        out["virtual_joints"] = [
            {"name": v.name, "type": v.type, "parent_frame": v.parent_frame, "child_link": v.child_link}
            for v in sem.virtual_joints
        ]
    groups = []
    for g in sem.groups:
        gd: dict[str, Any] = {"name": g.name}
        if g.chains:
            # chain: is the first (as a hand-written spec has it), chains: the group's others, in order
            gd["chain"] = {"base": g.chains[0][0], "tip": g.chains[0][1]}
            if len(g.chains) > 1:
                gd["chains"] = [{"base": b, "tip": t} for b, t in g.chains[1:]]
        for key, values in (("links", g.links), ("joints", g.joints), ("subgroups", g.subgroups)):
            if values:
                gd[key] = list(values)
        groups.append(gd)
    if groups:
        out["groups"] = groups
    if sem.states:
        out["group_states"] = [
            {
                "name": s.name,
                "group": s.group,
                "joints": {
                    n: {"value": _value(robot, n, v, w), "source": w.source_of(s.where)}
                    for n, v in s.values
                    if math.isfinite(v)  # an unreadable value: reported (IMP011), not kept
                }
                | {n: {"value": _values(_type(sem, n), vs, w), "source": w.source_of(s.where)} for n, vs in s.multi},
            }
            for s in sem.states
        ]
    if sem.end_effectors:
        out["end_effectors"] = [
            {"name": e.name, "group": e.group, "parent_link": e.parent_link}
            | ({"parent_group": e.parent_group} if e.parent_group else {})
            for e in sem.end_effectors
        ]
    if sem.passive_joints:
        out["passive_joints"] = list(sem.passive_joints)
    if sem.disabled_collisions:
        out["disable_collisions"] = [
            {"link1": d.link1, "link2": d.link2, "reason": d.reason} for d in sem.disabled_collisions
        ]
    return out
