"""Pydantic v2 models of the spec YAML: structure, names and fixed-kind quantities.

Unknown keys are errors (``extra="forbid"``). Every model is frozen. Cross-element rules
(names exist, one root, limits ordered...) are not here: they are rules over the built
model in ``descgen/audit/rules``, shared with ``descgen audit``.
"""

import datetime
import math
import re
from typing import Annotated, Any, Literal, Self

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    JsonValue,
    StringConstraints,
    WithJsonSchema,
    model_validator,
)

from descgen.spec.quantity import (
    ZERO,
    ZERO_ANGLE,
    Angle,
    AngularVelocity,
    Duration,
    Frequency,
    InertiaQ,
    JointRaw,
    Length,
    LinearAcceleration,
    LinearVelocity,
    Mass,
    Measured,
    Raw,
    Size,
    Tolerance,
    error,
)

NAME_PATTERN = r"^[A-Za-z][A-Za-z0-9_]*$"
Name = Annotated[str, StringConstraints(pattern=NAME_PATTERN, max_length=128)]
"""Names descgen or ROS turn into identifiers: the robot (package and file names), parts (Xacro
macros), controllers (ROS node names), SRDF groups, known poses, hardware params. Plain
identifiers (see docs/reference/conventions.md)."""

# Link, joint and frame names are what ROS 2 Jazzy accepts: urdfdom takes any string (unique),
# tf2 refuses an empty id and a leading '/' (validateFrameId), MoveIt's SRDF trims whitespace, so
# a name with whitespace would not be the same name there. Real robots use '-', '.', leading
# digits ('flange-tool0', 'link_0.0', '2dof_planar'); outputs escape them or derive identifiers
# from them (render/views.py). '$' is refused: the Xacro writes names where xacro evaluates '$'.
ELEMENT_NAME_PATTERN = r"^[^/$\s\x00-\x1f\x7f-\x9f][^$\s\x00-\x1f\x7f-\x9f]*$"
_NOT_IN_NAME = re.compile(
    # U+061C, the Arabic letter mark, is a bidi control too (Unicode's Bidi_Control set)
    r"[$\s\x00-\x1f\x7f-\x9f\u061c\u2028\u2029\u200b-\u200f\u202a-\u202e\u2060-\u206f\ufeff\ud800-\udfff\ufffe\uffff]"
)


def _element_name(value: str) -> str:
    hint = "use a name without spaces, '$' or control characters, not starting with '/' (e.g. elbow_joint)"
    if not value:
        raise error("SPEC050", "the name is empty", hint)
    bad = _NOT_IN_NAME.search(value)
    if bad:
        raise error(
            "SPEC050",
            f"{value!r} is not a valid name: {'whitespace' if bad.group().isspace() else 'the character'} "
            f"'{_shown(bad.group())}' at position {bad.start() + 1}",
            hint,
        )
    if value.startswith("/"):
        raise error("SPEC050", f"{value!r} is not a valid name: tf2 refuses a frame id that starts with '/'", hint)
    return value


def is_element_name(value: str) -> bool:
    """Whether ``value`` is a link, joint or frame name the spec accepts."""
    return 0 < len(value) <= 128 and not value.startswith("/") and _NOT_IN_NAME.search(value) is None


ElementName = Annotated[
    str,
    StringConstraints(max_length=128),
    AfterValidator(_element_name),
    Field(json_schema_extra={"pattern": ELEMENT_NAME_PATTERN}),
]
"""Link, joint and frame names, and every reference to one."""

# Spec text reaches XML, Python, YAML, Markdown, Mermaid and DOT outputs. Templates escape
# it for each; what no escaping can carry is refused here, so that validate accepts nothing
# generate refuses: characters XML cannot hold at all (Text), and in one-line fields any
# line break or control character (an XML attribute would read it back as a space).
_NOT_XML = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\ud800-\udfff\ufffe\uffff]")
_NOT_ONE_LINE = re.compile(r"[\x00-\x1f\x7f-\x9f\u2028\u2029\ud800-\udfff\ufffe\uffff]")


def _shown(ch: str) -> str:
    return repr(ch)[1:-1] if ch.isascii() else f"U+{ord(ch):04X}"


def _text(value: str) -> str:
    bad = _NOT_XML.search(value)
    if bad:
        raise error(
            "SPEC020",
            f"text contains the control character {_shown(bad.group())} at position {bad.start() + 1}",
            "remove it: XML (URDF, SRDF, package.xml) cannot hold control characters",
        )
    return value


def _one_line(value: object) -> object:
    if isinstance(value, str):
        bad = _NOT_ONE_LINE.search(value)
        if bad:
            raise error(
                "SPEC021",
                f"this value is one line of text, but it contains {_shown(bad.group())} at position {bad.start() + 1}",
                "write it on one line without tabs or control characters "
                "(an XML attribute reads a line break back as a space)",
            )
    return value


Text = Annotated[str, StringConstraints(max_length=4000), AfterValidator(_text)]
OneLine = Annotated[str, BeforeValidator(_one_line)]
"""Free text that is one line: names of visuals and materials, file names, citations."""
Source = Annotated[
    str,
    BeforeValidator(lambda v: str(v) if isinstance(v, int) else v),
    StringConstraints(max_length=200),
    BeforeValidator(_one_line),
]

_AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def _axis(value: object) -> object:
    if isinstance(value, str):
        text = value.strip().lower()
        sign = -1.0 if text.startswith("-") else 1.0
        key = text.lstrip("+-")
        if key in _AXES:
            return tuple(sign * c + 0.0 for c in _AXES[key])
        raise error("SPEC003", f"axis '{value}' is not one of +x, -x, +y, -y, +z, -z", "write e.g. +y or [0, 1, 0]")
    if isinstance(value, list | tuple):
        parts = [_yaml11_float(c) for c in value]
        if any(isinstance(c, str) for c in parts):
            raise error(
                "SPEC003", "axis components are plain numbers (a direction has no unit)", "write e.g. [0, 1, 0]"
            )
        return parts
    return value


def _yaml11_float(value: object) -> object:
    """PyYAML (YAML 1.1) reads ``1e-3`` as text; accept it as the number it means."""
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return value
    return value


def _finite(value: object) -> object:
    value = _yaml11_float(value)
    if isinstance(value, float) and not math.isfinite(value):
        raise error("SPEC003", "not a finite number", "write a finite number")
    return value


Number = Annotated[float, BeforeValidator(_finite)]
Axis = Annotated[
    tuple[Number, Number, Number],
    BeforeValidator(_axis),
    WithJsonSchema(
        {
            "anyOf": [
                {"type": "string", "enum": ["+x", "-x", "+y", "-y", "+z", "-z", "x", "y", "z"]},
                {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3},
            ]
        }
    ),
]


def _one_or_many(value: object) -> object:
    return [value] if isinstance(value, dict) else value


class Base(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, defer_build=True)


class Origin(Base):
    """Pose of a child frame in its parent: xyz, then roll-pitch-yaw about the fixed axes."""

    xyz: tuple[Length, Length, Length] = (ZERO, ZERO, ZERO)
    """Position of the child frame in the parent frame: three lengths x, y, z (e.g. `[0, 0, 75 mm]`; a bare `0` needs
    no unit). Default `[0, 0, 0]`; each a plausible offset (UNIT004, `plausibility.offset`)."""
    rpy: tuple[Angle, Angle, Angle] = (ZERO_ANGLE, ZERO_ANGLE, ZERO_ANGLE)
    """Rotation of the child frame: roll, pitch, yaw angles about the parent's fixed x, y, z axes, applied in that
    order (e.g. `[90 deg, 0, 0]`). Default `[0, 0, 0]`; each a plausible angle (UNIT004)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class BoxSpec(Base):
    size: tuple[Size, Size, Size]
    """Side lengths along the shape's x, y, z, three lengths (e.g. `[600 mm, 450 mm, 200 mm]`); the box is centred on
    its origin. Each a plausible size (UNIT004, `plausibility.size`; UNIT012)."""


class _Round(Base):
    radius: Size | None = None
    """Radius, a length (e.g. `30 mm`); give exactly one of `radius` and `diameter` (SPEC004). A plausible size
    (UNIT004, `plausibility.size`)."""
    diameter: Size | None = None
    """Diameter, a length (e.g. `60 mm`), instead of `radius` (exactly one of them, SPEC004); the URDF gets half of it.
    A plausible size (UNIT004)."""

    @model_validator(mode="after")
    def _one_size(self) -> Self:
        if (self.radius is None) == (self.diameter is None):
            raise error("SPEC004", "give exactly one of radius and diameter", "keep the one you measured")
        return self

    @property
    def r(self) -> float:
        if self.radius is not None:
            return float(self.radius.si)
        assert self.diameter is not None  # guaranteed by _one_size
        return float(self.diameter.si) / 2


class CylinderSpec(_Round):
    length: Size
    """Length along the cylinder's own z axis, a length (e.g. `100 mm`); the cylinder is centred on its origin. A
    plausible size (UNIT004; UNIT012)."""


class SphereSpec(_Round):
    pass


class MeshSpec(Base):
    """A mesh file. ``size`` is what you measured of the part (the scaled mesh's bounding box
    extents along the mesh's x, y, z); the file is checked against it within ``tolerance``
    (default 1 mm), so a mesh exported in millimetres or inches is caught (GEOM030)."""

    filename: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)]
    """The mesh file: `package://<package>/<path>` (found through `package_paths`, `--package-path` or the sourced
    workspace) or a path relative to the spec, which generate copies into the package. A file that cannot be found
    or used is SPEC060-SPEC063; STL, OBJ and COLLADA files are measured."""
    scale: tuple[Number, Number, Number] = (1.0, 1.0, 1.0)
    """Scale factors along the mesh's x, y, z, plain numbers; default `[1, 1, 1]` (`[0.001, 0.001, 0.001]` for a file
    in millimetres). A factor other than 1 or 0.001 is flagged (UNIT013)."""
    size: tuple[Size, Size, Size] | None = None
    """The part's measured size: the scaled mesh's bounding-box extents along the mesh's x, y, z, three lengths (e.g.
    `[100 mm, 200 mm, 300 mm]`). When given, the file is checked against it within `tolerance` (GEOM030), which
    catches a mesh exported in millimetres or inches."""
    tolerance: Tolerance | None = None
    """How far each extent of the scaled mesh may differ from `size`, a length; default `1 mm` (GEOM030)."""


class GeometrySpec(Base):
    box: BoxSpec | None = None
    """A box (`size`). A geometry is exactly one of box, cylinder, sphere and mesh (SPEC004)."""
    cylinder: CylinderSpec | None = None
    """A cylinder along its own z axis (`radius` or `diameter`, and `length`); exactly one shape per geometry
    (SPEC004)."""
    sphere: SphereSpec | None = None
    """A sphere (`radius` or `diameter`); exactly one shape per geometry (SPEC004)."""
    mesh: MeshSpec | None = None
    """A mesh file (`filename`, optional `scale` and measured `size`); exactly one shape per geometry (SPEC004)."""

    @model_validator(mode="after")
    def _exactly_one(self) -> Self:
        given = [k for k in ("box", "cylinder", "sphere", "mesh") if getattr(self, k) is not None]
        if len(given) != 1:
            raise error(
                "SPEC004",
                "a geometry is exactly one of box, cylinder, sphere, mesh",
                "keep one shape per visual or collision; add another entry for more",
            )
        return self


class MaterialSpec(Base):
    name: Annotated[OneLine, StringConstraints(min_length=1, max_length=200)]
    """The material's name, which visuals name in `material:`; each name once in `materials` (SPEC026)."""
    rgba: tuple[Number, Number, Number, Number] | None = None
    """Colour as red, green, blue, alpha: plain numbers from 0 to 1 (divide 0-255 values by 255; SPEC003). A material
    needs `rgba` or `texture` (SPEC004)."""
    texture: Annotated[OneLine, StringConstraints(max_length=1000)] | None = None
    """An image file name, written as the URDF's `<texture filename>`. A material needs `rgba` or `texture`
    (SPEC004)."""

    @model_validator(mode="after")
    def _colour(self) -> Self:
        if self.rgba is None and self.texture is None:
            raise error(
                "SPEC004",
                f"material '{self.name}' needs rgba or texture",
                "write rgba: [r, g, b, a] with values 0 to 1",
            )
        if self.rgba is not None and not all(0.0 <= c <= 1.0 for c in self.rgba):
            raise error("SPEC003", "rgba components are between 0 and 1", "divide 0-255 values by 255")
        return self


class VisualSpec(Base):
    name: Annotated[OneLine, StringConstraints(max_length=200)] | None = None
    """Optional name of the visual (the URDF's `<visual name>`)."""
    origin: Origin = Origin()
    """Pose of the shape in the link frame (`xyz`, `rpy`); default the link frame itself."""
    geometry: GeometrySpec
    """The shape: exactly one of box, cylinder, sphere, mesh (SPEC004)."""
    material: Annotated[OneLine, StringConstraints(min_length=1, max_length=200)] | None = None
    """The name of a material declared under the robot's `materials:` (written as `<material name>`)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class CollisionSpec(Base):
    name: Annotated[OneLine, StringConstraints(max_length=200)] | None = None
    """Optional name of the collision shape (the URDF's `<collision name>`)."""
    origin: Origin = Origin()
    """Pose of the shape in the link frame (`xyz`, `rpy`); default the link frame itself."""
    geometry: GeometrySpec
    """The shape collisions are checked with (often simpler than the visual): exactly one of box, cylinder, sphere,
    mesh (SPEC004). Its volume is compared with the visual's (GEOM002)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class InertiaSpec(Base):
    ixx: InertiaQ
    """Moment of inertia about the x axis through the centre of mass (in the inertial origin's axes), an inertia (e.g.
    `0.01 kg*m^2`). The tensor must be positive definite (INER003), meet the triangle inequality (INER004) and suit
    the mass and size (INER006, INER011)."""
    iyy: InertiaQ
    """Moment of inertia about the y axis through the centre of mass, an inertia (e.g. `0.01 kg*m^2`); checked with the
    tensor (INER003, INER004, INER006, INER011)."""
    izz: InertiaQ
    """Moment of inertia about the z axis through the centre of mass, an inertia (e.g. `0.01 kg*m^2`); checked with the
    tensor (INER003, INER004, INER006, INER011)."""
    ixy: InertiaQ = ZERO
    """Product of inertia xy about the centre of mass, an inertia (e.g. `0.001 kg*m^2`); default 0."""
    ixz: InertiaQ = ZERO
    """Product of inertia xz about the centre of mass, an inertia (e.g. `0.001 kg*m^2`); default 0."""
    iyz: InertiaQ = ZERO
    """Product of inertia yz about the centre of mass, an inertia (e.g. `0.001 kg*m^2`); default 0."""


class InertialSpec(Base):
    """Mass, centre of mass, and either a tensor or ``from: collision|visual``.

    With ``from``, the tensor is that of the first collision (or visual) primitive of
    uniform density, about its own centroid, rotated into the link frame. The centre of
    mass is ``origin.xyz`` when given, else the primitive's centre.
    """

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)

    mass: Mass
    """The link's mass (e.g. `1200 g`, `28 kg`), a plausible mass (UNIT004, `plausibility.mass`). Zero on a moving link
    is INER001; mass over collision volume must be a plausible density (UNIT010)."""
    origin: Origin | None = None
    """The centre of mass in the link frame (`xyz`) and, with `inertia`, the orientation of the tensor's axes (`rpy`).
    With `from` only `xyz` is used, default the shape's centre. Far outside the collision shapes: INER005."""
    inertia: InertiaSpec | None = None
    """The inertia tensor about the centre of mass (`ixx`, `iyy`, `izz`; products default 0), in `kg*m^2`. Give exactly
    one of `inertia` and `from` (SPEC004)."""
    from_: Literal["collision", "visual"] | None = Field(default=None, alias="from")
    """`collision` or `visual`: the tensor of the link's first collision (or visual) shape at uniform density, about
    its centroid, in link axes. Exactly one of `inertia` and `from` (SPEC004); no such shape is INER010, a mesh must
    be watertight (INER030)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""

    @model_validator(mode="after")
    def _tensor(self) -> Self:
        if (self.inertia is None) == (self.from_ is None):
            raise error(
                "SPEC004",
                "give exactly one of inertia and from",
                "write inertia: {ixx: ..., iyy: ..., izz: ...} or from: collision",
            )
        return self


class LinkBody(Base):
    visual: Annotated[list[VisualSpec], BeforeValidator(_one_or_many)] = []
    """What the link looks like: one visual or a list, each a shape with its origin and material."""
    collision: Annotated[list[CollisionSpec], BeforeValidator(_one_or_many)] = []
    """The link's collision shapes, one or a list. A moving link with visuals but no collision shape is GEOM001."""
    inertial: InertialSpec | None = None
    """Mass, centre of mass and inertia tensor. A link with geometry that a moving joint carries needs one, on itself
    or on a link welded to it (INER002)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""
    description: Text | None = None
    """A note about the link, written as a comment above it in the URDF and Xacro (with its sources)."""


class LinkSpec(LinkBody):
    name: ElementName
    """The link's name, its tf frame id: unique (NAME001), without spaces, `$` or a leading `/` (SPEC050)."""


class LimitSpec(Base):
    """Units follow the joint type: angles or lengths, N*m or N, rad/s or m/s."""

    lower: Raw | None = None
    """Lowest position: an angle for a revolute joint (e.g. `-170 deg`), a length for a prismatic one (e.g. `0 mm`).
    Revolute and prismatic joints need `lower` and `upper` (JOINT003), `lower` <= `upper` (JOINT004); a continuous
    joint takes neither (JOINT006)."""
    upper: Raw | None = None
    """Highest position: an angle for a revolute joint (e.g. `170 deg`), a length for a prismatic one (e.g. `300 mm`);
    needed with `lower` (JOINT003), not below it (JOINT004)."""
    effort: Raw
    """Largest effort: a torque for revolute and continuous joints (e.g. `40 N*m`), a force for prismatic ones (e.g.
    `500 N`). Positive (JOINT005) and enough to hold the joint against gravity (JOINT008)."""
    velocity: Raw
    """Largest speed: an angular velocity for revolute and continuous joints (e.g. `90 deg/s`, `30 rpm`), a linear one
    for prismatic joints (e.g. `0.1 m/s`). Positive (JOINT005); MoveIt needs it (SPEC111)."""
    acceleration: Raw | None = None
    """Largest acceleration, for MoveIt's joint_limits.yaml (the URDF has no such attribute): e.g. `360 deg/s^2`, or
    `0.2 m/s^2` for a prismatic joint. Required on planning-group joints with `moveit:` (SPEC110), positive
    (SPEC116)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class DynamicsSpec(Base):
    damping: Raw | None = None
    """Viscous damping (the URDF's `<dynamics damping>`): `N*m*s/rad` for revolute and continuous joints (e.g.
    `0.5 N*m*s/rad`), `N*s/m` for prismatic ones. Default 0."""
    friction: Raw | None = None
    """Static friction (the URDF's `<dynamics friction>`): a torque for revolute and continuous joints (e.g.
    `0.2 N*m`), a force for prismatic ones (e.g. `5 N`). Default 0."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class MimicSpec(Base):
    joint: ElementName
    """The leader joint this joint follows, `q = multiplier * q_leader + offset`: an existing joint, not this one and
    not itself a mimic (JOINT007)."""
    multiplier: Number = 1.0
    """Factor on the leader's position, a plain number; default 1."""
    offset: Raw | None = None
    """Added to `multiplier * q_leader`, in this joint's unit (an angle, or a length for a prismatic joint, e.g.
    `10 deg`); default 0."""


class SafetySpec(Base):
    soft_lower_limit: Raw | None = None
    """Lower position where the safety controller starts limiting, in the joint's unit (an angle, or a length for a
    prismatic joint); default 0. Written to the URDF's `<safety_controller>`."""
    soft_upper_limit: Raw | None = None
    """Upper position where the safety controller starts limiting, in the joint's unit (an angle, or a length for a
    prismatic joint); default 0."""
    k_position: Raw | None = None
    """Position gain of the safety controller, in `1/s` (e.g. `100 1/s`); default 0."""
    k_velocity: Raw
    """Velocity gain of the safety controller (required): `N*m*s/rad` for revolute joints (e.g. `10 N*m*s/rad`),
    `N*s/m` for prismatic ones."""


JointType = Literal["fixed", "revolute", "continuous", "prismatic", "floating", "planar"]


class JointBody(Base):
    type: JointType
    """`fixed`, `revolute` (rotation within limits), `continuous` (unlimited rotation), `prismatic` (sliding),
    `floating` or `planar`; robot_state_publisher does not move the last two in tf (FRAME003)."""
    parent: ElementName
    """Name of the parent link (TOPO004 when it does not exist)."""
    axis: Axis | None = None
    """Axis of rotation or translation in the joint frame: `+x`, `-x`, `+y`, `-y`, `+z`, `-z` or three plain numbers
    (e.g. `[0, 1, 0]`), non-zero and of length 1 (JOINT001, JOINT002). Default `+x` (URDF's); ignored on fixed and
    floating joints."""
    limit: LimitSpec | None = None
    """Position, effort and velocity limits (and MoveIt's acceleration), in the units of the joint type. Revolute and
    prismatic joints need one (JOINT003)."""
    dynamics: DynamicsSpec | None = None
    """Damping and friction for simulators (the URDF's `<dynamics>`)."""
    mimic: MimicSpec | None = None
    """Makes this joint follow another: `q = multiplier * q_leader + offset` (JOINT007; known poses: POSE020)."""
    safety_controller: SafetySpec | None = None
    """Soft limits and gains of the URDF's `<safety_controller>`."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""
    description: Text | None = None
    """A note about the joint, written as a comment above it in the URDF and Xacro (with its sources)."""


class JointSpec(JointBody):
    name: ElementName
    """The joint's name: unique (NAME002); a moving joint's name is best a plain identifier (NAME003)."""
    child: ElementName
    """Name of the child link, which the joint moves; a link has one parent joint (TOPO002)."""
    origin: Origin = Origin()
    """Pose of the joint frame, which is the child link's frame, in the parent link's frame at joint position zero. An
    offset far beyond the robot's size is UNIT011."""


class PartInstance(Base):
    link: ElementName
    """Name of this copy's link (e.g. `left_wheel_link`)."""
    joint: ElementName
    """Name of this copy's joint (e.g. `left_wheel_joint`)."""
    origin: Origin = Origin()
    """Pose of this copy's joint in the parent link of the part's joint (e.g. `{xyz: [0, 225 mm, 0]}`)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


# The Xacro writes a part as <xacro:macro name="PART">, called as <xacro:PART .../>: a part
# named like one of xacro's own tags would be read as that tag (xacro 2.x, process_doc).
XACRO_TAGS = frozenset(
    ("arg", "attribute", "call", "element", "if", "include", "insert_block", "macro", "property", "unless")
)


def _not_xacro_tag(name: str) -> str:
    if name in XACRO_TAGS:
        raise error(
            "SPEC022",
            f"part name '{name}' is a xacro tag; <xacro:{name}> would not call the part's macro",
            f"rename the part (e.g. {name}_part)",
        )
    return name


class PartSpec(Base):
    """A part built more than once (left/right wheel, fingers): declared once, instanced
    with per-instance names and origin. The Xacro output makes it one macro."""

    name: Annotated[Name, AfterValidator(_not_xacro_tag)]
    """The part's name, an identifier (the Xacro macro's name); not a xacro tag such as `macro` (SPEC022)."""
    link: LinkBody = LinkBody()
    """The link body every copy gets: visuals, collisions, inertial. Default: a link without geometry."""
    joint: JointBody
    """The joint body every copy gets: type, parent, axis, limits; each instance gives the names and the origin."""
    instances: Annotated[list[PartInstance], Field(min_length=1)]
    """The copies, each with its own link and joint names and origin; at least one."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""
    description: Text | None = None
    """A note about the part for readers of the spec (the outputs carry the link's and the joint's own
    `description`)."""


class SensorSpec(Base):
    """A sensor frame ``<name>_link`` on a fixed joint ``<name>_joint``. A camera also gets
    ``<name>_optical_frame`` (z forward, x right, y down; REP 103)."""

    name: ElementName
    """The sensor's name: its frame is `<name>_link`, on the fixed joint `<name>_joint`."""
    type: Literal["camera", "lidar", "imu", "generic"]
    """`camera`, `lidar`, `imu` or `generic`. A camera also gets `<name>_optical_frame`, turned by the REP 103 rotation
    (z forward, x right, y down)."""
    parent: ElementName
    """Name of the link the sensor is mounted on."""
    origin: Origin = Origin()
    """Pose of the sensor frame (e.g. its optical centre) in the parent link; default the parent's frame."""
    link: LinkBody = LinkBody()
    """Body of the sensor link: its housing's visuals, collisions and inertial. Default: a frame without geometry."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""
    description: Text | None = None
    """A note about the sensor, written as a comment above its joint in the URDF and Xacro."""


class InterfaceLimitSpec(Base):
    min: Raw | None = None
    max: Raw | None = None


INTERFACE_PATTERN = r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z0-9_]+)*$"
InterfaceName = Annotated[str, StringConstraints(pattern=INTERFACE_PATTERN, max_length=128)]


JointInterfaceName = Literal["position", "velocity", "acceleration", "effort"]
# interfaces whose params have a unit descgen knows per joint type (acceleration: name only)
ParamInterfaceName = Literal["position", "velocity", "effort"]
DataType = Literal["double", "bool", "float32", "uint8", "int8", "uint16", "int16", "uint32", "int32"]


class JointCommandSpec(Base):
    """A joint command interface with its ros2_control params. ``min``/``max`` (in the units of
    the joint and interface: ``90 deg/s``, ``20 N``) replace the ones taken from the joint limits;
    ros2_control reads them only on command interfaces (hardware_interface component_parser.cpp)."""

    name: ParamInterfaceName
    """`position`, `velocity` or `effort`: the command interface these limits are for."""
    data_type: DataType | None = None
    """The interface's ros2_control `data_type`: `double` (ros2_control's default, when left out), `bool`, `float32`,
    or an integer type (`uint8` ... `int32`)."""
    min: Raw | None = None
    """Lowest command, in the units of the joint and interface (e.g. `-90 deg/s`, `-20 N`). Default: from the joint's
    limits (`lower`, or minus the velocity or effort limit); never wider than them (CTRL008)."""
    max: Raw | None = None
    """Highest command, in the units of the joint and interface (e.g. `90 deg/s`, `20 N`). Default: from the joint's
    limits (`upper`, or the velocity or effort limit); never wider than them (CTRL008)."""


class JointStateSpec(Base):
    """A joint state interface; ``initial_value`` in the joint's units (``position`` may use the
    joint's ``initial_position`` instead, not both)."""

    name: ParamInterfaceName
    """`position`, `velocity` or `effort`: the state interface."""
    data_type: DataType | None = None
    """The interface's ros2_control `data_type`: `double` (ros2_control's default, when left out), `bool`, `float32`,
    or an integer type (`uint8` ... `int32`)."""
    initial_value: Raw | None = None
    """The value the state starts at, in the units of the joint and interface (e.g. `150 mm`). Default 0 (a position
    outside its limits at 0: the middle of them); for `position`, not together with the joint's `initial_position`
    (CTRL080)."""


Plugin = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_/:]+$")]
# a ros2_control <param name="...">: the parser takes any string; drivers use spaces and dots
# ("Goal Velocity" of a Dynamixel gpio). Nothing markup or xacro could read: no quote, <, & or $
PARAM_NAME_PATTERN = r"^[A-Za-z0-9_][A-Za-z0-9_ ./()-]*$"
ParamName = Annotated[str, StringConstraints(pattern=PARAM_NAME_PATTERN, max_length=128)]
HwParams = dict[ParamName, Annotated[str | int | float | bool, BeforeValidator(_one_line)]]
# a <gpio name>: any identifier, a digit first too (franka's gpios are 0, 1, ...)
GPIO_NAME_PATTERN = r"^[A-Za-z0-9_][A-Za-z0-9_]*$"
GpioName = Annotated[str, StringConstraints(pattern=GPIO_NAME_PATTERN, max_length=128)]


class ControlJointSpec(Base):
    """A ros2_control ``<joint>``. Its interfaces are the standard ones (whose min, max and
    initial values have the joint's units) or any other name the hardware exports (a leg's
    ``kp``/``kd`` gains: Jazzy's parser takes any name); ``params`` are ``<param>``s of the
    joint itself, kept as written (e.g. a driver's per-joint id)."""

    name: ElementName
    """Name of a moving URDF joint (CTRL001), listed once (CTRL005) and in one block only (SPEC085)."""
    command: list[JointInterfaceName | JointCommandSpec | InterfaceName] = []
    """Command interfaces: `position`, `velocity`, `acceleration`, `effort`, `{name, min, max}`, or any name the
    hardware exports (a leg's `kp`). Controllers can claim only these (CTRL002); a mimic joint has none (CTRL040)."""
    state: list[JointInterfaceName | JointStateSpec | InterfaceName] = []
    """State interfaces, e.g. `[position, velocity]`: names or `{name, initial_value}`. A moving joint's /joint_states
    come from its position state (FRAME002)."""
    initial_position: Raw | None = None
    """Start value of the position state, in the joint's unit (e.g. `150 mm`, `-90 deg`). Default 0, or the middle of
    the limits when 0 is outside them; not together with the position state's `initial_value` (CTRL080)."""
    on_limit: Literal["reject", "clip"] = "reject"
    """What `descgen control` does with a command beyond the joint's limits: `reject` it (default; CTRL012) or `clip`
    it to the limit."""
    mimic: bool | None = None
    """Jazzy's `<joint mimic>`: unset, a URDF `<mimic>` joint is a mimic joint (state from its leader, no command
    interface); `false` makes it an ordinary joint; `true` needs a URDF `<mimic>` (CTRL041)."""
    params: HwParams = {}
    """The joint's own `<param>`s (e.g. a driver's per-joint id), written as given; pre-Jazzy `initial_<interface>`
    params are flagged (CTRL046)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


MOCK_PLUGIN = "mock_components/GenericSystem"
GZ_PLUGIN = "gz_ros2_control/GazeboSimSystem"
MUJOCO_PLUGIN = "mujoco_ros2_control/MujocoSystemInterface"  # docs/mujoco_ros2_control.md


class HardwareVariantSpec(Base):
    """The ``<hardware>`` of one value of the Xacro argument ``hardware`` (gazebo or real)."""

    plugin: Plugin | None = None
    """The variant's hardware plugin: for `gazebo`, `gz_ros2_control/GazeboSimSystem` (the default and the only one
    Jazzy has, SPEC081); for `real`, the vendor's driver plugin, required (SPEC082)."""
    params: HwParams = {}
    """The variant's hardware `<param>`s (e.g. `device: /dev/ttyACM0`), written as given."""


class HardwareSpec(Base):
    """``plugin``/``params`` are the default hardware. With ``variants``, they are the ``mock``
    variant and the generated Xacro takes ``hardware:=mock|gazebo|real`` (default mock)."""

    plugin: Plugin = MOCK_PLUGIN
    """The hardware plugin, `package/Class`; default `mock_components/GenericSystem`, which `variants` require as the
    mock variant (SPEC080). Jazzy has no `fake_components` (CTRL045)."""
    params: HwParams = {}
    """Hardware `<param>`s (e.g. `device: /dev/ttyACM0`), written as given; GenericSystem params renamed before Jazzy
    are flagged (CTRL046)."""
    variants: dict[Literal["gazebo", "real", "mujoco"], HardwareVariantSpec] = {}
    """Other hardware under `gazebo`, `real` and `mujoco`: the generated Xacro then takes
    `hardware:=mock|gazebo|real|mujoco` (default mock). `mujoco` is mujoco_ros2_control with the MJCF model
    generate writes (mujoco/<robot>.xml; docs/mujoco_ros2_control.md)."""
    group: Name | None = None
    """`<hardware><group>`: hardware components of one group are read and written together (Jazzy's resource
    manager); unset: not written."""

    @model_validator(mode="after")
    def _variants_known(self) -> Self:
        if self.variants and self.plugin != MOCK_PLUGIN:
            raise error(
                "SPEC080",
                f"with variants, hardware.plugin is the mock variant, but it is '{self.plugin}'",
                f"write plugin: {MOCK_PLUGIN} and put the vendor plugin under variants.real",
            )
        gz = self.variants.get("gazebo")
        if gz is not None and gz.plugin not in (None, GZ_PLUGIN):
            raise error(
                "SPEC081",
                f"variants.gazebo.plugin is '{gz.plugin}', but Jazzy simulates with {GZ_PLUGIN}",
                f"leave plugin out or write {GZ_PLUGIN} (gazebo_ros2_control is Gazebo Classic, not in Jazzy)",
            )
        mj = self.variants.get("mujoco")
        if mj is not None and (mj.plugin not in (None, MUJOCO_PLUGIN) or "mujoco_model" in mj.params):
            raise error(
                "SPEC149",
                f"variants.mujoco is {mj.plugin or MUJOCO_PLUGIN} with params {sorted(mj.params)}: Jazzy's "
                f"mujoco_ros2_control is {MUJOCO_PLUGIN}, and generate gives it mujoco_model",
                f"leave plugin and mujoco_model out (write {MUJOCO_PLUGIN} if at all)",
            )
        real = self.variants.get("real")
        stand_ins = ("mock_components", "gz_ros2_control")
        if real is not None and (real.plugin is None or real.plugin.split("/")[0] in stand_ins):
            raise error(
                "SPEC082",
                f"variants.real.plugin is {repr(real.plugin) if real.plugin else 'missing'}: "
                "the real variant names the vendor's hardware plugin",
                "write the driver's plugin, e.g. plugin: my_robot_driver/MyRobotSystem",
            )
        return self


ParamValue = Any


class CalibratedSpec(Base):
    """A value measured on the robot (odometry calibration), with its source; checked
    against the URDF-derived value within ``tolerance`` (default 5 mm; CTRL006/CTRL051)."""

    value: Size
    """The value measured on the robot (odometry calibration), a length (e.g. `412 mm`); written to the controllers
    file instead of the URDF-derived value."""
    source: Source
    """Where the measurement comes from (required), e.g. `C07`."""
    tolerance: Tolerance | None = None
    """How far `value` may be from the URDF-derived value, a length; default `5 mm`. Beyond it: CTRL051 (warning); a
    unit slip is CTRL006."""


CALIBRATABLE = {"diff_drive_controller/DiffDriveController": ("wheel_separation", "wheel_radius")}


class ControllerSpec(Base):
    name: Name
    """The controller's name (its ROS node and its key in ros2_controllers.yaml), an identifier."""
    type: Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_]+/[A-Za-z0-9_]+$")]
    """The controller plugin, `package/Class` (e.g. `joint_trajectory_controller/JointTrajectoryController`); the
    interfaces an unknown type claims are not checked (CTRL049)."""
    params: dict[str, ParamValue] = {}
    """The controller's `ros__parameters`, checked against Jazzy's definition of its type (CTRL060-CTRL065; joint
    names: CTRL009). Text with a number and a unit (`500 ms`, `90 deg/s`) is written in SI."""
    calibrated: dict[str, CalibratedSpec] = {}
    """A diff_drive_controller's `wheel_separation` or `wheel_radius` measured on the robot (CTRL048), compared with
    the URDF's (CTRL006, CTRL051). Left out: the URDF-derived value is written."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""

    @model_validator(mode="after")
    def _calibrated_known(self) -> Self:
        allowed = CALIBRATABLE.get(self.type, ())
        for key in self.calibrated:
            if key not in allowed:
                raise error(
                    "CTRL048",
                    f"calibrated: '{key}' is not a calibratable parameter of {self.type}",
                    "calibrated: takes wheel_separation and wheel_radius of diff_drive_controller/DiffDriveController",
                )
            if key in self.params:
                raise error(
                    "CTRL048",
                    f"'{key}' is both in params and in calibrated",
                    f"keep only calibrated.{key} (the value written to the controllers file)",
                )
        return self


class InterfaceSpec(Base):
    """A sensor or gpio interface with its ros2_control parameters (data_type, initial_value,
    min, max: plain numbers, as ros2_control parses them)."""

    name: InterfaceName
    """The interface's name (e.g. `orientation.x`)."""
    data_type: DataType | None = None
    """The interface's ros2_control `data_type`: `double` (ros2_control's default, when left out), `bool`, `float32`,
    or an integer type (`uint8` ... `int32`)."""
    initial_value: Number | None = None
    """The value the interface starts at, a plain number (as ros2_control parses it)."""
    min: Number | None = None
    """The interface's `min` param, a plain number."""
    max: Number | None = None
    """The interface's `max` param, a plain number."""


Iface = InterfaceName | InterfaceSpec
# a <gpio>'s interfaces are a driver's own registers: Dynamixel's "Goal Position" (ROBOTIS's
# open_manipulator); any such name, without quote, <, & or $
GPIO_INTERFACE_PATTERN = r"^[A-Za-z0-9_][A-Za-z0-9_ .()-]*$"
GpioInterfaceName = Annotated[str, StringConstraints(pattern=GPIO_INTERFACE_PATTERN, max_length=128)]


class GpioInterfaceSpec(InterfaceSpec):
    name: GpioInterfaceName
    """The interface's name as the driver exports it; spaces, dots and brackets allowed (e.g. `Goal Position`)."""


GpioIface = GpioInterfaceName | GpioInterfaceSpec


class ControlSensorSpec(Base):
    """A ros2_control ``<sensor>``. ``kind: imu`` / ``force_torque`` fill ``state`` with the
    interfaces the IMU / force-torque broadcasters read when it is left empty."""

    name: Name
    """The sensor component's name (its interfaces are `<name>/<interface>`); unique among the block's joints, sensors
    and gpios (SPEC084)."""
    kind: Literal["imu", "force_torque", "generic"] = "generic"
    """`imu`, `force_torque` or `generic` (default). With `state` empty, `imu` and `force_torque` get the interfaces
    the IMU or force-torque broadcaster reads."""
    frame: ElementName | None = None
    """The link the sensor measures in (SPEC083), written as its `frame_id` param unless `params` gives one."""
    state: list[Iface] = []
    """State interfaces: names or `{name, data_type, initial_value, min, max}`, each once (SPEC084)."""
    params: HwParams = {}
    """The sensor's `<param>`s, written as given."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class GpioSpec(Base):
    name: GpioName
    """The gpio component's name (a leading digit is allowed, e.g. `0`); unique among the block's joints, sensors and
    gpios (SPEC084)."""
    command: list[GpioIface] = []
    """Command interfaces: the driver's names (e.g. `Goal Position`) or `{name, data_type, initial_value, min, max}`,
    each once (SPEC084)."""
    state: list[GpioIface] = []
    """State interfaces: the driver's names or `{name, data_type, initial_value, min, max}`, each once (SPEC084)."""
    params: HwParams = {}
    """The gpio's `<param>`s (e.g. an index), written as given."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class Ros2ControlBlockSpec(Base):
    """One more ``<ros2_control>`` block (one hardware component, e.g. a gripper on its own bus);
    its joints, sensors and gpios belong to no other block."""

    name: Name
    """The hardware component's name (`<ros2_control name>`), unique across blocks (SPEC086)."""
    type: Literal["system", "actuator", "sensor"] = "system"
    """`system` (default), `actuator` or `sensor`. A sensor has no command interfaces (SPEC087); the mock and Gazebo
    plugins need `system` (SPEC088)."""
    is_async: bool | None = None
    """`<ros2_control is_async>`: true runs the component in its own thread. Unset: not written (Jazzy's default,
    false)."""
    rw_rate: Frequency | None = None
    """`<ros2_control rw_rate>`: how often the component is read and written, a whole number of Hz (e.g. `50 Hz`);
    unset, or above the controller manager's rate, it runs at that rate (SPEC146, CTRL067)."""
    thread_priority: Annotated[int, Field(ge=1)] | None = None
    """`<ros2_control thread_priority>`: the priority of an async component's thread (Jazzy's default 50); read
    only when `is_async` is true (SPEC147)."""
    hardware: HardwareSpec = HardwareSpec()
    """The block's hardware plugin and params, with the same `variants` as the first block (SPEC089)."""
    joints: list[ControlJointSpec] = []
    """The joints this component drives, each in no other block (SPEC085)."""
    sensors: list[ControlSensorSpec] = []
    """The component's sensors (`<sensor>`)."""
    gpios: list[GpioSpec] = []
    """The component's gpios (`<gpio>`), e.g. a gripper's digital outputs."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class Ros2ControlSpec(Base):
    """The first ``<ros2_control>`` block, the controller manager's rate and the controllers;
    ``blocks`` lists further hardware components (written after the first)."""

    name: Name
    """The first hardware component's name (`<ros2_control name>`, e.g. `WarehouseArmSystem`), unique across blocks
    (SPEC086)."""
    type: Literal["system", "actuator", "sensor"] = "system"
    """`system` (default), `actuator` or `sensor`. A sensor has no command interfaces (SPEC087); the mock and Gazebo
    plugins need `system` (SPEC088)."""
    is_async: bool | None = None
    """`<ros2_control is_async>`: true runs the component in its own thread. Unset: not written (Jazzy's default,
    false)."""
    rw_rate: Frequency | None = None
    """`<ros2_control rw_rate>`: how often the component is read and written, a whole number of Hz (e.g. `50 Hz`);
    unset, or above the controller manager's rate, it runs at that rate (SPEC146, CTRL067)."""
    thread_priority: Annotated[int, Field(ge=1)] | None = None
    """`<ros2_control thread_priority>`: the priority of an async component's thread (Jazzy's default 50); read
    only when `is_async` is true (SPEC147)."""
    hardware: HardwareSpec = HardwareSpec()
    """The hardware plugin and params; default the mock `mock_components/GenericSystem`."""
    update_rate: Frequency
    """The controller_manager's loop rate, a frequency (e.g. `100 Hz`), a whole number of Hz (CTRL007)."""
    joints: list[ControlJointSpec] = []
    """The joints this component drives, each in no other block (SPEC085)."""
    sensors: list[ControlSensorSpec] = []
    """The component's sensors (`<sensor>`), e.g. an IMU."""
    gpios: list[GpioSpec] = []
    """The component's gpios (`<gpio>`), e.g. a gripper's digital outputs."""
    blocks: list[Ros2ControlBlockSpec] = []
    """Further `<ros2_control>` blocks (hardware components, e.g. a gripper on its own bus), written after the first."""
    controllers: list[ControllerSpec] = []
    """The controllers written to ros2_controllers.yaml; with any, one should be a joint_state_broadcaster (CTRL003)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class ChainSpec(Base):
    base: ElementName
    """The chain's first link; an ancestor of `tip` (SRDF001)."""
    tip: ElementName
    """The chain's last link (e.g. the tool flange)."""


class GroupSpec(Base):
    name: Name
    """The planning group's name (e.g. `arm`), declared once (SPEC024)."""
    chain: ChainSpec | None = None
    """A chain from `base` to `tip`: the group holds the joints between them (SRDF001)."""
    chains: list[ChainSpec] = []
    """More chains of the same group (an SRDF group may hold several; import writes them)."""
    links: list[ElementName] = []
    """Links of the group, by name (SRDF001)."""
    joints: list[ElementName] = []
    """Joints of the group, by name (SRDF001); a passive joint in a group is SRDF020."""
    subgroups: list[Name] = []
    """Other groups this one includes, by name (SRDF001)."""


class GroupStateSpec(Base):
    name: ElementName
    """The state's name (e.g. `ready`, or `hold-up` as MoveIt allows), once per group (SPEC024)."""
    group: Name
    """The planning group the state is of (SRDF002)."""
    pose: Name | None = None
    """A known pose to take the joint values from (SRDF010); the state then lists every moving joint of the group,
    those the pose leaves out at zero."""
    joints: dict[ElementName, JointRaw] = {}
    """Joint values, each in its joint's unit (e.g. `{elbow_joint: -90 deg}`), over those of `pose`; a planar or
    floating joint takes a list in MoveIt's variable order (SPEC125). Within limits (SRDF002)."""

    @model_validator(mode="after")
    def _values(self) -> Self:
        if self.pose is None and not self.joints:
            raise error(
                "SPEC004",
                f"group state '{self.name}' needs pose or joints",
                "name a known pose (pose: ready) or list joint values",
            )
        return self


class EndEffectorSpec(Base):
    name: Name
    """The end effector's name (e.g. `gripper`)."""
    group: Name
    """The group of the end effector's own links (e.g. the gripper's); SRDF003."""
    parent_link: ElementName
    """The link the end effector is attached to (e.g. `tool_link`); SRDF003."""
    parent_group: Name | None = None
    """Optional: the planning group that holds `parent_link` (e.g. `arm`)."""


class VirtualJointSpec(Base):
    name: ElementName
    """The virtual joint's name (e.g. `virtual_joint`)."""
    type: Literal["fixed", "floating", "planar"]
    """`fixed` (bolted to the world), `planar` (a base moving on the floor) or `floating`."""
    parent_frame: ElementName
    """The frame outside the robot it connects to (e.g. `world`, `odom`)."""
    child_link: ElementName
    """The robot's root link (SRDF003)."""


class DisabledPairSpec(Base):
    link1: ElementName
    """One link of a pair MoveIt never checks for collision (SRDF003)."""
    link2: ElementName
    """The other link of the pair; each pair once (SPEC024)."""
    reason: Annotated[OneLine, StringConstraints(max_length=200)] = "User"
    """Why the pair is disabled: free text, MoveIt's own reasons being `Adjacent`, `Default`, `Always` and `Never`;
    default `User` (disabled by hand)."""


class CollisionMatrixSpec(Base):
    """Settings of the sampled self-collision matrix; every field is written into the SRDF
    and evidence/collision_matrix.md, so the same spec gives the same bytes."""

    default_state: Name | None = None
    """The group state whose contacts are disabled as `Default` (SPEC100); default the first group state."""
    seed: Annotated[int, Field(ge=0, le=2**32 - 1)] = 0
    """Seed of the random configurations (numpy PCG64), 0 to 2^32-1; default 0."""
    samples: Annotated[int, Field(ge=100, le=1_000_000)] = 10000
    """How many random configurations are checked, 100 to 1,000,000; default 10000."""
    fraction: Annotated[float, Field(gt=0.0, lt=1.0)] = 0.95
    """A pair in collision in more than this share of the samples is disabled as `Always`; between 0 and 1, default
    0.95."""
    padding: Length = ZERO
    """Margin around every collision shape (coal's security margin), a length from 0 to 100 mm (SPEC101); default 0."""


class SemanticSpec(Base):
    virtual_joints: list[VirtualJointSpec] = []
    """Joints from a frame outside the robot (`world`, `odom`) to its root link (SRDF `<virtual_joint>`)."""
    groups: list[GroupSpec] = []
    """Planning groups (SRDF `<group>`): chains, links, joints, subgroups."""
    group_states: list[GroupStateSpec] = []
    """Named joint values of a group (SRDF `<group_state>`), e.g. `ready`."""
    end_effectors: list[EndEffectorSpec] = []
    """End effectors (SRDF `<end_effector>`)."""
    passive_joints: list[ElementName] = []
    """Joints no actuator drives (SRDF `<passive_joint>`): they have no command interface (SRDF004) and belong in no
    planning group (SRDF020)."""
    disable_collisions: list[DisabledPairSpec] = []
    """Link pairs MoveIt never checks for collision, each with its reason; kept beside the pairs the collision matrix
    computes."""
    collision_matrix: CollisionMatrixSpec | None = None
    """Settings of the sampled self-collision matrix that `generate` writes into the SRDF (needs `descgen[collision]`,
    GEN070)."""


class FrameMeasurementSpec(Base):
    frame: ElementName
    """The frame whose position was measured (e.g. `tool_link`); POSE002 when there is none."""
    xyz: tuple[Length, Length, Length]
    """Its measured position in `relative_to`, three lengths (e.g. `[501 mm, 0 mm, 459 mm]`), compared with forward
    kinematics axis by axis (POSE010)."""
    tolerance: Tolerance
    """Allowed difference on each axis between measured and model position, a length (e.g. `2 mm`); plausible (UNIT004,
    `plausibility.tolerance`)."""
    relative_to: ElementName | None = None
    """The frame the position is measured in (POSE002 when there is none); default the root link."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class KnownPoseSpec(Base):
    name: Name
    """The pose's name (e.g. `ready`), an identifier; group states (`pose:`), `poses` and `simulate --pose` use it."""
    joints: dict[ElementName, JointRaw] = {}
    """Joint values at this pose, each in its joint's unit (e.g. `{lift_joint: 150 mm}`); the others at zero. Unknown
    joints: POSE001; outside limits: POSE003. A planar or floating virtual joint takes a list (not used by forward
    kinematics)."""
    frames: list[FrameMeasurementSpec] = []
    """Frame positions measured at this pose, checked against forward kinematics (POSE010)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""
    description: Text | None = None
    """A note about the pose for readers of the spec."""
    nominal: bool = False
    """True when the positions are the nominal model's (an import's forward kinematics, a CAD export), not measured
    on the robot: they are checked against the model without its `calibration:` layer. Default false: measured on
    the robot, checked against the robot as calibrated."""


class ExternalFrameSpec(Base):
    """A transform something outside the URDF publishes (localisation, a driver, calibration)."""

    parent: ElementName
    """The transform's parent frame (e.g. `map`)."""
    child: ElementName
    """The transform's child frame (e.g. `odom`); one publisher per child frame (FRAME001)."""
    owner: Annotated[str, StringConstraints(pattern=r"^[A-Za-z][A-Za-z0-9_/]*$")]
    """The node that publishes it (e.g. `amcl`)."""
    static: bool = False
    """True: published on /tf_static (e.g. a calibration); false (default): on /tf."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class JointStateSourceSpec(Base):
    """A node publishing /joint_states; ``desired`` marks one that publishes commands."""

    node: Annotated[str, StringConstraints(pattern=r"^[A-Za-z][A-Za-z0-9_/]*$")]
    """The node that publishes /joint_states (e.g. `gripper_driver`)."""
    kind: Literal["measured", "desired"] = "measured"
    """`measured` (default) or `desired`: a node that publishes commanded values there is FRAME005."""
    joints: list[ElementName] = []
    """The joints it publishes; empty (default): every joint. A joint with two publishers is FRAME005."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


class FramesSpec(Base):
    external: list[ExternalFrameSpec] = []
    """Transforms published outside the URDF (localisation, a driver, calibration), each with its owner (FRAME001,
    FRAME003, FRAME004)."""
    joint_state_sources: list[JointStateSourceSpec] = []
    """/joint_states publishers besides ros2_control's joint_state_broadcaster (FRAME002, FRAME005)."""


class RangeSpec(Base):
    min: Raw | None = None
    """The smallest plausible magnitude for this role, a quantity of its kind (e.g. `0.1 mm` for `size`); default the
    built-in bound (UNIT004)."""
    max: Raw | None = None
    """The largest plausible magnitude for this role, a quantity of its kind (e.g. `30 m` for `offset`); default the
    built-in bound (UNIT004)."""


# What catkin_pkg (colcon's package.xml parser) accepts, so that generate's package.xml
# check cannot refuse what validate passed: its email and version expressions, verbatim
# (the version without leading zeros, which catkin_pkg warns about).
_CATKIN_EMAIL = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$")
_CATKIN_VERSION = re.compile(r"^(0|[1-9][0-9]*)\.(0|[1-9][0-9]*)\.(0|[1-9][0-9]*)$")


def _package_field(what: str, pattern: re.Pattern[str] | None, hint: str) -> tuple[AfterValidator, Any]:
    """The check (a finding with a hint, not pydantic's pattern message) and, for editors,
    the same rule in the JSON Schema."""

    def check(value: str) -> str:
        if not value.strip() or (pattern is not None and not pattern.fullmatch(value)):
            raise error("SPEC025", f"{value!r} is not a package {what} that catkin_pkg accepts", hint)
        return value

    shown: dict[str, JsonValue] = {"pattern": pattern.pattern} if pattern else {"minLength": 1, "pattern": r"\S"}
    return AfterValidator(check), Field(json_schema_extra=shown)


# REP 144 (https://ros.org/reps/rep-0144.html), "a name must": lowercase alphanumerics and _
# separators, starting with a letter; no two _ in a row; at least two characters.
REP144_PATTERN = r"^[a-z](?:[a-z0-9]|_(?!_))+$"


def rep144_problem(name: str) -> str | None:
    """Why ``name`` is not a REP 144 package name, or None."""
    if re.fullmatch(REP144_PATTERN, name):
        return None
    if not name[:1].islower() or not name[:1].isascii():
        return "a package name starts with a lowercase letter"
    if "__" in name:
        return "a package name has no two '_' in a row"
    if len(name) < 2:
        return "a package name has at least two characters"
    return "a package name holds only lowercase letters, digits and '_'"


def suggest_package_name(name: str) -> str:
    """A REP 144 name close to ``name``: lowercase, other characters as single '_', and
    ``robot_`` in front of a name that does not start with a letter."""
    text = re.sub(r"_+", "_", re.sub(r"[^a-z0-9]", "_", name.lower())).strip("_") or "robot"
    return text if text[0].isalpha() and len(text) > 1 else f"robot_{text}"


def _package_name(value: str) -> str:
    why = rep144_problem(value)
    if why is not None:
        raise error(
            "SPEC120",
            f"package name {value!r} is not a ROS package name: {why} (REP 144)",
            f"write e.g. name: {suggest_package_name(value)}",
        )
    return value


class PackageSpec(Base):
    """The generated ament package's metadata (package.xml)."""

    name: (
        Annotated[
            str,
            StringConstraints(max_length=128),
            AfterValidator(_package_name),
            Field(json_schema_extra={"pattern": REP144_PATTERN}),
        ]
        | None
    ) = None
    """The generated package's name, a REP 144 name (SPEC120); default `<robot>_description`. Set it when the robot's
    name makes none (`2dof_planar`) or the name is taken (UR's meshes are in `ur_description`)."""
    version: Annotated[str, *_package_field("version", _CATKIN_VERSION, "write MAJOR.MINOR.PATCH, e.g. 0.1.0")] = (
        "0.1.0"
    )
    """package.xml `<version>`, `MAJOR.MINOR.PATCH` (SPEC025); default `0.1.0`."""
    maintainer: Annotated[
        OneLine, StringConstraints(max_length=200), *_package_field("maintainer", None, "write a name")
    ] = "descgen user"
    """package.xml `<maintainer>` name (SPEC025); default `descgen user`."""
    email: Annotated[
        str, *_package_field("email", _CATKIN_EMAIL, "write an address like name@example.com (no | ! # or spaces)")
    ] = "maintainer@example.com"
    """The maintainer's email address, as catkin_pkg accepts it (SPEC025); default `maintainer@example.com`."""
    license: Annotated[
        OneLine,
        StringConstraints(max_length=200),
        *_package_field("license", None, "write an SPDX id, e.g. Apache-2.0"),
    ] = "Apache-2.0"
    """package.xml `<license>`, an SPDX id (SPEC025); default `Apache-2.0`."""


KinematicsPlugin = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_]+/[A-Za-z0-9_:]+$", max_length=200)]
KDL = "kdl_kinematics_plugin/KDLKinematicsPlugin"


class KinematicsSpec(Base):
    """One planning group's IK solver (MoveIt's kinematics.yaml); the defaults are what the
    MoveIt Setup Assistant writes (group_meta_config.hpp, jazzy)."""

    solver: KinematicsPlugin = KDL
    """The IK plugin, `package/Class`; default `kdl_kinematics_plugin/KDLKinematicsPlugin`, which solves a chain only
    (MOVEIT017)."""
    search_resolution: Annotated[Number, Field(gt=0.0, le=10.0)] = 0.005
    """`kinematics_solver_search_resolution`, a plain number over 0 and at most 10; default 0.005."""
    timeout: Duration = Measured(0.005, "5 ms", "time")
    """`kinematics_solver_timeout`, a positive duration (SPEC116); default `5 ms`."""


class PilzLimitsSpec(Base):
    """Cartesian limits of the Pilz industrial motion planner (pilz_cartesian_limits.yaml);
    the defaults are the Setup Assistant's template values."""

    max_trans_vel: LinearVelocity = Measured(1.0, "1 m/s", "linear_velocity")
    """Largest Cartesian translation speed, a linear velocity; default `1 m/s`, positive (SPEC116)."""
    max_trans_acc: LinearAcceleration = Measured(2.25, "2.25 m/s^2", "linear_acceleration")
    """Largest Cartesian translation acceleration; default `2.25 m/s^2`, positive (SPEC116)."""
    max_trans_dec: LinearAcceleration = Measured(-5.0, "-5 m/s^2", "linear_acceleration")
    """Largest Cartesian translation deceleration, negative as Pilz writes it; default `-5 m/s^2`."""
    max_rot_vel: AngularVelocity = Measured(1.57, "1.57 rad/s", "angular_velocity")
    """Largest Cartesian rotation speed, an angular velocity; default `1.57 rad/s`, positive (SPEC116)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


Scaling = Annotated[Number, Field(gt=0.0, le=1.0)]


class MoveItSpec(Base):
    """Turns on the MoveIt config package ``<robot>_moveit_config`` (docs/moveit_config.md).
    Every joint of a planning group then needs velocity and acceleration limits (SPEC110)."""

    kinematics: dict[Name, KinematicsSpec] = {}
    """IK solver settings per planning group (SPEC112 for an unknown group); a one-chain group not listed gets the KDL
    defaults."""
    default_velocity_scaling_factor: Scaling = 0.1
    """Share of each joint's velocity limit MoveIt plans with by default, over 0 and at most 1; default 0.1."""
    default_acceleration_scaling_factor: Scaling = 0.1
    """Share of each joint's acceleration limit MoveIt plans with by default, over 0 and at most 1; default 0.1."""
    initial_state: ElementName | None = None
    """The group state written to initial_positions.yaml, where the demo's mock hardware starts (SPEC113); default
    `semantic.collision_matrix.default_state`, else MoveIt's defaults."""
    pilz_cartesian_limits: PilzLimitsSpec = PilzLimitsSpec()
    """Cartesian limits of the Pilz industrial motion planner (pilz_cartesian_limits.yaml); default the Setup
    Assistant's values."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


def _passthrough_xml(xml: str) -> str:
    from descgen.spec.passthrough import problem

    why = problem(xml)
    if why is not None:
        raise error("IMP010", f"pass-through XML {why}", "write one plain XML element, as descgen import keeps it")
    return xml


class PassthroughSpec(Base):
    """One XML element the spec cannot express (a <gazebo> tag, a <transmission>, ...),
    written verbatim into the URDF; in the Xacro every ``$`` stays data (never evaluated)."""

    xml: Annotated[str, AfterValidator(_text), AfterValidator(_passthrough_xml)]
    """One XML element written verbatim into the URDF (e.g. a `<gazebo>` tag); not a link, joint or material, and no
    DOCTYPE or xacro instruction (IMP010)."""
    source: Source | None = None
    """Where this element's values come from (a measurement-sheet row, drawing or datasheet, e.g. `M07`); it covers
    every value inside the element. With `require_sources: true`, a value with no source on itself or around it is
    SPEC010."""


def _some_links(links: list[LinkSpec]) -> list[LinkSpec]:
    # parts and sensors hang below a link of links:, so a robot needs at least one there
    if not links:
        raise error(
            "SPEC023",
            "the robot has no links (a URDF needs at least one <link>)",
            "add links: with the root link, e.g. - name: base_link",
        )
    return links


# The robot's name is the URDF's <robot name> and the stem of the generated files; ROS takes a
# leading digit there (example-robot-data's 2dof_planar). The package name is checked apart.
ROBOT_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_]*$"


def _robot_name(value: str) -> str:
    if not re.fullmatch(ROBOT_NAME_PATTERN, value):
        raise error(
            "SPEC050",
            f"{value!r} is not a valid robot name",
            "use letters, digits and _ (e.g. warehouse_arm): it names the URDF, the SRDF and their files",
        )
    return value


RobotName = Annotated[
    str,
    StringConstraints(max_length=128),
    AfterValidator(_robot_name),
    Field(json_schema_extra={"pattern": ROBOT_NAME_PATTERN}),
]


PREFIX_PATTERN = r"^[A-Za-z][A-Za-z0-9_]*$"
# rcl's rules for a namespace (rcl_validate_namespace): tokens of letters, digits and _ that do
# not start with a digit, separated by single slashes; a leading / is allowed, a trailing one not
NAMESPACE_PATTERN = r"^/?[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*$"


def _prefix(value: str) -> str:
    if not re.fullmatch(PREFIX_PATTERN, value):
        raise error(
            "SPEC140",
            f"{value!r} is not a valid prefix",
            "use letters, digits and _ starting with a letter, e.g. left_: it is written before every name",
        )
    return value


def _namespace(value: str) -> str:
    if not re.fullmatch(NAMESPACE_PATTERN, value):
        raise error(
            "SPEC141",
            f"{value!r} is not a ROS namespace",
            "use names of letters, digits and _ separated by /, e.g. left_arm or /cell1/left_arm",
        )
    return value


Prefix = Annotated[
    str, StringConstraints(max_length=64), AfterValidator(_prefix), Field(json_schema_extra={"pattern": PREFIX_PATTERN})
]
Namespace = Annotated[
    str,
    StringConstraints(max_length=255),
    AfterValidator(_namespace),
    Field(json_schema_extra={"pattern": NAMESPACE_PATTERN}),
]


class ComposeSpec(Base):
    """Another robot's spec mounted on a frame of this one: its every name behind `prefix`, its root on a fixed
    joint from `parent` (docs/multi-robot.md)."""

    spec: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)]
    """The other robot's spec file, relative to this spec and inside the project (SPEC142)."""
    prefix: Prefix
    """Written before every name of the mounted robot, as its own `prefix:` would be (e.g. `left_`); each mounted
    robot needs its own (SPEC144)."""
    parent: Annotated[OneLine, StringConstraints(min_length=1, max_length=256)]
    """The frame of this robot the mounted robot's root hangs from (SPEC143)."""
    origin: Origin = Origin()
    """Where the mounted robot's root sits in `parent`."""
    joint: Name | None = None
    """The fixed joint's name; default `<prefix><root>_mount_joint`."""
    source: Source | None = None
    """Where the mounting pose comes from (a drawing, a measurement)."""


class CalibrationSourceSpec(Base):
    """Where a set of calibration values comes from: the provenance every entry cites by name."""

    method: Annotated[OneLine, StringConstraints(min_length=1, max_length=400)]
    """How the values were obtained, e.g. `UR factory calibration read from the controller` or `hand-eye (Tsai)`."""
    tool: Annotated[OneLine, StringConstraints(min_length=1, max_length=200)] | None = None
    """The tool that produced them, e.g. `ur_calibration`, `easy_handeye2`, `descgen drift`."""
    file: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)] | None = None
    """The file they were imported from, as given to `descgen import-calibration`."""
    date: (
        Annotated[
            OneLine,
            BeforeValidator(lambda v: v.isoformat() if isinstance(v, datetime.date) else v),
            StringConstraints(min_length=1, max_length=40),
        ]
        | None
    ) = None
    """When they were measured, e.g. `2026-11-02`."""
    hash: Annotated[OneLine, StringConstraints(min_length=1, max_length=200)] | None = None
    """The vendor's checksum of the calibration, e.g. UR's `calib_12345...`, kept so the driver's check can be
    traced."""


class OriginCorrectionSpec(Base):
    """A correction added to a joint origin's components: xyz (lengths), then roll, pitch, yaw (angles)."""

    xyz: tuple[Length, Length, Length] = (ZERO, ZERO, ZERO)
    """Added to the nominal origin's x, y, z, e.g. `[0.4 mm, 0, -0.1 mm]`."""
    rpy: tuple[Angle, Angle, Angle] = (ZERO_ANGLE, ZERO_ANGLE, ZERO_ANGLE)
    """Added to the nominal origin's roll, pitch, yaw, e.g. `[0, 0.02 deg, 0]`."""


class JointCalibrationSpec(Base):
    """A joint's calibration: its zero offset and a correction of its origin, both on top of the nominal joint."""

    source: Name
    """The name of the entry of `calibration.sources` these values come from (CAL001)."""
    offset: Raw | None = None
    """The joint's zero offset: the joint reports q and is at q + offset (an angle for a revolute joint, a length
    for a prismatic one), e.g. `0.5 deg`. Written into the joint origin, as a rotation about (or a shift along) its
    axis."""
    origin: OriginCorrectionSpec = OriginCorrectionSpec()
    """A correction added to the nominal origin (`xyz`, `rpy`)."""


class SensorCalibrationSpec(Base):
    """A sensor's measured mount (extrinsics): replaces the nominal origin of its `<name>_joint`."""

    source: Name
    """The name of the entry of `calibration.sources` these values come from (CAL001)."""
    origin: Origin
    """The calibrated pose of the sensor frame in the sensor's parent, e.g. from a hand-eye calibration."""


class DriftCheckSpec(Base):
    """Samples of the running robot that `report` compares the model with (`descgen drift`), shown on the evidence
    page as the residual over time."""

    samples: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)]
    """A CSV of samples relative to the spec, inside the project: `time`, one column per moving joint of the chain
    (rad, m), then `x,y,z` (m) of `frame` in `base` (CAL005)."""
    frame: ElementName
    """The link whose position was measured, e.g. `tool_link`."""
    base: ElementName | None = None
    """The link the positions are in; default the root link."""
    tolerance: Tolerance | None = None
    """The 95th percentile of the residual beyond which the robot has drifted (the page's verdict fails); default
    `1 mm`."""
    parameters: list[Annotated[OneLine, StringConstraints(min_length=1, max_length=200)]] = []
    """Patterns of the calibration parameters to fit, e.g. `joint:*:offset`; default every offset and origin
    component on the chain."""


class CalibrationSpec(Base):
    """The robot as measured: corrections on top of the nominal model, each citing its provenance. generate writes
    them to `config/calibration/default.yaml`, which the Xacro reads (`calibration:=FILE` picks another, e.g.
    `config/calibration/nominal.yaml`)."""

    sources: dict[Name, CalibrationSourceSpec] = {}
    """Named provenances that entries cite: method, tool, file, date, hash."""
    joints: dict[ElementName, JointCalibrationSpec] = {}
    """Per joint (by name): its zero offset and origin correction."""
    sensors: dict[Name, SensorCalibrationSpec] = {}
    """Per sensor of `sensors:` (by name): its calibrated mount."""
    drift: DriftCheckSpec | None = None
    """Samples of the running robot that `report` compares the calibrated model with (section 11 of the evidence
    page: the residual over time, and the parameters that explain it)."""


class WaiverSpec(Base):
    """A finding the team accepts for now: ``code`` and ``subject`` exactly as findings print
    them (``INER004``, ``link:finger``), and why. The finding is still reported, as waived,
    in every output; it fails no command. A waiver that matches nothing is a warning."""

    code: Annotated[str, StringConstraints(pattern=r"^[A-Z]+[0-9]{3}$")]
    """The finding's code, e.g. `INER004`; only an audit rule's finding can be waived."""
    subject: Annotated[OneLine, StringConstraints(min_length=1, max_length=400)]
    """The finding's subject exactly as findings print it, e.g. `link:finger`."""
    reason: Annotated[OneLine, StringConstraints(min_length=1, max_length=400)]
    """Why the team accepts the finding for now (SARIF's justification), e.g. `CAD inertia pending`."""


class RobotSpec(Base):
    """One robot. See specs/warehouse_arm.yaml for a complete example."""

    name: RobotName
    """The robot's name: the URDF's `<robot name>` and the stem of the generated files; letters, digits and `_`
    (SPEC050)."""
    description: Text | None = None
    """About the robot: a comment at the top of the URDF and the package.xml `<description>` (default
    `Robot description of <name>`)."""
    package: PackageSpec = PackageSpec()
    """The generated package's metadata (package.xml): name, version, maintainer, email, license."""
    require_sources: bool = False
    """When true, every measured value cites a source, on itself or on an element around it (SPEC010); default false."""
    plausibility: dict[str, RangeSpec] = {}
    """Plausible ranges per role (`offset`, `size`, `mass`, `angle`, `joint_angle`, `joint_travel`, ..., `density`)
    overriding the built-in ones, e.g. `{offset: {max: 30 m}}` (UNIT004, UNIT010)."""
    materials: list[MaterialSpec] = []
    """Named colours and textures that visuals refer to, each name once (SPEC026)."""
    links: Annotated[
        list[LinkSpec], AfterValidator(_some_links), Field(validate_default=True, json_schema_extra={"minItems": 1})
    ] = []
    """The robot's links; at least one (SPEC023), and exactly one without a parent joint (TOPO001)."""
    joints: list[JointSpec] = []
    """The joints that connect the links into one tree (TOPO001-TOPO005)."""
    parts: list[PartSpec] = []
    """Parts built more than once (left and right wheel): one link and joint body, one copy per instance; one Xacro
    macro."""
    sensors: list[SensorSpec] = []
    """Sensor frames: `<name>_link` on a fixed `<name>_joint`; a camera also gets its optical frame."""
    ros2_control: Ros2ControlSpec | None = None
    """The ros2_control hardware (`<ros2_control>` blocks), the controller manager's rate and the controllers
    (ros2_controllers.yaml)."""
    semantic: SemanticSpec | None = None
    """The SRDF: planning groups, group states, end effectors, virtual and passive joints, disabled collision pairs."""
    known_poses: list[KnownPoseSpec] = []
    """Poses measured on the robot: joint values and frame positions, checked by forward kinematics (POSE010)."""
    frames: FramesSpec = FramesSpec()
    """Transforms and /joint_states publishers outside the URDF, for the frame-ownership checks (FRAME001-FRAME005)."""
    package_paths: list[Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)]] = []
    """Folders, relative to the spec and inside the project, that hold the ROS packages `package://` meshes name, so
    every command resolves them alike (SPEC062, SPEC064)."""
    templates: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)] | None = None
    """A folder of template overrides relative to the spec, which generate and check both use; rendered sandboxed, as a
    spec may be someone else's data (SPEC064, GEN061)."""
    passthrough: list[PassthroughSpec] = []
    """XML elements the spec cannot express (`<gazebo>`, `<transmission>`, ...), written verbatim into the URDF
    (IMP010)."""
    moveit: MoveItSpec | None = None
    """Turns on the MoveIt config package `<robot>_moveit_config`; every planning joint then needs velocity and
    acceleration limits (SPEC111, SPEC110)."""
    calibration: CalibrationSpec | None = None
    """The robot as measured (joint zero offsets, origin corrections, sensor mounts), each with its provenance; a
    layer on top of the nominal model (docs/calibration.md)."""
    waivers: list[WaiverSpec] = []
    """Findings the team accepts for now, by code and subject: still reported, as waived, and failing no command; a
    waiver that matches nothing is SPEC130."""
    prefix: Prefix | None = None
    """Written before every frame, joint, ros2_control joint, sensor and GPIO name and the names controllers are given
    (joint lists, wheel names, frame ids), so robots share one ROS graph (ROS 2 has no tf_prefix); the Xacro takes it
    as its `prefix` argument, default this value (docs/multi-robot.md, SPEC140)."""
    namespace: Namespace | None = None
    """The ROS namespace the launch files start the robot's nodes in (robot_state_publisher, the controller manager,
    the spawners), e.g. `left_arm` (SPEC141)."""
    compose: list[ComposeSpec] = []
    """Other robots' specs mounted on frames of this one, each behind its own prefix: one URDF, one ros2_control
    controller manager (their controllers' names prefixed too), one SRDF (docs/multi-robot.md, SPEC142-SPEC144)."""


__all__ = ["Measured", "RobotSpec"]
