"""The spec's ``moveit:`` section -> the model's MoveIt settings, and what turning it on
requires of the rest of the spec (SPEC110-SPEC116).

MoveIt on Jazzy refuses to time-parameterise a trajectory for a joint without velocity or
acceleration limits (time_optimal_trajectory_generation.cpp), and a URDF has no
acceleration attribute, so with ``moveit:`` every joint MoveIt plans for needs
``limit.acceleration`` in the spec (docs/reference/moveit_config.md §3).
"""

from __future__ import annotations

from descgen.codes.spec import SPEC110, SPEC111, SPEC112, SPEC113, SPEC114, SPEC115, SPEC116
from descgen.core import model as m
from descgen.physics.moveit_groups import group_joints, unserved
from descgen.spec import models as s
from descgen.spec.convert import Converter

_SECTION = ("moveit",)


def moveit(conv: Converter, spec: s.MoveItSpec, robot: m.Robot) -> m.MoveItSettings:
    """The settings, after reporting what the spec lacks for a MoveIt package."""
    sem = robot.semantic
    groups = {g.name: g for g in sem.groups} if sem else {}
    if not groups:
        conv.error(
            SPEC115,
            "moveit: is set, but the spec has no planning groups",
            "add semantic.groups (e.g. - name: arm, chain: {base: base_link, tip: tool_link}) or remove moveit:",
            "moveit",
            conv.where(_SECTION),
        )
    _limits(conv, robot)
    for name in spec.kinematics:
        if name not in groups:
            conv.error(
                SPEC112,
                f"moveit.kinematics names unknown group '{name}'",
                f"groups: {', '.join(groups) or 'none'}",
                f"group:{name}",
                conv.where((*_SECTION, "kinematics", name)),
            )
    states = {st.name for st in sem.states} if sem else set()
    if spec.initial_state is not None and spec.initial_state not in states:
        conv.error(
            SPEC113,
            f"moveit.initial_state names unknown group state '{spec.initial_state}'",
            f"group states: {', '.join(sorted(states)) or 'none'}",
            "moveit:initial_state",
            conv.where((*_SECTION, "initial_state")),
        )
    _positive(conv, spec)
    settings = m.MoveItSettings(
        _kinematics(spec, groups),
        spec.default_velocity_scaling_factor,
        spec.default_acceleration_scaling_factor,
        spec.initial_state,
        spec.pilz_cartesian_limits.max_trans_vel.si,
        spec.pilz_cartesian_limits.max_trans_acc.si,
        spec.pilz_cartesian_limits.max_trans_dec.si,
        spec.pilz_cartesian_limits.max_rot_vel.si,
        conv.where(_SECTION),
    )
    for g, missing in unserved(robot):
        conv.findings.append(
            SPEC114.finding(
                f"no controller serves planning group '{g.name}' (joints {', '.join(missing)}): "
                "MoveIt can plan for it but not execute",
                "add a ros2_control controller with an action server for these joints "
                "(joint_trajectory_controller/JointTrajectoryController), or accept plan-only use",
                f"group:{g.name}",
                g.where,
            )
        )
    return settings


def _limits(conv: Converter, robot: m.Robot) -> None:
    """SPEC111/SPEC110 at each planning joint without a velocity or acceleration limit."""
    seen: set[str] = set()
    for g in robot.semantic.groups if robot.semantic else ():
        for j in group_joints(robot, g.name):
            if j.name in seen:
                continue
            seen.add(j.name)
            unit = "m/s" if j.type == "prismatic" else "deg/s"
            lm = j.limit
            if lm is None or lm.velocity is None or lm.velocity <= 0.0:
                conv.error(
                    SPEC111,
                    f"joint '{j.name}' of planning group '{g.name}' has no velocity limit; "
                    "MoveIt cannot time a trajectory without one",
                    f"add 'limit: {{velocity: <value> {unit}, acceleration: <value> {unit}^2, effort: ...}}' "
                    "with its source to this joint",
                    j.subject,
                    j.where,
                )
            elif lm.acceleration is None:
                conv.error(
                    SPEC110,
                    f"joint '{j.name}' of planning group '{g.name}' has no acceleration limit; "
                    "MoveIt on Jazzy refuses to time a trajectory without one (and a URDF cannot hold it)",
                    f"add 'acceleration: <value> {unit}^2' with its source under this joint's limit:",
                    j.subject,
                    j.where,
                )
            elif lm.acceleration <= 0.0:
                conv.error(
                    SPEC116,
                    f"joint '{j.name}' has acceleration limit {lm.acceleration:g} {unit.replace('deg', 'rad')}^2; "
                    "a limit is a positive magnitude",
                    f"write the largest acceleration the joint may use, e.g. 'acceleration: 180 {unit}^2'",
                    j.subject,
                    lm.where,
                )


def _positive(conv: Converter, spec: s.MoveItSpec) -> None:
    """SPEC116 for chosen limits MoveIt reads as magnitudes."""
    p = spec.pilz_cartesian_limits
    checks = [
        (("pilz_cartesian_limits", "max_trans_vel"), p.max_trans_vel.si),
        (("pilz_cartesian_limits", "max_trans_acc"), p.max_trans_acc.si),
        (("pilz_cartesian_limits", "max_rot_vel"), p.max_rot_vel.si),
    ] + [(("kinematics", g, "timeout"), k.timeout.si) for g, k in spec.kinematics.items()]
    for path, value in checks:
        if value <= 0.0:
            conv.error(
                SPEC116,
                f"moveit.{'.'.join(path)} is {value:g} (SI); it must be positive",
                "write a positive value with its unit",
                "moveit",
                conv.where((*_SECTION, *path)),
            )


def _kinematics(spec: s.MoveItSpec, groups: dict[str, m.Group]) -> tuple[m.Kinematics, ...]:
    """One entry per group listed under moveit.kinematics, and the defaults (KDL, as the Setup
    Assistant writes them) for every other group that is one chain: KDL solves a chain."""
    default = s.KinematicsSpec()
    out = []
    for name, g in groups.items():
        k = spec.kinematics.get(name)
        if k is None:
            if len(g.chains) != 1 or g.joints or g.links or g.subgroups:
                continue
            k = default
        out.append(m.Kinematics(name, k.solver, k.search_resolution, k.timeout.si))
    return tuple(out)
