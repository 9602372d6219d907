"""Codes of reading a spec: YAML, the schema, units, and the spec's own consistency.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("spec")


CAL001 = declare(
    "CAL001",
    "calibration-source-unknown",
    "error",
    "A calibration entry cites a source that calibration.sources does not name.",
    """Every calibrated value keeps its provenance (the method, tool, file and date of the measurement); an entry
      citing a name that is not in calibration.sources has none. Add the source, or cite one that exists.""",
)

CAL002 = declare(
    "CAL002",
    "calibration-target-unknown",
    "error",
    "A calibration entry names a joint or sensor the robot does not have, or calibrates one joint twice.",
    """A correction for a joint that is not there would be silently unused (a renamed joint, a prefix), and a
      sensor's mount given both under sensors: and under joints: has two values. Name an existing joint or sensor,
      once.""",
)

CAL003 = declare(
    "CAL003",
    "calibration-offset-without-motion",
    "error",
    "A zero offset is given for a joint that does not move about or along one axis (fixed, floating, planar).",
    """A zero offset shifts what a revolute, continuous or prismatic joint reports; a joint without one axis of
      motion reports nothing to shift. Correct its origin instead.""",
)

CAL004 = declare(
    "CAL004",
    "calibration-correction-large",
    "warning",
    "A calibration moves a frame by more than 20 mm or turns it by more than 5 degrees from the nominal model.",
    """Calibration corrects what machining and assembly leave: fractions of a millimetre or a degree on an arm, a
      few millimetres on a sensor mount. A larger correction is usually a unit slip, a result pasted into the wrong
      frame, or a nominal model that is wrong; check the nominal value first.""",
)


CAL005 = declare(
    "CAL005",
    "drift-samples-unusable",
    "error",
    "calibration.drift.samples is absolute, leaves the project folder, or is not a regular file.",
    """The samples are read by every report and check on every machine, so they are named relative to the spec
      and kept inside the project (the folder holding specs/), like templates; a FIFO or a device would never
      end. Commit the CSV beside the spec and name it relative to it.""",
)


CTRL048 = declare(
    "CTRL048",
    "bad-calibrated-parameter",
    "error",
    "A controller's calibrated: names a parameter that cannot be calibrated for its type, or one "
    "that is also in params.",
    """calibrated: holds measured values (wheel_separation, wheel_radius of DiffDriveController)
      that are compared with what the URDF implies and written to the controllers file; any other key
      would be silently unused, and a key in both places has two values. Keep only calibrated.<key>.""",
)

CTRL080 = declare(
    "CTRL080",
    "initial-position-given-twice",
    "error",
    "A ros2_control joint's initial position is given twice (initial_position and a state initial_value).",
    """Both become the position state interface's initial_value param; two values for one param
      leave the reader to guess which one the hardware starts at. Keep one.""",
)

IMP010 = declare(
    "IMP010",
    "passthrough-invalid",
    "error",
    "A passthrough: entry is not one plain XML element (malformed, a DOCTYPE or entity, a link, joint or "
    "material, or a xacro instruction).",
    """Pass-through XML is written verbatim into the URDF and the Xacro: it must be well-formed, must not
      duplicate what the spec writes itself, and must not hold xacro instructions, which xacro would run.""",
)

INER010 = declare(
    "INER010",
    "inertia-not-derivable",
    "error",
    "inertial from: visual/collision, but the link has no such geometry.",
    """descgen derives a tensor from a box, cylinder, sphere or watertight mesh (INER030, INER031);
      without one the link would get no tensor. Add a shape, or give the inertia explicitly (e.g. from CAD).""",
)

INER030 = declare(
    "INER030",
    "mesh-inertia-not-watertight",
    "error",
    "inertial from: a mesh that is not watertight (open edges or inconsistent winding), or bounds no volume.",
    """An open mesh bounds no solid, so its volume, centre of mass and tensor are meaningless numbers
      (trimesh warns the same). Close the mesh in CAD (or export its convex hull as the collision), or give
      the inertia explicitly.""",
)

INER031 = declare(
    "INER031",
    "mesh-inertia-unreadable",
    "error",
    "inertial from: a mesh whose file cannot be found or read (format, size, triangle count, parser error).",
    """Without the mesh there is nothing to integrate; a guessed tensor would be worse than none.
      Fix the path (relative to the spec), convert the file to STL, OBJ or DAE, or give the inertia explicitly.""",
)

INER032 = declare(
    "INER032",
    "inertia-not-finite",
    "error",
    "inertial from: a shape whose computed tensor overflows (inf or nan), with plausibility ranges widened.",
    """A mass and a size at the edge of the floats (1e300 kg, 1e200 m) give moments beyond them; no
      simulator or rule can use an infinite tensor. Give a mass and size a real part has, or the inertia
      explicitly.""",
)

SPEC001 = declare(
    "SPEC001",
    "unknown-key",
    "error",
    "A key the spec schema does not know (usually a typo).",
    """Unknown keys are errors, not ignored, because a misspelt key (`orgin:`) would silently drop
      the value the author meant. Use the suggested key, or remove it; `descgen schema` lists the keys.""",
)

SPEC002 = declare(
    "SPEC002",
    "missing-key",
    "error",
    "A required key is missing.",
    """Without it the element cannot be built (a joint needs parent, child and type). Add the key;
      the hint names it.""",
)

SPEC003 = declare(
    "SPEC003",
    "wrong-value-type",
    "error",
    "A value has the wrong type or is not one of the allowed "
    "choices (e.g. a joint type, a source that is not text, a spec that is not a mapping).",
    """A value of the wrong shape cannot mean what the author intended. Write one of the allowed
      values; `descgen schema` gives the form of every field.""",
)

SPEC004 = declare(
    "SPEC004",
    "ambiguous-shape",
    "error",
    "A shape or material is over- or under-specified "
    "(both radius and diameter, not exactly one geometry, a material without rgba or texture).",
    """Two values for one thing can disagree, and none leaves it undefined. Keep exactly the one
      you measured.""",
)

SPEC005 = declare(
    "SPEC005",
    "duplicate-key",
    "error",
    "A mapping holds the same key twice.",
    """YAML keeps the last one silently, so the first value (often the measured one) would be lost
      without a word. Remove or rename one of them.""",
)

SPEC010 = declare(
    "SPEC010",
    "value-without-source",
    "error",
    "With require_sources: true, a measured value has no source on itself or on an element that contains it.",
    """A value that cites no measurement cannot be reviewed or re-checked. Add source: <row ID> to
      the value or its element, or set require_sources: false.""",
)

SPEC020 = declare(
    "SPEC020",
    "control-character",
    "error",
    "A spec text holds a control character.",
    """XML (URDF, SRDF, package.xml) cannot hold control characters, and printed ones can rewrite a
      terminal or forge output lines (docs/security.md). Remove it.""",
)

SPEC021 = declare(
    "SPEC021",
    "line-break-in-one-line-value",
    "error",
    "A value that is written as one line (an XML attribute, a name) contains a line break or tab.",
    """An XML attribute reads a line break back as a space, so the value would not round-trip, and
      a line break in a one-line output can inject text. Write it on one line.""",
)

SPEC022 = declare(
    "SPEC022",
    "part-named-like-xacro-tag",
    "error",
    "A part is named like a Xacro directive (property, include, macro, ...).",
    """The part's macro would be called as <xacro:NAME>, which Xacro reads as its own directive, so
      the generated Xacro would not call the part. Rename the part (e.g. NAME_part).""",
)

SPEC023 = declare(
    "SPEC023",
    "no-links",
    "error",
    "The spec has no links.",
    """A URDF needs at least one <link>; generate would write a file urdfdom refuses. Add the root
      link.""",
)

SPEC024 = declare(
    "SPEC024",
    "duplicate-semantic-name",
    "error",
    "A name is declared twice in one semantic section (groups, group states, end effectors, ...).",
    """The SRDF keeps one element per name, so MoveIt would see only one of the two. Remove or rename
      the second.""",
)

SPEC025 = declare(
    "SPEC025",
    "package-field-refused",
    "error",
    "A package email, version, maintainer or license that catkin_pkg refuses.",
    """colcon and rosdep parse package.xml with catkin_pkg; a value it refuses breaks the build of
      the generated package. Write a valid email, a MAJOR.MINOR.PATCH version and a non-empty name
      and license.""",
)

SPEC026 = declare(
    "SPEC026",
    "duplicate-material-name",
    "error",
    "Two entries of materials: have the same name.",
    """urdfdom refuses a URDF whose robot-level materials are not unique ("material 'x' is not unique"),
      so robot_state_publisher, pinocchio's collision matrix and check_urdf all fail on the generated
      file. Remove the second entry or rename it (and the visuals that use it).""",
)

SPEC050 = declare(
    "SPEC050",
    "invalid-name",
    "error",
    "A name in the spec does not match the pattern its field requires (e.g. an identifier).",
    """Link, joint, frame, controller and package names reach URDF, tf, ros2_control and file names;
      ROS tools refuse or misread names with spaces, dashes or leading digits. Until issue 10 this
      was reported as NAME001, which is the duplicate-link-name rule. Rename it as the hint says.""",
)

SPEC060 = declare(
    "SPEC060",
    "mesh-not-found",
    "error",
    "A mesh the spec references does not exist (relative to the spec, or in the package named by package://).",
    """generate would write a package whose URDF names a file that is not there: RViz shows nothing
      and collision checking loses the part, while every other check passes. Fix the path, or add
      the file beside the spec (descgen/meshes/paths.py).""",
)

SPEC061 = declare(
    "SPEC061",
    "mesh-path-escapes",
    "error",
    "A mesh path leaves the spec's folder or its package (.., an absolute path, file://, a link out).",
    """A spec is someone else's data: it may name only files beside it or in the packages it lists,
      or validating it could read (and generate copy) any file of the machine, like /etc/passwd
      (docs/security.md). Keep the mesh in the spec's folder, or name it with package://.""",
)

SPEC062 = declare(
    "SPEC062",
    "mesh-package-unknown",
    "error",
    "A package:// mesh names a package that package_paths:, --package-path and the sourced environment "
    "do not hold (or the generated one).",
    """The package must be found to check the file and to depend on it (exec_depend). Record the
      folder holding the package under package_paths: (relative to the spec), pass --package-path,
      or source the workspace (docs/packages.md); for the robot's own meshes, write a path
      relative to the spec, which generate copies into the package.""",
)

SPEC063 = declare(
    "SPEC063",
    "mesh-not-a-file",
    "error",
    "A mesh path names a folder, FIFO or device, or a file larger than the mesh limit (64 MiB).",
    """Meshes are read and copied; a FIFO would block, a device never ends, and a huge file is not a
      robot part. Name the mesh file itself.""",
)

SPEC064 = declare(
    "SPEC064",
    "spec-folder-unusable",
    "error",
    "A package_paths or templates entry is absolute or not a folder, or templates leaves the project folder.",
    """Recorded folders make every command and every machine resolve the same files, so they are
      relative to the spec. Package folders may lie outside the project (a workspace beside it):
      only packages are read there, each inside itself (docs/packages.md). Templates render the
      package, so they stay inside the project (the folder holding specs/).""",
)

SPEC065 = declare(
    "SPEC065",
    "mesh-copy-clash",
    "error",
    "Two different mesh files would be copied to the same place in the package.",
    """A path relative to the spec is copied to meshes/<path> (a leading meshes/ is not doubled), so
      meshes/a.stl and a.stl both land on meshes/a.stl and one would silently replace the other.
      Move or rename one of them.""",
)

SPEC066 = declare(
    "SPEC066",
    "passthrough-names-generated-package",
    "error",
    "A pass-through element names the package descgen generates ($(find pkg) or package://pkg/).",
    """The reference would find the generated package, which holds descgen's files, not the ones the
      description meant (a bringup's controllers file, a world). Name the package that has the file,
      or give the generated package another name (package: {name: ...}) (docs/packages.md).""",
)

SPEC080 = declare(
    "SPEC080",
    "variants-without-mock-default",
    "error",
    "ros2_control.hardware declares variants but its own plugin is not mock_components/GenericSystem.",
    """With variants, hardware.plugin/params are the `mock` variant, the default of the generated
      Xacro's `hardware` argument and the hardware of the generated URDF. A vendor plugin there would
      make the default description drive the real robot. Put the vendor plugin under variants.real.""",
)

SPEC081 = declare(
    "SPEC081",
    "gazebo-variant-plugin",
    "error",
    "The gazebo hardware variant names a plugin other than gz_ros2_control/GazeboSimSystem.",
    """Jazzy pairs with Gazebo Harmonic, whose ros2_control plugin is gz_ros2_control/GazeboSimSystem
      (docs/ros2_control_jazzy.md §6); gazebo_ros2_control (Gazebo Classic) is not released for
      Jazzy. Leave the plugin out (it defaults to GazeboSimSystem) or write it.""",
)

SPEC082 = declare(
    "SPEC082",
    "real-variant-plugin",
    "error",
    "The real hardware variant has no plugin, or names the mock or Gazebo plugin.",
    """hardware:=real must load the robot's driver; a mock or simulation plugin there would make a
      launch on the robot silently move nothing. Name the vendor's hardware plugin.""",
)

SPEC083 = declare(
    "SPEC083",
    "control-sensor-frame-unknown",
    "error",
    "A ros2_control sensor's frame is not a link of the robot.",
    """The frame is written as the sensor's frame_id parameter, and the broadcasters stamp their
      messages with it; tf cannot place data in a frame that does not exist. Name a link (a sensor
      link is <name>_link).""",
)

SPEC084 = declare(
    "SPEC084",
    "control-interface-repeated",
    "error",
    "A ros2_control sensor or gpio lists the same interface twice, or two components share a name.",
    """ros2_control exports `<component>/<interface>` once; the resource manager refuses a second
      interface with the same full name, so the hardware would not load. Remove the duplicate.""",
)

SPEC085 = declare(
    "SPEC085",
    "control-component-in-two-blocks",
    "error",
    "A joint, sensor or gpio is in two ros2_control blocks.",
    """Every block's interfaces go into one map of the resource manager, keyed `<component>/<interface>`;
      a second one with the same key throws "ResourceStorage: Tried to insert ... with already existing
      key" (ros2_control jazzy, hardware_interface/src/resource_manager.cpp), so no hardware loads.
      Keep each component in one block.""",
)

SPEC086 = declare(
    "SPEC086",
    "control-block-name-repeated",
    "error",
    "Two ros2_control blocks have the same name.",
    """The resource manager keys hardware components by name and stops loading at a repeated one:
      "Hardware name %s is duplicated. Please provide a unique 'name' in the URDF."
      (hardware_interface/src/resource_manager.cpp, load_and_initialize_components).""",
)

SPEC087 = declare(
    "SPEC087",
    "sensor-block-with-commands",
    "error",
    "A ros2_control block of type sensor declares command interfaces.",
    """A sensor component exports no command interfaces (hardware_interface/sensor_interface.hpp,
      on_export_command_interfaces returns {}) and is never written, so the commands would not exist
      and every controller claiming one fails to activate. Make the block a system or drop the commands.""",
)

SPEC088 = declare(
    "SPEC088",
    "system-plugin-in-non-system-block",
    "error",
    "An actuator or sensor block uses mock_components/GenericSystem or gz_ros2_control/GazeboSimSystem.",
    """Both are registered with pluginlib only as hardware_interface::SystemInterface
      (hardware_interface/mock_components_plugin_description.xml; gz_ros2_control's GazeboSimSystemInterface),
      so the resource manager cannot load them for an actuator or sensor component. Make the block a system.""",
)

SPEC089 = declare(
    "SPEC089",
    "control-block-variants-differ",
    "error",
    "A further ros2_control block declares other hardware variants than the first block.",
    """One Xacro argument, hardware:=mock|gazebo|real, selects the hardware of every block; a block
      without the selected variant would keep a mock (or no) plugin on the real robot or in Gazebo.
      Declare the same variants under every block's hardware.""",
)

SPEC100 = declare(
    "SPEC100",
    "collision-matrix-unknown-state",
    "error",
    "semantic.collision_matrix.default_state names no group state of the spec.",
    """The Default reason disables pairs in collision at that state; a misspelt name would fall back
      to another pose and disable the wrong pairs. Name one of semantic.group_states.""",
)

SPEC101 = declare(
    "SPEC101",
    "collision-matrix-padding-range",
    "error",
    "semantic.collision_matrix.padding is negative or larger than 100 mm.",
    """Padding inflates every collision shape while sampling: a large value makes near pairs look
      Always or Default and disables checks MoveIt needs; a negative one shrinks shapes and marks
      touching pairs Never. Use 0 to a few millimetres.""",
)

SPEC110 = declare(
    "SPEC110",
    "moveit-acceleration-missing",
    "error",
    "With moveit:, a joint of a planning group has no limit.acceleration.",
    """MoveIt on Jazzy refuses to time-parameterise a trajectory for a joint without an acceleration
      limit ("No acceleration limit was defined for joint", TOTG), and Pilz PTP throws; a URDF has no
      acceleration attribute, so joint_limits.yaml is the only place for it. State the team's chosen
      limit with its source under the joint's limit: (e.g. 'acceleration: 180 deg/s^2').""",
)

SPEC111 = declare(
    "SPEC111",
    "moveit-velocity-missing",
    "error",
    "With moveit:, a joint of a planning group has no (positive) velocity limit.",
    """TOTG refuses a joint without a bounded velocity ("No velocity limit was defined for joint"), so
      the MoveIt package would plan nothing for the group. Add limit: with velocity and acceleration.""",
)

SPEC112 = declare(
    "SPEC112",
    "moveit-kinematics-unknown-group",
    "error",
    "moveit.kinematics names a group the spec does not define.",
    """MoveIt skips kinematics.yaml entries for groups missing from the SRDF, so a misspelt group
      silently keeps no IK solver. Name one of semantic.groups.""",
)

SPEC113 = declare(
    "SPEC113",
    "moveit-initial-state-unknown",
    "error",
    "moveit.initial_state names no group state of the spec.",
    """initial_positions.yaml is written from that state; a misspelt name would silently start the
      demo at another pose. Name one of semantic.group_states.""",
)

SPEC114 = declare(
    "SPEC114",
    "moveit-group-without-controller",
    "warning",
    "With moveit:, no ros2_control action-server controller commands some joints of a planning group.",
    """MoveIt executes through controllers listed in moveit_controllers.yaml; without one for the group
      it can plan but execution fails ("Unable to identify any set of controllers that can actuate the
      specified joints"). Add a joint_trajectory_controller for the group's joints, or accept plan-only use.""",
)

SPEC115 = declare(
    "SPEC115",
    "moveit-without-groups",
    "error",
    "moveit: is set, but the spec has no semantic.groups.",
    """A MoveIt config package plans for SRDF groups; without one there is nothing to configure.""",
)

SPEC116 = declare(
    "SPEC116",
    "moveit-limit-not-positive",
    "error",
    "A MoveIt limit that is a magnitude (joint acceleration, Pilz limits, IK timeout) is zero or negative.",
    """TOTG rejects a negative max_acceleration, and zero stops every motion; Pilz and the IK plugins
      read these as magnitudes. Write a positive value with its unit.""",
)

SPEC120 = declare(
    "SPEC120",
    "package-name-not-rep144",
    "error",
    "The generated package's name (package.name, or <robot>_description) does not start with a "
    "lowercase letter or is no REP 144 name.",
    """The package name is package.xml's <name>, the CMake project, FindPackageShare in the launch
      files and every package:// URI; colcon, rosdep and the ament index expect REP 144 names (lowercase
      letters, digits and single '_', starting with a letter). A robot named 2dof_planar is a good URDF
      name but its package cannot be 2dof_planar_description: add package: {name: ...} with the
      suggested name (the robot and its files keep their name).""",
)

SPEC121 = declare(
    "SPEC121",
    "derived-package-name-advice",
    "warning",
    "The derived package name <robot>_description has uppercase letters or '__' (REP 144 says it must not).",
    """catkin_pkg accepts such a name with a warning, so specs that generated before still do; but
      REP 144 requires lowercase (file systems without case) and no '__' (generated symbols use it as a
      separator). Add package: {name: ...} with the suggested name.""",
)

SPEC125 = declare(
    "SPEC125",
    "multi-dof-value-count",
    "error",
    "A group-state or known-pose value has the wrong number of values for its joint type.",
    """srdfdom reads one number per variable, and MoveIt (RobotModel::buildGroupStates) drops a joint's
      value whose count differs from the joint model's variables, with only a log line: planar takes x, y,
      theta, floating trans_x..z and rot_x..w (planar_joint_model.cpp, floating_joint_model.cpp), a 1-DOF
      joint exactly one. The hint shows a list in that order.""",
)

SPEC126 = declare(
    "SPEC126",
    "floating-value-not-unit-quaternion",
    "error",
    "A floating joint's group-state value has a rotation that is not a unit quaternion (within 1e-9).",
    """MoveIt renormalises such a quaternion silently (FloatingJointModel::normalizeRotation), so the
      pose the SRDF names is not the one written; a typo in a component goes unnoticed.""",
)

SPEC127 = declare(
    "SPEC127",
    "quaternion-component-not-a-number",
    "error",
    "A quaternion component of a floating joint's value is not a plain number.",
    """rot_x..rot_w have no unit; a text such as "1 deg" or "a" would be a guess about what was meant.""",
)

SPEC130 = declare(
    "SPEC130",
    "waiver-unused",
    "warning",
    "A waiver in the spec matches no finding (its code and subject, exactly as findings print them).",
    """A waiver that waives nothing hides nothing today, but it would silently accept a new finding
      of that code and subject tomorrow, and a typo in it means the finding it was written for still
      fails. Remove it, or copy the code and subject from the finding (as ruff reports an unused noqa).""",
)

SPEC140 = declare(
    "SPEC140",
    "prefix-invalid",
    "error",
    "The spec's prefix is not letters, digits and _ starting with a letter.",
    """The prefix is written before every frame, joint and ros2_control name, and into the Xacro as the
      `prefix` argument's default; a name it makes must stay a plain identifier (e.g. left_).""",
)

SPEC141 = declare(
    "SPEC141",
    "namespace-invalid",
    "error",
    "The spec's namespace is not a ROS namespace: names of letters, digits and _ (not starting with a digit), "
    "separated by /.",
    """The launch files start every node of the robot in this namespace (robot_state_publisher, the controller
      manager, the spawners); rcl refuses a namespace with other characters, a doubled or a trailing /.""",
)

SPEC142 = declare(
    "SPEC142",
    "composed-spec-unusable",
    "error",
    "A compose: entry's spec cannot be used: an absolute path, one that leaves the project, a missing or refused "
    "file, a spec that composes itself (directly or not), or composition nested too deep.",
    """The mounted robot is read as descgen reads any spec; its own errors are listed beside this one, in its file.
      A spec is named relative to the one that composes it and stays inside the project, so the composition works
      on any machine and reads nothing else.""",
)

SPEC143 = declare(
    "SPEC143",
    "composed-parent-unknown",
    "error",
    "A compose: entry's parent is not a frame of the robot that composes it.",
    """The mounted robot's root hangs from this frame on a fixed joint; a frame that does not exist would leave the
      mounted robot a second tree. Name one of this robot's links (or a robot composed before it).""",
)

SPEC144 = declare(
    "SPEC144",
    "composition-conflict",
    "error",
    "Composing the robots would give two elements one name, or mix what one robot cannot hold: a name both have "
    "after their prefixes, pass-through XML (its names cannot be prefixed), or hardware variants that differ.",
    """Every mounted robot needs its own prefix, and names of the composing robot must not start with one. A
      pass-through element names links and joints in text descgen does not rewrite; keep it in the composing spec,
      written with the prefixed names. The Xacro's hardware:= argument selects one variant for every
      <ros2_control> block, so the robots must offer the same variants.""",
)

SPEC145 = declare(
    "SPEC145",
    "composed-odometry-tf-off",
    "info",
    "A mounted robot's diff drive controller published its root frame (odom -> base); mounted on a fixed joint, "
    "its odometry tf is turned off (enable_odom_tf: false).",
    """A robot's root has one parent on /tf. Mounted, the fixed joint publishes the root; the diff drive's odom tf
      would publish it too (FRAME001). Robots that drive in one graph are separate specs, each with its own prefix
      and namespace, audited with descgen audit --together (docs/multi-robot.md).""",
)

SPEC146 = declare(
    "SPEC146",
    "rw-rate-not-whole",
    "error",
    "A <ros2_control> block's rw_rate is not a whole, non-negative number of Hz.",
    """ros2_control reads rw_rate as an integer (std::stoi: 12.5 Hz would run at 12 Hz, without a word) and refuses a
      negative one. Write a whole number of Hz, or leave it out to run at the controller manager's rate.""",
)

SPEC147 = declare(
    "SPEC147",
    "thread-priority-without-async",
    "error",
    "A <ros2_control> block sets thread_priority but is not is_async: true.",
    """Jazzy's parser reads thread_priority only for an async component; on any other it is ignored, so the value
      written would mean nothing. Set is_async: true, or leave thread_priority out.""",
)

SPEC148 = declare(
    "SPEC148",
    "moveit-with-namespace",
    "error",
    "A spec sets both moveit: and namespace:; descgen's MoveIt config package does not run in a namespace yet.",
    """The MoveIt package's launch files start ros2_control_node, move_group and the spawners at the root namespace,
      while the namespaced controllers YAML names /<ns>/controller_manager: the package would not run. Leave one
      out (docs/multi-robot.md).""",
)

SPEC149 = declare(
    "SPEC149",
    "mujoco-variant-plugin",
    "error",
    "The mujoco hardware variant names another plugin than mujoco_ros2_control/MujocoSystemInterface, or its own "
    "mujoco_model.",
    """Jazzy's mujoco_ros2_control (0.1.0) is the plugin mujoco_ros2_control/MujocoSystemInterface, and its
      mujoco_model parameter is the MJCF file generate writes beside the URDF (mujoco/<robot>.xml), which the proofs
      compile and compare with the robot (docs/mujoco_ros2_control.md).""",
)

SRDF010 = declare(
    "SRDF010",
    "group-state-unknown-pose",
    "error",
    "A semantic group state names a known pose that the spec does not define.",
    """The SRDF group state is written from the known pose's joint values; with no such pose there
      is nothing to write. Name one of the known poses.""",
)

UNIT001 = declare(
    "UNIT001",
    "missing-unit",
    "error",
    "A quantity is a bare number (or not a quantity at all) where a value with a unit is expected.",
    """A bare 300 could be millimetres or metres; reading it in the wrong unit is off by 1000 and
      nothing downstream could tell. Write the unit it was measured in; the hint suggests one that
      fits the field's kind and the number's size. Exactly 0 needs no unit.""",
)

UNIT002 = declare(
    "UNIT002",
    "unreadable-quantity",
    "error",
    "Quantity text that pint cannot read, is empty, holds a comma, or is not finite.",
    """pint would misread some text ("1,5 m" is 15 m), and a NaN or infinite value poisons every
      computation. Write a number and a unit, e.g. "300 mm", with a decimal point.""",
)

UNIT003 = declare(
    "UNIT003",
    "wrong-kind-of-quantity",
    "error",
    "A quantity of the wrong kind for its field "
    "(a mass where a length belongs, an angle unit where none is allowed, an energy for a torque).",
    """Converting it would produce a number in the wrong SI unit. Write a quantity of the field's
      kind; the hint gives an example.""",
)

UNIT004 = declare(
    "UNIT004",
    "implausible-value",
    "error",
    "A value outside the plausible range for its role (offset, size, mass, joint travel, ...).",
    """The ranges are wide on purpose: they catch values a thousand times off (millimetres typed as
      metres, grams as kilograms), not design choices. Fix the unit, or widen plausibility.<role> in
      the spec if the value is right.""",
)

UNIT020 = declare(
    "UNIT020",
    "quantity-too-complex",
    "error",
    "Quantity text that is too long, has too many "
    "digits, or raises to a power pint would need unbounded time to evaluate.",
    """pint evaluates quantity text as arithmetic, so "9**9**9 kg" would hang; such text is refused
      before pint sees it (docs/security.md). Write a plain number and unit.""",
)

YAML001 = declare(
    "YAML001",
    "yaml-unreadable",
    "error",
    "The spec is not well-formed YAML, or uses YAML that is refused "
    "(merge keys, non-scalar keys, unbuildable tags, too deep, too many nodes).",
    """Nothing can be checked in a file that does not parse, and some YAML features (aliases that
      expand exponentially, tags, merge keys) hide what a value really is. Fix the YAML at the given
      line; write keys out instead of merging them.""",
)

YAML002 = declare(
    "YAML002",
    "spec-not-found",
    "error",
    "The spec file (or a folder of specs) could not be read.",
    """A missing or unreadable file is a typo in the path or a permission problem. Check the path;
      a folder must hold *.yaml specs.""",
)

YAML003 = declare(
    "YAML003",
    "spec-not-text",
    "error",
    "The spec is binary, not UTF-8, or larger than the size limit.",
    """A spec is a few kilobytes of UTF-8 text; anything else is the wrong file, and reading a huge
      one would exhaust memory (docs/security.md). Save the spec as UTF-8 text.""",
)

YAML004 = declare(
    "YAML004",
    "spec-empty",
    "error",
    "The spec file is empty.",
    """An empty file describes no robot. Write a spec (see specs/warehouse_arm.yaml).""",
)

YAML010 = declare(
    "YAML010",
    "spec-not-regular-file",
    "error",
    "The named spec is a FIFO, device, socket or folder.",
    """Reading a FIFO or a device can block forever or never end, so it is refused before it is
      opened (docs/security.md). Name a regular file.""",
)
