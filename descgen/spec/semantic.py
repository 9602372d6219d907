"""Known poses and the semantic (SRDF) section -> the model's; a group state may take its
joint values from a known pose, and then lists every moving joint of its group."""

from __future__ import annotations

from dataclasses import replace

from .. import model as m
from ..yamlsource import Path_
from . import models as s
from .convert import Converter


def known_pose(conv: Converter, kp: s.KnownPoseSpec, path: Path_) -> m.KnownPose:
    """Needs ``conv.joint_types``: each value is in its joint's unit."""
    values = tuple((j, conv.joint_value(j, w, (*path, "joints", j))) for j, w in kp.joints.items())
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
    return m.KnownPose(kp.name, values, frames, kp.source, conv.where(path))


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
            "SPEC100",
            f"collision_matrix.default_state names unknown group state '{cm.default_state}'",
            f"group states: {', '.join(g.name for g in sem.group_states) or 'none'}",
            "semantic:collision_matrix",
            conv.where((*path, "default_state")),
        )
    padding = cm.padding.si
    if not 0.0 <= padding <= 0.1:
        conv.error(
            "SPEC101",
            f"collision_matrix.padding {padding * 1000:g} mm is outside 0 to 100 mm",
            "padding inflates every collision shape; use a few millimetres at most",
            "semantic:collision_matrix",
            conv.where((*path, "padding")),
        )
    return m.MatrixSettings(cm.default_state, cm.seed, cm.samples, cm.fraction, padding, conv.where(path))


def _group_states(conv: Converter, sem: s.SemanticSpec, poses: tuple[m.KnownPose, ...]) -> tuple[m.GroupState, ...]:
    by_name = {p.name: p for p in poses}
    states = []
    for i, gs in enumerate(sem.group_states):
        p = ("semantic", "group_states", i)
        values: dict[str, float] = {}
        if gs.pose is not None:
            kp = by_name.get(gs.pose)
            if kp is None:
                conv.error(
                    "SRDF010",
                    f"group state '{gs.name}' names unknown known pose '{gs.pose}'",
                    f"known poses: {', '.join(by_name) or 'none'}",
                    f"group_state:{gs.name}",
                    conv.where((*p, "pose")),
                )
            else:
                values.update(kp.joints)
        for j, w in gs.joints.items():
            values[j] = conv.joint_value(j, w, (*p, "joints", j))
        states.append(m.GroupState(gs.name, gs.group, tuple(values.items()), conv.where(p)))
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
