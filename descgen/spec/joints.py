"""A spec joint body -> a model joint: limits, dynamics, mimic and safety controller in the
units of the joint type (angles or lengths, N*m or N, rad/s or m/s), and its axis."""

from __future__ import annotations

from descgen.core import model as m
from descgen.infra.yamlsource import Path_
from descgen.spec import models as s
from descgen.spec.convert import ACCELERATION, DAMPING, EFFORT, FRICTION, POSITION, VELOCITY, Converter
from descgen.spec.geometry import pose


def joint(
    conv: Converter,
    name: str,
    body: s.JointBody,
    child: str,
    origin: s.Origin,
    path: Path_,
    part: str | None = None,
    source: str | None = None,
) -> m.Joint:
    jt = body.type
    pos_kind, pos_role = POSITION.get(jt, ("angle", "joint_angle"))
    return m.Joint(
        name,
        jt,
        body.parent,
        child,
        pose(origin),
        _axis(body),
        _limit(conv, body, path),
        _dynamics(conv, body, path),
        _mimic(conv, body, path, pos_kind),
        _safety(conv, body, path, pos_kind, pos_role),
        conv.where(path),
        conv.sources(body, origin.source, source),
        part,
        body.description,
    )


def _limit(conv: Converter, body: s.JointBody, path: Path_) -> m.Limit | None:
    if body.limit is None:
        return None
    jt = body.type
    pos_kind, pos_role = POSITION.get(jt, ("angle", "joint_angle"))
    eff_kind, eff_role = EFFORT.get(jt, ("torque", "torque"))
    vel_kind, vel_role = VELOCITY.get(jt, ("angular_velocity", "angular_velocity"))
    acc_kind, acc_role = ACCELERATION.get(jt, ("angular_acceleration", "angular_acceleration"))
    lp = (*path, "limit")
    lm = body.limit
    return m.Limit(
        conv.si(lm.lower, pos_kind, pos_role, (*lp, "lower")),
        conv.si(lm.upper, pos_kind, pos_role, (*lp, "upper")),
        conv.si(lm.effort, eff_kind, eff_role, (*lp, "effort")),
        conv.si(lm.velocity, vel_kind, vel_role, (*lp, "velocity")),
        conv.where(lp),
        acceleration=conv.si(lm.acceleration, acc_kind, acc_role, (*lp, "acceleration")),
    )


def _dynamics(conv: Converter, body: s.JointBody, path: Path_) -> m.Dynamics | None:
    if body.dynamics is None:
        return None
    dp = (*path, "dynamics")
    jt = body.type
    return m.Dynamics(
        conv.si(body.dynamics.damping, DAMPING.get(jt, "angular_damping"), None, (*dp, "damping"), 0.0) or 0.0,
        conv.si(body.dynamics.friction, FRICTION.get(jt, "torque"), None, (*dp, "friction"), 0.0) or 0.0,
    )


def _mimic(conv: Converter, body: s.JointBody, path: Path_, pos_kind: str) -> m.Mimic | None:
    if body.mimic is None:
        return None
    mp = (*path, "mimic")
    return m.Mimic(
        body.mimic.joint,
        body.mimic.multiplier,
        conv.si(body.mimic.offset, pos_kind, None, (*mp, "offset"), 0.0) or 0.0,
        conv.where(mp),
    )


def _safety(conv: Converter, body: s.JointBody, path: Path_, pos_kind: str, pos_role: str) -> m.SafetyController | None:
    if body.safety_controller is None:
        return None
    sp = (*path, "safety_controller")
    sc = body.safety_controller
    prismatic = body.type == "prismatic"
    gain_kind = "linear_stiffness_gain" if prismatic else "angular_stiffness_gain"
    kv_kind = "linear_damping" if prismatic else "angular_damping"
    return m.SafetyController(
        conv.si(sc.k_velocity, kv_kind, None, (*sp, "k_velocity"), 0.0) or 0.0,
        conv.si(sc.k_position, gain_kind, None, (*sp, "k_position"), 0.0) or 0.0,
        conv.si(sc.soft_lower_limit, pos_kind, pos_role, (*sp, "soft_lower_limit"), 0.0) or 0.0,
        conv.si(sc.soft_upper_limit, pos_kind, pos_role, (*sp, "soft_upper_limit"), 0.0) or 0.0,
    )


def _axis(body: s.JointBody) -> m.Vec3 | None:
    if body.type in m.NO_AXIS:
        return None
    if body.axis is None:
        return (1.0, 0.0, 0.0)  # URDF's default when <axis> is absent
    return (float(body.axis[0]), float(body.axis[1]), float(body.axis[2]))
