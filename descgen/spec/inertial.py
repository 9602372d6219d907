"""A link's inertial: explicit, or from its first visual or collision primitive.

``from: collision`` / ``from: visual`` takes the primitive's uniform-density tensor about
its centroid, turned into link axes (``descgen.inertia``); the centre of mass is the
inertial origin if given, else the primitive's centre.
"""

from __future__ import annotations

from .. import inertia as mass_props
from .. import model as m
from ..yamlsource import Path_
from . import models as s
from .convert import Converter
from .geometry import pose


def inertial(
    conv: Converter,
    spec: s.InertialSpec,
    visuals: tuple[m.Visual, ...],
    collisions: tuple[m.Collision, ...],
    path: Path_,
) -> m.Inertial:
    mass = spec.mass.si
    if spec.inertia is not None:
        t = spec.inertia
        tensor = m.Inertia(t.ixx.si, t.ixy.si, t.ixz.si, t.iyy.si, t.iyz.si, t.izz.si)
        return m.Inertial(mass, pose(spec.origin), tensor, conv.where(path))
    shapes: tuple[m.Visual | m.Collision, ...] = collisions if spec.from_ == "collision" else visuals
    subject = ".".join(map(str, path))
    if not shapes or shapes[0].geometry is None:
        conv.error(
            "INER010",
            f"inertial from {spec.from_}, but the link has no {spec.from_} geometry",
            f"add a {spec.from_} primitive or give inertia explicitly",
            subject,
            conv.where((*path, "from")),
        )
        return m.Inertial(mass, pose(spec.origin), None, conv.where(path))
    shape = shapes[0]
    tensor_or_none = mass_props.in_link_frame(shape.geometry, mass, shape.origin) if shape.geometry else None
    if tensor_or_none is None:
        conv.error(
            "INER010",
            f"cannot compute inertia from a mesh {spec.from_}",
            "give inertia explicitly (from your CAD tool), or use a primitive",
            subject,
            conv.where((*path, "from")),
        )
    com = shape.origin.xyz if spec.origin is None else pose(spec.origin).xyz
    return m.Inertial(mass, m.Pose(com, (0.0, 0.0, 0.0)), tensor_or_none, conv.where(path))
