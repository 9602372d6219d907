"""Validated spec -> SI robot model.

Converts the quantities whose kind depends on context (joint limits by joint type, pose
values by the joint they move) with the same ``units.to_si`` as the schema, expands
repeated parts and sensors, and computes what is derived (inertia from a primitive, the
camera's optical frame). Problems become findings at the YAML position of the value.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import replace
from typing import Any

from pydantic import BaseModel

from .. import inertia as mass_props
from .. import model as m
from .. import units
from ..findings import Finding, Where
from ..yamlsource import Document, Path_
from . import models as s
from .quantity import Measured, Written, check_range, convert

# REP 103: the optical frame is z forward, x right, y down relative to the body frame
# (x forward, y left, z up); as fixed-axis rpy this is (-pi/2, 0, -pi/2). See
# reference/conventions.md.
OPTICAL_RPY = (-math.pi / 2, 0.0, -math.pi / 2)

# What a joint's limit, value and gains are, by joint type: (value kind, plausibility role).
_POSITION = {
    "revolute": ("angle", "joint_angle"),
    "continuous": ("angle", "joint_angle"),
    "prismatic": ("length", "joint_travel"),
}
_EFFORT = {"prismatic": ("force", "force")}
_VELOCITY = {"prismatic": ("linear_velocity", "linear_velocity")}
_DAMPING = {"prismatic": "linear_damping"}
_FRICTION = {"prismatic": "force"}
_NUMERIC_START = re.compile(r"^\s*[-+]?(\d|\.\d)")


class Builder:
    def __init__(self, doc: Document, spec: s.RobotSpec, ranges: dict[str, units.Range]) -> None:
        self.doc = doc
        self.spec = spec
        self.ranges = ranges
        self.findings: list[Finding] = []
        self.joint_types: dict[str, str] = {}

    # -- helpers -------------------------------------------------------------------------

    def where(self, path: Path_) -> Where:
        return self.doc.where(path)

    def si(
        self, w: Written | None, kind: str, role: str | None, path: Path_, default: float | None = None
    ) -> float | None:
        if w is None:
            return default
        try:
            return convert(w, kind, role, self.ranges).si
        except Exception as exc:  # PydanticCustomError from convert/check_range
            ctx: dict[str, Any] = getattr(exc, "context", None) or {}
            code = getattr(exc, "type", "UNIT002")
            self.findings.append(
                Finding(
                    code,
                    "error",
                    str(ctx.get("message", exc)),
                    str(ctx.get("hint", "")),
                    ".".join(map(str, path)),
                    self.where(path),
                )
            )
            return default

    @staticmethod
    def pose(o: s.Origin | None) -> m.Pose:
        if o is None:
            return m.Pose()
        xyz = (o.xyz[0].si, o.xyz[1].si, o.xyz[2].si)
        rpy = (o.rpy[0].si, o.rpy[1].si, o.rpy[2].si)
        return m.Pose(xyz, rpy)

    @staticmethod
    def geometry(g: s.GeometrySpec) -> m.Geometry:
        if g.box is not None:
            x, y, z = g.box.size
            return m.Box((x.si, y.si, z.si))
        if g.cylinder is not None:
            return m.Cylinder(g.cylinder.r, g.cylinder.length.si)
        if g.sphere is not None:
            return m.Sphere(g.sphere.r)
        assert g.mesh is not None  # GeometrySpec guarantees exactly one
        sx, sy, sz = g.mesh.scale
        return m.Mesh(g.mesh.filename, (float(sx), float(sy), float(sz)))

    # -- elements ------------------------------------------------------------------------

    def link(
        self,
        name: str,
        body: s.LinkBody,
        path: Path_,
        part: str | None = None,
        source: str | None = None,
        where: Where | None = None,
    ) -> m.Link:
        visuals = tuple(
            m.Visual(
                self.geometry(v.geometry), self.pose(v.origin), v.name, v.material, self.where((*path, "visual", i))
            )
            for i, v in enumerate(body.visual)
        )
        collisions = tuple(
            m.Collision(self.geometry(c.geometry), self.pose(c.origin), c.name, self.where((*path, "collision", i)))
            for i, c in enumerate(body.collision)
        )
        inertial = None
        if body.inertial is not None:
            inertial = self.inertial(body.inertial, visuals, collisions, (*path, "inertial"))
        return m.Link(
            name,
            visuals,
            collisions,
            inertial,
            where or self.where(path),
            sources(body, source),
            part,
            body.description,
        )

    def inertial(
        self, spec: s.InertialSpec, visuals: tuple[m.Visual, ...], collisions: tuple[m.Collision, ...], path: Path_
    ) -> m.Inertial:
        mass = spec.mass.si
        if spec.inertia is not None:
            t = spec.inertia
            origin = self.pose(spec.origin)
            tensor = m.Inertia(t.ixx.si, t.ixy.si, t.ixz.si, t.iyy.si, t.iyz.si, t.izz.si)
            return m.Inertial(mass, origin, tensor, self.where(path))
        shapes: tuple[m.Visual | m.Collision, ...] = collisions if spec.from_ == "collision" else visuals
        if not shapes or shapes[0].geometry is None:
            self.findings.append(
                Finding(
                    "INER010",
                    "error",
                    f"inertial from {spec.from_}, but the link has no {spec.from_} geometry",
                    f"add a {spec.from_} primitive or give inertia explicitly",
                    ".".join(map(str, path)),
                    self.where((*path, "from")),
                )
            )
            return m.Inertial(mass, self.pose(spec.origin), None, self.where(path))
        shape = shapes[0]
        tensor_or_none = mass_props.in_link_frame(shape.geometry, mass, shape.origin) if shape.geometry else None
        if tensor_or_none is None:
            self.findings.append(
                Finding(
                    "INER010",
                    "error",
                    f"cannot compute inertia from a mesh {spec.from_}",
                    "give inertia explicitly (from your CAD tool), or use a primitive",
                    ".".join(map(str, path)),
                    self.where((*path, "from")),
                )
            )
        com = shape.origin.xyz if spec.origin is None else self.pose(spec.origin).xyz
        return m.Inertial(mass, m.Pose(com, (0.0, 0.0, 0.0)), tensor_or_none, self.where(path))

    def joint(
        self,
        name: str,
        body: s.JointBody,
        child: str,
        origin: s.Origin,
        path: Path_,
        origin_path: Path_,
        part: str | None = None,
        source: str | None = None,
    ) -> m.Joint:
        jt = body.type
        pos_kind, pos_role = _POSITION.get(jt, ("angle", "joint_angle"))
        eff_kind, eff_role = _EFFORT.get(jt, ("torque", "torque"))
        vel_kind, vel_role = _VELOCITY.get(jt, ("angular_velocity", "angular_velocity"))
        limit = None
        if body.limit is not None:
            lp = (*path, "limit")
            lm = body.limit
            limit = m.Limit(
                self.si(lm.lower, pos_kind, pos_role, (*lp, "lower")),
                self.si(lm.upper, pos_kind, pos_role, (*lp, "upper")),
                self.si(lm.effort, eff_kind, eff_role, (*lp, "effort")),
                self.si(lm.velocity, vel_kind, vel_role, (*lp, "velocity")),
                self.where(lp),
            )
        dynamics = None
        if body.dynamics is not None:
            dp = (*path, "dynamics")
            dynamics = m.Dynamics(
                self.si(body.dynamics.damping, _DAMPING.get(jt, "angular_damping"), None, (*dp, "damping"), 0.0) or 0.0,
                self.si(body.dynamics.friction, _FRICTION.get(jt, "torque"), None, (*dp, "friction"), 0.0) or 0.0,
            )
        mimic = None
        if body.mimic is not None:
            mp = (*path, "mimic")
            mimic = m.Mimic(
                body.mimic.joint,
                body.mimic.multiplier,
                self.si(body.mimic.offset, pos_kind, None, (*mp, "offset"), 0.0) or 0.0,
                self.where(mp),
            )
        safety = None
        if body.safety_controller is not None:
            sp = (*path, "safety_controller")
            sc = body.safety_controller
            gain_kind = "linear_stiffness_gain" if jt == "prismatic" else "angular_stiffness_gain"
            kv_kind = "linear_damping" if jt == "prismatic" else "angular_damping"
            safety = m.SafetyController(
                self.si(sc.k_velocity, kv_kind, None, (*sp, "k_velocity"), 0.0) or 0.0,
                self.si(sc.k_position, gain_kind, None, (*sp, "k_position"), 0.0) or 0.0,
                self.si(sc.soft_lower_limit, pos_kind, pos_role, (*sp, "soft_lower_limit"), 0.0) or 0.0,
                self.si(sc.soft_upper_limit, pos_kind, pos_role, (*sp, "soft_upper_limit"), 0.0) or 0.0,
            )
        axis: m.Vec3 | None
        if jt in ("fixed", "floating"):
            axis = None
        elif body.axis is None:
            axis = (1.0, 0.0, 0.0)  # URDF's default when <axis> is absent
        else:
            axis = (float(body.axis[0]), float(body.axis[1]), float(body.axis[2]))
        pose = self.pose(origin)
        return m.Joint(
            name,
            jt,
            body.parent,
            child,
            pose,
            axis,
            limit,
            dynamics,
            mimic,
            safety,
            self.where(path),
            sources(body, origin.source, source),
            part,
            body.description,
        )

    # -- the robot -----------------------------------------------------------------------

    def build(self) -> m.Robot:
        spec = self.spec
        links: list[m.Link] = []
        joints: list[m.Joint] = []
        sensors: list[m.Sensor] = []
        materials = tuple(
            m.Material(mt.name, mt.rgba, mt.texture, self.where(("materials", i)))
            for i, mt in enumerate(spec.materials)
        )
        for i, lk in enumerate(spec.links):
            links.append(self.link(lk.name, lk, ("links", i)))
        for i, jt in enumerate(spec.joints):
            joints.append(self.joint(jt.name, jt, jt.child, jt.origin, ("joints", i), ("joints", i, "origin")))
        for i, part in enumerate(spec.parts):
            pp = ("parts", i)
            for k, inst in enumerate(part.instances):
                ip = (*pp, "instances", k)
                links.append(
                    self.link(
                        inst.link, part.link, (*pp, "link"), part.name, sources(part, inst.source), self.where(ip)
                    )
                )
                j = self.joint(
                    inst.joint,
                    part.joint,
                    inst.link,
                    inst.origin,
                    (*pp, "joint"),
                    (*ip, "origin"),
                    part.name,
                    sources(part, inst.source),
                )
                joints.append(_replace_where(j, self.where(ip)))
        for i, sn in enumerate(spec.sensors):
            sp = ("sensors", i)
            link_name, joint_name = f"{sn.name}_link", f"{sn.name}_joint"
            links.append(self.link(link_name, sn.link, (*sp, "link"), None, sources(sn), self.where(sp)))
            joints.append(
                m.Joint(
                    joint_name,
                    "fixed",
                    sn.parent,
                    link_name,
                    self.pose(sn.origin),
                    None,
                    where=self.where(sp),
                    source=sources(sn, sn.origin.source),
                    description=sn.description,
                )
            )
            optical = optical_joint = None
            if sn.type == "camera":
                optical, optical_joint = f"{sn.name}_optical_frame", f"{sn.name}_optical_joint"
                links.append(
                    m.Link(
                        optical,
                        where=self.where(sp),
                        source="REP 103",
                        description="optical frame: z forward, x right, y down",
                    )
                )
                joints.append(
                    m.Joint(
                        optical_joint,
                        "fixed",
                        link_name,
                        optical,
                        m.Pose((0.0, 0.0, 0.0), OPTICAL_RPY),
                        None,
                        where=self.where(sp),
                        source="REP 103",
                    )
                )
            sensors.append(m.Sensor(sn.name, sn.type, link_name, joint_name, optical, optical_joint, self.where(sp)))
        self.joint_types = {j.name: j.type for j in joints}
        ros2_control = self.ros2_control(spec.ros2_control) if spec.ros2_control else None
        poses = tuple(self.known_pose(kp, ("known_poses", i)) for i, kp in enumerate(spec.known_poses))
        robot = m.Robot(
            spec.name,
            tuple(links),
            tuple(joints),
            materials,
            tuple(sensors),
            ros2_control,
            None,
            poses,
            description=spec.description,
            where=self.where(()),
            source_file=self.doc.file,
            package=m.PackageInfo(
                spec.package.version, spec.package.maintainer, spec.package.email, spec.package.license
            ),
            external_frames=tuple(
                m.ExternalFrame(e.parent, e.child, e.owner, e.static, self.where(("frames", "external", i)))
                for i, e in enumerate(spec.frames.external)
            ),
            joint_state_sources=tuple(
                m.JointStateSource(js.node, js.kind, tuple(js.joints), self.where(("frames", "joint_state_sources", i)))
                for i, js in enumerate(spec.frames.joint_state_sources)
            ),
        )
        if spec.semantic is None:
            return robot
        semantic = self.semantic(spec.semantic, poses)
        return _complete_states(replace(robot, semantic=semantic), spec.semantic)

    def joint_value(self, joint: str, w: Written, path: Path_) -> float:
        jt = self.joint_types.get(joint)
        if jt in _POSITION:
            kind, role = _POSITION[jt]
            return self.si(w, kind, role, path, math.nan) or 0.0
        # unknown or non-1-DOF joint: a rule reports it; keep the value if it reads as anything
        for kind in ("angle", "length"):
            try:
                return units.to_si(w.value, kind)
            except units.QuantityError:
                continue
        return math.nan

    def ros2_control(self, rc: s.Ros2ControlSpec) -> m.Ros2Control:
        base = ("ros2_control",)
        joints = []
        for i, cj in enumerate(rc.joints):
            p = (*base, "joints", i)
            initial = None
            if cj.initial_position is not None:
                initial = self.joint_value(cj.name, cj.initial_position, (*p, "initial_position"))
            state = tuple(m.Interface(n, initial_value=initial if n == "position" else None) for n in cj.state)
            mimic = None if cj.mimic is None else _param_text(cj.mimic)
            joints.append(
                m.ControlJoint(
                    cj.name, tuple(m.Interface(n) for n in cj.command), state, cj.on_limit, self.where(p), mimic
                )
            )
        controllers = []
        for i, c in enumerate(rc.controllers):
            p = (*base, "controllers", i)
            params = tuple((k, self.param(v, (*p, "params", k))) for k, v in c.params.items())
            calibrated = tuple(
                m.Calibrated(
                    k,
                    cal.value.si,
                    None if cal.tolerance is None else cal.tolerance.si,
                    cal.source,
                    self.where((*p, "calibrated", k)),
                )
                for k, cal in c.calibrated.items()
            )
            controllers.append(m.Controller(c.name, c.type, params, self.where(p), calibrated))
        hw = tuple((k, _param_text(v)) for k, v in rc.hardware.params.items())
        return m.Ros2Control(
            rc.name,
            rc.type,
            rc.hardware.plugin,
            hw,
            tuple(joints),
            rc.update_rate.si,
            tuple(controllers),
            self.where(base),
        )

    def param(self, value: object, path: Path_) -> object:
        """Controller parameters pass through; text that starts with a number and has a
        unit (``"500 ms"``, ``"0.5 m/s"``, ``"90 deg/s"``) is converted to SI."""
        if isinstance(value, str) and _NUMERIC_START.match(value):
            try:
                q = units.parse(value)
            except units.QuantityError:
                return value
            if q.unitless:
                return value
            return float(q.to_base_units().magnitude) + 0.0
        if isinstance(value, list):
            return tuple(self.param(v, (*path, i)) for i, v in enumerate(value))
        if isinstance(value, dict):
            return tuple((str(k), self.param(v, (*path, str(k)))) for k, v in value.items())
        return value

    def known_pose(self, kp: s.KnownPoseSpec, path: Path_) -> m.KnownPose:
        values = tuple((j, self.joint_value(j, w, (*path, "joints", j))) for j, w in kp.joints.items())
        frames = tuple(
            m.FrameMeasurement(
                f.frame,
                (f.xyz[0].si, f.xyz[1].si, f.xyz[2].si),
                f.tolerance.si,
                f.relative_to,
                f.source or kp.source,
                self.where((*path, "frames", i)),
            )
            for i, f in enumerate(kp.frames)
        )
        return m.KnownPose(kp.name, values, frames, kp.source, self.where(path))

    def semantic(self, sem: s.SemanticSpec, poses: tuple[m.KnownPose, ...]) -> m.Semantic:
        base = ("semantic",)
        self.unique_semantics(sem)
        groups = tuple(
            m.Group(
                g.name,
                tuple(g.links),
                tuple(g.joints),
                ((g.chain.base, g.chain.tip),) if g.chain else (),
                tuple(g.subgroups),
                self.where((*base, "groups", i)),
            )
            for i, g in enumerate(sem.groups)
        )
        by_name = {p.name: p for p in poses}
        states = []
        for i, gs in enumerate(sem.group_states):
            p = (*base, "group_states", i)
            values: dict[str, float] = {}
            if gs.pose is not None:
                kp = by_name.get(gs.pose)
                if kp is None:
                    self.findings.append(
                        Finding(
                            "SRDF010",
                            "error",
                            f"group state '{gs.name}' names unknown known pose '{gs.pose}'",
                            f"known poses: {', '.join(by_name) or 'none'}",
                            f"group_state:{gs.name}",
                            self.where((*p, "pose")),
                        )
                    )
                else:
                    values.update(kp.joints)
            for j, w in gs.joints.items():
                values[j] = self.joint_value(j, w, (*p, "joints", j))
            states.append(m.GroupState(gs.name, gs.group, tuple(values.items()), self.where(p)))
        return m.Semantic(
            groups,
            tuple(states),
            tuple(
                m.EndEffector(e.name, e.group, e.parent_link, e.parent_group, self.where((*base, "end_effectors", i)))
                for i, e in enumerate(sem.end_effectors)
            ),
            tuple(
                m.VirtualJoint(v.name, v.type, v.parent_frame, v.child_link, self.where((*base, "virtual_joints", i)))
                for i, v in enumerate(sem.virtual_joints)
            ),
            tuple(sem.passive_joints),
            tuple(
                m.DisabledPair(d.link1, d.link2, d.reason, self.where((*base, "disable_collisions", i)))
                for i, d in enumerate(sem.disable_collisions)
            ),
            self.where(base),
        )

    def unique_semantics(self, sem: s.SemanticSpec) -> None:
        """SPEC024: MoveIt keys SRDF elements by name (a group state by name and group, a
        disabled pair by its links), so a second one with the same key would silently
        replace the first; refuse it at the second."""
        keyed: list[tuple[str, list[tuple[object, str]]]] = [
            ("groups", [(g.name, f"group '{g.name}'") for g in sem.groups]),
            ("group_states", [((g.name, g.group), f"group state '{g.name}' of '{g.group}'") for g in sem.group_states]),
            ("end_effectors", [(e.name, f"end effector '{e.name}'") for e in sem.end_effectors]),
            ("virtual_joints", [(v.name, f"virtual joint '{v.name}'") for v in sem.virtual_joints]),
            ("passive_joints", [(n, f"passive joint '{n}'") for n in sem.passive_joints]),
            (
                "disable_collisions",
                [(frozenset((d.link1, d.link2)), f"disabled pair {d.link1}/{d.link2}") for d in sem.disable_collisions],
            ),
        ]
        for section, entries in keyed:
            seen: set[object] = set()
            for i, (key, what) in enumerate(entries):
                if key in seen:
                    self.findings.append(
                        Finding(
                            "SPEC024",
                            "error",
                            f"{what} is declared twice in semantic.{section}",
                            "remove or rename the second one (the SRDF keeps one per name)",
                            f"semantic.{section}.{i}",
                            self.where(("semantic", section, i)),
                        )
                    )
                seen.add(key)


def _replace_where(j: m.Joint, where: Where) -> m.Joint:
    return replace(j, where=where)


def _complete_states(robot: m.Robot, sem: s.SemanticSpec) -> m.Robot:
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


def _param_text(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"  # ros2_control's parse_bool takes only true/false
    return str(v)


def _walk_sources(obj: object) -> Iterator[str]:
    """Every source inside a spec element, in spec order."""
    if isinstance(obj, Measured | Written):
        if obj.source:
            yield obj.source
    elif isinstance(obj, BaseModel):
        src = getattr(obj, "source", None)
        if isinstance(src, str):
            yield src
        for name in type(obj).model_fields:
            if name != "source":
                yield from _walk_sources(getattr(obj, name))
    elif isinstance(obj, list | tuple):
        for item in obj:
            yield from _walk_sources(item)
    elif isinstance(obj, dict):
        for item in obj.values():
            yield from _walk_sources(item)


def sources(*objs: object) -> str | None:
    seen: list[str] = []
    for obj in objs:
        for src in [obj] if isinstance(obj, str) else _walk_sources(obj):
            for part in (p.strip() for p in src.split(",")):
                if part and part not in seen:
                    seen.append(part)
    return ", ".join(seen) if seen else None


def missing_sources(doc: Document, spec: s.RobotSpec) -> list[Finding]:
    """``require_sources: true``: every written quantity needs a source, on itself or on
    an element that contains it."""
    out: list[Finding] = []

    def walk(obj: object, path: Path_, covered: bool) -> None:
        if isinstance(obj, Measured | Written):
            if not covered and not obj.source and path in doc.value_marks:
                out.append(
                    Finding(
                        "SPEC010",
                        "error",
                        f'measured value "{getattr(obj, "text", obj)}" has no source',
                        "add source: <row ID> to the value or to its element, or set require_sources: false",
                        ".".join(map(str, path)),
                        doc.where(path),
                    )
                )
        elif isinstance(obj, BaseModel):
            here = covered or bool(getattr(obj, "source", None))
            for name, info in type(obj).model_fields.items():
                walk(getattr(obj, name), (*path, info.alias or name), here)
        elif isinstance(obj, list | tuple):
            for i, item in enumerate(obj):
                walk(item, (*path, i), covered)
        elif isinstance(obj, dict):
            for k, item in obj.items():
                walk(item, (*path, k), covered)

    for name, info in type(spec).model_fields.items():
        if name != "plausibility":  # bounds chosen for checking, not measurements
            walk(getattr(spec, name), (info.alias or name,), False)
    return out


def ranges_from(doc: Document) -> tuple[dict[str, units.Range], list[Finding]]:
    """The spec's plausibility overrides, read before the rest so that validation uses them."""
    ranges = dict(units.DEFAULT_RANGES)
    findings: list[Finding] = []
    raw = doc.data.get("plausibility") if isinstance(doc.data, dict) else None
    if not isinstance(raw, dict):
        return ranges, findings
    for role, bounds in raw.items():
        p: Path_ = ("plausibility", role)
        if role not in ranges:
            findings.append(
                Finding(
                    "SPEC001",
                    "error",
                    f"unknown plausibility role '{role}'",
                    f"roles: {', '.join(ranges)}",
                    ".".join(map(str, p)),
                    doc.where(p, key=True),
                )
            )
            continue
        if not isinstance(bounds, dict):
            continue  # the schema reports the shape
        r = ranges[role]
        low, high = r.low, r.high
        for key in ("min", "max"):
            if key in bounds:
                try:
                    v = abs(units.to_si(bounds[key], r.kind))
                except units.QuantityError as exc:
                    findings.append(
                        Finding(
                            exc.code,
                            "error",
                            exc.message,
                            exc.hint,
                            ".".join(map(str, (*p, key))),
                            doc.where((*p, key)),
                        )
                    )
                    continue
                if key == "min":
                    low = v
                else:
                    high = v
        ranges[role] = units.Range(r.kind, low, high)
    return ranges, findings


__all__ = ["Builder", "check_range", "missing_sources", "ranges_from"]
