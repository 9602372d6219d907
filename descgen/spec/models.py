"""Pydantic v2 models of the spec YAML: structure, names and fixed-kind quantities.

Unknown keys are errors (``extra="forbid"``). Every model is frozen. Cross-element rules
(names exist, one root, limits ordered...) are not here: they are rules over the built
model in ``descgen/audit/rules``, shared with ``descgen audit``.
"""

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
    rpy: tuple[Angle, Angle, Angle] = (ZERO_ANGLE, ZERO_ANGLE, ZERO_ANGLE)
    source: Source | None = None


class BoxSpec(Base):
    size: tuple[Size, Size, Size]


class _Round(Base):
    radius: Size | None = None
    diameter: Size | None = None

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


class SphereSpec(_Round):
    pass


class MeshSpec(Base):
    """A mesh file. ``size`` is what you measured of the part (the scaled mesh's bounding box
    extents along the mesh's x, y, z); the file is checked against it within ``tolerance``
    (default 1 mm), so a mesh exported in millimetres or inches is caught (GEOM030)."""

    filename: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)]
    scale: tuple[Number, Number, Number] = (1.0, 1.0, 1.0)
    size: tuple[Size, Size, Size] | None = None
    tolerance: Tolerance | None = None


class GeometrySpec(Base):
    box: BoxSpec | None = None
    cylinder: CylinderSpec | None = None
    sphere: SphereSpec | None = None
    mesh: MeshSpec | None = None

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
    rgba: tuple[Number, Number, Number, Number] | None = None
    texture: Annotated[OneLine, StringConstraints(max_length=1000)] | None = None

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
    origin: Origin = Origin()
    geometry: GeometrySpec
    material: Annotated[OneLine, StringConstraints(min_length=1, max_length=200)] | None = None
    source: Source | None = None


class CollisionSpec(Base):
    name: Annotated[OneLine, StringConstraints(max_length=200)] | None = None
    origin: Origin = Origin()
    geometry: GeometrySpec
    source: Source | None = None


class InertiaSpec(Base):
    ixx: InertiaQ
    iyy: InertiaQ
    izz: InertiaQ
    ixy: InertiaQ = ZERO
    ixz: InertiaQ = ZERO
    iyz: InertiaQ = ZERO


class InertialSpec(Base):
    """Mass, centre of mass, and either a tensor or ``from: collision|visual``.

    With ``from``, the tensor is that of the first collision (or visual) primitive of
    uniform density, about its own centroid, rotated into the link frame. The centre of
    mass is ``origin.xyz`` when given, else the primitive's centre.
    """

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)

    mass: Mass
    origin: Origin | None = None
    inertia: InertiaSpec | None = None
    from_: Literal["collision", "visual"] | None = Field(default=None, alias="from")
    source: Source | None = None

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
    collision: Annotated[list[CollisionSpec], BeforeValidator(_one_or_many)] = []
    inertial: InertialSpec | None = None
    source: Source | None = None
    description: Text | None = None


class LinkSpec(LinkBody):
    name: ElementName


class LimitSpec(Base):
    """Units follow the joint type: angles or lengths, N*m or N, rad/s or m/s."""

    lower: Raw | None = None
    upper: Raw | None = None
    effort: Raw
    velocity: Raw
    # rad/s^2 (deg/s^2) or m/s^2; not in the URDF (it has no such attribute), written to MoveIt's
    # joint_limits.yaml; required for the joints of planning groups when ``moveit:`` is set (SPEC110)
    acceleration: Raw | None = None
    source: Source | None = None


class DynamicsSpec(Base):
    damping: Raw | None = None
    friction: Raw | None = None
    source: Source | None = None


class MimicSpec(Base):
    joint: ElementName
    multiplier: Number = 1.0
    offset: Raw | None = None


class SafetySpec(Base):
    soft_lower_limit: Raw | None = None
    soft_upper_limit: Raw | None = None
    k_position: Raw | None = None
    k_velocity: Raw


JointType = Literal["fixed", "revolute", "continuous", "prismatic", "floating", "planar"]


class JointBody(Base):
    type: JointType
    parent: ElementName
    axis: Axis | None = None
    limit: LimitSpec | None = None
    dynamics: DynamicsSpec | None = None
    mimic: MimicSpec | None = None
    safety_controller: SafetySpec | None = None
    source: Source | None = None
    description: Text | None = None


class JointSpec(JointBody):
    name: ElementName
    child: ElementName
    origin: Origin = Origin()


class PartInstance(Base):
    link: ElementName
    joint: ElementName
    origin: Origin = Origin()
    source: Source | None = None


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
    link: LinkBody = LinkBody()
    joint: JointBody
    instances: Annotated[list[PartInstance], Field(min_length=1)]
    source: Source | None = None
    description: Text | None = None


class SensorSpec(Base):
    """A sensor frame ``<name>_link`` on a fixed joint ``<name>_joint``. A camera also gets
    ``<name>_optical_frame`` (z forward, x right, y down; REP 103)."""

    name: ElementName
    type: Literal["camera", "lidar", "imu", "generic"]
    parent: ElementName
    origin: Origin = Origin()
    link: LinkBody = LinkBody()
    source: Source | None = None
    description: Text | None = None


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
    data_type: DataType | None = None
    min: Raw | None = None
    max: Raw | None = None


class JointStateSpec(Base):
    """A joint state interface; ``initial_value`` in the joint's units (``position`` may use the
    joint's ``initial_position`` instead, not both)."""

    name: ParamInterfaceName
    data_type: DataType | None = None
    initial_value: Raw | None = None


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
    command: list[JointInterfaceName | JointCommandSpec | InterfaceName] = []
    state: list[JointInterfaceName | JointStateSpec | InterfaceName] = []
    initial_position: Raw | None = None
    on_limit: Literal["reject", "clip"] = "reject"
    # Jazzy's ros2_control <joint mimic="...">: unset, a URDF <mimic> joint is a mimic joint
    # (state from its leader, no command interface); false: an ordinary joint
    mimic: bool | None = None
    params: HwParams = {}
    source: Source | None = None


MOCK_PLUGIN = "mock_components/GenericSystem"
GZ_PLUGIN = "gz_ros2_control/GazeboSimSystem"


class HardwareVariantSpec(Base):
    """The ``<hardware>`` of one value of the Xacro argument ``hardware`` (gazebo or real)."""

    plugin: Plugin | None = None  # gazebo: gz_ros2_control/GazeboSimSystem when left out
    params: HwParams = {}


class HardwareSpec(Base):
    """``plugin``/``params`` are the default hardware. With ``variants``, they are the ``mock``
    variant and the generated Xacro takes ``hardware:=mock|gazebo|real`` (default mock)."""

    plugin: Plugin = MOCK_PLUGIN
    params: HwParams = {}
    variants: dict[Literal["gazebo", "real"], HardwareVariantSpec] = {}

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
    source: Source
    tolerance: Tolerance | None = None


CALIBRATABLE = {"diff_drive_controller/DiffDriveController": ("wheel_separation", "wheel_radius")}


class ControllerSpec(Base):
    name: Name
    type: Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_]+/[A-Za-z0-9_]+$")]
    params: dict[str, ParamValue] = {}
    calibrated: dict[str, CalibratedSpec] = {}
    source: Source | None = None

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
    data_type: DataType | None = None
    initial_value: Number | None = None
    min: Number | None = None
    max: Number | None = None


Iface = InterfaceName | InterfaceSpec
# a <gpio>'s interfaces are a driver's own registers: Dynamixel's "Goal Position" (ROBOTIS's
# open_manipulator); any such name, without quote, <, & or $
GPIO_INTERFACE_PATTERN = r"^[A-Za-z0-9_][A-Za-z0-9_ .()-]*$"
GpioInterfaceName = Annotated[str, StringConstraints(pattern=GPIO_INTERFACE_PATTERN, max_length=128)]


class GpioInterfaceSpec(InterfaceSpec):
    name: GpioInterfaceName


GpioIface = GpioInterfaceName | GpioInterfaceSpec


class ControlSensorSpec(Base):
    """A ros2_control ``<sensor>``. ``kind: imu`` / ``force_torque`` fill ``state`` with the
    interfaces the IMU / force-torque broadcasters read when it is left empty."""

    name: Name
    kind: Literal["imu", "force_torque", "generic"] = "generic"
    frame: ElementName | None = None  # the link it measures in; written as its frame_id param
    state: list[Iface] = []
    params: HwParams = {}
    source: Source | None = None


class GpioSpec(Base):
    name: GpioName
    command: list[GpioIface] = []
    state: list[GpioIface] = []
    params: HwParams = {}  # <param>s of the gpio (e.g. an index), kept as written
    source: Source | None = None


class Ros2ControlBlockSpec(Base):
    """One more ``<ros2_control>`` block (one hardware component, e.g. a gripper on its own bus);
    its joints, sensors and gpios belong to no other block."""

    name: Name
    type: Literal["system", "actuator", "sensor"] = "system"
    is_async: bool | None = None  # <ros2_control is_async="...">: its own thread (Jazzy's parser)
    hardware: HardwareSpec = HardwareSpec()
    joints: list[ControlJointSpec] = []
    sensors: list[ControlSensorSpec] = []
    gpios: list[GpioSpec] = []
    source: Source | None = None


class Ros2ControlSpec(Base):
    """The first ``<ros2_control>`` block, the controller manager's rate and the controllers;
    ``blocks`` lists further hardware components (written after the first)."""

    name: Name
    type: Literal["system", "actuator", "sensor"] = "system"
    is_async: bool | None = None  # <ros2_control is_async="...">: its own thread (Jazzy's parser)
    hardware: HardwareSpec = HardwareSpec()
    update_rate: Frequency
    joints: list[ControlJointSpec] = []
    sensors: list[ControlSensorSpec] = []
    gpios: list[GpioSpec] = []
    blocks: list[Ros2ControlBlockSpec] = []
    controllers: list[ControllerSpec] = []
    source: Source | None = None


class ChainSpec(Base):
    base: ElementName
    tip: ElementName


class GroupSpec(Base):
    name: Name
    chain: ChainSpec | None = None
    # more chains of the same group (an SRDF group may hold several; descgen import writes them)
    chains: list[ChainSpec] = []
    links: list[ElementName] = []
    joints: list[ElementName] = []
    subgroups: list[Name] = []


class GroupStateSpec(Base):
    # MoveIt takes any string ('hold-up' in xarm7.srdf); a known pose it names stays an identifier
    name: ElementName
    group: Name
    pose: Name | None = None  # take the joint values of a known pose
    joints: dict[ElementName, JointRaw] = {}  # a list for a planar/floating joint

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
    group: Name
    parent_link: ElementName
    parent_group: Name | None = None


class VirtualJointSpec(Base):
    name: ElementName
    type: Literal["fixed", "floating", "planar"]
    parent_frame: ElementName
    child_link: ElementName


class DisabledPairSpec(Base):
    link1: ElementName
    link2: ElementName
    reason: Annotated[OneLine, StringConstraints(max_length=200)] = "User"


class CollisionMatrixSpec(Base):
    """Settings of the sampled self-collision matrix; every field is written into the SRDF
    and evidence/collision_matrix.md, so the same spec gives the same bytes."""

    default_state: Name | None = None  # a group state; default: the first one
    seed: Annotated[int, Field(ge=0, le=2**32 - 1)] = 0
    samples: Annotated[int, Field(ge=100, le=1_000_000)] = 10000
    fraction: Annotated[float, Field(gt=0.0, lt=1.0)] = 0.95
    padding: Length = ZERO


class SemanticSpec(Base):
    virtual_joints: list[VirtualJointSpec] = []
    groups: list[GroupSpec] = []
    group_states: list[GroupStateSpec] = []
    end_effectors: list[EndEffectorSpec] = []
    passive_joints: list[ElementName] = []
    disable_collisions: list[DisabledPairSpec] = []
    collision_matrix: CollisionMatrixSpec | None = None


class FrameMeasurementSpec(Base):
    frame: ElementName
    xyz: tuple[Length, Length, Length]
    tolerance: Tolerance
    relative_to: ElementName | None = None
    source: Source | None = None


class KnownPoseSpec(Base):
    name: Name
    joints: dict[ElementName, JointRaw] = {}  # a list for a planar/floating virtual joint (no FK)
    frames: list[FrameMeasurementSpec] = []
    source: Source | None = None
    description: Text | None = None


class ExternalFrameSpec(Base):
    """A transform something outside the URDF publishes (localisation, a driver, calibration)."""

    parent: ElementName
    child: ElementName
    owner: Annotated[str, StringConstraints(pattern=r"^[A-Za-z][A-Za-z0-9_/]*$")]
    static: bool = False
    source: Source | None = None


class JointStateSourceSpec(Base):
    """A node publishing /joint_states; ``desired`` marks one that publishes commands."""

    node: Annotated[str, StringConstraints(pattern=r"^[A-Za-z][A-Za-z0-9_/]*$")]
    kind: Literal["measured", "desired"] = "measured"
    joints: list[ElementName] = []
    source: Source | None = None


class FramesSpec(Base):
    external: list[ExternalFrameSpec] = []
    joint_state_sources: list[JointStateSourceSpec] = []


class RangeSpec(Base):
    min: Raw | None = None
    max: Raw | None = None


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

    # default <robot>_description (mesh_paths.package_name); set it when the robot's name
    # makes no package name (2dof_planar) or the name is taken (UR's meshes are in ur_description)
    name: (
        Annotated[
            str,
            StringConstraints(max_length=128),
            AfterValidator(_package_name),
            Field(json_schema_extra={"pattern": REP144_PATTERN}),
        ]
        | None
    ) = None
    version: Annotated[str, *_package_field("version", _CATKIN_VERSION, "write MAJOR.MINOR.PATCH, e.g. 0.1.0")] = (
        "0.1.0"
    )
    maintainer: Annotated[
        OneLine, StringConstraints(max_length=200), *_package_field("maintainer", None, "write a name")
    ] = "descgen user"
    email: Annotated[
        str, *_package_field("email", _CATKIN_EMAIL, "write an address like name@example.com (no | ! # or spaces)")
    ] = "maintainer@example.com"
    license: Annotated[
        OneLine,
        StringConstraints(max_length=200),
        *_package_field("license", None, "write an SPDX id, e.g. Apache-2.0"),
    ] = "Apache-2.0"


KinematicsPlugin = Annotated[str, StringConstraints(pattern=r"^[A-Za-z0-9_]+/[A-Za-z0-9_:]+$", max_length=200)]
KDL = "kdl_kinematics_plugin/KDLKinematicsPlugin"


class KinematicsSpec(Base):
    """One planning group's IK solver (MoveIt's kinematics.yaml); the defaults are what the
    MoveIt Setup Assistant writes (group_meta_config.hpp, jazzy)."""

    solver: KinematicsPlugin = KDL
    search_resolution: Annotated[Number, Field(gt=0.0, le=10.0)] = 0.005
    timeout: Duration = Measured(0.005, "5 ms", "time")


class PilzLimitsSpec(Base):
    """Cartesian limits of the Pilz industrial motion planner (pilz_cartesian_limits.yaml);
    the defaults are the Setup Assistant's template values."""

    max_trans_vel: LinearVelocity = Measured(1.0, "1 m/s", "linear_velocity")
    max_trans_acc: LinearAcceleration = Measured(2.25, "2.25 m/s^2", "linear_acceleration")
    max_trans_dec: LinearAcceleration = Measured(-5.0, "-5 m/s^2", "linear_acceleration")
    max_rot_vel: AngularVelocity = Measured(1.57, "1.57 rad/s", "angular_velocity")
    source: Source | None = None


Scaling = Annotated[Number, Field(gt=0.0, le=1.0)]


class MoveItSpec(Base):
    """Turns on the MoveIt config package ``<robot>_moveit_config`` (docs/moveit_config.md).
    Every joint of a planning group then needs velocity and acceleration limits (SPEC110)."""

    # per group; a group that is one chain and is not listed gets the KDL defaults
    kinematics: dict[Name, KinematicsSpec] = {}
    default_velocity_scaling_factor: Scaling = 0.1
    default_acceleration_scaling_factor: Scaling = 0.1
    # the group state written to initial_positions.yaml; default: semantic.collision_matrix.default_state
    initial_state: ElementName | None = None
    pilz_cartesian_limits: PilzLimitsSpec = PilzLimitsSpec()
    source: Source | None = None


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
    source: Source | None = None


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


class WaiverSpec(Base):
    """A finding the team accepts for now: ``code`` and ``subject`` exactly as findings print
    them (``INER004``, ``link:finger``), and why. The finding is still reported, as waived,
    in every output; it fails no command. A waiver that matches nothing is a warning."""

    code: Annotated[str, StringConstraints(pattern=r"^[A-Z]+[0-9]{3}$")]
    subject: Annotated[OneLine, StringConstraints(min_length=1, max_length=400)]
    reason: Annotated[OneLine, StringConstraints(min_length=1, max_length=400)]


class RobotSpec(Base):
    """One robot. See specs/warehouse_arm.yaml for a complete example."""

    name: RobotName
    description: Text | None = None
    package: PackageSpec = PackageSpec()
    require_sources: bool = False
    plausibility: dict[str, RangeSpec] = {}
    materials: list[MaterialSpec] = []
    links: Annotated[
        list[LinkSpec], AfterValidator(_some_links), Field(validate_default=True, json_schema_extra={"minItems": 1})
    ] = []
    joints: list[JointSpec] = []
    parts: list[PartSpec] = []
    sensors: list[SensorSpec] = []
    ros2_control: Ros2ControlSpec | None = None
    semantic: SemanticSpec | None = None
    known_poses: list[KnownPoseSpec] = []
    frames: FramesSpec = FramesSpec()
    # Folders relative to the spec (inside the project) that hold the ROS packages its
    # ``package://`` meshes name; recorded so every command resolves them alike (mesh_paths.py).
    package_paths: list[Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)]] = []
    # A folder of template overrides relative to the spec, so generate and check use the same;
    # rendered sandboxed, since a spec is someone else's data (--templates is not).
    templates: Annotated[OneLine, StringConstraints(min_length=1, max_length=1000)] | None = None
    passthrough: list[PassthroughSpec] = []
    moveit: MoveItSpec | None = None
    waivers: list[WaiverSpec] = []


__all__ = ["Measured", "RobotSpec"]
