"""Model elements as ready-to-print attribute text, for the URDF and the Xacro.

One layout (templates/_elements.xml.j2) prints both files. What differs is how a value
is written: the URDF prints numbers; the Xacro prints ``${property}`` references to the
measured constants it declares once at the top, each with its source (a value with no
source is written inline, as in the URDF), and a repeated
part becomes one macro whose instances differ only by names and origin.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

from markupsafe import Markup

from descgen.core.model import (
    NO_AXIS,
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
from descgen.core.naming import GLOBAL_FRAMES
from descgen.core.record import record
from descgen.render.formatting import num, vec, xacro_text


@record
class Prop:
    name: str
    value: str
    source: str | None


@record
class ShapeView:
    name: str | None
    xyz: str
    rpy: str
    kind: str  # box | cylinder | sphere | mesh
    attrs: tuple[tuple[str, str], ...]
    material: str | None = None


@record
class InertialView:
    xyz: str
    rpy: str
    mass: str
    tensor: tuple[tuple[str, str], ...]


@record
class LinkView:
    name: str
    comment: str | None
    visuals: tuple[ShapeView, ...]
    collisions: tuple[ShapeView, ...]
    inertial: InertialView | None


@record
class JointView:
    name: str
    type: str
    parent: str
    child: str
    xyz: str
    rpy: str
    comment: str | None
    axis: str | None = None
    limit: tuple[tuple[str, str], ...] = ()
    dynamics: tuple[tuple[str, str], ...] = ()
    mimic: tuple[tuple[str, str], ...] = ()
    safety: tuple[tuple[str, str], ...] = ()


@record
class Item:
    """One entry of the element list: a link with its parent joint, or a part instance."""

    link: LinkView
    joint: JointView | None
    call: tuple[tuple[str, str], ...] = ()  # xacro macro call attributes, for part instances
    part: str | None = None


@record
class PartMacro:
    name: str
    params: str
    link: LinkView
    joint: JointView
    comment: str | None


@dataclass
class Values:
    """Writes values either as numbers (URDF) or as property references (Xacro)."""

    xacro: bool
    props: list[Prop] = field(default_factory=list)
    _index: dict[str, Prop] = field(default_factory=dict)
    # joint name -> its key in config/calibration/*.yaml: a calibrated joint's origin is read
    # from the calibration file in the Xacro (calibration_keys)
    calibrated: dict[str, str] = field(default_factory=dict)
    # the robot's declared prefix (spec ``prefix:``): the Xacro writes it as its ``prefix`` argument
    prefix: str = ""

    def name(self, n: str) -> str:
        """A frame or joint name as written: in the Xacro, the prefix as ``$(arg prefix)``."""
        return prefix_arg(n, self.prefix) if self.xacro else n

    def origin(self, j: Joint, stem: str) -> tuple[str, str]:
        """The origin attributes of ``j``: from the calibration file when it is calibrated (the
        Xacro), else as values or property references."""
        key = self.calibrated.get(j.name) if self.xacro else None
        if key is not None:
            # the key is an identifier (calibration_keys): the expression holds no spec text, so
            # it is written as is (Markup), not with its quotes escaped as XML entities
            ref = f"calibration_yaml['joints']['{key}']"
            xyz = " ".join("${" + f"{ref}['{c}']" + "}" for c in ("x", "y", "z"))
            rpy = " ".join("${" + f"{ref}['{c}']" + "}" for c in ("roll", "pitch", "yaw"))
            return Markup(xyz), Markup(rpy)
        src = j.source
        xyz = self(f"{stem}_xyz", vec(j.origin.xyz), src) if j.origin.xyz != (0.0, 0.0, 0.0) else _ZERO
        rpy = self(f"{stem}_rpy", vec(j.origin.rpy), src) if j.origin.rpy != (0.0, 0.0, 0.0) else _ZERO
        return xyz, rpy

    def __call__(self, name: str, value: str, source: str | None) -> str:
        # a property is for a measurement a reviewer checks against its source (the comment
        # beside it); a value with no source is written inline, as in the URDF: properties
        # without one only made the file longer and xacro slower (each one is evaluated
        # through every later reference: 8000 properties took xacro 4 s at 1000 links)
        if not self.xacro or not source:
            return value
        return "${" + self._property(name, value, source).name + "}"

    def _property(self, stem: str, value: str, source: str | None) -> Prop:
        """The property for ``value`` named ``stem``, or ``stem_2``, ``stem_3``... when another
        value already took the name: names are built from spec names (link ``a_collision``'s
        box and link ``a``'s collision box are both ``a_collision_size``), and xacro keeps only
        the last definition of a name. The same stem and value always give the same property."""
        stem = identifier(stem)
        name, k = stem, 1
        while (existing := self._index.get(name)) is not None:
            if existing.value == value:
                return existing
            k += 1
            name = f"{stem}_{k}"
        prop = Prop(name, value, self.text(source))
        self._index[name] = prop
        self.props.append(prop)
        return prop

    def text(self, s: str | None) -> str | None:
        """Free text from the spec, in an attribute xacro evaluates."""
        if s is None:
            return None
        return xacro_text(s) if self.xacro else s


_NOT_IDENTIFIER = re.compile(r"[^A-Za-z0-9_]")


def identifier(stem: str) -> str:
    """``stem`` as a xacro property name: xacro takes only Python identifiers that do not start
    with ``__`` (xacro 2.x ``is_valid_name``), but link and joint names may hold ``-``, ``.``
    or a leading digit (``flange-tool0``, ``link_0.0``, ``2dof_planar``). Every other character
    becomes ``_`` and a name not starting with a letter gets ``p_``; names made equal this way
    are kept apart by ``Values`` (``_2``, ``_3``...)."""
    out = _NOT_IDENTIFIER.sub("_", stem)
    return out if out[:1].isalpha() else "p_" + out


_ZERO = "0 0 0"


def _geometry(g: Geometry | None, key: str, v: Values, source: str | None) -> tuple[str, tuple[tuple[str, str], ...]]:
    if isinstance(g, Box):
        return "box", (("size", v(f"{key}_size", vec(g.size), source)),)
    if isinstance(g, Cylinder):
        return "cylinder", (
            ("radius", v(f"{key}_radius", num(g.radius), source)),
            ("length", v(f"{key}_length", num(g.length), source)),
        )
    if isinstance(g, Sphere):
        return "sphere", (("radius", v(f"{key}_radius", num(g.radius), source)),)
    if isinstance(g, Mesh):
        attrs = [("filename", v.text(g.filename) or "")]
        if g.scale != (1.0, 1.0, 1.0):
            attrs.append(("scale", vec(g.scale)))
        return "mesh", tuple(attrs)
    return "box", (("size", "0 0 0"),)


def _shape_keys(prefix: str, link: Link) -> tuple[list[str], list[str]]:
    """Property name stems for each visual and collision; a collision with the same
    geometry as a visual shares its properties."""
    vis = [prefix if i == 0 else f"{prefix}_visual{i}" for i in range(len(link.visuals))]
    col = []
    for i, c in enumerate(link.collisions):
        same = next((vis[k] for k, vv in enumerate(link.visuals) if vv.geometry == c.geometry), None)
        col.append(same or (f"{prefix}_collision" if i == 0 else f"{prefix}_collision{i}"))
    return vis, col


def _shape(s: Visual | Collision, key: str, v: Values, source: str | None) -> ShapeView:
    kind, attrs = _geometry(s.geometry, key, v, source)
    material = v.text(s.material) if isinstance(s, Visual) else None
    return ShapeView(v.text(s.name), vec(s.origin.xyz), vec(s.origin.rpy), kind, attrs, material)


def _inertial(i: Inertial, key: str, v: Values, source: str | None) -> InertialView:
    tensor: tuple[tuple[str, str], ...] = ()
    if i.inertia is not None:
        t = i.inertia
        # derived (computed from mass and geometry) or typed: printed, not a property
        tensor = tuple((k, num(getattr(t, k))) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"))
    mass = v(f"{key}_mass", num(i.mass or 0.0), source)
    return InertialView(vec(i.origin.xyz), vec(i.origin.rpy), mass, tensor)


def link_view(link: Link, v: Values, name: str | None = None, key: str | None = None) -> LinkView:
    stem = key or link.name
    vis_keys, col_keys = _shape_keys(stem, link)
    src = link.source
    return LinkView(
        name or v.name(link.name),
        v.text(_comment(link.description, link.source)),
        tuple(_shape(s, k, v, src) for s, k in zip(link.visuals, vis_keys, strict=True)),
        tuple(_shape(s, k, v, src) for s, k in zip(link.collisions, col_keys, strict=True)),
        _inertial(link.inertial, stem, v, src) if link.inertial else None,
    )


def joint_view(
    j: Joint,
    v: Values,
    name: str | None = None,
    child: str | None = None,
    origin: tuple[str, str] | None = None,
    key: str | None = None,
) -> JointView:
    stem = key or j.name
    src = j.source
    xyz, rpy = v.origin(j, stem) if origin is None else origin
    limit: list[tuple[str, str]] = []
    if j.limit is not None and j.type != "fixed":
        lm = j.limit
        for attr in ("lower", "upper", "effort", "velocity"):
            value = getattr(lm, attr)
            if value is not None and not (attr in ("lower", "upper") and j.type == "continuous" and value == 0):
                limit.append((attr, v(f"{stem}_{attr}", num(value), src)))
    dynamics: tuple[tuple[str, str], ...] = ()
    if j.dynamics is not None:
        dynamics = (("damping", num(j.dynamics.damping)), ("friction", num(j.dynamics.friction)))
    mimic: tuple[tuple[str, str], ...] = ()
    if j.mimic is not None:
        mimic = (
            ("joint", v.name(j.mimic.joint)),
            ("multiplier", num(j.mimic.multiplier)),
            ("offset", num(j.mimic.offset)),
        )
    safety: tuple[tuple[str, str], ...] = ()
    if j.safety is not None:
        s = j.safety
        safety = (
            ("soft_lower_limit", num(s.soft_lower_limit)),
            ("soft_upper_limit", num(s.soft_upper_limit)),
            ("k_position", num(s.k_position)),
            ("k_velocity", num(s.k_velocity)),
        )
    axis = vec(j.axis) if j.axis is not None and j.type not in NO_AXIS else None
    comment = v.text(_comment(j.description, j.source))
    return JointView(
        name or v.name(j.name),
        j.type,
        v.name(j.parent or ""),
        child or v.name(j.child or ""),
        xyz,
        rpy,
        comment,
        axis,
        tuple(limit),
        dynamics,
        mimic,
        safety,
    )


PREFIX_ARG = "$(arg prefix)"


def prefix_arg(name: str, prefix: str) -> str:
    """``name`` with its leading ``prefix`` written as the Xacro's prefix argument (a name
    without it, such as a shared ``world``, is written as is)."""
    if not prefix or not name.startswith(prefix) or name in GLOBAL_FRAMES:  # "world" with prefix "wo"
        return name
    return PREFIX_ARG + name[len(prefix) :]


def name_writer(robot: Robot, xacro: bool) -> Callable[[str], str]:
    """How a template family writes the robot's names: the Xacro with its prefix argument."""
    prefix = robot.prefix.value if robot.prefix is not None and xacro else ""
    return lambda name: prefix_arg(name, prefix)


def calibration_keys(robot: Robot) -> dict[str, str]:
    """Joint name -> its key in the calibration files: a Python identifier (the key is written
    into a xacro expression, where a joint name could be code), made unique like properties."""
    out: dict[str, str] = {}
    taken: set[str] = set()
    for e in robot.calibration:
        stem = identifier(e.joint)
        key, k = stem, 1
        while key in taken:
            k += 1
            key = f"{stem}_{k}"
        taken.add(key)
        out[e.joint] = key
    return out


def _comment(description: str | None, source: str | None) -> str | None:
    if description and source:
        return f"{description} ({source})"
    return description or source


def items(robot: Robot, v: Values) -> tuple[list[Item], list[PartMacro]]:
    """Every link with its parent joint, in spec order; a part's instances become macro
    calls (Xacro) or are written out (URDF)."""
    out: list[Item] = []
    macros: dict[str, PartMacro] = {}
    written_joints: set[str] = set()
    for link in robot.links:
        j = robot.parent_joint(link.name)
        if link.part is not None and j is not None and j.part == link.part:
            if v.xacro and link.part not in macros:
                macros[link.part] = PartMacro(
                    link.part,
                    "link joint xyz rpy",
                    link_view(link, v, name="${link}", key=link.part),
                    joint_view(j, v, name="${joint}", child="${link}", origin=("${xyz}", "${rpy}"), key=link.part),
                    v.text(link.description),
                )
            xyz, rpy = v.origin(j, j.name)
            if xyz == _ZERO:  # a part's instance states its place, even at the parent's origin
                xyz = v(f"{j.name}_xyz", vec(j.origin.xyz), j.source)
            call = (("link", v.name(link.name)), ("joint", v.name(j.name)), ("xyz", xyz), ("rpy", rpy))
            out.append(
                Item(
                    link_view(link, v, key=link.part),
                    joint_view(j, v, key=link.part, origin=(xyz, rpy)),
                    call,
                    link.part,
                )
            )
            written_joints.add(j.name)
            continue
        jv = joint_view(j, v) if j is not None else None
        if j is not None:
            written_joints.add(j.name)
        out.append(Item(link_view(link, v), jv))
    return out, list(macros.values())


__all__ = ["Item", "PartMacro", "Pose", "Prop", "Values", "items"]
