"""The robot model: immutable, SI only (m, rad, kg, s, N, N*m).

Specs and third-party descriptions are both read into this model; everything downstream
(rules, kinematics, renderers) reads only this. Fields that a broken description may
lack are Optional, so a defective robot can still be modelled and audited.
Each element keeps ``where`` (file, line) for messages.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator
from typing import Literal

from descgen.core.findings import Where
from descgen.core.moveit_model import MoveItConfig
from descgen.core.record import record

Vec3 = tuple[float, float, float]
NOWHERE = Where("<unknown>")

# Joint types, written out once: every part asks these rather than spelling a tuple.
JOINT_TYPES = ("fixed", "revolute", "continuous", "prismatic", "floating", "planar")
MOVABLE = ("revolute", "continuous", "prismatic", "floating", "planar")  # every type but fixed
ONE_DOF = ("revolute", "continuous", "prismatic")  # one joint value: what joint_states and poses set
ROTATING = ("revolute", "continuous")  # the value is an angle about the axis
WITH_LIMITS = ("revolute", "prismatic")  # <limit lower/upper> bounds the value
WITH_AXIS = ("revolute", "continuous", "prismatic", "planar")  # <axis> means something (planar: the normal)
NO_AXIS = ("fixed", "floating")  # <axis> is ignored: URDF readers drop it
VIRTUAL_JOINT_TYPES = ("fixed", "floating", "planar")  # an SRDF <virtual_joint>
MULTI_DOF = ("floating", "planar")  # joints (virtual ones too) with more than one value

# What audit/inputs.mesh_status found for a mesh filename.
MeshState = Literal["ok", "missing", "escapes", "unresolved"]


@record
class Pose:
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)


@record
class Box:
    size: Vec3


@record
class Cylinder:
    radius: float
    length: float


@record
class Sphere:
    radius: float


@record
class Mesh:
    filename: str
    scale: Vec3 = (1.0, 1.0, 1.0)
    # A spec's measured size of the scaled mesh (bounding box extents, m) and how far the
    # file may differ from it (m); None: not stated (GEOM030).
    size: Vec3 | None = None
    size_tolerance: float | None = None


Geometry = Box | Cylinder | Sphere | Mesh


@record
class Material:
    name: str
    rgba: tuple[float, float, float, float] | None = None
    texture: str | None = None
    where: Where = NOWHERE


@record
class Visual:
    geometry: Geometry | None
    origin: Pose = Pose()
    name: str | None = None
    material: str | None = None
    where: Where = NOWHERE


@record
class Collision:
    geometry: Geometry | None
    origin: Pose = Pose()
    name: str | None = None
    where: Where = NOWHERE


@record
class Inertia:
    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float

    def matrix(self) -> tuple[Vec3, Vec3, Vec3]:
        return (
            (self.ixx, self.ixy, self.ixz),
            (self.ixy, self.iyy, self.iyz),
            (self.ixz, self.iyz, self.izz),
        )


@record
class Inertial:
    mass: float | None
    origin: Pose = Pose()
    inertia: Inertia | None = None
    where: Where = NOWHERE


@record
class Link:
    name: str
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    inertial: Inertial | None = None
    where: Where = NOWHERE
    source: str | None = None
    part: str | None = None  # the repeated part this link is an instance of
    description: str | None = None

    @property
    def subject(self) -> str:
        return f"link:{self.name}"

    def shapes(self) -> tuple[Visual | Collision, ...]:
        return (*self.visuals, *self.collisions)


@record
class Limit:
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    where: Where = NOWHERE
    # rad/s^2 or m/s^2; a spec value only (a URDF has no acceleration): MoveIt's joint_limits.yaml
    acceleration: float | None = None


@record
class Dynamics:
    damping: float = 0.0
    friction: float = 0.0


@record
class Mimic:
    joint: str
    multiplier: float = 1.0
    offset: float = 0.0
    where: Where = NOWHERE


@record
class SafetyController:
    k_velocity: float
    k_position: float = 0.0
    soft_lower_limit: float = 0.0
    soft_upper_limit: float = 0.0


@record
class Joint:
    name: str
    type: str
    parent: str | None
    child: str | None
    origin: Pose = Pose()
    axis: Vec3 | None = (1.0, 0.0, 0.0)
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    mimic: Mimic | None = None
    safety: SafetyController | None = None
    where: Where = NOWHERE
    source: str | None = None
    part: str | None = None
    description: str | None = None

    @property
    def subject(self) -> str:
        return f"joint:{self.name}"

    @property
    def movable(self) -> bool:
        return self.type in MOVABLE

    def outside_limits(self, value: float) -> bool:
        """True when a bounded joint (revolute, prismatic) is given a value beyond its limits."""
        lm = self.limit
        if self.type not in WITH_LIMITS or lm is None or lm.lower is None or lm.upper is None:
            return False
        return not lm.lower - 1e-12 <= value <= lm.upper + 1e-12

    def range_text(self) -> str:
        lm = self.limit
        if lm is None or lm.lower is None or lm.upper is None:
            return "unbounded"
        return f"[{self.show(lm.lower)}, {self.show(lm.upper)}]"

    def show(self, value: float) -> str:
        """A joint value for people: metres for prismatic, radians and degrees otherwise."""
        if self.type == "prismatic":
            return f"{value:.6g} m"
        return f"{value:.6g} rad ({math.degrees(value):.6g} deg)"


@record
class Sensor:
    """A sensor frame: ``link`` on a fixed joint; cameras also get ``optical_frame``."""

    name: str
    type: str  # camera | lidar | imu | generic
    link: str
    joint: str
    optical_frame: str | None = None
    optical_joint: str | None = None
    where: Where = NOWHERE


@record
class Interface:
    name: str
    min: float | None = None
    max: float | None = None
    initial_value: float | None = None
    data_type: str | None = None  # ros2_control's data_type attribute; None: not written (double)


@record
class ControlJoint:
    name: str
    command: tuple[Interface, ...] = ()
    state: tuple[Interface, ...] = ()
    on_limit: str = "reject"  # reject | clip: what the command/state boundary does beyond limits
    where: Where = NOWHERE
    mimic: str | None = None  # the ros2_control ``mimic`` attribute as written; None: not set
    params: tuple[tuple[str, str], ...] = ()  # joint-level <param>s (pre-Jazzy mimic lived here)
    block: str = ""  # name of the <ros2_control> block holding the joint


@record
class ControlSensor:
    """A ros2_control ``<sensor>``: state interfaces only, not checked against the URDF."""

    name: str
    state: tuple[Interface, ...] = ()
    where: Where = NOWHERE
    params: tuple[tuple[str, str], ...] = ()  # <param>s of the sensor (e.g. frame_id)
    frame: str | None = None  # the link the sensor measures in (spec only; checked against the model)
    block: str = ""  # name of the <ros2_control> block holding the sensor


@record
class ControlGpio:
    """A ros2_control ``<gpio>``: command and state interfaces, not checked against the URDF."""

    name: str
    command: tuple[Interface, ...] = ()
    state: tuple[Interface, ...] = ()
    where: Where = NOWHERE
    block: str = ""  # name of the <ros2_control> block holding the gpio
    params: tuple[tuple[str, str], ...] = ()  # <param>s of the gpio


@record
class HardwareVariant:
    """One value of the generated Xacro's ``hardware`` argument: the plugin and parameters of
    the ``<hardware>`` element when the description is expanded with ``hardware:=<name>``."""

    name: str  # mock | gazebo | real
    plugin: str
    params: tuple[tuple[str, str], ...] = ()
    where: Where = NOWHERE


@record
class HardwareBlock:
    """One ``<ros2_control>`` block's hardware (a robot may have several, one per bus)."""

    name: str
    plugin: str
    params: tuple[tuple[str, str], ...] = ()
    where: Where = NOWHERE
    type: str = "system"  # system | actuator | sensor
    variants: tuple[HardwareVariant, ...] = ()  # as Ros2Control.variants, for this block
    is_async: bool | None = None  # the is_async attribute; None: not written (ros2_control: false)
    rw_rate: int | None = None  # Hz; None: not written (ros2_control: the controller manager's rate)
    thread_priority: int | None = None  # an async block's thread priority; None: not written (50)
    group: str | None = None  # <hardware><group>: components of one group are read and written together


@record
class Calibrated:
    """A controller parameter measured on the robot (e.g. diff drive wheel_separation),
    checked against the value the URDF gives within ``tolerance`` (SI)."""

    param: str
    value: float
    tolerance: float | None = None
    source: str | None = None
    where: Where = NOWHERE


@record
class Controller:
    name: str
    type: str
    params: tuple[tuple[str, object], ...] = ()
    where: Where = NOWHERE
    calibrated: tuple[Calibrated, ...] = ()
    # where each parameter's value is written ("key", or "key[i]" for a list item; "type"
    # too); empty for a spec's controllers, whose findings stay at the controller
    marks: tuple[tuple[str, Where], ...] = ()

    def param(self, key: str, default: object = None) -> object:
        return dict(self.params).get(key, default)

    def where_of(self, key: str, index: int | None = None) -> Where:
        """The most specific known place of parameter ``key`` (item ``index`` of a list):
        the item, else the value, else the controller itself (e.g. for a missing key)."""
        marks = dict(self.marks)
        return marks.get(f"{key}[{index}]") or marks.get(key) or self.where


@record
class Ros2Control:
    name: str
    type: str = "system"
    plugin: str = "mock_components/GenericSystem"
    params: tuple[tuple[str, str], ...] = ()
    joints: tuple[ControlJoint, ...] = ()
    update_rate: float | None = None  # Hz
    controllers: tuple[Controller, ...] = ()
    where: Where = NOWHERE
    sensors: tuple[ControlSensor, ...] = ()
    blocks: tuple[HardwareBlock, ...] = ()  # every block read from a URDF; empty for a spec (one block)
    sim_plugins: tuple[tuple[str, Where], ...] = ()  # <gazebo><plugin filename> entries of the description
    # hardware variants selected by the Xacro argument ``hardware`` (spec only); empty: one hardware.
    # The first is the default, which ``plugin``/``params`` above describe.
    variants: tuple[HardwareVariant, ...] = ()
    gpios: tuple[ControlGpio, ...] = ()
    update_rate_where: Where = NOWHERE  # its value in an audited controllers file; else unknown
    is_async: bool | None = None  # the first block's is_async attribute; None: not written
    rw_rate: int | None = None  # the first block's, as HardwareBlock's
    thread_priority: int | None = None
    group: str | None = None

    def hardware_blocks(self) -> tuple[HardwareBlock, ...]:
        """Every ``<ros2_control>`` block in document order; a spec with one block has no
        ``blocks``, so it is the block described by the fields above."""
        first = HardwareBlock(
            self.name,
            self.plugin,
            self.params,
            self.where,
            self.type,
            self.variants,
            self.is_async,
            self.rw_rate,
            self.thread_priority,
            self.group,
        )
        return self.blocks or (first,)


@record
class Group:
    name: str
    links: tuple[str, ...] = ()
    joints: tuple[str, ...] = ()
    chains: tuple[tuple[str, str], ...] = ()
    subgroups: tuple[str, ...] = ()
    where: Where = NOWHERE


@record
class GroupState:
    name: str
    group: str
    values: tuple[tuple[str, float], ...]
    where: Where = NOWHERE
    # planar/floating (virtual) joints: every variable in MoveIt's order (x y theta; trans_x..z rot_x..w)
    multi: tuple[tuple[str, tuple[float, ...]], ...] = ()


@record
class EndEffector:
    name: str
    group: str
    parent_link: str
    parent_group: str | None = None
    where: Where = NOWHERE


@record
class VirtualJoint:
    name: str
    type: str
    parent_frame: str
    child_link: str
    where: Where = NOWHERE


@record
class DisabledPair:
    link1: str
    link2: str
    reason: str
    where: Where = NOWHERE


@record
class MatrixSettings:
    """How the self-collision matrix is sampled (``semantic.collision_matrix``)."""

    default_state: str | None = None  # a group state's name; None: the first group state
    seed: int = 0
    samples: int = 10000
    fraction: float = 0.95  # "Always": in collision in more than this fraction of samples
    padding: float = 0.0  # metres added around every collision shape
    where: Where = NOWHERE


@record
class CollisionMatrix:
    """The computed matrix (descgen/physics/collision.py): what generate writes into the SRDF."""

    settings: MatrixSettings
    input_hash: str  # the key (descgen/infra/keys.py) of geometry, joints, settings and libraries
    pairs: tuple[DisabledPair, ...]  # Adjacent, Default, Always, Never; sorted
    skipped: tuple[str, ...]  # links without collision geometry
    checked: int  # link pairs with geometry on both sides
    state: str  # the group state the Default test used ("" = all joints at zero)
    libraries: tuple[tuple[str, str], ...] = ()  # (distribution, version) that computed the pairs


@record
class Semantic:
    groups: tuple[Group, ...] = ()
    states: tuple[GroupState, ...] = ()
    end_effectors: tuple[EndEffector, ...] = ()
    virtual_joints: tuple[VirtualJoint, ...] = ()
    passive_joints: tuple[str, ...] = ()
    disabled_collisions: tuple[DisabledPair, ...] = ()
    where: Where = NOWHERE
    robot_name: str | None = None  # the SRDF's <robot name>; None for a spec's semantic (SRDF005)
    collision_matrix: MatrixSettings | None = None  # sample a matrix (generate fills ``matrix``)
    matrix: CollisionMatrix | None = None


@record
class FrameMeasurement:
    frame: str
    xyz: Vec3
    tolerance: float  # per axis, metres
    relative_to: str | None = None  # None: the root link
    source: str | None = None
    where: Where = NOWHERE


@record
class KnownPose:
    name: str
    joints: tuple[tuple[str, float], ...] = ()  # values not listed are zero
    frames: tuple[FrameMeasurement, ...] = ()
    source: str | None = None
    where: Where = NOWHERE
    # planar/floating virtual joints (as GroupState.multi): kept for the SRDF, outside the URDF's FK
    multi: tuple[tuple[str, tuple[float, ...]], ...] = ()
    # the positions are the nominal model's, not measured: judged without the calibration layer
    nominal: bool = False


@record
class ExternalFrame:
    parent: str
    child: str
    owner: str
    static: bool = False
    where: Where = NOWHERE

    @property
    def subject(self) -> str:
        return f"frame:{self.child}"


@record
class JointStateSource:
    node: str
    kind: str = "measured"  # measured | desired
    joints: tuple[str, ...] = ()  # empty: every joint
    where: Where = NOWHERE


@record
class PackageInfo:
    version: str = "0.1.0"
    maintainer: str = "descgen user"
    email: str = "maintainer@example.com"
    license: str = "Apache-2.0"
    name: str | None = None  # the spec's package.name; None: <robot>_description (mesh_paths.package_name)


@record
class Kinematics:
    """One planning group's IK settings (MoveIt's kinematics.yaml)."""

    group: str
    solver: str
    search_resolution: float
    timeout: float  # s


@record
class MoveItSettings:
    """What a team chooses for its MoveIt config package (spec ``moveit:``, SI); what the
    package derives from the rest of the robot is computed in descgen/moveit/."""

    kinematics: tuple[Kinematics, ...] = ()  # one per group written to kinematics.yaml
    velocity_scaling: float = 0.1
    acceleration_scaling: float = 0.1
    initial_state: str | None = None  # a group state; None: each joint at MoveIt's default value
    # Pilz cartesian limits: m/s, m/s^2, m/s^2 (negative, as MoveIt's Setup Assistant writes it), rad/s
    max_trans_vel: float = 1.0
    max_trans_acc: float = 2.25
    max_trans_dec: float = -5.0
    max_rot_vel: float = 1.57
    where: Where = NOWHERE


WAIVERS_FILE = "descgen-waivers.yaml"  # a generated package's waivers, at its root (audit reads it)


@record
class CalibrationSource:
    """Where calibration values come from (spec ``calibration.sources``)."""

    name: str
    method: str
    tool: str | None = None
    file: str | None = None
    date: str | None = None
    hash: str | None = None


@record
class JointCalibration:
    """One joint of the calibration layer: the nominal origin the spec states, and the corrections
    that give the robot as measured. ``Robot.joints`` hold the calibrated origin (descgen/physics/
    calibration.py: calibrated_origin); this record keeps the nominal one beside it. A sensor's
    mount is the same record for its ``<sensor>_joint``, with ``sensor`` set and the measured pose
    as ``replaced``."""

    joint: str
    source: str
    nominal: Pose
    calibrated: Pose
    offset: float = 0.0  # rad or m: the joint reports q and is at q + offset
    dxyz: Vec3 = (0.0, 0.0, 0.0)
    drpy: Vec3 = (0.0, 0.0, 0.0)
    sensor: str | None = None
    where: Where = NOWHERE


@record
class DriftCheck:
    """Samples of the running robot the evidence page compares the model with (spec
    ``calibration.drift``): an absolute path resolved beside the spec, inside the project."""

    samples: str
    frame: str
    base: str | None = None
    tolerance: float = 0.001
    parameters: tuple[str, ...] = ()
    where: Where = NOWHERE


@record
class Waiver:
    """A finding the team accepts for now (spec ``waivers:``): its code and subject exactly as
    findings print them, and why. The finding is still reported, as waived; it fails nothing."""

    code: str
    subject: str
    reason: str
    where: Where = NOWHERE


@record
class Mounted:
    """A robot composed into this one (spec ``compose:``; descgen/spec/compose.py): whose spec,
    behind which prefix, hung from which frame by which fixed joint."""

    robot: str
    spec: str  # the spec file as the composing spec names it
    prefix: str
    parent: str
    joint: str
    where: Where = NOWHERE


@record
class NamePrefix:
    """The prefix every name of one robot carries, so robots share a ROS graph (ROS 2 has no
    tf_prefix): where a description declares it (a Xacro's ``prefix`` or ``tf_prefix`` argument,
    the convention of ros2_control_demos and the UR description). NAME014 checks it."""

    value: str
    declared: str  # how the finding names the declaration, e.g. "the Xacro argument tf_prefix"
    where: Where = NOWHERE


@record
class Robot:
    name: str
    links: tuple[Link, ...] = ()
    joints: tuple[Joint, ...] = ()
    materials: tuple[Material, ...] = ()
    sensors: tuple[Sensor, ...] = ()
    ros2_control: Ros2Control | None = None
    semantic: Semantic | None = None
    known_poses: tuple[KnownPose, ...] = ()
    description: str | None = None
    package: PackageInfo = PackageInfo()
    external_frames: tuple[ExternalFrame, ...] = ()
    joint_state_sources: tuple[JointStateSource, ...] = ()
    where: Where = NOWHERE
    spec_hash: str | None = None
    # Plausible density (kg/m^3, low and high) from a spec's ``plausibility.density``; None:
    # units.DEFAULT_RANGES (UNIT010). Kept as numbers so the model needs no unit parser.
    density_range: tuple[float, float] | None = None
    # (mesh filename, state) for every mesh of a read description (audit/inputs.mesh_status);
    # empty when nobody resolved the files, e.g. a spec loaded for generation (GEOM003-005).
    mesh_status: tuple[tuple[str, MeshState], ...] = ()
    # (mesh filename, absolute path of the file it resolved to) for every mesh found on disk
    # (descgen/meshes/paths.py). A spec's own meshes are already renamed here to
    # package://<robot>_description/meshes/..., and the path is the source file beside the spec.
    mesh_files: tuple[tuple[str, str], ...] = ()
    # XML elements the spec cannot express (spec ``passthrough:``), written verbatim into the URDF
    passthrough: tuple[str, ...] = ()
    # fixed joints a <gazebo reference="joint"> keeps from sdformat's lumping (preserveFixedJoint or
    # disableFixedJointLumping); read from a URDF, empty for a spec (GEOM040, GEOM041)
    sdf_preserved_joints: tuple[str, ...] = ()
    # the spec's ``moveit:`` section: generate writes <robot>_moveit_config/ when it is set
    moveit: MoveItSettings | None = None
    # a MoveIt config package read with the robot (``audit --moveit-config``; the MOVEIT rules)
    moveit_config: MoveItConfig | None = None
    # the spec's ``waivers:`` (descgen/audit/waivers.py); empty for a description
    waivers: tuple[Waiver, ...] = ()
    # the spec's ``calibration:`` layer; the joints above already hold the calibrated origins
    calibration: tuple[JointCalibration, ...] = ()
    calibration_sources: tuple[CalibrationSource, ...] = ()
    drift_check: DriftCheck | None = None
    # (block name, Jazzy's component parser's own message, where) for every throw the parser would
    # raise on the <ros2_control> blocks of a read description or of a spec's pass-through
    # (descgen/physics/component_parser.py; CTRL066)
    control_refusals: tuple[tuple[str, str, Where], ...] = ()
    # the declared name prefix (NAME014); None: the robot declares none
    prefix: NamePrefix | None = None
    # the spec's ROS namespace for the launch files' nodes; None: the root namespace
    namespace: str | None = None
    # the robots a spec's compose: mounted into this one, in order
    mounted: tuple[Mounted, ...] = ()

    # Lookups. Broken descriptions may repeat names; these return the first. The indexes
    # are built once per (immutable) robot, so rules stay linear on 1000-link chains.
    @functools.cached_property
    def _links_by_name(self) -> dict[str, Link]:
        out: dict[str, Link] = {}
        for lk in self.links:
            out.setdefault(lk.name, lk)
        return out

    @functools.cached_property
    def _joints_by_name(self) -> dict[str, Joint]:
        out: dict[str, Joint] = {}
        for j in self.joints:
            out.setdefault(j.name, j)
        return out

    @functools.cached_property
    def _parent_joint_of(self) -> dict[str, Joint]:
        out: dict[str, Joint] = {}
        for j in self.joints:
            if j.child is not None:
                out.setdefault(j.child, j)
        return out

    @functools.cached_property
    def _children_of(self) -> dict[str, list[Joint]]:
        out: dict[str, list[Joint]] = {}
        for j in self.joints:
            if j.parent is not None:
                out.setdefault(j.parent, []).append(j)
        return out

    @functools.cached_property
    def _bodies(self) -> dict[str, frozenset[str]]:
        """Links welded together by fixed joints, per link (one rigid body).

        Every link of a body maps to the same frozenset, and the smaller group is merged into
        the larger: memory and time stay linear in the links (10,000 welded links)."""
        group: dict[str, set[str]] = {lk.name: {lk.name} for lk in self.links}
        for j in self.joints:
            if j.type == "fixed" and j.parent in group and j.child in group:
                a, b = group[j.parent], group[j.child]
                if a is not b:
                    if len(a) < len(b):
                        a, b = b, a
                    a |= b
                    for name in b:
                        group[name] = a
        frozen: dict[int, frozenset[str]] = {}
        for g in group.values():
            if id(g) not in frozen:
                frozen[id(g)] = frozenset(g)
        return {name: frozen[id(g)] for name, g in group.items()}

    def body_of(self, link: str) -> frozenset[str]:
        """``link`` and every link welded to it by fixed joints."""
        return self._bodies.get(link, frozenset({link}))

    def link(self, name: str) -> Link | None:
        return self._links_by_name.get(name)

    def joint(self, name: str) -> Joint | None:
        return self._joints_by_name.get(name)

    def child_joints(self, link: str) -> Iterator[Joint]:
        return iter(self._children_of.get(link, ()))

    def parent_joint(self, link: str) -> Joint | None:
        return self._parent_joint_of.get(link)

    def roots(self) -> list[str]:
        children = set(self._parent_joint_of)
        return list(dict.fromkeys(lk.name for lk in self.links if lk.name not in children))

    def root(self) -> str | None:
        roots = self.roots()
        return roots[0] if len(roots) == 1 else None

    def tree_joints(self) -> Iterator[Joint]:
        """The joints that reach a new link from the root, each parent before its child (depth
        first, a link's joints in file order): what forward kinematics composes. Safe on cycles
        and on links reached twice (the first joint wins); nothing without a single root."""
        root = self.root()
        if root is None:
            return
        seen = {root}
        todo = [root]
        while todo:
            parent = todo.pop()
            for j in self.child_joints(parent):
                if j.child is None or j.child in seen:
                    continue
                seen.add(j.child)
                yield j
                todo.append(j.child)

    def descendants(self, link: str) -> list[str]:
        """Every link below ``link``, nearest first; safe on cycles."""
        out: list[str] = []
        seen: set[str] = {link}
        todo = [link]
        while todo:
            for j in self.child_joints(todo.pop(0)):
                if j.child and j.child not in seen:
                    seen.add(j.child)
                    out.append(j.child)
                    todo.append(j.child)
        return out

    def chain_joints(self, base: str, tip: str) -> list[Joint]:
        """Joints from ``base`` down to ``tip`` (empty if ``base`` is not above ``tip``)."""
        path = self.path_to_root(tip)
        for i, j in enumerate(path):
            if j.parent == base:
                return path[i:]
        return []

    def group_joints(self, group: str) -> list[Joint]:
        """Every joint of a planning group, in tree order (chains, joints, links' parent joints, subgroups)."""
        sem = self.semantic
        if sem is None:
            return []
        out: list[Joint] = []
        todo, seen = [group], set()
        while todo:
            g = next((x for x in sem.groups if x.name == todo[0]), None)
            seen.add(todo.pop(0))
            if g is None:
                continue
            for base, tip in g.chains:
                out += self.chain_joints(base, tip)
            out += [j for n in g.joints if (j := self.joint(n)) is not None]
            out += [j for n in g.links if (j := self.parent_joint(n)) is not None]
            todo += [s for s in g.subgroups if s not in seen]
        unique: list[Joint] = []
        for j in out:
            if all(j is not u for u in unique):
                unique.append(j)
        return unique

    def path_to_root(self, link: str) -> list[Joint]:
        """Joints from the root down to ``link`` (empty for the root); stops on cycles."""
        chain: list[Joint] = []
        seen: set[str] = set()
        cur = link
        while cur not in seen:
            seen.add(cur)
            j = self.parent_joint(cur)
            if j is None or j.parent is None:
                break
            chain.append(j)
            cur = j.parent
        chain.reverse()
        return chain
