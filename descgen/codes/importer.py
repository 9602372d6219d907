"""Codes of ``descgen import``: a URDF or Xacro (with its SRDF and controllers) becomes a spec.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("import")


IMP001 = declare(
    "IMP001",
    "import-roundtrip-differs",
    "error",
    "The imported spec, loaded, rendered and read back, is not the description it came from.",
    """import proves the spec before writing it: a difference means a value would change on the way
      to the generated URDF. Nothing is written; the message names the element and both values. It is a
      bug of descgen import: please report it with the description.""",
)

IMP002 = declare(
    "IMP002",
    "import-already-spec",
    "error",
    "The file given to import is already a descgen spec.",
    """import reads a URDF or a Xacro; a spec is validated and generated as it is.""",
)

IMP003 = declare(
    "IMP003",
    "import-passthrough",
    "info",
    "An element the spec has no field for (Gazebo tag, transmission, ros2_control, unknown tag) is kept "
    "verbatim in passthrough:.",
    """Nothing may be lost silently. generate writes the element back unchanged (in the Xacro every $ stays
      data), and the round trip proves it comes back as the same XML. Review it like the rest of the spec.""",
)

IMP004 = declare(
    "IMP004",
    "import-not-kept",
    "warning",
    "An element is not kept in the spec: inside a link or joint where the spec has no field, or a "
    "top-level element that cannot be pass-through (a xacro instruction).",
    """The generated description will lack it. Add what it means by hand if the robot needs it; a xacro
      instruction in pass-through would be run by xacro, so it is never kept.""",
)

IMP005 = declare(
    "IMP005",
    "import-controllers-not-imported",
    "warning",
    "The controllers YAML given to import is not written into the spec.",
    """The <ros2_control> blocks stay verbatim in passthrough:, and the spec's controllers section would
      generate a second block. Keep the controllers file beside the generated package.""",
)

IMP007 = declare(
    "IMP007",
    "import-output-exists",
    "error",
    "The -o spec file exists already.",
    """A spec is reviewed and edited by hand; import never replaces one unless told to. Choose another
      file, or pass --force.""",
)

IMP011 = declare(
    "IMP011",
    "import-state-value-not-kept",
    "warning",
    "A group-state value of the SRDF that the spec cannot hold (several numbers for a joint that is no "
    "planar/floating virtual joint, or unreadable) is not kept.",
    """The spec holds one number per joint in a group state, or a list for a planar or floating virtual
      joint (kept since the spec takes lists). Anything else cannot be written there. Nothing may be lost
      silently: the value and its SRDF line are reported, and the generated SRDF lacks it until it is
      added by hand.""",
)

declare.retired(
    "IMP012",
    "import-package-outside-project",
    "info",
    "A package named by package:// meshes lies outside the imported spec's project, so the spec cannot "
    "record it under package_paths:.",
    """A spec recorded package folders only inside its project; a package elsewhere had to be named on
      the command line of every later command.""",
    issue=28,
    why="a spec's package_paths: may now lie outside the project (only packages are read there, each "
    "inside itself), so import records the folder relative to the spec; a package the sourced "
    "environment finds is found again the same way on any machine",
)

IMP013 = declare(
    "IMP013",
    "import-structure-not-used",
    "info",
    "Repeated parts or cameras that import recognised are written as plain links and joints, because the "
    "spec with parts:/sensors: did not give back the same robot.",
    """parts: and sensors: are written only when the generated URDF stays the same robot; otherwise the
      flat spec (which the round trip proves) is written instead. Nothing is lost.""",
)

IMP014 = declare(
    "IMP014",
    "import-package-name-chosen",
    "info",
    "The imported spec names its package (package.name) because <robot>_description is no REP 144 name "
    "or is the package its meshes come from.",
    """A robot named 2dof_planar is a valid URDF, but 2dof_planar_description is no ROS package name
      (REP 144: it must start with a lowercase letter); UR's robot ur would generate ur_description, the
      upstream package that holds its meshes, and two packages of one name shadow each other. import
      writes a valid, distinct name (robot_2dof_planar_description, ur_descgen_description); rename it
      as you like.""",
)

IMP020 = declare(
    "IMP020",
    "import-ros2-control-variant",
    "info",
    "A <ros2_control> block is imported into ros2_control: with the hardware the description expands to "
    "for the given --xacro-arg values.",
    """A Xacro may choose its hardware plugin by an argument (use_mock_hardware, use_gazebo): import sees one
      expansion, so it says which hardware it imported. Other variants are added under hardware.variants by
      hand (or seen by importing with other arguments).""",
)

IMP021 = declare(
    "IMP021",
    "import-ros2-control-passthrough",
    "info",
    "A <ros2_control> block holds something the spec's ros2_control: cannot say, so every block stays "
    "verbatim in passthrough:.",
    """Nothing may be lost silently: a transmission, a joint-level param, an interface size or an unknown
      param has no spec field. All blocks stay together (one block in the spec and one in pass-through would be
      two sources of one hardware); the message names what could not be expressed.""",
)

IMP022 = declare(
    "IMP022",
    "import-ros2-control-derived-params",
    "info",
    "generate writes interface params that the imported <ros2_control> block leaves to ros2_control's "
    "defaults: command min/max from the URDF limits, state initial_value.",
    """The generated block always states them. Jazzy only tightens the URDF limits with min/max, so equal
      values change nothing, and 0 is GenericSystem's start value; a joint whose range excludes 0 starts mid-range.
      The round trip allows exactly these additions and lists them so a reviewer can check them.""",
)

IMP023 = declare(
    "IMP023",
    "import-update-rate-default",
    "info",
    "No controller_manager update_rate was given; the imported spec says 100 Hz, controller_manager's default.",
    """The spec states the rate the generated controllers file writes; 100 Hz is what controller_manager runs at
      without one. Write the real rate of your hardware.""",
)

IMP024 = declare(
    "IMP024",
    "import-controllers-entry-not-imported",
    "warning",
    "An entry of the controllers YAML is not imported: a controller_manager parameter other than update_rate "
    "and the controller types, an entry that names no controller, or a controller whose name or type the spec "
    "cannot hold.",
    """The generated config/ros2_controllers.yaml lacks it, so it is said, never silently dropped. Keep it in a
      parameters file of your own if the robot needs it.""",
)

IMP025 = declare(
    "IMP025",
    "import-wheel-params-derived",
    "info",
    "A diff_drive_controller in the imported controllers file gives no wheel_separation/wheel_radius; "
    "generate writes the values derived from the URDF.",
    """diff_drive_controller needs both; descgen derives them from the wheel joints and collision cylinders.
      State measured values under calibrated: if the robot has them.""",
)

IMP026 = declare(
    "IMP026",
    "import-continuous-limit-dropped",
    "info",
    "A continuous joint's lower/upper limit is left out of the imported spec.",
    """urdfdom reads lower and upper on any joint, but no consumer applies them to a continuous one:
      ros2_control's joint_limits (joint_limits_urdf.hpp) marks it angle_wraparound, MoveIt unbounds it
      (RevoluteJointModel::setContinuous, after reading them), and descgen's URDF does not write them.
      Kept, they would read as limits the robot does not have; dropped, the round trip compares what
      every reader uses. Reported so nothing is lost silently.""",
)

IMP027 = declare(
    "IMP027",
    "import-variant-option",
    "error",
    "--variant is malformed, repeats a name, lacks the mock variant, or is given for a file that is no Xacro.",
    """The spec's hardware variants are mock (the spec's own hardware), gazebo and real, selected in the
      generated Xacro by hardware:=; import needs the Xacro arguments that give each, and the mock one
      because the spec's hardware.plugin must be mock_components/GenericSystem when variants exist.""",
)

IMP028 = declare(
    "IMP028",
    "import-variants-differ",
    "error",
    "Two hardware variants of a Xacro expand to different robots (links, joints, limits, pass-through or "
    "<ros2_control> components), not only different <hardware>.",
    """The spec's hardware.variants change the hardware plugin and its params and nothing else; a variant
      that changes a link could not be given back by hardware:=, so import stops at the first difference
      and writes nothing.""",
)

IMP029 = declare(
    "IMP029",
    "import-variant-hardware",
    "error",
    "A hardware variant's plugin is not what the spec allows under that name (mock: GenericSystem, gazebo: "
    "GazeboSimSystem, real: a vendor plugin), or the blocks cannot leave pass-through.",
    """The spec would refuse the variant on load (SPEC080-082); refusing at import names the variant and
      its arguments, which the spec error could not.""",
)

IMP030 = declare(
    "IMP030",
    "import-variants-imported",
    "info",
    "The <ros2_control> hardware is imported for several variants; the generated Xacro selects them with hardware:=.",
    """Replaces IMP020 (one variant) when --variant is given: the launch files that passed
      use_mock_hardware or sim_gazebo now pass hardware:=mock|gazebo|real.""",
)

IMP031 = declare(
    "IMP031",
    "import-launch-substitution",
    "info",
    "A launch substitution in the controllers YAML was replaced by its --launch-arg value (or the file's "
    "default) in the imported spec.",
    """The spec holds the names the controller sees with these launch arguments, not the $(var) text:
      the generated controllers file is loaded without substitutions. Import with the values your
      launch file uses.""",
)

IMP032 = declare(
    "IMP032",
    "import-launch-substitution-unresolved",
    "error",
    "The controllers YAML holds a launch substitution without a value ($(var NAME) without --launch-arg), or "
    "one descgen does not evaluate; the import stops.",
    """The spec's controller joint names must be the robot's joints, and the literal $(var ...) is
      none; guessing a value would import a robot that differs from the one launched. Pass
      --launch-arg NAME:=VALUE, or write the value into the file. Exit 2, nothing written.""",
)

IMP033 = declare(
    "IMP033",
    "import-output-not-regular",
    "error",
    "The -o path is a symbolic link, FIFO, device or folder.",
    """import writes a spec as a regular file; --force replaces only a regular file, never a link (it
      would write through or replace it) nor a device or FIFO (run as root, replacing /dev/null breaks the
      machine). Name a file path.""",
)

IMP034 = declare(
    "IMP034",
    "import-output-unwritable",
    "error",
    "The -o spec file cannot be written (a file in the way of its folder, no permission, a read-only disk).",
    """Nothing is written. Choose another -o file.""",
)

IMP035 = declare(
    "IMP035",
    "import-too-large",
    "error",
    "The description has more links than descgen answers for (10,000), or its spec would be larger than "
    "validate reads (16 MiB, 2,000,000 YAML nodes); the import stops.",
    """A spec that validate refuses is no import: every command that reads it would stop at the size
      bound, and the round trip could not prove it. Exit 2, nothing written; split the description.""",
)

IMP036 = declare(
    "IMP036",
    "import-absolute-mesh-as-package",
    "info",
    "A mesh named by an absolute path or file:// (a Xacro's file://$(find pkg)/... expanded) lies in a "
    "package, and is written package://pkg/... in the spec.",
    """The expansion holds this machine's path; a spec records nothing machine-specific (SPEC061 refuses
      an absolute mesh), and package:// is what RViz, Gazebo and MoveIt resolve to the same file on any
      machine that has the package (docs/packages.md). The file is the same one: the audit read it.""",
)

IMP037 = declare(
    "IMP037",
    "import-disabled-pair-repeated",
    "info",
    "The SRDF disables one link pair twice; the spec keeps the first (MoveIt's collision matrix holds the "
    "pair once, whatever the reasons).",
    """MoveIt allows a repeated <disable_collisions> (the allowed collision matrix marks the pair again);
      a spec names each pair once (SPEC024), so import keeps the first with its reason and says which
      line it left out.""",
)

IMP038 = declare(
    "IMP038",
    "import-waivers-written",
    "info",
    "The description has defects the spec's rules report as errors; import writes a waiver for each "
    "(reason 'imported as is'), so validate, generate, check and report work at once.",
    """The spec is the description as it is, defects included, and the defects are still reported,
      as waived, in every output and on the evidence page: the list of what is left to fix. Remove a
      waiver when its defect is fixed (an unused waiver is SPEC130). Input errors (a spec that cannot be
      built) and descgen's own proofs are never waived.""",
)

IMP039 = declare(
    "IMP039",
    "import-fixed",
    "info",
    "import --fix applied the fixes that cannot change the robot to the imported spec (Jazzy's one-to-one "
    "renames, parameters Jazzy removed): the spec is no longer the description word for word there.",
    """Each fix is listed; the rest of the spec is the description as it is, its defects waived as usual
      (IMP038). The same fixes are what descgen fix SPEC applies to a spec you have.""",
)

IMP040 = declare(
    "IMP040",
    "import-group-state-without-group",
    "warning",
    "The SRDF has a group state with no group; MoveIt's SRDF parser refuses such a state, so the spec leaves it out.",
    """srdfdom requires a group_state's group and skips the state without one, so MoveIt never offers it;
      a spec's group state names its group (SPEC050). Add the group to the SRDF's state (the audit of the
      original reports it too) and import again, or write it under group_states: in the spec.""",
)

IMP041 = declare(
    "IMP041",
    "import-prefix-recognised",
    "info",
    "Every name of the Xacro carries its prefix (its prefix or tf_prefix argument): the spec says prefix: once "
    "and names everything without it.",
    """descgen applies the spec's prefix: to every frame, joint, ros2_control and controller name, and the
      generated Xacro takes it as its prefix argument, as the original took its own (docs/multi-robot.md). A
      description where some name lacks the prefix is imported name for name instead, and the audit's NAME014
      lists what lacks it.""",
)
