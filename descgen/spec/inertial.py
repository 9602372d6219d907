"""A link's inertial: explicit, or from its first visual or collision shape.

``from: collision`` / ``from: visual`` takes the shape's uniform-density tensor about
its centroid, turned into link axes (``descgen.physics.inertia``); the centre of mass is the
inertial origin if given, else the shape's centroid. A mesh shape must be watertight
(INER030) and readable (INER031): its solid is integrated triangle by triangle.
"""

from __future__ import annotations

import math
from pathlib import Path

from descgen.codes.spec import INER010, INER030, INER031, INER032
from descgen.core import model as m
from descgen.core.findings import Where
from descgen.infra.yamlsource import Path_
from descgen.meshes import paths as mesh_paths
from descgen.physics import inertia as mass_props
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.geometry import pose


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
            INER010,
            f"inertial from {spec.from_}, but the link has no {spec.from_} geometry",
            f"add a {spec.from_} primitive or give inertia explicitly",
            subject,
            conv.where((*path, "from")),
        )
        return m.Inertial(mass, pose(spec.origin), None, conv.where(path))
    shape = shapes[0]
    if isinstance(shape.geometry, m.Mesh):
        return _from_mesh(conv, spec, shape.geometry, shape.origin, path)
    tensor_or_none = mass_props.in_link_frame(shape.geometry, mass, shape.origin) if shape.geometry else None
    if tensor_or_none is None:
        conv.error(
            INER010,
            f"cannot compute inertia from a mesh {spec.from_}",
            "give inertia explicitly (from your CAD tool), or use a primitive",
            subject,
            conv.where((*path, "from")),
        )
    tensor_or_none = _finite(conv, spec, tensor_or_none, subject, conv.where((*path, "from")))
    com = shape.origin.xyz if spec.origin is None else pose(spec.origin).xyz
    return m.Inertial(mass, m.Pose(com, (0.0, 0.0, 0.0)), tensor_or_none, conv.where(path))


def _finite(
    conv: Converter, spec: s.InertialSpec, tensor: m.Inertia | None, subject: str, where: Where
) -> m.Inertia | None:
    """The tensor, or None with INER032 when it overflows: plausibility ranges widened to the
    edge of the floats (1e300 kg, 1e200 m) give moments of inf, and an infinite tensor has no
    principal moments, for the rules or for any simulator."""
    if tensor is None or all(
        math.isfinite(v) for v in (tensor.ixx, tensor.ixy, tensor.ixz, tensor.iyy, tensor.iyz, tensor.izz)
    ):
        return tensor
    conv.error(
        INER032,
        f"the inertia computed from the {spec.from_} shape overflows (not a finite number): "
        "the mass or the shape's size is beyond what a part can have",
        "give the measured mass and size, or the inertia explicitly; widen plausibility: ranges only as far as a "
        "real robot needs",
        subject,
        where,
    )
    return None


def _from_mesh(conv: Converter, spec: s.InertialSpec, mesh: m.Mesh, origin: m.Pose, path: Path_) -> m.Inertial:
    """Mass given, centre of mass and tensor from the watertight mesh at uniform density."""
    subject = ".".join(map(str, path))
    where = conv.where((*path, "from"))
    where_file = _resolved(conv, mesh.filename)
    if where_file.state != "ok" and Path(conv.doc.file).is_file():
        # the spec loader reports a mesh it cannot find (mesh_paths.resolve_spec, SPEC060-063)
        return m.Inertial(spec.mass.si, pose(spec.origin), None, conv.where(path))
    file = where_file.path if where_file.state == "ok" else None
    problem = f"mesh '{mesh.filename}' is not a readable file beside the spec" if file is None else None
    loaded = None
    if file is not None:
        from descgen.meshes import (
            load as meshes,  # numpy, and trimesh for some formats: only for a spec with a mesh inertial
        )

        try:
            loaded = meshes.load(file)
        except meshes.MeshError as exc:
            problem = f"mesh '{mesh.filename}': {exc}"
    if loaded is None:
        conv.error(INER031, f"cannot compute inertia from {spec.from_}: {problem}", _GIVE, subject, where)
        return m.Inertial(spec.mass.si, pose(spec.origin), None, conv.where(path))
    if not loaded.watertight:
        conv.error(
            INER030,
            f"cannot compute inertia from {spec.from_}: mesh '{mesh.filename}' is not watertight "
            f"({loaded.open_edges} open edges, or inconsistent winding), so it bounds no solid",
            "close the mesh in your CAD tool (or use its convex hull), or " + _GIVE,
            subject,
            where,
        )
        return m.Inertial(spec.mass.si, pose(spec.origin), None, conv.where(path))
    found = mass_props.from_mesh(
        loaded.vertices * (loaded.facts.unit_meter or 1.0), loaded.faces, spec.mass.si, mesh.scale, origin
    )
    if found is None:
        conv.error(INER030, f"mesh '{mesh.filename}' bounds no volume", _GIVE, subject, where)
        return m.Inertial(spec.mass.si, pose(spec.origin), None, conv.where(path))
    com, computed = found
    tensor = _finite(conv, spec, computed, subject, where)
    com = com if spec.origin is None else pose(spec.origin).xyz
    return m.Inertial(spec.mass.si, m.Pose(com, (0.0, 0.0, 0.0)), tensor, conv.where(path))


_GIVE = "give inertia explicitly (from your CAD tool), or use a primitive"


def _resolved(conv: Converter, name: str) -> mesh_paths.Resolved:
    """The mesh file as resolve_spec finds it: beside the spec, or package:// in the
    spec's recorded package_paths, then the command line's --package-path."""
    spec = Path(conv.doc.file)
    recorded = conv.doc.data.get("package_paths") if isinstance(conv.doc.data, dict) else None
    folders = [mesh_paths.spec_folder(spec, w) for w in recorded or [] if isinstance(w, str)]
    base = spec.resolve().parent
    return mesh_paths.resolve(name, base, base, [*(f for f in folders if f is not None), *conv.package_paths])
