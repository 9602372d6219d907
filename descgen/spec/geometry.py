"""Spec origins and shapes -> model poses and geometry (already SI after validation)."""

from __future__ import annotations

from descgen.core import model as m
from descgen.spec import models as s


def pose(o: s.Origin | None) -> m.Pose:
    if o is None:
        return m.Pose()
    xyz = (o.xyz[0].si, o.xyz[1].si, o.xyz[2].si)
    rpy = (o.rpy[0].si, o.rpy[1].si, o.rpy[2].si)
    return m.Pose(xyz, rpy)


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
    size = None if g.mesh.size is None else (g.mesh.size[0].si, g.mesh.size[1].si, g.mesh.size[2].si)
    tolerance = None if g.mesh.tolerance is None else g.mesh.tolerance.si
    return m.Mesh(g.mesh.filename, (float(sx), float(sy), float(sz)), size, tolerance)
