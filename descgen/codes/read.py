"""Codes of reading third-party descriptions: URDF, Xacro, SRDF, controllers YAML (launch substitutions too).

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("read")


CTRL052 = declare(
    "CTRL052",
    "launch-var-without-value",
    "warning",
    "A controllers YAML holds a $(var NAME) launch substitution and no --launch-arg NAME:=VALUE (or default "
    "in the file) gives its value; names that hold it are not checked against the URDF.",
    """A launch file loads such a file with ParameterFile(..., allow_substs=True) (ros2_control_demos
      example_1: $(var joint_prefix)1), so the literal text is not what the controller sees. Reporting
      the literal as an unknown joint would be a false error; the warning stands for it. Pass the launch
      argument's value with --launch-arg to check the names.""",
)

CTRL053 = declare(
    "CTRL053",
    "launch-substitution-not-evaluated",
    "warning",
    "A controllers YAML holds a launch substitution descgen does not evaluate ($(env), $(eval), $(command), "
    "$(find-pkg-share), ..., or one launch cannot parse); it is left as written.",
    """An audited file is data: evaluating it would read the environment (secrets), run Python or
      commands, or search the file system. Only $(var NAME) is evaluated, from --launch-arg values.
      Names that hold the substitution are not checked; write the value, or a $(var) given with
      --launch-arg.""",
)

CTRL054 = declare(
    "CTRL054",
    "launch-substitution-refused",
    "error",
    "A --launch-arg is not NAME:=VALUE (or its value holds a control character or is too long), or a "
    "controllers YAML holds too many, too deeply nested or too large launch substitutions.",
    """Limits keep a hostile file (a substitution bomb) from exhausting memory or time, and a
      newline in a value would add YAML lines that are not in the file. Exit 2, nothing read further.""",
)

CTRL055 = declare(
    "CTRL055",
    "launch-arg-without-controllers",
    "error",
    "--launch-arg is given to audit or import without --controllers: nothing would read its value.",
    """Launch arguments are the values of $(var NAME) substitutions in the controllers YAML named by
      --controllers (a MoveIt config's ros2_controllers.yaml is read as written). Ignoring the option
      silently would let a user believe a substitution was checked with that value. Exit 2, nothing
      read or written.""",
)

CTRL056 = declare(
    "CTRL056",
    "controllers-entry-without-type",
    "info",
    "A top-level entry of a controllers YAML has ros__parameters but no type, neither its own nor under "
    "controller_manager: it is not read as a controller, so nothing in it is checked.",
    """Jazzy takes a controller's type from controller_manager.ros__parameters.<name>.type or from
      <name>.ros__parameters.type; a spawner may also pass --controller-type, and one parameter file
      may hold other nodes' parameters. descgen cannot tell which, so it does not guess a type and
      says that the entry went unchecked, instead of dropping it silently.""",
)

MOVEIT020 = declare(
    "MOVEIT020",
    "moveit-config-not-mapping",
    "error",
    "A MoveIt config YAML file (joint_limits, moveit_controllers, kinematics, initial_positions) "
    "is empty or its root is not a mapping.",
    """MoveItConfigsBuilder loads each file as a mapping of ROS parameters; a list, a scalar or an
      empty file gives MoveIt nothing (or an exception), so there is nothing to audit. Write key: value
      lines, as the Setup Assistant lays the file out.""",
)

MOVEIT021 = declare(
    "MOVEIT021",
    "moveit-config-folder-unusable",
    "error",
    "The --moveit-config folder does not exist, or holds none of the MoveIt config files.",
    """A wrong folder would otherwise audit nothing and report no finding, which reads as a clean
      MoveIt config. Name the package folder (or its config/) that holds joint_limits.yaml.""",
)

READ001 = declare(
    "READ001",
    "description-unreadable",
    "error",
    "A description file is missing, unreadable, or not well-formed XML.",
    """Nothing in a file that does not parse can be audited. Check the path, or fix the XML at the
      given position.""",
)

READ002 = declare(
    "READ002",
    "xml-doctype",
    "error",
    "An XML description declares a DTD (<!DOCTYPE ...>).",
    """Entities in a DTD can expand exponentially or read local files (XXE); URDF and SRDF need no
      DTD, so it is refused. Remove the declaration.""",
)

READ003 = declare(
    "READ003",
    "not-a-urdf",
    "error",
    "The XML root element is not <robot>.",
    """The file is probably not a URDF (a launch file, an SDF). Name the robot's URDF or Xacro.""",
)

READ004 = declare(
    "READ004",
    "xacro-failed",
    "error",
    "xacro could not expand the file.",
    """A Xacro that does not expand gives no robot to audit; usually an argument or a package path
      is missing. Pass --xacro-arg NAME:=VALUE and --package-path DIR.""",
)

READ005 = declare(
    "READ005",
    "bad-xacro-arg-option",
    "error",
    "A --xacro-arg option is not NAME:=VALUE.",
    """xacro's argument syntax is name:=value; anything else would be silently ignored. Write e.g.
      --xacro-arg use_gripper:=true.""",
)

READ010 = declare(
    "READ010",
    "urdf-value-malformed",
    "error",
    "A URDF attribute or element is malformed "
    "(wrong count of numbers, not numbers, an empty <geometry>, a missing required attribute).",
    """urdfdom refuses or misreads such values, so the robot would not load in ROS. Write the value
      as the URDF specification requires; the message names the element.""",
)

READ011 = declare(
    "READ011",
    "srdf-value-not-one-number",
    "varies",
    "An SRDF group-state joint value is not one number (a warning for multi-DOF values, an error otherwise).",
    """Group states of 1-DOF joints are one number; descgen cannot check other values against the
      URDF limits. Write one number per 1-DOF joint.""",
)

READ012 = declare(
    "READ012",
    "robot-without-name",
    "error",
    "<robot> has no name attribute.",
    """urdfdom refuses a robot without a name. Add name="..." to <robot>.""",
)

READ013 = declare(
    "READ013",
    "robot-without-links",
    "error",
    "The robot has no links.",
    """urdfdom refuses an empty robot; this is usually the wrong file or a Xacro whose arguments
      switched everything off.""",
)

READ020 = declare(
    "READ020",
    "controllers-not-mapping",
    "error",
    "A controllers YAML file is not a mapping.",
    """controller_manager reads a mapping of node names to ros__parameters; anything else configures
      nothing. Check that this is the controllers file.""",
)

READ030 = declare(
    "READ030",
    "xacro-code-refused",
    "error",
    "An audited Xacro expression uses code outside the restricted evaluator's allow-list.",
    """xacro evaluates ${} and $(eval) as Python, so an audited file could run code. descgen's
      evaluator allows arithmetic, math and properties only (docs/security.md). If you trust the file,
      pass --trust-xacro.""",
)

READ031 = declare(
    "READ031",
    "xacro-file-outside-package",
    "error",
    "An audited Xacro includes or loads a file "
    "outside its package and the --package-path folders, or one that is not a regular file.",
    """Reading any file would let a description exfiltrate secrets into findings. Pass the package's
      folder with --package-path, or move the file into the package.""",
)

READ032 = declare(
    "READ032",
    "xacro-environment-refused",
    "error",
    "An audited Xacro reads an environment variable outside the allow-list, or $(cwd).",
    """The environment holds secrets (tokens, paths); only ROS_DISTRO, ROS_VERSION and
      ROS_PYTHON_VERSION are readable. Pass the value as --xacro-arg instead.""",
)

READ033 = declare(
    "READ033",
    "xacro-limit-exceeded",
    "error",
    "An audited Xacro exceeds a bound (number size, string length, loop, macro calls, elements, text, evaluation "
    "steps, time).",
    """Unbounded expansion would hang or exhaust memory; the bounds are far beyond any real robot.
      Simplify the expression, or pass --trust-xacro for a file you trust.""",
)

READ040 = declare(
    "READ040",
    "description-not-regular-file",
    "error",
    "A named description is a FIFO, device, socket or folder.",
    """Reading it could block forever or never end, so it is refused before it is opened. Name a
      regular file.""",
)

READ041 = declare(
    "READ041",
    "description-too-large",
    "error",
    "A description file is larger than the limit (64 MiB).",
    """Real descriptions are a few megabytes at most; a larger file is the wrong file and would
      exhaust memory. Check the path.""",
)

READ042 = declare(
    "READ042",
    "non-finite-number",
    "error",
    "A URDF, SRDF or controllers value is nan, inf or overflows (1e999).",
    """A non-finite number poisons kinematics, inertia and limits; the value is treated as missing.
      Write the measured value as a plain decimal number.""",
)

declare.redirected(
    "READ043",
    "controllers-shape",
    "error",
    "A controllers YAML has a list or a scalar where a mapping belongs.",
    """ros2_control reads parameters from mappings; the wrong shape configures nothing or crashes
      the node. Write key: value lines indented below the key. Since controllers files are read as
      rcl reads them, such a file is one ROS refuses to load: READ045.""",
    to="READ045",
    issue=28,
)

READ044 = declare(
    "READ044",
    "link-out-of-named-folder",
    "error",
    "A file of a folder you named (--moveit-config, a template folder) is a symbolic link out of it.",
    """Only files inside the folders you name are read (docs/security.md): a link to
      /proc/self/environ or ~/.ssh would put their text into findings or generated files. Copy the
      file into the folder instead of linking to it.""",
)

READ045 = declare(
    "READ045",
    "params-file-not-loadable",
    "error",
    "A controllers (parameter) file holds what ROS's parameter parser refuses: an alias, a value above "
    "ros__parameters, an empty value, a list of mixed types or of mappings, an invalid node name.",
    """rcl_yaml_param_parser refuses the whole file (docs/ros2_parameters.md), so the controller manager
      starts without any of it; descgen reads it as nothing rather than guess. Write the value out, quote
      a string, split a list of mappings into named parameters, or fix the node name.""",
)

READ046 = declare(
    "READ046",
    "parameter-given-twice",
    "warning",
    "A parameter file gives one node's parameter twice (in one block, or in two blocks naming the same "
    "node): ROS keeps the later value in the earlier place.",
    """rcl finds the parameter again and overwrites its value (docs/ros2_parameters.md), so one of the two
      lines is dead text that a reader may take for the value in force. Delete the one that is not meant.""",
)

READ047 = declare(
    "READ047",
    "not-an-srdf",
    "error",
    "The file given as the SRDF is not one: its root is not <robot>, it is a URDF (links and joints), "
    "or it still holds Xacro after reading.",
    """An SRDF read as something else would give an empty semantic model with no word: every group,
      state and disabled pair missing, and the audit silent about them. Give the SRDF (an .srdf.xacro
      is expanded with --xacro-arg values), or leave --srdf out.""",
)

READ048 = declare(
    "READ048",
    "parameter-without-value",
    "error",
    "A parameter file gives a parameter an empty list; rclcpp refuses a parameter without a value, so "
    "the nodes it reaches (a controller, the controller manager) do not start.",
    """rcl keeps the parameter with no value and rclcpp's parameter_value_from throws "No parameter value
      set" when a node that it reaches starts (docs/ros2_parameters.md). Give the list its values, or
      delete the line.""",
)

READ049 = declare(
    "READ049",
    "waivers-file-invalid",
    "error",
    "The package's descgen-waivers.yaml is not a list of waivers (code, subject and reason, each a string).",
    """descgen generate writes the file from the spec's waivers: and descgen audit reads it for a
      description inside the package; a file it cannot read as waivers would waive nothing, or the wrong
      findings. Regenerate the package (descgen generate), fix the file, or audit with --no-waivers.""",
)
