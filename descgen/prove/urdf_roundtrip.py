"""Check 2: the written URDF, read back by a parser that did not write it, is the model.

Field by field, within 1e-9: names, types, parents, children, origins (as transforms),
axes, limits, dynamics, mimic, safety controllers, every visual and collision with its
geometry, origin, scale and material, materials, and inertials. A mismatch names the
field path, both values, and the URDF line.

Two readers, one comparison. ``check`` and ``generate`` read back with
``readers/urdf_readback.py``: lxml and urdfdom's rules, no code shared with the model, the
templates or the renderer, a few milliseconds. yourdfpy, the reader this proof used first,
costs a second of every run in imports (trimesh, scipy), so it runs under
``descgen check --thorough`` (:func:`urdf_roundtrip_yourdfpy`), in the importer's proof, and
as the tests' oracle for the small reader (both agree on the example-robot-data corpus).
check_urdf (urdfdom's own C++ parser, check 3) reads every URDF as well.
"""

from __future__ import annotations

import io
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any, cast

from descgen.codes.generate import GEN030
from descgen.core.findings import Finding, Where
from descgen.core.model import (
    Box,
    Collision,
    Cylinder,
    Geometry,
    Inertial,
    Joint,
    Link,
    Mesh,
    Pose,
    Robot,
    Sphere,
    Visual,
)
from descgen.core.xmlcompare import line_of, parse
from descgen.physics.rigid import rpy_rot
from descgen.read import urdf_readback as rb

TOL = 1e-9


def _close(a: Any, b: Any) -> bool:
    """Same shape and every element within TOL: ``np.allclose(a, b, rtol=0, atol=TOL)`` on
    equal shapes, in plain floats for numbers and (nested) tuples, lists and arrays of numbers
    (a 1000-link model compares ~20,000 fields; numpy costs ~20 us per call)."""
    if a is None or b is None:
        return a is None and b is None
    if type(a) is float and type(b) is float:  # most fields: one number each
        return _near(a, b)
    fa: list[float] = []
    fb: list[float] = []
    sa, sb = _shape(a, fa), _shape(b, fb)
    if sa is not None and sb is not None:
        return sa == sb and all(map(_near, fa, fb))
    import numpy as np  # only for what _shape cannot walk (a field that is neither numbers nor arrays)

    try:
        x = np.asarray(a, dtype=float)
        y = np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return bool(a == b)
    return x.shape == y.shape and bool(np.allclose(x, y, rtol=0, atol=TOL))


def _near(x: float, y: float) -> bool:
    # numpy's isclose: infinities are close only to themselves (inf - inf is NaN, so the
    # equality decides), NaN to nothing (neither test holds)
    return x == y or abs(x - y) <= TOL


def _shape(v: Any, flat: list[float]) -> tuple[int, ...] | None:
    """The shape of a number or a regular nesting of sequences of numbers, appending its
    numbers to ``flat``; None for anything else (then numpy decides)."""
    if isinstance(v, int | float):
        flat.append(float(v))
        return ()
    if _is_array(v):
        if v.dtype.kind not in "biuf":
            return None
        flat.extend(float(x) for x in v.ravel().tolist())
        return tuple(v.shape)
    if isinstance(v, tuple | list):
        if all(type(x) is float for x in v):  # a vector, or a matrix's row: no recursion
            flat.extend(v)
            return (len(v),)
        shapes = {_shape(x, flat) for x in v}
        inner = shapes.pop() if len(shapes) == 1 else () if not shapes else None
        if inner is None:
            return None
        return (len(v), *inner)
    return None


def _is_array(v: Any) -> bool:
    """Whether ``v`` is a numpy array, without importing numpy: check and generate compare
    plain floats only (the read-back reader and the model build no arrays), and numpy's import
    is ~60 ms of a cold check. An array exists only if numpy is already imported."""
    np = sys.modules.get("numpy")
    return np is not None and isinstance(v, np.ndarray)


def _show(v: Any) -> str:
    if _is_array(v):
        import numpy as np

        return np.array2string(v, precision=12, separator=", ").replace("\n", "")
    return repr(v)


Field = str | tuple[str, ...]


class _Compare:
    def __init__(self, lines: dict[tuple[str, str], int], file: str, reader: str) -> None:
        self.lines = lines
        self.file = file
        self.reader = reader
        self.found: list[Finding] = []

    def diff(self, kind: str, name: str, field: Field, model: Any, urdf: Any) -> None:
        """A finding at ``kind:name``; ``field`` is its path, or the path's parts (joined here,
        so that the ~20,000 equal fields of a 1000-link robot build no text)."""
        field = field if isinstance(field, str) else "/".join(field)
        line = self.lines.get((kind, name), 0)
        self.found.append(
            GEN030.finding(
                f"URDF read back by {self.reader} differs at {kind}:{name}/{field}: "
                f"model {_show(model)}, URDF {_show(urdf)}",
                "the URDF template writes this field wrong (or the file was edited)",
                f"{kind}:{name}",
                Where(self.file, line),
            )
        )

    def eq(self, kind: str, name: str, field: Field, model: Any, urdf: Any, exact: bool = False) -> None:
        same = (model == urdf) if exact else _close(model, urdf)
        if not same:
            self.diff(kind, name, field, model, urdf)

    def eq_matrix(self, kind: str, name: str, field: Field, model: Rows | None, urdf: Rows) -> None:
        """``eq`` for a matrix (origins, inertia tensors): both sides are rows of numbers
        (the readers build them so), compared without _close's generic shape walk; a
        difference shows the model's as the array it is."""
        if model is None or not _rows_close(model, urdf):
            import numpy as np  # a difference is shown as the array numpy prints; only then imported

            self.diff(kind, name, field, None if model is None else np.asarray(model, dtype=float), urdf)


Rows = Sequence[Sequence[float]]


def _rows_close(a: Rows, b: Rows) -> bool:
    """``_close`` for two matrices of plain numbers: same shape, every element within TOL."""
    # nearly always the same floats, read back as written: one comparison in C. Tuples compare
    # items by identity first, so a NaN would equal itself there: a finite sum rules NaN out
    # (and an inf, whose sum may be NaN, takes the loop below as before)
    if a == b and (total := sum(map(sum, a))) == total:
        return True
    if len(a) != len(b):
        return False
    for ra, rb_ in zip(a, b, strict=True):
        if len(ra) != len(rb_):
            return False
        for x, y in zip(ra, rb_, strict=True):
            if not (x == y or abs(x - y) <= TOL):
                return False
    return True


def _pose(p: Pose) -> tuple[tuple[float, ...], ...]:
    """The model's 4x4 transform of an origin, in plain floats (``descgen.physics.rigid``: the formula
    of ``transforms.pose_matrix`` without numpy's ~10 us per small array)."""
    r0, r1, r2 = rpy_rot(p.rpy)
    x, y, z = p.xyz
    return ((*r0, float(x)), (*r1, float(y)), (*r2, float(z)), (0.0, 0.0, 0.0, 1.0))


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


def _their_geometry(g: rb.Geometry) -> dict[str, Any]:
    if g.kind == "box":
        return {"type": "box", "size": g.size}
    if g.kind == "cylinder":
        return {"type": "cylinder", "radius": g.radius, "length": g.length}
    if g.kind == "sphere":
        return {"type": "sphere", "radius": g.radius}
    if g.kind == "mesh":
        return {"type": "mesh", "filename": g.filename, "scale": g.scale}
    return {"type": None}


def _shapes(c: _Compare, link: str, tag: str, ours: Sequence[Visual | Collision], theirs: Sequence[rb.Shape]) -> None:
    if len(ours) != len(theirs):
        c.diff("link", link, f"{tag} count", len(ours), len(theirs))
        return
    for i, (a, b) in enumerate(zip(ours, theirs, strict=True)):
        f = f"{tag}[{i}]"
        c.eq("link", link, (f, "name"), a.name, b.name, exact=True)
        c.eq_matrix("link", link, (f, "origin"), _pose(a.origin), b.origin)
        ga, gb = _geometry(a.geometry), _their_geometry(b.geometry)
        if ga["type"] != gb["type"]:
            c.diff("link", link, (f, "geometry"), ga["type"], gb["type"])
            continue
        for key in ga:
            if key != "type":
                c.eq("link", link, (f, "geometry", key), ga[key], gb[key], exact=key == "filename")
        if isinstance(a, Visual):
            c.eq("link", link, (f, "material"), a.material, b.material, exact=True)


def _inertial(c: _Compare, link: str, ours: Inertial | None, theirs: rb.Inertial | None) -> None:
    if ours is None or theirs is None:
        if (ours is None) != (theirs is None):
            c.diff("link", link, "inertial", ours is not None, theirs is not None)
        return
    c.eq("link", link, "inertial/mass", ours.mass, theirs.mass)
    c.eq_matrix("link", link, "inertial/origin", _pose(ours.origin), theirs.origin)
    tensor = ours.inertia.matrix() if ours.inertia else None
    c.eq_matrix("link", link, "inertial/inertia", tensor, theirs.inertia)


def _joint(c: _Compare, ours: Joint, theirs: rb.Joint) -> None:
    n = ours.name
    c.eq("joint", n, "type", ours.type, theirs.type, exact=True)
    c.eq("joint", n, "parent", ours.parent, theirs.parent, exact=True)
    c.eq("joint", n, "child", ours.child, theirs.child, exact=True)
    c.eq_matrix("joint", n, "origin", _pose(ours.origin), theirs.origin)
    if ours.axis is not None:
        c.eq("joint", n, "axis", ours.axis, theirs.axis)
    lm, tl = ours.limit if ours.type != "fixed" else None, theirs.limit
    if lm is None or tl is None:
        if (lm is None) != (tl is None):
            c.diff("joint", n, "limit", lm is not None, tl is not None)
    else:
        # a bound the model does not have is not written, and urdfdom reads a missing lower/upper as 0
        lower, upper = (0.0 if v is None else v for v in (lm.lower, lm.upper))
        for attr, value in (("lower", lower), ("upper", upper), ("effort", lm.effort), ("velocity", lm.velocity)):
            c.eq("joint", n, ("limit", attr), value, getattr(tl, attr))
    dyn = ours.dynamics
    c.eq("joint", n, "dynamics", None if dyn is None else (dyn.damping, dyn.friction), theirs.dynamics)
    mm, tm = ours.mimic, theirs.mimic
    c.eq("joint", n, "mimic/joint", None if mm is None else mm.joint, None if tm is None else tm[0], exact=True)
    c.eq("joint", n, "mimic", None if mm is None else (mm.multiplier, mm.offset), None if tm is None else tm[1:])
    sc = ours.safety
    c.eq(
        "joint",
        n,
        "safety_controller",
        None if sc is None else (sc.soft_lower_limit, sc.soft_upper_limit, sc.k_position, sc.k_velocity),
        theirs.safety,
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


def _unreadable(reader: str, why: str, file: str, line: int = 0) -> list[Finding]:
    return [
        GEN030.finding(
            f"{reader} cannot read the URDF: {why}",
            "the URDF template writes an invalid file (or the file was edited)",
            "file",
            Where(file, line),
        )
    ]


def compare_read(
    robot: Robot, theirs: rb.Robot, lines: dict[tuple[str, str], int], file: str, reader: str
) -> list[Finding]:
    """Differences between the model and a URDF already read (by either reader)."""
    c = _Compare(lines, file, reader)
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
        c.eq("material", m.name, "rgba", m.rgba, tm.rgba)
        c.eq("material", m.name, "texture", m.texture, tm.texture, exact=True)
    if len(theirs.materials) != len(robot.materials):
        c.diff("robot", robot.name, "material count", len(robot.materials), len(theirs.materials))
    return c.found


def compare_readback(robot: Robot, urdf_text: str, file: str) -> list[Finding]:
    """Differences between the model and ``urdf_text`` as the lxml read-back reader reads it."""
    from lxml import etree

    reader = "the lxml read-back reader"
    try:
        theirs = rb.read(urdf_text)
    except rb.ReadbackError as exc:
        return _unreadable(reader, str(exc), file, exc.line)
    except etree.XMLSyntaxError as exc:
        return _unreadable(reader, f"XMLSyntaxError: {exc}", file, exc.lineno or 0)
    lines = {("link", x.name): x.line for x in reversed(theirs.links)}
    lines |= {("joint", x.name): x.line for x in reversed(theirs.joints)}
    lines |= {("material", x.name): x.line for x in reversed(theirs.materials)}
    return compare_read(robot, theirs, lines, file, reader)


def from_yourdfpy(robot: Any) -> rb.Robot:
    """yourdfpy's robot in the read-back reader's terms, urdfdom's defaults filled in where
    yourdfpy leaves None (limit lower/upper, dynamics, safety controller soft limits)."""
    import numpy as np  # yourdfpy's values are numpy arrays (and it imports numpy itself)

    def origin(m: Any) -> rb.Matrix:
        a = np.eye(4) if m is None else np.asarray(m, dtype=float)
        return cast("rb.Matrix", tuple(tuple(float(v) for v in row) for row in a))

    def f(v: Any, default: float | None = None) -> Any:
        return default if v is None else float(v)

    def vec(v: Any) -> Any:
        return None if v is None else tuple(float(x) for x in np.ravel(v))

    def geometry(g: Any) -> rb.Geometry:
        if g is None:
            return rb.Geometry("none")
        if g.box is not None:
            return rb.Geometry("box", size=vec(g.box.size))
        if g.cylinder is not None:
            return rb.Geometry("cylinder", radius=f(g.cylinder.radius), length=f(g.cylinder.length))
        if g.sphere is not None:
            return rb.Geometry("sphere", radius=f(g.sphere.radius))
        if g.mesh is not None:
            s = g.mesh.scale
            scale = (1.0, 1.0, 1.0) if s is None else (float(s),) * 3 if np.ndim(s) == 0 else vec(s)
            return rb.Geometry("mesh", filename=g.mesh.filename, scale=scale)
        return rb.Geometry("none")

    def shape(s: Any) -> rb.Shape:
        mat = getattr(s, "material", None)
        return rb.Shape(s.name, origin(s.origin), geometry(s.geometry), None if mat is None else mat.name)

    def inertial(i: Any) -> rb.Inertial | None:
        if i is None:
            return None
        tensor = np.asarray(i.inertia, dtype=float)
        rows = cast("tuple[rb.Vec3, rb.Vec3, rb.Vec3]", tuple(tuple(float(v) for v in r) for r in tensor))
        return rb.Inertial(f(i.mass), origin(i.origin), rows)

    def joint(j: Any) -> rb.Joint:
        lm, d, m, s = j.limit, j.dynamics, j.mimic, j.safety_controller
        return rb.Joint(
            j.name,
            j.type,
            j.parent,
            j.child,
            origin(j.origin),
            vec(j.axis),
            None if lm is None else rb.Limit(f(lm.lower, 0.0), f(lm.upper, 0.0), f(lm.effort), f(lm.velocity)),
            None if d is None else (f(d.damping, 0.0), f(d.friction, 0.0)),
            None if m is None else (m.joint, f(m.multiplier, 1.0), f(m.offset, 0.0)),
            None
            if s is None
            else (f(s.soft_lower_limit, 0.0), f(s.soft_upper_limit, 0.0), f(s.k_position, 0.0), f(s.k_velocity)),
            0,
        )

    def material(m: Any) -> rb.Material:
        rgba = None if m.color is None else vec(m.color.rgba)
        return rb.Material(m.name, rgba, None if m.texture is None else m.texture.filename, 0)

    return rb.Robot(
        robot.name,
        tuple(
            rb.Link(lk.name, tuple(map(shape, lk.visuals)), tuple(map(shape, lk.collisions)), inertial(lk.inertial), 0)
            for lk in robot.links
        ),
        tuple(joint(j) for j in robot.joints),
        tuple(material(m) for m in robot.materials),
    )


def read_yourdfpy(urdf_text: str) -> rb.Robot:
    """``urdf_text`` as yourdfpy reads it (imports yourdfpy, and with it trimesh and scipy)."""
    import yourdfpy

    urdf = yourdfpy.URDF.load(
        io.StringIO(urdf_text),
        build_scene_graph=False,
        build_collision_scene_graph=False,
        load_meshes=False,
        load_collision_meshes=False,
    )
    return from_yourdfpy(urdf.robot)


def compare(robot: Robot, urdf_text: str, file: str) -> list[Finding]:
    """Differences between the model and ``urdf_text`` as yourdfpy reads it."""
    try:
        theirs = read_yourdfpy(urdf_text)
        lines = source_lines(urdf_text)
    except Exception as exc:  # yourdfpy raises assorted errors on malformed files
        return _unreadable("yourdfpy", f"{type(exc).__name__}: {exc}", file)
    return compare_read(robot, theirs, lines, file, "yourdfpy")


def _link(c: _Compare, ours: Link, theirs: rb.Link) -> None:
    _shapes(c, ours.name, "visual", ours.visuals, theirs.visuals)
    _shapes(c, ours.name, "collision", ours.collisions, theirs.collisions)
    _inertial(c, ours.name, ours.inertial, theirs.inertial)


def _names_differ(ours: Sequence[Any], theirs: Sequence[Any]) -> Iterator[str]:
    a = [x.name for x in ours]
    b = [x.name for x in theirs]
    yield from sorted(set(a) ^ set(b))


def urdf_roundtrip(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    """Proof 2 as check and generate run it: the lxml read-back reader."""
    rel = f"urdf/{robot.name}.urdf"
    return compare_readback(robot, files[rel], str(where / rel))


def urdf_roundtrip_yourdfpy(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    """Proof 2 with yourdfpy (``check --thorough``)."""
    rel = f"urdf/{robot.name}.urdf"
    return compare(robot, files[rel], str(where / rel))
