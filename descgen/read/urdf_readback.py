"""A small, strict URDF reader for proof 2 (the written URDF read back is the model).

Why not yourdfpy here: yourdfpy imports trimesh at module level, and trimesh pulls scipy;
that was about 0.7-1.1 s of every ``descgen check`` (issue 17), far more than the rest of the
proofs. This reader takes milliseconds and needs only lxml.

Why it is still an independent proof: it shares no code with what wrote the URDF. It
does not import the model, the templates, the renderer, ``descgen.physics.transforms`` or the audit's
tolerant URDF reader (``readers/urdf.py``, which builds the model classes): it turns the
XML into its own plain tuples, with its own rpy -> matrix, following urdfdom's rules
(``docs/reference/urdf.md``, the Jazzy parser robot_state_publisher uses) rather than
the model's. yourdfpy stays what it was, the oracle: ``tests/test_urdf_readback.py`` requires
both readers to agree on every example-robot-data URDF and on the generated one, and
``descgen check --thorough`` runs the yourdfpy read-back too.

urdfdom semantics kept (where yourdfpy differs, the difference is noted):
- missing ``<origin>`` / ``xyz`` / ``rpy`` are zero; R = Rz(yaw) Ry(pitch) Rx(roll);
- a missing ``<axis>`` is (1, 0, 0); ``<axis/>`` without ``xyz`` is (0, 0, 0) (yourdfpy: 1 0 0);
- ``<limit>``: ``effort`` and ``velocity`` required, ``lower``/``upper`` default 0 (yourdfpy: None);
- ``<dynamics>``: each of damping and friction defaults to 0; neither is an error;
- ``<safety_controller>``: ``k_velocity`` required, the others default 0 (yourdfpy: None);
- ``<mimic>``: ``joint`` required, multiplier 1, offset 0;
- ``<inertial>``: ``<mass value>`` and all six ``<inertia>`` attributes required (yourdfpy
  fills 0 and 1);
- ``<geometry>`` is its first child element; mesh ``scale`` defaults to 1 1 1;
- numbers are whole decimal tokens (no ``1,5``, no ``nan``), vectors exactly 3 numbers.
Only ``<link>``, ``<joint>`` and ``<material>`` children of ``<robot>`` are read, as urdfdom does.
"""

from __future__ import annotations

import math
import re

from lxml import etree

from descgen.core.record import record

Matrix = tuple[tuple[float, float, float, float], ...]  # 4x4 homogeneous transform, row major
Vec3 = tuple[float, float, float]

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


class ReadbackError(ValueError):
    """The URDF is not one urdfdom would read as written; ``line`` is where (0 when unknown)."""

    def __init__(self, message: str, line: int) -> None:
        super().__init__(message)
        self.line = line


@record
class Geometry:
    kind: str  # box, cylinder, sphere, mesh
    size: Vec3 | None = None
    radius: float | None = None
    length: float | None = None
    filename: str | None = None
    scale: Vec3 | None = None


@record
class Shape:
    """A ``<visual>`` or ``<collision>``; ``material`` is the visual's material name."""

    name: str | None
    origin: Matrix
    geometry: Geometry
    material: str | None


@record
class Inertial:
    mass: float
    origin: Matrix
    inertia: tuple[Vec3, Vec3, Vec3]


@record
class Link:
    name: str
    visuals: tuple[Shape, ...]
    collisions: tuple[Shape, ...]
    inertial: Inertial | None
    line: int


@record
class Limit:
    lower: float
    upper: float
    effort: float
    velocity: float


@record
class Joint:
    name: str
    type: str
    parent: str
    child: str
    origin: Matrix
    axis: Vec3
    limit: Limit | None
    dynamics: tuple[float, float] | None  # damping, friction
    mimic: tuple[str, float, float] | None  # joint, multiplier, offset
    safety: tuple[float, float, float, float] | None  # soft_lower, soft_upper, k_position, k_velocity
    line: int


@record
class Material:
    name: str
    rgba: tuple[float, ...] | None
    texture: str | None
    line: int


@record
class Robot:
    name: str
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    materials: tuple[Material, ...]


def _first(e: etree._Element, tag: str) -> etree._Element | None:
    """``e.find(tag)`` (the first child element named ``tag``, no namespace) without lxml's
    path parser, which costs more than the rest of reading an element."""
    return next(e.iterchildren(tag), None)


def _line(e: etree._Element) -> int:
    v = e.sourceline
    return v if isinstance(v, int) else 0


def _number(text: str, e: etree._Element, key: str) -> float:
    """``text``, attribute ``key`` of ``e`` (or one of its tokens), as a number."""
    if not _NUMBER.fullmatch(text.strip()):
        raise ReadbackError(f"<{e.tag}> {key} is not a number: {text!r}", _line(e))
    return float(text)


def _attr(e: etree._Element, key: str, default: float | None = None) -> float:
    value = e.get(key)
    if value is None:
        if default is None:
            raise ReadbackError(f"<{e.tag}> has no {key}", _line(e))
        return default
    return _number(value, e, key)


def _numbers(e: etree._Element, key: str, n: int | None, default: tuple[float, ...] | None) -> tuple[float, ...]:
    value = e.get(key)
    if value is None:
        if default is None:
            raise ReadbackError(f"<{e.tag}> has no {key}", _line(e))
        return default
    tokens = value.split()
    if not all(map(_NUMBER.fullmatch, tokens)):  # the common case checked in one C loop
        for t in tokens:
            _number(t, e, key)  # raises at the first token that is not a number
    out = tuple(map(float, tokens))
    if n is not None and len(out) != n:
        raise ReadbackError(f"<{e.tag}> {key} needs {n} numbers, has {len(out)}: {value!r}", _line(e))
    return out


# three numbers apart by spaces (how XML hands over any attribute whose whitespace was not
# written as a character reference): read in one match; anything else takes _numbers's path
_VEC3 = re.compile(rf" *({_NUMBER.pattern}) +({_NUMBER.pattern}) +({_NUMBER.pattern}) *")


def _vec3(e: etree._Element, key: str, default: Vec3 | None) -> Vec3:
    value = e.get(key)
    m = None if value is None else _VEC3.fullmatch(value)
    if m is not None:
        return (float(m[1]), float(m[2]), float(m[3]))
    x, y, z = _numbers(e, key, 3, default)
    return (x, y, z)


def rpy_matrix(xyz: Vec3, rpy: Vec3) -> Matrix:
    """The transform of ``<origin xyz rpy>``: R = Rz(yaw) Ry(pitch) Rx(roll) (fixed axes)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, xyz[0]),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, xyz[1]),
        (-sp, cp * sr, cp * cr, xyz[2]),
        (0.0, 0.0, 0.0, 1.0),
    )


_ZERO: Vec3 = (0.0, 0.0, 0.0)


def _kids(e: etree._Element) -> dict[str, etree._Element]:
    """The first child element of each tag (no namespace, like ``find``)."""
    out: dict[str, etree._Element] = {}
    for c in e.iterchildren(etree.Element):
        out.setdefault(c.tag, c)
    return out


def _origin(parent: etree._Element) -> Matrix:
    return _pose(_first(parent, "origin"))


def _pose(e: etree._Element | None) -> Matrix:
    """The transform of an ``<origin>`` element, identity when there is none."""
    if e is None:
        return rpy_matrix(_ZERO, _ZERO)
    return rpy_matrix(_vec3(e, "xyz", _ZERO), _vec3(e, "rpy", _ZERO))


def _geometry(parent: etree._Element) -> Geometry:
    g = _first(parent, "geometry")
    shapes = [] if g is None else [c for c in g if isinstance(c.tag, str)]
    if not shapes:
        raise ReadbackError(f"<{parent.tag}> has no geometry", _line(parent))
    s = shapes[0]
    if s.tag == "box":
        return Geometry("box", size=_vec3(s, "size", None))
    if s.tag == "cylinder":
        return Geometry("cylinder", radius=_attr(s, "radius"), length=_attr(s, "length"))
    if s.tag == "sphere":
        return Geometry("sphere", radius=_attr(s, "radius"))
    if s.tag == "mesh":
        filename = s.get("filename")
        if filename is None:
            raise ReadbackError("<mesh> has no filename", _line(s))
        return Geometry("mesh", filename=filename, scale=_vec3(s, "scale", (1.0, 1.0, 1.0)))
    raise ReadbackError(f"unknown geometry type <{s.tag}>", _line(s))


def _shape(e: etree._Element) -> Shape:
    mat = _first(e, "material") if e.tag == "visual" else None
    return Shape(e.get("name"), _origin(e), _geometry(e), None if mat is None else mat.get("name"))


def _inertial(link: etree._Element) -> Inertial | None:
    e = _first(link, "inertial")
    if e is None:
        return None
    mass, inertia = _first(e, "mass"), _first(e, "inertia")
    if mass is None or inertia is None:
        raise ReadbackError("<inertial> needs <mass> and <inertia>", _line(e))
    xx, xy, xz, yy, yz, zz = (_attr(inertia, k) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
    return Inertial(_attr(mass, "value"), _origin(e), ((xx, xy, xz), (xy, yy, yz), (xz, yz, zz)))


def _name(e: etree._Element) -> str:
    name = e.get("name")
    if name is None:
        raise ReadbackError(f"<{e.tag}> has no name", _line(e))
    return name


def _link(e: etree._Element) -> Link:
    return Link(
        _name(e),
        tuple(map(_shape, e.iterchildren("visual"))),
        tuple(map(_shape, e.iterchildren("collision"))),
        _inertial(e),
        _line(e),
    )


_TYPES = {"revolute", "continuous", "prismatic", "fixed", "floating", "planar"}


def _end(e: etree._Element, kids: dict[str, etree._Element], tag: str) -> str:
    x = kids.get(tag)
    link = None if x is None else x.get("link")
    if link is None:
        raise ReadbackError(f"joint {e.get('name')!r} has no <{tag} link>", _line(e))
    return link


def _joint(e: etree._Element) -> Joint:
    name, kind = _name(e), e.get("type", "")
    if kind not in _TYPES:
        raise ReadbackError(f"joint {name!r} has type {kind!r}, not one of {sorted(_TYPES)}", _line(e))
    kids = _kids(e)  # a joint's children looked up by tag: one pass instead of eight searches
    axis_e = kids.get("axis")
    axis = (1.0, 0.0, 0.0) if axis_e is None else _vec3(axis_e, "xyz", _ZERO)
    lim = kids.get("limit")
    if lim is None and kind in ("revolute", "prismatic"):
        raise ReadbackError(f"{kind} joint {name!r} has no <limit>", _line(e))
    limit = None
    if lim is not None:
        limit = Limit(_attr(lim, "lower", 0.0), _attr(lim, "upper", 0.0), _attr(lim, "effort"), _attr(lim, "velocity"))
    dyn = kids.get("dynamics")
    dynamics = None
    if dyn is not None:
        if dyn.get("damping") is None and dyn.get("friction") is None:
            raise ReadbackError(f"<dynamics> of joint {name!r} has neither damping nor friction", _line(dyn))
        dynamics = (_attr(dyn, "damping", 0.0), _attr(dyn, "friction", 0.0))
    mim = kids.get("mimic")
    mimic = None
    if mim is not None:
        leader = mim.get("joint")
        if leader is None:
            raise ReadbackError(f"<mimic> of joint {name!r} has no joint", _line(mim))
        mimic = (leader, _attr(mim, "multiplier", 1.0), _attr(mim, "offset", 0.0))
    sc = kids.get("safety_controller")
    safety = None
    if sc is not None:
        safety = (
            _attr(sc, "soft_lower_limit", 0.0),
            _attr(sc, "soft_upper_limit", 0.0),
            _attr(sc, "k_position", 0.0),
            _attr(sc, "k_velocity"),
        )
    return Joint(
        name,
        kind,
        _end(e, kids, "parent"),
        _end(e, kids, "child"),
        _pose(kids.get("origin")),
        axis,
        limit,
        dynamics,
        mimic,
        safety,
        _line(e),
    )


def _material(e: etree._Element) -> Material:
    color, texture = _first(e, "color"), _first(e, "texture")
    rgba = None if color is None else _numbers(color, "rgba", 4, None)
    return Material(_name(e), rgba, None if texture is None else texture.get("filename"), _line(e))


def read(text: str) -> Robot:
    """The robot as urdfdom reads ``text``. Raises ReadbackError (with a line) when urdfdom
    would refuse it or read it otherwise than written, and lxml's XMLSyntaxError on bad XML."""
    # the same safe parser settings as everywhere: no network, no entities, no huge trees
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True, huge_tree=False)
    root = etree.fromstring(text.encode("utf-8"), parser)
    if root.tag != "robot":
        raise ReadbackError(f"the root element is <{root.tag}>, not <robot>", _line(root))
    return Robot(
        _name(root),
        tuple(map(_link, root.iterchildren("link"))),
        tuple(map(_joint, root.iterchildren("joint"))),
        tuple(map(_material, root.iterchildren("material"))),
    )
