"""A read description (the SI model) -> the data of a spec, every value with its source.

Quantities are written by :mod:`.quantity` (exact, in the reviewer's unit). Each element
cites ``file:line`` of the element it came from, so ``require_sources: true`` holds from
the first import. Where an imported value lies outside the spec's default plausibility
range, the spec widens that range (``plausibility:``) instead of changing the value: the
spec describes the robot as it is, and the audit still reports what it would report.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

from descgen.commands.importer.quantity import Units, quantity, si_text
from descgen.core import model as m
from descgen.core import units
from descgen.core.findings import Where
from descgen.spec.convert import DAMPING, EFFORT, FRICTION, POSITION, VELOCITY

Data = dict[str, Any]


class SpecWriter:
    """Builds the spec data of one robot; remembers what each plausibility role saw."""

    def __init__(self, chosen: Units, sources: Callable[[Where], str]) -> None:
        self.units = chosen
        self.source_of = sources
        self.seen: dict[str, tuple[float, float]] = {}  # role -> smallest, largest non-zero magnitude

    def q(self, value: float, kind: str, role: str | None = None) -> str | int:
        if role is not None and value != 0:
            mag = abs(value)
            lo, hi = self.seen.get(role, (mag, mag))
            self.seen[role] = (min(lo, mag), max(hi, mag))
        unit = {"length": self.units.length, "angle": self.units.angle, "mass": self.units.mass}.get(kind, "")
        if kind == "angular_velocity" and self.units.angle == "deg":
            unit = "deg/s"
        return quantity(value, kind, unit)

    # -- elements ---------------------------------------------------------------------------

    def origin(self, pose: m.Pose) -> Data | None:
        out: Data = {}
        if any(pose.xyz):
            out["xyz"] = [self.q(v, "length", "offset") for v in pose.xyz]
        if any(pose.rpy):
            out["rpy"] = [self.q(v, "angle", "angle") for v in pose.rpy]
        return out or None

    def geometry(self, g: m.Geometry | None) -> Data | None:
        if isinstance(g, m.Box):
            return {"box": {"size": [self.q(v, "length", "size") for v in g.size]}}
        if isinstance(g, m.Cylinder):
            return {
                "cylinder": {"radius": self.q(g.radius, "length", "size"), "length": self.q(g.length, "length", "size")}
            }
        if isinstance(g, m.Sphere):
            return {"sphere": {"radius": self.q(g.radius, "length", "size")}}
        if isinstance(g, m.Mesh):
            mesh: Data = {"filename": g.filename}
            if g.scale != (1.0, 1.0, 1.0):
                mesh["scale"] = [number(v) for v in g.scale]
            return {"mesh": mesh}
        return None  # a geometry the reader could not read: the spec fails validate there too

    def shape(self, s: m.Visual | m.Collision) -> Data:
        out: Data = {}
        if s.name is not None:
            out["name"] = s.name
        if (o := self.origin(s.origin)) is not None:
            out["origin"] = o
        out["geometry"] = self.geometry(s.geometry)
        if isinstance(s, m.Visual) and s.material is not None:
            out["material"] = s.material
        out["source"] = self.source_of(s.where)
        return out

    def inertial(self, i: m.Inertial) -> Data:
        out: Data = {}
        if i.mass is not None:
            out["mass"] = self.q(i.mass, "mass", "mass")
        if (o := self.origin(i.origin)) is not None:
            out["origin"] = o
        if i.inertia is not None:
            t = i.inertia
            out["inertia"] = {k: self.q(getattr(t, k), "inertia") for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")}
        out["source"] = self.source_of(i.where)
        return out

    def link(self, lk: m.Link) -> Data:
        out: Data = {"name": lk.name}
        if lk.visuals:
            out["visual"] = [self.shape(v) for v in lk.visuals]
        if lk.collisions:
            out["collision"] = [self.shape(c) for c in lk.collisions]
        if lk.inertial is not None:
            out["inertial"] = self.inertial(lk.inertial)
        out["source"] = self.source_of(lk.where)
        return out

    def joint(self, j: m.Joint) -> Data:
        out: Data = {"name": j.name, "type": j.type, "parent": j.parent, "child": j.child}
        if (o := self.origin(j.origin)) is not None:
            out["origin"] = o
        if j.type in m.WITH_AXIS and j.axis is not None:
            out["axis"] = axis(j.axis)
        pos_kind, pos_role = POSITION.get(j.type, ("angle", "joint_angle"))
        if j.limit is not None and j.type != "fixed":
            out["limit"] = self.limit(j, j.limit, pos_kind, pos_role)
        if j.dynamics is not None:
            d = j.dynamics
            out["dynamics"] = {
                "damping": self.q(d.damping, DAMPING.get(j.type, "angular_damping")),
                "friction": self.q(d.friction, FRICTION.get(j.type, "torque")),
            }
        if j.mimic is not None:
            mm: Data = {"joint": j.mimic.joint}
            if j.mimic.multiplier != 1.0:
                mm["multiplier"] = number(j.mimic.multiplier)
            if j.mimic.offset:
                mm["offset"] = self.q(j.mimic.offset, pos_kind)
            out["mimic"] = mm
        if j.safety is not None:
            s = j.safety
            gain = "linear_stiffness_gain" if j.type == "prismatic" else "angular_stiffness_gain"
            out["safety_controller"] = {
                "soft_lower_limit": self.q(s.soft_lower_limit, pos_kind, pos_role),
                "soft_upper_limit": self.q(s.soft_upper_limit, pos_kind, pos_role),
                "k_position": self.q(s.k_position, gain),
                "k_velocity": self.q(s.k_velocity, _k_velocity_kind(j.type)),
            }
        out["source"] = self.source_of(j.where)
        return out

    def limit(self, j: m.Joint, lm: m.Limit, pos_kind: str, pos_role: str) -> Data:
        eff_kind, eff_role = EFFORT.get(j.type, ("torque", "torque"))
        vel_kind, vel_role = VELOCITY.get(j.type, ("angular_velocity", "angular_velocity"))
        out: Data = {}
        if lm.lower is not None:
            out["lower"] = self.q(lm.lower, pos_kind, pos_role)
        if lm.upper is not None:
            out["upper"] = self.q(lm.upper, pos_kind, pos_role)
        if lm.effort is not None:
            out["effort"] = self.q(lm.effort, eff_kind, eff_role)
        if lm.velocity is not None:
            out["velocity"] = self.q(lm.velocity, vel_kind, vel_role)
        out["source"] = self.source_of(lm.where)
        return out

    def material(self, mat: m.Material) -> Data:
        out: Data = {"name": mat.name}
        if mat.rgba is not None:
            out["rgba"] = [number(c) for c in mat.rgba]
        if mat.texture is not None:
            out["texture"] = mat.texture
        return out

    def plausibility(self) -> Data:
        """Ranges widened just enough to hold every imported value (the defaults elsewhere)."""
        out: Data = {}
        for role, (lo, hi) in sorted(self.seen.items()):
            r = units.DEFAULT_RANGES.get(role)
            if r is None or (r.low <= lo and hi <= r.high):
                continue
            unit = units.KINDS[r.kind].si_unit
            out[role] = {"min": f"{si_text(min(lo, r.low))} {unit}", "max": f"{si_text(max(hi, r.high))} {unit}"}
        return out


def _k_velocity_kind(joint_type: str) -> str:
    # URDF's k_velocity is in N*s/m or N*m*s/rad: the damping kinds (spec/joints.py)
    return DAMPING.get(joint_type, "angular_damping")


def number(v: float) -> float | int:
    """A plain number (scale, rgba, multiplier) as YAML writes it back exactly."""
    return int(v) if v.is_integer() and abs(v) < 2**53 else v


def axis(v: m.Vec3) -> list[float | int]:
    return [number(c + 0.0) for c in v]


def source_name(where: Where, base: Path | None = None) -> str:
    """``file:line`` for a spec source: the file's name (without the ``(expanded)`` mark)."""
    name = where.file.removesuffix(" (expanded)")
    shown = Path(name).name if base is None else name
    return f"{shown}:{where.line}" if where.line else shown


def finite(values: list[float]) -> bool:
    return all(math.isfinite(v) for v in values)
