"""Check 2: the written URDF, read back by yourdfpy (an independent parser), is the model.

Field by field, within 1e-9: names, types, parents, children, origins (as transforms),
axes, limits, dynamics, mimic, safety controllers, every visual and collision with its
geometry, origin, scale and material, materials, and inertials. A mismatch names the
field path, both values, and the URDF line.
"""

from __future__ import annotations

import io
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..findings import Finding, Where
from ..model import Box, Collision, Cylinder, Geometry, Inertial, Joint, Link, Mesh, Robot, Sphere, Visual
from ..transforms import pose_matrix
from ..xmlcompare import line_of, parse

TOL = 1e-9


def _close(a: Any, b: Any) -> bool:
    if a is None or b is None:
        return a is None and b is None
    try:
        x = np.asarray(a, dtype=float)
        y = np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return bool(a == b)
    return x.shape == y.shape and bool(np.allclose(x, y, rtol=0, atol=TOL))


def _show(v: Any) -> str:
    if isinstance(v, np.ndarray):
        return np.array2string(v, precision=12, separator=", ").replace("\n", "")
    return repr(v)


class _Compare:
    def __init__(self, lines: dict[tuple[str, str], int], file: str) -> None:
        self.lines = lines
        self.file = file
        self.found: list[Finding] = []

    def diff(self, kind: str, name: str, field: str, model: Any, urdf: Any) -> None:
        line = self.lines.get((kind, name), 0)
        self.found.append(
            Finding(
                "GEN030",
                "error",
                f"URDF read back by yourdfpy differs at {kind}:{name}/{field}: "
                f"model {_show(model)}, URDF {_show(urdf)}",
                "the URDF template writes this field wrong (or the file was edited)",
                f"{kind}:{name}",
                Where(self.file, line),
            )
        )

    def eq(self, kind: str, name: str, field: str, model: Any, urdf: Any, exact: bool = False) -> None:
        same = (model == urdf) if exact else _close(model, urdf)
        if not same:
            self.diff(kind, name, field, model, urdf)


def _geometry(g: Geometry | None) -> dict[str, Any]:
    if isinstance(g, Box):
        return {"type": "box", "size": g.size}
    if isinstance(g, Cylinder):
        return {"type": "cylinder", "radius": g.radius, "length": g.length}
    if isinstance(g, Sphere):
        return {"type": "sphere", "radius": g.radius}
    if isinstance(g, Mesh):
        return {"type": "mesh", "filename": g.filename, "scale": g.scale}
    return {"type": None}


def _their_geometry(g: Any) -> dict[str, Any]:
    if g is None:
        return {"type": None}
    if g.box is not None:
        return {"type": "box", "size": g.box.size}
    if g.cylinder is not None:
        return {"type": "cylinder", "radius": g.cylinder.radius, "length": g.cylinder.length}
    if g.sphere is not None:
        return {"type": "sphere", "radius": g.sphere.radius}
    if g.mesh is not None:
        scale = g.mesh.scale if g.mesh.scale is not None else (1.0, 1.0, 1.0)
        return {"type": "mesh", "filename": g.mesh.filename, "scale": scale}
    return {"type": None}


def _shapes(c: _Compare, link: str, tag: str, ours: Sequence[Visual | Collision], theirs: Sequence[Any]) -> None:
    if len(ours) != len(theirs):
        c.diff("link", link, f"{tag} count", len(ours), len(theirs))
        return
    for i, (a, b) in enumerate(zip(ours, theirs, strict=True)):
        f = f"{tag}[{i}]"
        c.eq("link", link, f"{f}/name", a.name, b.name, exact=True)
        c.eq("link", link, f"{f}/origin", pose_matrix(a.origin.xyz, a.origin.rpy), b.origin)
        ga, gb = _geometry(a.geometry), _their_geometry(b.geometry)
        if ga["type"] != gb["type"]:
            c.diff("link", link, f"{f}/geometry", ga["type"], gb["type"])
            continue
        for key in ga:
            if key != "type":
                c.eq("link", link, f"{f}/geometry/{key}", ga[key], gb[key], exact=key == "filename")
        if isinstance(a, Visual):
            theirs_mat = b.material.name if b.material is not None else None
            c.eq("link", link, f"{f}/material", a.material, theirs_mat, exact=True)


def _inertial(c: _Compare, link: str, ours: Inertial | None, theirs: Any) -> None:
    if (ours is None) != (theirs is None):
        c.diff("link", link, "inertial", ours is not None, theirs is not None)
        return
    if ours is None:
        return
    c.eq("link", link, "inertial/mass", ours.mass, theirs.mass)
    c.eq("link", link, "inertial/origin", pose_matrix(ours.origin.xyz, ours.origin.rpy), theirs.origin)
    tensor = np.array(ours.inertia.matrix()) if ours.inertia else None
    c.eq("link", link, "inertial/inertia", tensor, theirs.inertia)


def _joint(c: _Compare, ours: Joint, theirs: Any) -> None:
    n = ours.name
    c.eq("joint", n, "type", ours.type, theirs.type, exact=True)
    c.eq("joint", n, "parent", ours.parent, theirs.parent, exact=True)
    c.eq("joint", n, "child", ours.child, theirs.child, exact=True)
    c.eq("joint", n, "origin", pose_matrix(ours.origin.xyz, ours.origin.rpy), theirs.origin)
    if ours.axis is not None:
        c.eq("joint", n, "axis", ours.axis, theirs.axis)
    lm, tl = ours.limit if ours.type != "fixed" else None, theirs.limit
    if (lm is None) != (tl is None):
        c.diff("joint", n, "limit", lm is not None, tl is not None)
    elif lm is not None:
        lower, upper = lm.lower, lm.upper
        if ours.type == "continuous" and lower == 0 and upper == 0:
            lower = upper = None
        for attr, value in (("lower", lower), ("upper", upper), ("effort", lm.effort), ("velocity", lm.velocity)):
            c.eq("joint", n, f"limit/{attr}", value, getattr(tl, attr))
    dyn = ours.dynamics
    td = theirs.dynamics
    c.eq(
        "joint",
        n,
        "dynamics",
        None if dyn is None else (dyn.damping, dyn.friction),
        None if td is None else (td.damping or 0.0, td.friction or 0.0),
    )
    mm, tm = ours.mimic, theirs.mimic
    c.eq("joint", n, "mimic/joint", None if mm is None else mm.joint, None if tm is None else tm.joint, exact=True)
    c.eq(
        "joint",
        n,
        "mimic",
        None if mm is None else (mm.multiplier, mm.offset),
        None if tm is None else (tm.multiplier, tm.offset),
    )
    sc, ts = ours.safety, theirs.safety_controller
    c.eq(
        "joint",
        n,
        "safety_controller",
        None if sc is None else (sc.soft_lower_limit, sc.soft_upper_limit, sc.k_position, sc.k_velocity),
        None if ts is None else (ts.soft_lower_limit, ts.soft_upper_limit, ts.k_position, ts.k_velocity),
    )


def _index(items: Sequence[Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for it in items:
        out.setdefault(it.name, it)
    return out


def source_lines(urdf_text: str) -> dict[tuple[str, str], int]:
    root = parse(urdf_text)
    out: dict[tuple[str, str], int] = {}
    for e in root:
        if isinstance(e.tag, str) and e.tag in ("link", "joint", "material"):
            out.setdefault((e.tag, e.get("name", "")), line_of(e))
    return out


def compare(robot: Robot, urdf_text: str, file: str) -> list[Finding]:
    """Differences between the model and ``urdf_text`` as yourdfpy reads it."""
    import yourdfpy

    try:
        theirs = yourdfpy.URDF.load(
            io.StringIO(urdf_text),
            build_scene_graph=False,
            build_collision_scene_graph=False,
            load_meshes=False,
            load_collision_meshes=False,
        ).robot
        lines = source_lines(urdf_text)
    except Exception as exc:  # yourdfpy raises assorted errors on malformed files
        return [
            Finding(
                "GEN030",
                "error",
                f"yourdfpy cannot read the URDF: {type(exc).__name__}: {exc}",
                "the URDF template writes an invalid file",
                "file",
                Where(file),
            )
        ]
    c = _Compare(lines, file)
    c.eq("robot", robot.name, "name", robot.name, theirs.name, exact=True)
    links, joints = _index(theirs.links), _index(theirs.joints)
    for name in _names_differ(robot.links, theirs.links):
        c.diff("link", name, "presence", name in {lk.name for lk in robot.links}, name in links)
    for name in _names_differ(robot.joints, theirs.joints):
        c.diff("joint", name, "presence", name in {j.name for j in robot.joints}, name in joints)
    for lk in robot.links:
        if lk.name in links:
            _link(c, lk, links[lk.name])
    for j in robot.joints:
        if j.name in joints:
            _joint(c, j, joints[j.name])
    mats = _index(theirs.materials)
    for m in robot.materials:
        tm = mats.get(m.name)
        if tm is None:
            c.diff("material", m.name, "presence", True, False)
            continue
        c.eq("material", m.name, "rgba", m.rgba, None if tm.color is None else tm.color.rgba)
        c.eq("material", m.name, "texture", m.texture, None if tm.texture is None else tm.texture.filename, exact=True)
    if len(theirs.materials) != len(robot.materials):
        c.diff("robot", robot.name, "material count", len(robot.materials), len(theirs.materials))
    return c.found


def _link(c: _Compare, ours: Link, theirs: Any) -> None:
    _shapes(c, ours.name, "visual", ours.visuals, theirs.visuals)
    _shapes(c, ours.name, "collision", ours.collisions, theirs.collisions)
    _inertial(c, ours.name, ours.inertial, theirs.inertial)


def _names_differ(ours: Sequence[Any], theirs: Sequence[Any]) -> Iterator[str]:
    a = [x.name for x in ours]
    b = [x.name for x in theirs]
    yield from sorted(set(a) ^ set(b))


def urdf_roundtrip(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    rel = f"urdf/{robot.name}.urdf"
    return compare(robot, files[rel], str(where / rel))
