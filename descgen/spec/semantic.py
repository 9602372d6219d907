"""Known poses and the semantic (SRDF) section -> the model's; a group state may take its
joint values from a known pose, and then lists every moving joint of its group."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace

from descgen.codes.spec import SPEC100, SPEC101, SPEC125, SPEC126, SPEC127, SRDF010
from descgen.core import model as m
from descgen.infra.yamlsource import Path_
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.quantity import Written


def known_pose(
    conv: Converter, kp: s.KnownPoseSpec, path: Path_, virtual: Mapping[str, str] | None = None
) -> m.KnownPose:
    """Needs ``conv.joint_types``: each value is in its joint's unit. ``virtual``: the SRDF's
    virtual joints by name and type, whose values are lists (kept, not used by FK)."""
    values, multi = _joint_values(conv, kp.joints, path, virtual or {})
    frames = tuple(
        m.FrameMeasurement(
            f.frame,
            (f.xyz[0].si, f.xyz[1].si, f.xyz[2].si),
            f.tolerance.si,
            f.relative_to,
            f.source or kp.source,
            conv.where((*path, "frames", i)),
        )
        for i, f in enumerate(kp.frames)
    )
    return m.KnownPose(kp.name, values, frames, kp.source, conv.where(path), multi, kp.nominal)


# MoveIt's variables of a multi-DOF joint, in order (moveit_core planar_joint_model.cpp,
# floating_joint_model.cpp on jazzy), with the kind each is written in ("" = a plain number)
VARIABLES = {
    "planar": (("x", "length"), ("y", "length"), ("theta", "angle")),
    "floating": (
        ("trans_x", "length"),
        ("trans_y", "length"),
        ("trans_z", "length"),
        ("rot_x", ""),
        ("rot_y", ""),
        ("rot_z", ""),
        ("rot_w", ""),
    ),
}
UNIT_QUATERNION = 1e-9  # |q|^2 - 1; MoveIt renormalises anything further off (normalizeRotation)


def _joint_values(
    conv: Converter, given: dict[str, Written], path: Path_, virtual: Mapping[str, str]
) -> tuple[tuple[tuple[str, float], ...], tuple[tuple[str, tuple[float, ...]], ...]]:
    """One-number values, and the lists of planar/floating joints (virtual or in the URDF)."""
    values: list[tuple[str, float]] = []
    multi: list[tuple[str, tuple[float, ...]]] = []
    for j, w in given.items():
        at = (*path, "joints", j)
        jtype = conv.joint_types.get(j) or virtual.get(j)
        if jtype in VARIABLES or isinstance(w.value, tuple):
            got = _multi_value(conv, j, jtype, w, at)
            if got is not None:
                multi.append((j, got))
        else:
            values.append((j, conv.joint_value(j, w, at)))
    return tuple(values), tuple(multi)


def _multi_value(conv: Converter, joint: str, jtype: str | None, w: Written, at: Path_) -> tuple[float, ...] | None:
    variables = VARIABLES.get(jtype or "")
    items = w.value if isinstance(w.value, tuple) else (w.value,)
    if variables is None or len(items) != len(variables):
        want = (
            f"{len(variables)} values ({', '.join(n for n, _ in variables)})"
            if variables
            else "one value (only planar and floating joints take a list)"
        )
        example = {
            "planar": "[0 mm, 0 mm, 0 deg]",
            "floating": "[0 mm, 0 mm, 300 mm, 0, 0, 0, 1]",
        }.get(jtype or "", '"0 deg"')
        conv.error(
            SPEC125,
            f"joint '{joint}' ({jtype or 'unknown'}) takes {want}, got {len(items)}",
            f"write e.g. {joint}: {example} (MoveIt's variable order)",
            ".".join(map(str, at)),
            conv.where(at),
        )
        return None
    out: list[float] = []
    for i, (item, (name, kind)) in enumerate(zip(items, variables, strict=True)):
        if kind:
            v = conv.si(Written(item, w.source), kind, None, (*at, i))
        else:
            v = _plain(item)
            if v is None:
                conv.error(
                    SPEC127,
                    f"joint '{joint}' {name} '{item}' is not a plain number",
                    "write the quaternion component without a unit, e.g. 0.7071067811865476",
                    ".".join(map(str, at)),
                    conv.where((*at, i)),
                )
        if v is None:
            return None
        out.append(v)
    if jtype == "floating":
        norm = sum(c * c for c in out[3:])
        if abs(norm - 1.0) > UNIT_QUATERNION:
            conv.error(
                SPEC126,
                f"joint '{joint}' rotation (rot_x, rot_y, rot_z, rot_w) has squared norm {norm:.12g}, not 1",
                "write a unit quaternion, e.g. 0, 0, 0, 1 for no rotation; divide each component by the norm",
                ".".join(map(str, at)),
                conv.where(at),
            )
            return None
    return tuple(out)


def _plain(item: object) -> float | None:
    if isinstance(item, bool):
        return None
    try:
        v = float(item) if isinstance(item, int | float | str) else math.nan
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def semantic(conv: Converter, sem: s.SemanticSpec, poses: tuple[m.KnownPose, ...]) -> m.Semantic:
    base = ("semantic",)
    groups = tuple(
        m.Group(
            g.name,
            tuple(g.links),
            tuple(g.joints),
            (((g.chain.base, g.chain.tip),) if g.chain else ()) + tuple((c.base, c.tip) for c in g.chains),
            tuple(g.subgroups),
            conv.where((*base, "groups", i)),
        )
        for i, g in enumerate(sem.groups)
    )
    return m.Semantic(
        groups,
        _group_states(conv, sem, poses),
        tuple(
            m.EndEffector(e.name, e.group, e.parent_link, e.parent_group, conv.where((*base, "end_effectors", i)))
            for i, e in enumerate(sem.end_effectors)
        ),
        tuple(
            m.VirtualJoint(v.name, v.type, v.parent_frame, v.child_link, conv.where((*base, "virtual_joints", i)))
            for i, v in enumerate(sem.virtual_joints)
        ),
        tuple(sem.passive_joints),
        tuple(
            m.DisabledPair(d.link1, d.link2, d.reason, conv.where((*base, "disable_collisions", i)))
            for i, d in enumerate(sem.disable_collisions)
        ),
        conv.where(base),
        collision_matrix=_matrix_settings(conv, sem),
    )


def _matrix_settings(conv: Converter, sem: s.SemanticSpec) -> m.MatrixSettings | None:
    cm = sem.collision_matrix
    if cm is None:
        return None
    path = ("semantic", "collision_matrix")
    if cm.default_state is not None and cm.default_state not in {g.name for g in sem.group_states}:
        conv.error(
            SPEC100,
            f"collision_matrix.default_state names unknown group state '{cm.default_state}'",
            f"group states: {', '.join(g.name for g in sem.group_states) or 'none'}",
            "semantic:collision_matrix",
            conv.where((*path, "default_state")),
        )
    padding = cm.padding.si
    if not 0.0 <= padding <= 0.1:
        conv.error(
            SPEC101,
            f"collision_matrix.padding {padding * 1000:g} mm is outside 0 to 100 mm",
            "padding inflates every collision shape; use a few millimetres at most",
            "semantic:collision_matrix",
            conv.where((*path, "padding")),
        )
    return m.MatrixSettings(cm.default_state, cm.seed, cm.samples, cm.fraction, padding, conv.where(path))


def _group_states(conv: Converter, sem: s.SemanticSpec, poses: tuple[m.KnownPose, ...]) -> tuple[m.GroupState, ...]:
    by_name = {p.name: p for p in poses}
    virtual = {v.name: v.type for v in sem.virtual_joints}
    states = []
    for i, gs in enumerate(sem.group_states):
        p = ("semantic", "group_states", i)
        values: dict[str, float] = {}
        multi: dict[str, tuple[float, ...]] = {}
        if gs.pose is not None:
            kp = by_name.get(gs.pose)
            if kp is None:
                conv.error(
                    SRDF010,
                    f"group state '{gs.name}' names unknown known pose '{gs.pose}'",
                    f"known poses: {', '.join(by_name) or 'none'}",
                    f"group_state:{gs.name}",
                    conv.where((*p, "pose")),
                )
            else:
                values.update(kp.joints)
                multi.update(kp.multi)
        one, lists = _joint_values(conv, gs.joints, p, virtual)
        values.update(one)
        multi.update(lists)
        states.append(m.GroupState(gs.name, gs.group, tuple(values.items()), conv.where(p), tuple(multi.items())))
    return tuple(states)


def complete_states(robot: m.Robot, sem: s.SemanticSpec) -> m.Robot:
    """A state taken from a known pose lists every moving joint of its group: the pose
    leaves unlisted joints at zero, and an SRDF state must name them all."""
    assert robot.semantic is not None
    states = []
    for st, st_spec in zip(robot.semantic.states, sem.group_states, strict=True):
        if st_spec.pose is None:
            states.append(st)
            continue
        given = dict(st.values)
        full = [(j.name, given.pop(j.name, 0.0)) for j in robot.group_joints(st.group) if j.type in m.ONE_DOF]
        states.append(replace(st, values=tuple(full + list(given.items()))))
    return replace(robot, semantic=replace(robot.semantic, states=tuple(states)))
