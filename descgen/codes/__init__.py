"""The one catalogue of finding codes: every code any command can print, with its rationale.

Audit rules register themselves with ``@rule`` (descgen/audit/registry.py) and their
docstring is their documentation. Every other code (the spec loader, the readers,
``generate``/``check``, ``control``, the recording commands, the command line) is a
:class:`Code` entry below. :func:`explain` and :func:`entries` read both, so
``descgen rules CODE`` and SARIF rule help cover every code.

Codes are stable: a code keeps its meaning, and a retired code is never reused (keep
its entry, marked retired). A code registered twice fails at import time, here or in
``@rule``.
"""

from __future__ import annotations

from typing import Literal

from descgen.core.findings import Severity
from descgen.core.record import record

SeverityOrVaries = Severity | Literal["varies"]

# Where a code comes from, in the order ``descgen rules`` lists them.
GROUPS: dict[str, str] = {
    "spec": "reading a spec (YAML, schema, units)",
    "rule": "whole-model rules (validate, audit)",
    "read": "reading third-party descriptions (URDF, Xacro, SRDF, controllers YAML)",
    "generate": "generate and check (the proofs of the written package)",
    "control": "descgen control (trajectory, options, the ros2_control model)",
    "recording": "recordings (tf-audit, tf-scenario)",
    "simulate": "descgen simulate (MuJoCo as a consumer)",
    "import": "descgen import (a URDF or Xacro becomes a spec)",
    "command": "the command line",
    "sweep": "descgen sweep (each joint through its range: directions and self-collisions)",
}


@record
class Code:
    """A finding code that is not an audit rule."""

    code: str
    name: str  # short kebab-case name
    severity: SeverityOrVaries
    group: str  # a key of GROUPS
    summary: str  # one line: what it reports
    rationale: str  # why it matters and what to do


@record
class Entry:
    """What the catalogue knows about one code, rule or not."""

    code: str
    name: str
    severity: SeverityOrVaries
    group: str
    summary: str
    doc: str  # markdown: a rule's docstring, or the summary and rationale

    @property
    def is_rule(self) -> bool:
        return self.group == "rule"


CODES: dict[str, Code] = {}
NAMES: set[str] = set()  # the names in CODES: a duplicate is found without scanning CODES


def register(*codes: Code) -> None:
    """Add codes to the catalogue; a code or name registered twice is a bug, raised now."""
    for c in codes:
        if c.code in CODES:
            raise ValueError(f"duplicate finding code {c.code}")
        if c.name in NAMES:
            raise ValueError(f"duplicate code name {c.name} ({c.code})")
        if c.group not in GROUPS or c.group == "rule":
            raise ValueError(f"code {c.code}: unknown group {c.group!r}")
        if not c.summary.strip() or not c.rationale.strip():
            raise ValueError(f"code {c.code} needs a summary and a rationale")
        CODES[c.code] = c
        NAMES.add(c.name)


def doc_of(c: Code) -> str:
    return f"## What it reports\n{c.summary}\n\n## Why it matters\n{c.rationale}\n"


def C(  # noqa: N802 - a compact table row
    code: str, name: str, severity: SeverityOrVaries, group: str, summary: str, rationale: str
) -> Code:
    return Code(code, name, severity, group, summary, " ".join(rationale.split()))


# --------------------------------------------------------------------------- reading a spec
register(
    C(
        "YAML001",
        "yaml-unreadable",
        "error",
        "spec",
        "The spec is not well-formed YAML, or uses YAML that is refused "
        "(merge keys, non-scalar keys, unbuildable tags, too deep, too many nodes).",
        """Nothing can be checked in a file that does not parse, and some YAML features (aliases that
      expand exponentially, tags, merge keys) hide what a value really is. Fix the YAML at the given
      line; write keys out instead of merging them.""",
    ),
    C(
        "YAML002",
        "spec-not-found",
        "error",
        "spec",
        "The spec file (or a folder of specs) could not be read.",
        """A missing or unreadable file is a typo in the path or a permission problem. Check the path;
      a folder must hold *.yaml specs.""",
    ),
    C(
        "YAML003",
        "spec-not-text",
        "error",
        "spec",
        "The spec is binary, not UTF-8, or larger than the size limit.",
        """A spec is a few kilobytes of UTF-8 text; anything else is the wrong file, and reading a huge
      one would exhaust memory (docs/security.md). Save the spec as UTF-8 text.""",
    ),
    C(
        "YAML004",
        "spec-empty",
        "error",
        "spec",
        "The spec file is empty.",
        """An empty file describes no robot. Write a spec (see specs/warehouse_arm.yaml).""",
    ),
    C(
        "YAML010",
        "spec-not-regular-file",
        "error",
        "spec",
        "The named spec is a FIFO, device, socket or folder.",
        """Reading a FIFO or a device can block forever or never end, so it is refused before it is
      opened (docs/security.md). Name a regular file.""",
    ),
    C(
        "SPEC100",
        "collision-matrix-unknown-state",
        "error",
        "spec",
        "semantic.collision_matrix.default_state names no group state of the spec.",
        """The Default reason disables pairs in collision at that state; a misspelt name would fall back
      to another pose and disable the wrong pairs. Name one of semantic.group_states.""",
    ),
    C(
        "SPEC101",
        "collision-matrix-padding-range",
        "error",
        "spec",
        "semantic.collision_matrix.padding is negative or larger than 100 mm.",
        """Padding inflates every collision shape while sampling: a large value makes near pairs look
      Always or Default and disables checks MoveIt needs; a negative one shrinks shapes and marks
      touching pairs Never. Use 0 to a few millimetres.""",
    ),
    C(
        "SPEC110",
        "moveit-acceleration-missing",
        "error",
        "spec",
        "With moveit:, a joint of a planning group has no limit.acceleration.",
        """MoveIt on Jazzy refuses to time-parameterise a trajectory for a joint without an acceleration
      limit ("No acceleration limit was defined for joint", TOTG), and Pilz PTP throws; a URDF has no
      acceleration attribute, so joint_limits.yaml is the only place for it. State the team's chosen
      limit with its source under the joint's limit: (e.g. 'acceleration: 180 deg/s^2').""",
    ),
    C(
        "SPEC111",
        "moveit-velocity-missing",
        "error",
        "spec",
        "With moveit:, a joint of a planning group has no (positive) velocity limit.",
        """TOTG refuses a joint without a bounded velocity ("No velocity limit was defined for joint"), so
      the MoveIt package would plan nothing for the group. Add limit: with velocity and acceleration.""",
    ),
    C(
        "SPEC112",
        "moveit-kinematics-unknown-group",
        "error",
        "spec",
        "moveit.kinematics names a group the spec does not define.",
        """MoveIt skips kinematics.yaml entries for groups missing from the SRDF, so a misspelt group
      silently keeps no IK solver. Name one of semantic.groups.""",
    ),
    C(
        "SPEC113",
        "moveit-initial-state-unknown",
        "error",
        "spec",
        "moveit.initial_state names no group state of the spec.",
        """initial_positions.yaml is written from that state; a misspelt name would silently start the
      demo at another pose. Name one of semantic.group_states.""",
    ),
    C(
        "SPEC114",
        "moveit-group-without-controller",
        "warning",
        "spec",
        "With moveit:, no ros2_control action-server controller commands some joints of a planning group.",
        """MoveIt executes through controllers listed in moveit_controllers.yaml; without one for the group
      it can plan but execution fails ("Unable to identify any set of controllers that can actuate the
      specified joints"). Add a joint_trajectory_controller for the group's joints, or accept plan-only use.""",
    ),
    C(
        "SPEC115",
        "moveit-without-groups",
        "error",
        "spec",
        "moveit: is set, but the spec has no semantic.groups.",
        """A MoveIt config package plans for SRDF groups; without one there is nothing to configure.""",
    ),
    C(
        "SPEC116",
        "moveit-limit-not-positive",
        "error",
        "spec",
        "A MoveIt limit that is a magnitude (joint acceleration, Pilz limits, IK timeout) is zero or negative.",
        """TOTG rejects a negative max_acceleration, and zero stops every motion; Pilz and the IK plugins
      read these as magnitudes. Write a positive value with its unit.""",
    ),
    C(
        "SPEC120",
        "package-name-not-rep144",
        "error",
        "spec",
        "The generated package's name (package.name, or <robot>_description) does not start with a "
        "lowercase letter or is no REP 144 name.",
        """The package name is package.xml's <name>, the CMake project, FindPackageShare in the launch
      files and every package:// URI; colcon, rosdep and the ament index expect REP 144 names (lowercase
      letters, digits and single '_', starting with a letter). A robot named 2dof_planar is a good URDF
      name but its package cannot be 2dof_planar_description: add package: {name: ...} with the
      suggested name (the robot and its files keep their name).""",
    ),
    C(
        "SPEC121",
        "derived-package-name-advice",
        "warning",
        "spec",
        "The derived package name <robot>_description has uppercase letters or '__' (REP 144 says it must not).",
        """catkin_pkg accepts such a name with a warning, so specs that generated before still do; but
      REP 144 requires lowercase (file systems without case) and no '__' (generated symbols use it as a
      separator). Add package: {name: ...} with the suggested name.""",
    ),
    C(
        "SPEC125",
        "multi-dof-value-count",
        "error",
        "spec",
        "A group-state or known-pose value has the wrong number of values for its joint type.",
        """srdfdom reads one number per variable, and MoveIt (RobotModel::buildGroupStates) drops a joint's
      value whose count differs from the joint model's variables, with only a log line: planar takes x, y,
      theta, floating trans_x..z and rot_x..w (planar_joint_model.cpp, floating_joint_model.cpp), a 1-DOF
      joint exactly one. The hint shows a list in that order.""",
    ),
    C(
        "SPEC126",
        "floating-value-not-unit-quaternion",
        "error",
        "spec",
        "A floating joint's group-state value has a rotation that is not a unit quaternion (within 1e-9).",
        """MoveIt renormalises such a quaternion silently (FloatingJointModel::normalizeRotation), so the
      pose the SRDF names is not the one written; a typo in a component goes unnoticed.""",
    ),
    C(
        "SPEC127",
        "quaternion-component-not-a-number",
        "error",
        "spec",
        "A quaternion component of a floating joint's value is not a plain number.",
        """rot_x..rot_w have no unit; a text such as "1 deg" or "a" would be a guess about what was meant.""",
    ),
    C(
        "SPEC001",
        "unknown-key",
        "error",
        "spec",
        "A key the spec schema does not know (usually a typo).",
        """Unknown keys are errors, not ignored, because a misspelt key (`orgin:`) would silently drop
      the value the author meant. Use the suggested key, or remove it; `descgen schema` lists the keys.""",
    ),
    C(
        "SPEC002",
        "missing-key",
        "error",
        "spec",
        "A required key is missing.",
        """Without it the element cannot be built (a joint needs parent, child and type). Add the key;
      the hint names it.""",
    ),
    C(
        "SPEC003",
        "wrong-value-type",
        "error",
        "spec",
        "A value has the wrong type or is not one of the allowed "
        "choices (e.g. a joint type, a source that is not text, a spec that is not a mapping).",
        """A value of the wrong shape cannot mean what the author intended. Write one of the allowed
      values; `descgen schema` gives the form of every field.""",
    ),
    C(
        "SPEC004",
        "ambiguous-shape",
        "error",
        "spec",
        "A shape or material is over- or under-specified "
        "(both radius and diameter, not exactly one geometry, a material without rgba or texture).",
        """Two values for one thing can disagree, and none leaves it undefined. Keep exactly the one
      you measured.""",
    ),
    C(
        "SPEC005",
        "duplicate-key",
        "error",
        "spec",
        "A mapping holds the same key twice.",
        """YAML keeps the last one silently, so the first value (often the measured one) would be lost
      without a word. Remove or rename one of them.""",
    ),
    C(
        "SPEC010",
        "value-without-source",
        "error",
        "spec",
        "With require_sources: true, a measured value has no source on itself or on an element that contains it.",
        """A value that cites no measurement cannot be reviewed or re-checked. Add source: <row ID> to
      the value or its element, or set require_sources: false.""",
    ),
    C(
        "SPEC020",
        "control-character",
        "error",
        "spec",
        "A spec text holds a control character.",
        """XML (URDF, SRDF, package.xml) cannot hold control characters, and printed ones can rewrite a
      terminal or forge output lines (docs/security.md). Remove it.""",
    ),
    C(
        "SPEC021",
        "line-break-in-one-line-value",
        "error",
        "spec",
        "A value that is written as one line (an XML attribute, a name) contains a line break or tab.",
        """An XML attribute reads a line break back as a space, so the value would not round-trip, and
      a line break in a one-line output can inject text. Write it on one line.""",
    ),
    C(
        "SPEC022",
        "part-named-like-xacro-tag",
        "error",
        "spec",
        "A part is named like a Xacro directive (property, include, macro, ...).",
        """The part's macro would be called as <xacro:NAME>, which Xacro reads as its own directive, so
      the generated Xacro would not call the part. Rename the part (e.g. NAME_part).""",
    ),
    C(
        "SPEC023",
        "no-links",
        "error",
        "spec",
        "The spec has no links.",
        """A URDF needs at least one <link>; generate would write a file urdfdom refuses. Add the root
      link.""",
    ),
    C(
        "SPEC024",
        "duplicate-semantic-name",
        "error",
        "spec",
        "A name is declared twice in one semantic section (groups, group states, end effectors, ...).",
        """The SRDF keeps one element per name, so MoveIt would see only one of the two. Remove or rename
      the second.""",
    ),
    C(
        "SPEC025",
        "package-field-refused",
        "error",
        "spec",
        "A package email, version, maintainer or license that catkin_pkg refuses.",
        """colcon and rosdep parse package.xml with catkin_pkg; a value it refuses breaks the build of
      the generated package. Write a valid email, a MAJOR.MINOR.PATCH version and a non-empty name
      and license.""",
    ),
    C(
        "SPEC026",
        "duplicate-material-name",
        "error",
        "spec",
        "Two entries of materials: have the same name.",
        """urdfdom refuses a URDF whose robot-level materials are not unique ("material 'x' is not unique"),
      so robot_state_publisher, pinocchio's collision matrix and check_urdf all fail on the generated
      file. Remove the second entry or rename it (and the visuals that use it).""",
    ),
    C(
        "SPEC080",
        "variants-without-mock-default",
        "error",
        "spec",
        "ros2_control.hardware declares variants but its own plugin is not mock_components/GenericSystem.",
        """With variants, hardware.plugin/params are the `mock` variant, the default of the generated
      Xacro's `hardware` argument and the hardware of the generated URDF. A vendor plugin there would
      make the default description drive the real robot. Put the vendor plugin under variants.real.""",
    ),
    C(
        "SPEC081",
        "gazebo-variant-plugin",
        "error",
        "spec",
        "The gazebo hardware variant names a plugin other than gz_ros2_control/GazeboSimSystem.",
        """Jazzy pairs with Gazebo Harmonic, whose ros2_control plugin is gz_ros2_control/GazeboSimSystem
      (docs/ros2_control_jazzy.md §6); gazebo_ros2_control (Gazebo Classic) is not released for
      Jazzy. Leave the plugin out (it defaults to GazeboSimSystem) or write it.""",
    ),
    C(
        "SPEC082",
        "real-variant-plugin",
        "error",
        "spec",
        "The real hardware variant has no plugin, or names the mock or Gazebo plugin.",
        """hardware:=real must load the robot's driver; a mock or simulation plugin there would make a
      launch on the robot silently move nothing. Name the vendor's hardware plugin.""",
    ),
    C(
        "SPEC083",
        "control-sensor-frame-unknown",
        "error",
        "spec",
        "A ros2_control sensor's frame is not a link of the robot.",
        """The frame is written as the sensor's frame_id parameter, and the broadcasters stamp their
      messages with it; tf cannot place data in a frame that does not exist. Name a link (a sensor
      link is <name>_link).""",
    ),
    C(
        "SPEC084",
        "control-interface-repeated",
        "error",
        "spec",
        "A ros2_control sensor or gpio lists the same interface twice, or two components share a name.",
        """ros2_control exports `<component>/<interface>` once; the resource manager refuses a second
      interface with the same full name, so the hardware would not load. Remove the duplicate.""",
    ),
    C(
        "SPEC085",
        "control-component-in-two-blocks",
        "error",
        "spec",
        "A joint, sensor or gpio is in two ros2_control blocks.",
        """Every block's interfaces go into one map of the resource manager, keyed `<component>/<interface>`;
      a second one with the same key throws "ResourceStorage: Tried to insert ... with already existing
      key" (ros2_control jazzy, hardware_interface/src/resource_manager.cpp), so no hardware loads.
      Keep each component in one block.""",
    ),
    C(
        "SPEC086",
        "control-block-name-repeated",
        "error",
        "spec",
        "Two ros2_control blocks have the same name.",
        """The resource manager keys hardware components by name and stops loading at a repeated one:
      "Hardware name %s is duplicated. Please provide a unique 'name' in the URDF."
      (hardware_interface/src/resource_manager.cpp, load_and_initialize_components).""",
    ),
    C(
        "SPEC087",
        "sensor-block-with-commands",
        "error",
        "spec",
        "A ros2_control block of type sensor declares command interfaces.",
        """A sensor component exports no command interfaces (hardware_interface/sensor_interface.hpp,
      on_export_command_interfaces returns {}) and is never written, so the commands would not exist
      and every controller claiming one fails to activate. Make the block a system or drop the commands.""",
    ),
    C(
        "SPEC088",
        "system-plugin-in-non-system-block",
        "error",
        "spec",
        "An actuator or sensor block uses mock_components/GenericSystem or gz_ros2_control/GazeboSimSystem.",
        """Both are registered with pluginlib only as hardware_interface::SystemInterface
      (hardware_interface/mock_components_plugin_description.xml; gz_ros2_control's GazeboSimSystemInterface),
      so the resource manager cannot load them for an actuator or sensor component. Make the block a system.""",
    ),
    C(
        "SPEC089",
        "control-block-variants-differ",
        "error",
        "spec",
        "A further ros2_control block declares other hardware variants than the first block.",
        """One Xacro argument, hardware:=mock|gazebo|real, selects the hardware of every block; a block
      without the selected variant would keep a mock (or no) plugin on the real robot or in Gazebo.
      Declare the same variants under every block's hardware.""",
    ),
    C(
        "SPEC050",
        "invalid-name",
        "error",
        "spec",
        "A name in the spec does not match the pattern its field requires (e.g. an identifier).",
        """Link, joint, frame, controller and package names reach URDF, tf, ros2_control and file names;
      ROS tools refuse or misread names with spaces, dashes or leading digits. Until issue 10 this
      was reported as NAME001, which is the duplicate-link-name rule. Rename it as the hint says.""",
    ),
    C(
        "SPEC060",
        "mesh-not-found",
        "error",
        "spec",
        "A mesh the spec references does not exist (relative to the spec, or in the package named by package://).",
        """generate would write a package whose URDF names a file that is not there: RViz shows nothing
      and collision checking loses the part, while every other check passes. Fix the path, or add
      the file beside the spec (descgen/meshes/paths.py).""",
    ),
    C(
        "SPEC061",
        "mesh-path-escapes",
        "error",
        "spec",
        "A mesh path leaves the spec's folder or its package (.., an absolute path, file://, a link out).",
        """A spec is someone else's data: it may name only files beside it or in the packages it lists,
      or validating it could read (and generate copy) any file of the machine, like /etc/passwd
      (docs/security.md). Keep the mesh in the spec's folder, or name it with package://.""",
    ),
    C(
        "SPEC062",
        "mesh-package-unknown",
        "error",
        "spec",
        "A package:// mesh names a package no folder of the spec's package_paths holds (or the generated one).",
        """The package must be found to check the file and to depend on it (exec_depend). Record the
      folder holding the package under package_paths: (relative to the spec); for the robot's own
      meshes, write a path relative to the spec, which generate copies into the package.""",
    ),
    C(
        "SPEC063",
        "mesh-not-a-file",
        "error",
        "spec",
        "A mesh path names a folder, FIFO or device, or a file larger than the mesh limit (64 MiB).",
        """Meshes are read and copied; a FIFO would block, a device never ends, and a huge file is not a
      robot part. Name the mesh file itself.""",
    ),
    C(
        "SPEC064",
        "spec-folder-unusable",
        "error",
        "spec",
        "A package_paths or templates entry is absolute, leaves the project folder, or is not a folder.",
        """Recorded folders make every command and every machine resolve the same files, so they are
      relative to the spec; they stay inside the project (the folder holding specs/) so a spec
      cannot point descgen at the rest of the machine.""",
    ),
    C(
        "SPEC065",
        "mesh-copy-clash",
        "error",
        "spec",
        "Two different mesh files would be copied to the same place in the package.",
        """A path relative to the spec is copied to meshes/<path> (a leading meshes/ is not doubled), so
      meshes/a.stl and a.stl both land on meshes/a.stl and one would silently replace the other.
      Move or rename one of them.""",
    ),
    C(
        "UNIT001",
        "missing-unit",
        "error",
        "spec",
        "A quantity is a bare number (or not a quantity at all) where a value with a unit is expected.",
        """A bare 300 could be millimetres or metres; reading it in the wrong unit is off by 1000 and
      nothing downstream could tell. Write the unit it was measured in; the hint suggests one that
      fits the field's kind and the number's size. Exactly 0 needs no unit.""",
    ),
    C(
        "UNIT002",
        "unreadable-quantity",
        "error",
        "spec",
        "Quantity text that pint cannot read, is empty, holds a comma, or is not finite.",
        """pint would misread some text ("1,5 m" is 15 m), and a NaN or infinite value poisons every
      computation. Write a number and a unit, e.g. "300 mm", with a decimal point.""",
    ),
    C(
        "UNIT003",
        "wrong-kind-of-quantity",
        "error",
        "spec",
        "A quantity of the wrong kind for its field "
        "(a mass where a length belongs, an angle unit where none is allowed, an energy for a torque).",
        """Converting it would produce a number in the wrong SI unit. Write a quantity of the field's
      kind; the hint gives an example.""",
    ),
    C(
        "UNIT004",
        "implausible-value",
        "error",
        "spec",
        "A value outside the plausible range for its role (offset, size, mass, joint travel, ...).",
        """The ranges are wide on purpose: they catch values a thousand times off (millimetres typed as
      metres, grams as kilograms), not design choices. Fix the unit, or widen plausibility.<role> in
      the spec if the value is right.""",
    ),
    C(
        "UNIT020",
        "quantity-too-complex",
        "error",
        "spec",
        "Quantity text that is too long, has too many "
        "digits, or raises to a power pint would need unbounded time to evaluate.",
        """pint evaluates quantity text as arithmetic, so "9**9**9 kg" would hang; such text is refused
      before pint sees it (docs/security.md). Write a plain number and unit.""",
    ),
    C(
        "INER010",
        "inertia-not-derivable",
        "error",
        "spec",
        "inertial from: visual/collision, but the link has no such geometry.",
        """descgen derives a tensor from a box, cylinder, sphere or watertight mesh (INER030, INER031);
      without one the link would get no tensor. Add a shape, or give the inertia explicitly (e.g. from CAD).""",
    ),
    C(
        "INER030",
        "mesh-inertia-not-watertight",
        "error",
        "spec",
        "inertial from: a mesh that is not watertight (open edges or inconsistent winding), or bounds no volume.",
        """An open mesh bounds no solid, so its volume, centre of mass and tensor are meaningless numbers
      (trimesh warns the same). Close the mesh in CAD (or export its convex hull as the collision), or give
      the inertia explicitly.""",
    ),
    C(
        "INER031",
        "mesh-inertia-unreadable",
        "error",
        "spec",
        "inertial from: a mesh whose file cannot be found or read (format, size, triangle count, parser error).",
        """Without the mesh there is nothing to integrate; a guessed tensor would be worse than none.
      Fix the path (relative to the spec), convert the file to STL, OBJ or DAE, or give the inertia explicitly.""",
    ),
    C(
        "INER032",
        "inertia-not-finite",
        "error",
        "spec",
        "inertial from: a shape whose computed tensor overflows (inf or nan), with plausibility ranges widened.",
        """A mass and a size at the edge of the floats (1e300 kg, 1e200 m) give moments beyond them; no
      simulator or rule can use an infinite tensor. Give a mass and size a real part has, or the inertia
      explicitly.""",
    ),
    C(
        "SRDF010",
        "group-state-unknown-pose",
        "error",
        "spec",
        "A semantic group state names a known pose that the spec does not define.",
        """The SRDF group state is written from the known pose's joint values; with no such pose there
      is nothing to write. Name one of the known poses.""",
    ),
)

# --------------------------------------------------------------------------- third-party files
register(
    C(
        "READ001",
        "description-unreadable",
        "error",
        "read",
        "A description file is missing, unreadable, or not well-formed XML.",
        """Nothing in a file that does not parse can be audited. Check the path, or fix the XML at the
      given position.""",
    ),
    C(
        "READ002",
        "xml-doctype",
        "error",
        "read",
        "An XML description declares a DTD (<!DOCTYPE ...>).",
        """Entities in a DTD can expand exponentially or read local files (XXE); URDF and SRDF need no
      DTD, so it is refused. Remove the declaration.""",
    ),
    C(
        "READ003",
        "not-a-urdf",
        "error",
        "read",
        "The XML root element is not <robot>.",
        """The file is probably not a URDF (a launch file, an SDF). Name the robot's URDF or Xacro.""",
    ),
    C(
        "READ004",
        "xacro-failed",
        "error",
        "read",
        "xacro could not expand the file.",
        """A Xacro that does not expand gives no robot to audit; usually an argument or a package path
      is missing. Pass --xacro-arg NAME:=VALUE and --package-path DIR.""",
    ),
    C(
        "READ005",
        "bad-xacro-arg-option",
        "error",
        "read",
        "A --xacro-arg option is not NAME:=VALUE.",
        """xacro's argument syntax is name:=value; anything else would be silently ignored. Write e.g.
      --xacro-arg use_gripper:=true.""",
    ),
    C(
        "READ010",
        "urdf-value-malformed",
        "error",
        "read",
        "A URDF attribute or element is malformed "
        "(wrong count of numbers, not numbers, an empty <geometry>, a missing required attribute).",
        """urdfdom refuses or misreads such values, so the robot would not load in ROS. Write the value
      as the URDF specification requires; the message names the element.""",
    ),
    C(
        "READ011",
        "srdf-value-not-one-number",
        "varies",
        "read",
        "An SRDF group-state joint value is not one number (a warning for multi-DOF values, an error otherwise).",
        """Group states of 1-DOF joints are one number; descgen cannot check other values against the
      URDF limits. Write one number per 1-DOF joint.""",
    ),
    C(
        "READ012",
        "robot-without-name",
        "error",
        "read",
        "<robot> has no name attribute.",
        """urdfdom refuses a robot without a name. Add name="..." to <robot>.""",
    ),
    C(
        "READ013",
        "robot-without-links",
        "error",
        "read",
        "The robot has no links.",
        """urdfdom refuses an empty robot; this is usually the wrong file or a Xacro whose arguments
      switched everything off.""",
    ),
    C(
        "READ020",
        "controllers-not-mapping",
        "error",
        "read",
        "A controllers YAML file is not a mapping.",
        """controller_manager reads a mapping of node names to ros__parameters; anything else configures
      nothing. Check that this is the controllers file.""",
    ),
    C(
        "READ030",
        "xacro-code-refused",
        "error",
        "read",
        "An audited Xacro expression uses code outside the restricted evaluator's allow-list.",
        """xacro evaluates ${} and $(eval) as Python, so an audited file could run code. descgen's
      evaluator allows arithmetic, math and properties only (docs/security.md). If you trust the file,
      pass --trust-xacro.""",
    ),
    C(
        "READ031",
        "xacro-file-outside-package",
        "error",
        "read",
        "An audited Xacro includes or loads a file "
        "outside its package and the --package-path folders, or one that is not a regular file.",
        """Reading any file would let a description exfiltrate secrets into findings. Pass the package's
      folder with --package-path, or move the file into the package.""",
    ),
    C(
        "READ032",
        "xacro-environment-refused",
        "error",
        "read",
        "An audited Xacro reads an environment variable outside the allow-list, or $(cwd).",
        """The environment holds secrets (tokens, paths); only ROS_DISTRO, ROS_VERSION and
      ROS_PYTHON_VERSION are readable. Pass the value as --xacro-arg instead.""",
    ),
    C(
        "READ033",
        "xacro-limit-exceeded",
        "error",
        "read",
        "An audited Xacro exceeds a bound (number size, string length, loop, macro calls, elements, text, evaluation "
        "steps, time).",
        """Unbounded expansion would hang or exhaust memory; the bounds are far beyond any real robot.
      Simplify the expression, or pass --trust-xacro for a file you trust.""",
    ),
    C(
        "READ040",
        "description-not-regular-file",
        "error",
        "read",
        "A named description is a FIFO, device, socket or folder.",
        """Reading it could block forever or never end, so it is refused before it is opened. Name a
      regular file.""",
    ),
    C(
        "READ041",
        "description-too-large",
        "error",
        "read",
        "A description file is larger than the limit (64 MiB).",
        """Real descriptions are a few megabytes at most; a larger file is the wrong file and would
      exhaust memory. Check the path.""",
    ),
    C(
        "READ042",
        "non-finite-number",
        "error",
        "read",
        "A URDF, SRDF or controllers value is nan, inf or overflows (1e999).",
        """A non-finite number poisons kinematics, inertia and limits; the value is treated as missing.
      Write the measured value as a plain decimal number.""",
    ),
    C(
        "READ043",
        "controllers-shape",
        "error",
        "read",
        "A controllers YAML has a list or a scalar where a mapping belongs.",
        """ros2_control reads parameters from mappings; the wrong shape configures nothing or crashes
      the node. Write key: value lines indented below the key.""",
    ),
    C(
        "READ044",
        "link-out-of-named-folder",
        "error",
        "read",
        "A file of a folder you named (--moveit-config, a template folder) is a symbolic link out of it.",
        """Only files inside the folders you name are read (docs/security.md): a link to
      /proc/self/environ or ~/.ssh would put their text into findings or generated files. Copy the
      file into the folder instead of linking to it.""",
    ),
    C(
        "MOVEIT020",
        "moveit-config-not-mapping",
        "error",
        "read",
        "A MoveIt config YAML file (joint_limits, moveit_controllers, kinematics, initial_positions) "
        "is empty or its root is not a mapping.",
        """MoveItConfigsBuilder loads each file as a mapping of ROS parameters; a list, a scalar or an
      empty file gives MoveIt nothing (or an exception), so there is nothing to audit. Write key: value
      lines, as the Setup Assistant lays the file out.""",
    ),
    C(
        "MOVEIT021",
        "moveit-config-folder-unusable",
        "error",
        "read",
        "The --moveit-config folder does not exist, or holds none of the MoveIt config files.",
        """A wrong folder would otherwise audit nothing and report no finding, which reads as a clean
      MoveIt config. Name the package folder (or its config/) that holds joint_limits.yaml.""",
    ),
)

# --------------------------------------------------------------------------- generate / check
register(
    C(
        "GEN001",
        "xacro-proof-failed",
        "error",
        "generate",
        "The generated Xacro does not expand, does not parse, or expands to a robot different from the generated URDF.",
        """The Xacro and the URDF must describe the same robot (check 1 of DESIGN.md); a difference means
      a template is wrong. Fix the template that changed (or the --templates override).""",
    ),
    C(
        "GEN002",
        "package-xml-invalid",
        "error",
        "generate",
        "The generated package.xml is invalid or not format 3.",
        """colcon cannot build a package with an invalid manifest. Check the spec's package: section or
      the package.xml template.""",
    ),
    C(
        "GEN003",
        "controllers-proof-failed",
        "error",
        "generate",
        "The generated controllers YAML does not load, has a non-integer update rate, or names a joint the URDF lacks.",
        """controller_manager would refuse the file or the controller would fail to configure. Fix the
      joint names in the spec, or the controllers template.""",
    ),
    C(
        "GEN004",
        "edited-by-hand",
        "error",
        "generate",
        "A generated file was edited by hand (its content no longer matches its header hash).",
        """Regenerating would destroy the edit, so it is not overwritten. Move the change into the spec
      or a template, or pass --force to discard it.""",
    ),
    C(
        "GEN005",
        "generated-file-stale",
        "error",
        "generate",
        "A committed generated file is stale: the spec, the templates or descgen changed since it was written.",
        """What is committed no longer matches its source, so reviewers read the wrong files. Run
      descgen generate and commit the result.""",
    ),
    C(
        "GEN006",
        "generated-file-missing",
        "error",
        "generate",
        "A file descgen generates is missing on disk.",
        """The package is incomplete. Run descgen generate.""",
    ),
    C(
        "GEN007",
        "file-no-longer-generated",
        "error",
        "generate",
        "A file in the package is no longer generated.",
        """A leftover file is shipped and reviewed as if it were current. Run descgen generate, which
      removes it.""",
    ),
    C(
        "GEN010",
        "templates-not-folder",
        "error",
        "generate",
        "--templates names something that is not a folder.",
        """Template overrides are a folder of jinja2 files. Name that folder.""",
    ),
    C(
        "GEN020",
        "urdfdom-missing",
        "varies",
        "generate",
        "check_urdf (urdfdom) is not installed, so the URDF "
        "was not checked by urdfdom (an error when DESCGEN_REQUIRE_TOOLS=1, else info).",
        """urdfdom is what ROS loads URDFs with; without it one proof is missing. Install Debian's
      liburdfdom-tools.""",
    ),
    C(
        "GEN021",
        "urdfdom-rejected",
        "error",
        "generate",
        "check_urdf rejected the generated URDF.",
        """robot_state_publisher and every ROS tool would refuse the file. The URDF template or the
      model is broken; the message quotes urdfdom.""",
    ),
    C(
        "GEN030",
        "urdf-readback-differs",
        "error",
        "generate",
        "The URDF read back by an independent parser differs from the model (or it cannot read it).",
        """An independent parser must read what descgen meant (check 2); a difference means the template
      writes a field wrong or the file was edited. The parser is descgen's lxml read-back reader
      (urdfdom's rules, no code shared with the renderer or the model), plus yourdfpy under
      check --thorough.""",
    ),
    C(
        "GEN031",
        "srdf-readback-differs",
        "error",
        "generate",
        "The generated SRDF, read back, differs from the spec's semantics (or does not parse).",
        """MoveIt would plan with groups or states other than those specified. Fix the SRDF template.""",
    ),
    C(
        "GEN032",
        "ros2-control-readback-differs",
        "error",
        "generate",
        "The generated <ros2_control> block, read back, differs from the spec.",
        """The hardware would export other interfaces than specified. Fix the ros2_control template.""",
    ),
    C(
        "GEN033",
        "controllers-readback-differs",
        "error",
        "generate",
        "The generated controllers YAML, read back, differs from the spec.",
        """controller_manager would load other controllers or parameters than specified. Fix the
      controllers template.""",
    ),
    C(
        "GEN060",
        "mesh-copy-stale",
        "error",
        "generate",
        "A mesh copied into the package differs from its source beside the spec (either was edited).",
        """Meshes are copied byte for byte, and binary files carry no header, so check compares each copy
      with its source (and the package's meshes/meshes.sha256 records what was copied). Run descgen
      generate and commit the result; change a mesh at its source, not in the package.""",
    ),
    C(
        "GEN070",
        "collision-matrix-unavailable",
        "error",
        "generate",
        "The spec asks for a sampled collision matrix (semantic.collision_matrix) but it cannot be computed: "
        "pinocchio (descgen[collision]) is missing or cannot load the collision geometry.",
        """Writing the SRDF without the matrix the spec asks for would silently leave MoveIt checking
      (or skipping) pairs nobody measured. Install the extra (pip install 'descgen[collision]'),
      fix the geometry pinocchio names, or remove semantic.collision_matrix.""",
    ),
    C(
        "GEN080",
        "evidence-page-stale",
        "error",
        "generate",
        "The evidence page (evidence/README.md, written by descgen report) no longer matches the proofs it summarises.",
        """A reviewer reads the page instead of re-running every proof, so a page that shows yesterday's
      verdicts is worse than none. check rebuilds it in memory (MuJoCo's machine-dependent lines aside)
      and compares. Run descgen report SPEC and commit the result.""",
    ),
    C(
        "GEN090",
        "moveit-readback-mismatch",
        "error",
        "generate",
        "A file of the MoveIt config package, parsed back, does not state what the model says.",
        """joint_limits.yaml, kinematics.yaml, moveit_controllers.yaml, initial_positions.yaml and
      pilz_cartesian_limits.yaml are read back with yaml.safe_load and compared with the model (joint
      names, SI limits, controller joints and action_ns). A mismatch is a descgen or template bug: a
      package that loads but plans with other limits than the spec states. Report it; fix the template.""",
    ),
    C(
        "GEN091",
        "moveit-integer-value",
        "error",
        "generate",
        "A MoveIt parameter declared double is written so that YAML reads it as an integer.",
        """MoveIt declares limits as PARAMETER_DOUBLE; an integer value (max_velocity: 3) aborts move_group
      with InvalidParameterTypeException (moveit/moveit2#2776). Every such value must read back as a float.""",
    ),
    C(
        "GEN092",
        "moveit-file-unreadable",
        "error",
        "generate",
        "A file of the MoveIt config package does not parse (YAML, Python launch file, package.xml).",
        """The package is loaded by moveit_configs_utils and colcon; a file that does not parse stops the
      launch. Report it; fix the template that wrote it.""",
    ),
    C(
        "GEN093",
        "moveit-mock-start-mismatch",
        "error",
        "generate",
        "The MoveIt package's config/<robot>.urdf.xacro, expanded, does not start the mock hardware at the "
        "initial state.",
        """MoveItConfigsBuilder loads config/<robot>.urdf.xacro, which passes initial_positions.yaml to the
      description's ros2_control Xacro; each position state's initial_value must then be the initial
      state's value, or the demo starts somewhere else than the spec says (and than MoveIt's start state).
      The file is expanded with xacro (sandboxed, both packages on the package path) and compared with the
      model. Report it; fix the template (robot.ros2_control.xacro.j2, moveit_urdf.xacro.j2) that changed.""",
    ),
    C(
        "GEN081",
        "evidence-page-refused",
        "error",
        "generate",
        "descgen report did not write the evidence page: the package is stale, a check failed or a verdict failed.",
        """The page is evidence for a reviewer; written over a failing package it would present a failure
      as a proof. Fix what descgen check reports (or the failed verdict quoted), then run report again.""",
    ),
    C(
        "VIEW001",
        "viewer-not-installed",
        "error",
        "command",
        "descgen view needs the optional viewer (viser with URDF support), which is not installed.",
        """The viewer is an optional extra so that descgen's proofs need no web stack. Install it with
      pip install 'descgen[view]'; its wheel ships the web client, so it works offline.""",
    ),
    C(
        "GEN061",
        "template-failed",
        "error",
        "generate",
        "A template override does not parse or fails to render, or (named by the spec) reaches past the sandbox.",
        """Templates recorded in a spec (templates:) are someone else's code and render in jinja2's
      immutable sandbox, so they cannot walk from a value to Python internals; a refusal or a broken
      override is reported at the template instead of a traceback. Fix the template.""",
    ),
    C(
        "GEN065",
        "template-not-a-file-in-folder",
        "error",
        "generate",
        "A template override is a symbolic link out of its folder, not a regular file, or too large.",
        """A template is read like any other input: a link to /proc/self/environ would render the
      environment (CI tokens) into the package, and a FIFO would block. Put the template itself in the
      folder, as a regular file of at most 1 MiB.""",
    ),
    C(
        "GEN040",
        "symlink-in-package",
        "error",
        "generate",
        "A symbolic link inside the package folder.",
        """Following it could write outside the output root; it is refused, never followed
      (docs/security.md). Replace the link with the file.""",
    ),
    C(
        "GEN041",
        "package-folder-unsafe",
        "error",
        "generate",
        "The package folder is a symbolic link, or exists but is not a folder.",
        """generate swaps the package folder as a whole; a link or file there could redirect the write.
      Move it away.""",
    ),
    C(
        "GEN042",
        "output-root-unsafe",
        "error",
        "generate",
        "The output root is a symbolic link or not a folder.",
        """Writes must stay inside the output root the user named. Name a folder with --out, or replace
      the link with a folder.""",
    ),
    C(
        "GEN043",
        "special-file-in-package",
        "error",
        "generate",
        "A FIFO, socket or device inside the package folder.",
        """Reading or replacing it could block or touch a device. Remove it from the package folder.""",
    ),
    C(
        "GEN044",
        "output-root-locked",
        "error",
        "generate",
        "Another descgen run holds the lock on the output root.",
        """Two runs writing one package would mix their files. Wait for the other run, then run again.""",
    ),
    C(
        "GEN045",
        "package-write-failed",
        "error",
        "generate",
        "The package could not be written (disk full, read-only --out, ...).",
        """Writes are all or nothing, so the previous package is unchanged. Check free space and
      permissions of the output folder.""",
    ),
)

# --------------------------------------------------------------------------- descgen control
register(
    C(
        "CTRL011",
        "tracking-error",
        "error",
        "control",
        "A joint's measured state did not follow the command within its tolerance.",
        """A joint that does not track its command is reversed, offset or not moving, and a controller
      built on it would fight the hardware. Check the joint's direction, encoder offset and that it
      moves.""",
    ),
    C(
        "CTRL012",
        "command-rejected-by-limits",
        "error",
        "control",
        "The trajectory commanded values beyond the joint limits, which the hardware rejected.",
        """A trajectory that hits the limits does not run as planned. Keep the trajectory inside the
      joint limits.""",
    ),
    C(
        "CTRL013",
        "controller-never-active",
        "error",
        "control",
        "A controller never became active in the ros2_control model.",
        """A controller that fails to configure or claim its interfaces leaves the joints uncommanded.
      See lifecycle.md in the evidence for the failed transition or claim.""",
    ),
    C(
        "CTRL014",
        "mock-hardware-echo",
        "info",
        "control",
        "The measured state is the mock hardware echoing the command.",
        """mock_components/GenericSystem reports what it was told, so the run proves the wiring, not the
      motion. Use --plant sim or real hardware to verify motion.""",
    ),
    C(
        "CTRL020",
        "trajectory-malformed",
        "error",
        "control",
        "The trajectory file is malformed (not a mapping, unknown keys, positions of the wrong length or unit).",
        """A trajectory that cannot be read cannot be run. Fix the trajectory at the given line.""",
    ),
    C(
        "CTRL021",
        "package-without-control",
        "error",
        "control",
        "The generated package has no controllers file or no <ros2_control> block.",
        """control runs the generated files; without them there is nothing to run. Run descgen generate
      first (and point --package at its output).""",
    ),
    C(
        "CTRL080",
        "initial-position-given-twice",
        "error",
        "spec",
        "A ros2_control joint's initial position is given twice (initial_position and a state initial_value).",
        """Both become the position state interface's initial_value param; two values for one param
      leave the reader to guess which one the hardware starts at. Keep one.""",
    ),
    C(
        "CTRL022",
        "trajectory-controller-unknown",
        "error",
        "control",
        "No joint_trajectory_controller of the trajectory's name in the controllers file.",
        """The trajectory would be sent to no one. Name the arm's controller.""",
    ),
    C(
        "CTRL030",
        "trajectory-empty",
        "error",
        "control",
        "The trajectory names no joints or has no points.",
        """Nothing would run, so the run would prove nothing. Give joints: and at least one point.""",
    ),
    C(
        "CTRL031",
        "trajectory-time-not-increasing",
        "error",
        "control",
        "A trajectory point's time_from_start is not after the previous point's.",
        """joint_trajectory_controller rejects trajectories whose times do not increase. List points in
      increasing time.""",
    ),
    C(
        "CTRL032",
        "bad-fault-option",
        "error",
        "control",
        "A --plant-fault option is not JOINT:=KIND with a known joint and fault kind.",
        """An unknown joint or fault kind would be silently ignored, and the run would not test what was
      asked. Write JOINT:=KIND with a kind from the list in the hint.""",
    ),
    C(
        "CTRL033",
        "trajectory-joint-not-commanded",
        "error",
        "control",
        "The trajectory names joints that its controller does not command.",
        """The controller would reject the trajectory. Use the controller's joints.""",
    ),
    C(
        "CTRL034",
        "evidence-folder-unwritable",
        "error",
        "control",
        "The evidence folder cannot be created.",
        """The run's evidence would be lost. Choose another --out.""",
    ),
    C(
        "CTRL035",
        "evidence-path-not-plain",
        "error",
        "control",
        "The evidence folder, or a file control writes in it (control_run/, a plot), is a symbolic link, "
        "FIFO or device.",
        """Evidence is written only as regular files inside the folder you named; a link would send it
      elsewhere and a FIFO would block. Nothing is written: remove the entry or choose another --out.""",
    ),
)

# --------------------------------------------------------------------------- recordings
register(
    C(
        "BAG001",
        "recording-unreadable",
        "error",
        "recording",
        "The rosbag2 recording cannot be read.",
        """A corrupt recording gives no lookups to check. Give a rosbag2 folder (metadata.yaml with
      .mcap or .db3 files).""",
    ),
    C(
        "BAG002",
        "topic-not-recorded",
        "error",
        "recording",
        "A --topic is not in the recording.",
        """Nothing can be looked up for a topic that was not recorded. List the topics with
      `ros2 bag info`.""",
    ),
    C(
        "BAG003",
        "recording-exists",
        "error",
        "recording",
        "The output recording folder already exists.",
        """A recording is written to a new folder so that an existing one is never overwritten. Choose
      another --out.""",
    ),
    C(
        "BAG010",
        "nothing-to-look-up",
        "error",
        "recording",
        "The recording has no sensor messages with a header, so tf-audit made no lookup.",
        """An audit that looked nothing up would pass without proving anything. Name a recorded sensor
      topic with --topic.""",
    ),
    C(
        "BAG011",
        "recording-unwritable",
        "error",
        "recording",
        "The recording cannot be written there.",
        """The parent folder is missing or not writable. Choose another --out.""",
    ),
    C(
        "BAG012",
        "target-frame-unknown",
        "error",
        "recording",
        "The --target frame appears nowhere in the recording.",
        """Every lookup would fail for the same reason, hiding real problems. Name a frame of the
      transform tree, e.g. odom or base_link.""",
    ),
    C(
        "BAG013",
        "topic-without-header",
        "error",
        "recording",
        "A --topic carries messages with no header.",
        """Without a header stamp and frame there is nothing to look up. Name a sensor topic whose
      messages have a std_msgs/Header.""",
    ),
    C(
        "BAG014",
        "not-a-recording",
        "error",
        "recording",
        "The path is not a rosbag2 folder (missing, a file, no metadata.yaml, or metadata too large).",
        """Only rosbag2 folders can be read. Give the recording's folder.""",
    ),
    C(
        "UNIT021",
        "option-time-out-of-range",
        "error",
        "command",
        "A duration or wait option is outside its allowed range.",
        """Absurd durations would run for hours or prove nothing; option values are bounded like spec
      values (docs/security.md). Give a time in the range the message states.""",
    ),
)

# --------------------------------------------------------------------------- command line
register(
    C(
        "RULE001",
        "unknown-code",
        "error",
        "command",
        "`descgen rules CODE` names a code that is not in the catalogue.",
        """Every code descgen prints is in the catalogue, so an unknown one is a typo. Run descgen rules
      for the list.""",
    ),
)

# --------------------------------------------------------------------------- added with issue 10
register(
    C(
        "CTRL048",
        "bad-calibrated-parameter",
        "error",
        "spec",
        "A controller's calibrated: names a parameter that cannot be calibrated for its type, or one "
        "that is also in params.",
        """calibrated: holds measured values (wheel_separation, wheel_radius of DiffDriveController)
      that are compared with what the URDF implies and written to the controllers file; any other key
      would be silently unused, and a key in both places has two values. Keep only calibrated.<key>.""",
    ),
)

# --------------------------------------------------------------------------- added with issue 14: descgen simulate
register(
    C(
        "SIM001",
        "mujoco-mass-below-minimum",
        "error",
        "simulate",
        "MuJoCo refuses a moving body whose mass or a principal inertia is below mjMINVAL (1e-15): "
        "zero, negative or all-zero inertia.",
        """MuJoCo will not load the robot at all ("mass and inertia of moving bodies must be larger than
      mjMINVAL"), and urdfdom accepts it, so the problem appears only in simulation. Give every moving
      link a positive mass and a positive-definite inertia tensor (or inertia from its collision shape).""",
    ),
    C(
        "SIM002",
        "mujoco-inertia-triangle",
        "error",
        "simulate",
        "MuJoCo refuses a body whose principal moments of inertia break the triangle inequality (A + B >= C).",
        """No rigid body has such moments; MuJoCo refuses the model, and with balanceinertia it silently
      replaces all three by their mean, a different body. Recompute the tensor (a unit slip in one
      entry is the usual cause).""",
    ),
    C(
        "SIM003",
        "mujoco-refused",
        "error",
        "simulate",
        "MuJoCo refused the model for another reason (its message is quoted).",
        """A description that MuJoCo cannot compile cannot be simulated there. The quoted message names
      the element; fix the description, or report a bug if the URDF is valid.""",
    ),
    C(
        "SIM004",
        "mujoco-fused-fixed-links",
        "info",
        "simulate",
        "Links on fixed joints are merged into their parent body (MuJoCo's fusestatic default for URDF).",
        """The merged links are no bodies in MuJoCo: they cannot carry sensors, sites or contacts of their
      own, and their names vanish from the model. Expected for tool and sensor frames; add
      <mujoco><compiler fusestatic="false"/></mujoco> to the URDF if a consumer needs them.""",
    ),
    C(
        "SIM005",
        "mujoco-visuals-dropped",
        "info",
        "simulate",
        "The visuals are discarded; only collision shapes exist in MuJoCo (discardvisual default for URDF).",
        """What is drawn in MuJoCo is the collision geometry, so a robot that looks right in RViz may look
      different there. A link with visuals but no collision is invisible and intangible in MuJoCo.""",
    ),
    C(
        "SIM006",
        "mujoco-mass-from-geometry",
        "warning",
        "simulate",
        "A link without <inertial> gets mass and inertia from its collision shapes at 1000 kg/m^3.",
        """urdfdom and RViz treat the link as massless, MuJoCo silently gives it the mass of water of its
      volume, so the two consumers simulate different robots. Give the link an <inertial>.""",
    ),
    C(
        "SIM007",
        "mujoco-unlimited-joint",
        "warning",
        "simulate",
        "A revolute or prismatic joint with lower > upper or only one bound becomes unlimited in MuJoCo.",
        """MuJoCo makes such a joint silently unlimited (sdformat swaps the bounds instead), so the joint
      can move anywhere in simulation. Write lower <= upper, both bounds.""",
    ),
    C(
        "SIM008",
        "mujoco-mesh-unavailable",
        "error",
        "simulate",
        "A collision mesh cannot be handed to MuJoCo (not found inside the named folders, or a format it "
        "does not read); the shape is left out.",
        """MuJoCo opens mesh filenames as plain paths and reads STL, OBJ and MSH only; without the shape the
      link neither collides nor draws there. Give --package-path, or convert the mesh.""",
    ),
    C(
        "SIM009",
        "mujoco-unavailable",
        "error",
        "simulate",
        "The mujoco Python package is not installed.",
        """descgen simulate compiles and runs the robot with MuJoCo, an optional dependency. Install it with
      pip install 'descgen[sim]' (or pip install 'mujoco>=3').""",
    ),
    C(
        "SIM010",
        "sim-not-finite",
        "error",
        "simulate",
        "The gravity run produced NaN or infinite positions or velocities.",
        """The simulation blew up: typically an inertia far too small for its link, a huge actuator gain,
      or no damping. The joint named is where it showed first; check its link's mass and inertia.""",
    ),
    C(
        "SIM011",
        "sim-unstable",
        "error",
        "simulate",
        "MuJoCo warned during the gravity run (bad acceleration, contact or constraint overflow).",
        """MuJoCo resets the state on a bad acceleration (mjWARN_BADQACC), so a run that looks calm may have
      blown up and restarted. Check masses, inertias, gains and damping.""",
    ),
    C(
        "SIM012",
        "sim-joint-left-pose",
        "error",
        "simulate",
        "A joint held by a PD controller at the pose drifted beyond its tolerance under gravity, or was "
        "still moving at the end.",
        """A joint that its effort limit cannot hold against gravity (mass too large, centre of mass too far
      out) sags or falls in simulation although RViz shows the pose. Check the masses carried by the joint
      and its effort limit.""",
    ),
    C(
        "SIM013",
        "sim-base-tipped",
        "error",
        "simulate",
        "The mobile base, free on a ground plane, tilted beyond the limit or left the floor.",
        """A centre of mass outside the support of wheels and casters tips the robot over; a description
      that looks right in RViz falls over in simulation. Check the base and arm masses and where their
      centres of mass are.""",
    ),
    C(
        "SIM014",
        "sim-unknown-pose",
        "error",
        "simulate",
        "--pose names no known pose (spec known_poses) and no SRDF group state.",
        """The run holds the joints at the named pose; an unknown name is a typo. The message lists the
      pose names there are.""",
    ),
    C(
        "SIM015",
        "sim-contacts-excluded",
        "info",
        "simulate",
        "Bodies of the robot touch at the pose; their contacts are left out of the gravity run.",
        """MuJoCo never filters contacts with the world body (a fixed root) and only filters parent and
      child, so shapes that overlap at rest would push the joints away from the pose. The run excludes
      them, as an SRDF's disabled collisions would; a consumer needs the same <exclude> pairs.""",
    ),
    C(
        "SIM016",
        "sim-nothing-to-hold",
        "error",
        "simulate",
        "The robot has no movable joint with one degree of freedom and is not on a free base: the gravity "
        "run proves nothing.",
        """Nothing moves, so nothing can sag or tip. Use --base floor for a mobile base, or simulate a
      description that has joints.""",
    ),
    C(
        "SIM017",
        "sim-too-large",
        "error",
        "simulate",
        "The robot is too large to simulate: more than 2,000 links, more than 500 degrees of freedom, or "
        "more mass-matrix work over the run than the bound; nothing is compiled (exit 2).",
        """MuJoCo's compiler and the servos' pseudo-inverse grow with the cube of the degrees of freedom, and
      each step factorises the mass matrix: a 10,000-link chain would run for hours. The bounds keep a run
      within about 15 s; simulate fewer --seconds, or a smaller description.""",
    ),
)

# --------------------------------------------------------------------------- added with issue 12: descgen import
register(
    C(
        "IMP001",
        "import-roundtrip-differs",
        "error",
        "import",
        "The imported spec, loaded, rendered and read back, is not the description it came from.",
        """import proves the spec before writing it: a difference means a value would change on the way
      to the generated URDF. Nothing is written; the message names the element and both values. It is a
      bug of descgen import: please report it with the description.""",
    ),
    C(
        "IMP002",
        "import-already-spec",
        "error",
        "import",
        "The file given to import is already a descgen spec.",
        """import reads a URDF or a Xacro; a spec is validated and generated as it is.""",
    ),
    C(
        "IMP003",
        "import-passthrough",
        "info",
        "import",
        "An element the spec has no field for (Gazebo tag, transmission, ros2_control, unknown tag) is kept "
        "verbatim in passthrough:.",
        """Nothing may be lost silently. generate writes the element back unchanged (in the Xacro every $ stays
      data), and the round trip proves it comes back as the same XML. Review it like the rest of the spec.""",
    ),
    C(
        "IMP004",
        "import-not-kept",
        "warning",
        "import",
        "An element is not kept in the spec: inside a link or joint where the spec has no field, or a "
        "top-level element that cannot be pass-through (a xacro instruction).",
        """The generated description will lack it. Add what it means by hand if the robot needs it; a xacro
      instruction in pass-through would be run by xacro, so it is never kept.""",
    ),
    C(
        "IMP005",
        "import-controllers-not-imported",
        "warning",
        "import",
        "The controllers YAML given to import is not written into the spec.",
        """The <ros2_control> blocks stay verbatim in passthrough:, and the spec's controllers section would
      generate a second block. Keep the controllers file beside the generated package.""",
    ),
    C(
        "IMP007",
        "import-output-exists",
        "error",
        "import",
        "The -o spec file exists already.",
        """A spec is reviewed and edited by hand; import never replaces one unless told to. Choose another
      file, or pass --force.""",
    ),
    C(
        "IMP033",
        "import-output-not-regular",
        "error",
        "import",
        "The -o path is a symbolic link, FIFO, device or folder.",
        """import writes a spec as a regular file; --force replaces only a regular file, never a link (it
      would write through or replace it) nor a device or FIFO (run as root, replacing /dev/null breaks the
      machine). Name a file path.""",
    ),
    C(
        "IMP034",
        "import-output-unwritable",
        "error",
        "import",
        "The -o spec file cannot be written (a file in the way of its folder, no permission, a read-only disk).",
        """Nothing is written. Choose another -o file.""",
    ),
    C(
        "IMP008",
        "import-bad-units",
        "error",
        "command",
        "--units of import names a unit that import does not write.",
        """Lengths are written in mm, cm or m, angles in deg or rad, masses in kg or g (or si for all SI).""",
    ),
    C(
        "IMP010",
        "passthrough-invalid",
        "error",
        "spec",
        "A passthrough: entry is not one plain XML element (malformed, a DOCTYPE or entity, a link, joint or "
        "material, or a xacro instruction).",
        """Pass-through XML is written verbatim into the URDF and the Xacro: it must be well-formed, must not
      duplicate what the spec writes itself, and must not hold xacro instructions, which xacro would run.""",
    ),
    C(
        "IMP011",
        "import-state-value-not-kept",
        "warning",
        "import",
        "A group-state value of the SRDF that the spec cannot hold (several numbers for a joint that is no "
        "planar/floating virtual joint, or unreadable) is not kept.",
        """The spec holds one number per joint in a group state, or a list for a planar or floating virtual
      joint (kept since the spec takes lists). Anything else cannot be written there. Nothing may be lost
      silently: the value and its SRDF line are reported, and the generated SRDF lacks it until it is
      added by hand.""",
    ),
    C(
        "IMP026",
        "import-continuous-limit-dropped",
        "info",
        "import",
        "A continuous joint's lower/upper limit is left out of the imported spec.",
        """urdfdom reads lower and upper on any joint, but no consumer applies them to a continuous one:
      ros2_control's joint_limits (joint_limits_urdf.hpp) marks it angle_wraparound, MoveIt unbounds it
      (RevoluteJointModel::setContinuous, after reading them), and descgen's URDF does not write them.
      Kept, they would read as limits the robot does not have; dropped, the round trip compares what
      every reader uses. Reported so nothing is lost silently.""",
    ),
    C(
        "IMP027",
        "import-variant-option",
        "error",
        "import",
        "--variant is malformed, repeats a name, lacks the mock variant, or is given for a file that is no Xacro.",
        """The spec's hardware variants are mock (the spec's own hardware), gazebo and real, selected in the
      generated Xacro by hardware:=; import needs the Xacro arguments that give each, and the mock one
      because the spec's hardware.plugin must be mock_components/GenericSystem when variants exist.""",
    ),
    C(
        "IMP028",
        "import-variants-differ",
        "error",
        "import",
        "Two hardware variants of a Xacro expand to different robots (links, joints, limits, pass-through or "
        "<ros2_control> components), not only different <hardware>.",
        """The spec's hardware.variants change the hardware plugin and its params and nothing else; a variant
      that changes a link could not be given back by hardware:=, so import stops at the first difference
      and writes nothing.""",
    ),
    C(
        "IMP029",
        "import-variant-hardware",
        "error",
        "import",
        "A hardware variant's plugin is not what the spec allows under that name (mock: GenericSystem, gazebo: "
        "GazeboSimSystem, real: a vendor plugin), or the blocks cannot leave pass-through.",
        """The spec would refuse the variant on load (SPEC080-082); refusing at import names the variant and
      its arguments, which the spec error could not.""",
    ),
    C(
        "IMP030",
        "import-variants-imported",
        "info",
        "import",
        "The <ros2_control> hardware is imported for several variants; the generated Xacro selects them with "
        "hardware:=.",
        """Replaces IMP020 (one variant) when --variant is given: the launch files that passed
      use_mock_hardware or sim_gazebo now pass hardware:=mock|gazebo|real.""",
    ),
    C(
        "IMP012",
        "import-package-outside-project",
        "info",
        "import",
        "A package named by package:// meshes lies outside the imported spec's project, so the spec cannot "
        "record it under package_paths:.",
        """A spec records package folders relative to itself and inside its project (docs/security.md), so
      it works on any machine. A package elsewhere is named on the command line instead: pass the folder
      that holds it as --package-path to validate, generate and check. The generated package references
      its meshes and depends on it (exec_depend) instead of copying another package's files.""",
    ),
    C(
        "IMP014",
        "import-package-name-chosen",
        "info",
        "import",
        "The imported spec names its package (package.name) because <robot>_description is no REP 144 name "
        "or is the package its meshes come from.",
        """A robot named 2dof_planar is a valid URDF, but 2dof_planar_description is no ROS package name
      (REP 144: it must start with a lowercase letter); UR's robot ur would generate ur_description, the
      upstream package that holds its meshes, and two packages of one name shadow each other. import
      writes a valid, distinct name (robot_2dof_planar_description, ur_descgen_description); rename it
      as you like.""",
    ),
    C(
        "IMP013",
        "import-structure-not-used",
        "info",
        "import",
        "Repeated parts or cameras that import recognised are written as plain links and joints, because the "
        "spec with parts:/sensors: did not give back the same robot.",
        """parts: and sensors: are written only when the generated URDF stays the same robot; otherwise the
      flat spec (which the round trip proves) is written instead. Nothing is lost.""",
    ),
)

# ------------------------------------------------------------------ issue 12: ros2_control and controllers import
register(
    C(
        "IMP020",
        "import-ros2-control-variant",
        "info",
        "import",
        "A <ros2_control> block is imported into ros2_control: with the hardware the description expands to "
        "for the given --xacro-arg values.",
        """A Xacro may choose its hardware plugin by an argument (use_mock_hardware, use_gazebo): import sees one
      expansion, so it says which hardware it imported. Other variants are added under hardware.variants by
      hand (or seen by importing with other arguments).""",
    ),
    C(
        "IMP021",
        "import-ros2-control-passthrough",
        "info",
        "import",
        "A <ros2_control> block holds something the spec's ros2_control: cannot say, so every block stays "
        "verbatim in passthrough:.",
        """Nothing may be lost silently: a transmission, a joint-level param, an interface size or an unknown
      param has no spec field. All blocks stay together (one block in the spec and one in pass-through would be
      two sources of one hardware); the message names what could not be expressed.""",
    ),
    C(
        "IMP022",
        "import-ros2-control-derived-params",
        "info",
        "import",
        "generate writes interface params that the imported <ros2_control> block leaves to ros2_control's "
        "defaults: command min/max from the URDF limits, state initial_value.",
        """The generated block always states them. Jazzy only tightens the URDF limits with min/max, so equal
      values change nothing, and 0 is GenericSystem's start value; a joint whose range excludes 0 starts mid-range.
      The round trip allows exactly these additions and lists them so a reviewer can check them.""",
    ),
    C(
        "IMP023",
        "import-update-rate-default",
        "info",
        "import",
        "No controller_manager update_rate was given; the imported spec says 100 Hz, controller_manager's default.",
        """The spec states the rate the generated controllers file writes; 100 Hz is what controller_manager runs at
      without one. Write the real rate of your hardware.""",
    ),
    C(
        "IMP024",
        "import-controllers-entry-not-imported",
        "warning",
        "import",
        "An entry of the controllers YAML is not imported: a controller_manager parameter other than update_rate "
        "and the controller types, an entry that names no controller, or a controller whose name or type the spec "
        "cannot hold.",
        """The generated config/ros2_controllers.yaml lacks it, so it is said, never silently dropped. Keep it in a
      parameters file of your own if the robot needs it.""",
    ),
    C(
        "IMP025",
        "import-wheel-params-derived",
        "info",
        "import",
        "A diff_drive_controller in the imported controllers file gives no wheel_separation/wheel_radius; "
        "generate writes the values derived from the URDF.",
        """diff_drive_controller needs both; descgen derives them from the wheel joints and collision cylinders.
      State measured values under calibrated: if the robot has them.""",
    ),
)

# --------------------------------------------------------------------------- added with issue 15: descgen sweep
register(
    C(
        "SWEEP001",
        "sweep-collision-at-limit",
        "warning",
        "sweep",
        "Two links the SRDF does not disable collide at a joint limit while that joint is swept (the others at "
        "the state); the message gives the limit's value and where the contact starts.",
        """A joint driven to its limit (homing, a planner using the whole range, a teleoperator) drives the
      robot into itself there. Narrow the limit so the motion stops before the contact, change the collision
      shapes if they are too large, or disable the pair in the SRDF if the contact is by design.""",
    ),
    C(
        "SWEEP002",
        "sweep-collision-in-range",
        "warning",
        "sweep",
        "Two links the SRDF does not disable collide inside a joint's range while that joint is swept (the others "
        "at the state); the message gives the joint values where the contact starts and ends.",
        """MoveIt plans around such a contact, but a jog or a controller that moves one joint alone runs into it.
      It is expected at some states (an arm folded over its base); check the shapes and the range.""",
    ),
    C(
        "SWEEP003",
        "sweep-no-range",
        "info",
        "sweep",
        "A joint is not swept: it has no lower and upper limit, or its range is empty.",
        """Only joints with a range can be moved through it. A revolute or prismatic joint without limits is
      reported by the audit; an empty range (lower equal to upper) holds the joint still.""",
    ),
    C(
        "SWEEP004",
        "sweep-unknown-state",
        "error",
        "sweep",
        "--state names no group state and no known pose of the robot.",
        """The other joints are held at the named state while each joint is swept; an unknown name is a typo.
      The message lists the names there are.""",
    ),
    C(
        "SWEEP005",
        "sweep-collisions-not-checked",
        "warning",
        "sweep",
        "The self-collisions of the sweep were not checked: pinocchio (the collision extra) is not installed, or "
        "it could not load the collision geometry. The directions are still reported.",
        """The collision check needs pinocchio with coal: pip install 'descgen[collision]'. A sweep without it
      says nothing about contacts, so it is said rather than left out.""",
    ),
    C(
        "SWEEP006",
        "sweep-mesh-left-out",
        "warning",
        "sweep",
        "A collision mesh was not found, so that shape is left out of the sweep's collision check.",
        """The mesh could not be resolved inside the description's package or --package-path (docs/security.md),
      so its link is checked without it and contacts with it are missed. Give --package-path or fix the
      filename.""",
    ),
    C(
        "SWEEP007",
        "sweep-too-large",
        "error",
        "sweep",
        "The robot is too large to sweep: joints x links x grid steps is more than the sweep's bound "
        "(500,000 link poses); nothing is swept (exit 2).",
        """Every joint is moved through every grid step and every link's pose is computed there, so the work
      grows with the joints times the links: a 10,000-link chain would take hours. The bound keeps a sweep
      within about 20 s; sweep with fewer --steps, or a smaller description.""",
    ),
    C(
        "SWEEP008",
        "sweep-collisions-too-many",
        "warning",
        "sweep",
        "The self-collisions of the sweep were not checked: more pair tests (pairs x grid steps) than the "
        "sweep's bound (2,000,000), or more collision shapes or a deeper tree than pinocchio is given "
        "(20,000 pairs of shapes, 1,000 joints deep). The directions are still reported.",
        """pinocchio keeps ~40 KB per pair of collision shapes, and its URDF parser overflows the stack on a
      tree thousands of joints deep (a crash, no message). Sweep with fewer --steps, disable pairs that
      cannot collide in the SRDF, or give fewer collision shapes.""",
    ),
)

# --------------------------------------------------------------------------- launch substitutions in a controllers YAML
register(
    C(
        "CTRL052",
        "launch-var-without-value",
        "warning",
        "read",
        "A controllers YAML holds a $(var NAME) launch substitution and no --launch-arg NAME:=VALUE (or default "
        "in the file) gives its value; names that hold it are not checked against the URDF.",
        """A launch file loads such a file with ParameterFile(..., allow_substs=True) (ros2_control_demos
      example_1: $(var joint_prefix)1), so the literal text is not what the controller sees. Reporting
      the literal as an unknown joint would be a false error; the warning stands for it. Pass the launch
      argument's value with --launch-arg to check the names.""",
    ),
    C(
        "CTRL053",
        "launch-substitution-not-evaluated",
        "warning",
        "read",
        "A controllers YAML holds a launch substitution descgen does not evaluate ($(env), $(eval), $(command), "
        "$(find-pkg-share), ..., or one launch cannot parse); it is left as written.",
        """An audited file is data: evaluating it would read the environment (secrets), run Python or
      commands, or search the file system. Only $(var NAME) is evaluated, from --launch-arg values.
      Names that hold the substitution are not checked; write the value, or a $(var) given with
      --launch-arg.""",
    ),
    C(
        "CTRL054",
        "launch-substitution-refused",
        "error",
        "read",
        "A --launch-arg is not NAME:=VALUE (or its value holds a control character or is too long), or a "
        "controllers YAML holds too many, too deeply nested or too large launch substitutions.",
        """Limits keep a hostile file (a substitution bomb) from exhausting memory or time, and a
      newline in a value would add YAML lines that are not in the file. Exit 2, nothing read further.""",
    ),
    C(
        "CTRL055",
        "launch-arg-without-controllers",
        "error",
        "read",
        "--launch-arg is given to audit or import without --controllers: nothing would read its value.",
        """Launch arguments are the values of $(var NAME) substitutions in the controllers YAML named by
      --controllers (a MoveIt config's ros2_controllers.yaml is read as written). Ignoring the option
      silently would let a user believe a substitution was checked with that value. Exit 2, nothing
      read or written.""",
    ),
    C(
        "CTRL056",
        "controllers-entry-without-type",
        "info",
        "read",
        "A top-level entry of a controllers YAML has ros__parameters but no type, neither its own nor under "
        "controller_manager: it is not read as a controller, so nothing in it is checked.",
        """Jazzy takes a controller's type from controller_manager.ros__parameters.<name>.type or from
      <name>.ros__parameters.type; a spawner may also pass --controller-type, and one parameter file
      may hold other nodes' parameters. descgen cannot tell which, so it does not guess a type and
      says that the entry went unchecked, instead of dropping it silently.""",
    ),
    C(
        "IMP031",
        "import-launch-substitution",
        "info",
        "import",
        "A launch substitution in the controllers YAML was replaced by its --launch-arg value (or the file's "
        "default) in the imported spec.",
        """The spec holds the names the controller sees with these launch arguments, not the $(var) text:
      the generated controllers file is loaded without substitutions. Import with the values your
      launch file uses.""",
    ),
    C(
        "IMP032",
        "import-launch-substitution-unresolved",
        "error",
        "import",
        "The controllers YAML holds a launch substitution without a value ($(var NAME) without --launch-arg), or "
        "one descgen does not evaluate; the import stops.",
        """The spec's controller joint names must be the robot's joints, and the literal $(var ...) is
      none; guessing a value would import a robot that differs from the one launched. Pass
      --launch-arg NAME:=VALUE, or write the value into the file. Exit 2, nothing written.""",
    ),
    C(
        "IMP035",
        "import-too-large",
        "error",
        "import",
        "The description has more links than descgen answers for (10,000), or its spec would be larger than "
        "validate reads (16 MiB, 2,000,000 YAML nodes); the import stops.",
        """A spec that validate refuses is no import: every command that reads it would stop at the size
      bound, and the round trip could not prove it. Exit 2, nothing written; split the description.""",
    ),
)
