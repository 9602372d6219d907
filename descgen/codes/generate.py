"""Codes of ``generate`` and ``check``: the written package and the proofs of it.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("generate")


GEN001 = declare(
    "GEN001",
    "xacro-proof-failed",
    "error",
    "The generated Xacro does not expand, does not parse, or expands to a robot different from the generated URDF.",
    """The Xacro and the URDF must describe the same robot (check 1 in the README); a difference means
      a template is wrong. Fix the template that changed (or the --templates override).""",
)

GEN002 = declare(
    "GEN002",
    "package-xml-invalid",
    "error",
    "The generated package.xml is invalid or not format 3.",
    """colcon cannot build a package with an invalid manifest. Check the spec's package: section or
      the package.xml template.""",
)

GEN003 = declare(
    "GEN003",
    "controllers-proof-failed",
    "error",
    "The generated controllers YAML does not load, has a non-integer update rate, or names a joint the URDF lacks.",
    """controller_manager would refuse the file or the controller would fail to configure. Fix the
      joint names in the spec, or the controllers template.""",
)

GEN004 = declare(
    "GEN004",
    "edited-by-hand",
    "error",
    "A generated file was edited by hand (its content no longer matches its header hash).",
    """Regenerating would destroy the edit, so it is not overwritten. Move the change into the spec
      or a template, or pass --force to discard it.""",
)

GEN005 = declare(
    "GEN005",
    "generated-file-stale",
    "error",
    "A committed generated file is stale: the spec, the templates or descgen changed since it was written.",
    """What is committed no longer matches its source, so reviewers read the wrong files. Run
      descgen generate and commit the result.""",
)

GEN006 = declare(
    "GEN006",
    "generated-file-missing",
    "error",
    "A file descgen generates is missing on disk.",
    """The package is incomplete. Run descgen generate.""",
)

GEN007 = declare(
    "GEN007",
    "file-no-longer-generated",
    "error",
    "A file in the package is no longer generated.",
    """A leftover file is shipped and reviewed as if it were current. Run descgen generate, which
      removes it.""",
)

GEN010 = declare(
    "GEN010",
    "templates-not-folder",
    "error",
    "--templates names something that is not a folder.",
    """Template overrides are a folder of jinja2 files. Name that folder.""",
)

GEN020 = declare(
    "GEN020",
    "urdfdom-missing",
    "varies",
    "check_urdf (urdfdom) is not installed, so the URDF "
    "was not checked by urdfdom (an error when DESCGEN_REQUIRE_TOOLS=1, else info).",
    """urdfdom is what ROS loads URDFs with; without it one proof is missing. Install Debian's
      liburdfdom-tools.""",
)

GEN021 = declare(
    "GEN021",
    "urdfdom-rejected",
    "error",
    "check_urdf rejected the generated URDF.",
    """robot_state_publisher and every ROS tool would refuse the file. The URDF template or the
      model is broken; the message quotes urdfdom.""",
)

GEN030 = declare(
    "GEN030",
    "urdf-readback-differs",
    "error",
    "The URDF read back by an independent parser differs from the model (or it cannot read it).",
    """An independent parser must read what descgen meant (check 2); a difference means the template
      writes a field wrong or the file was edited. The parser is descgen's lxml read-back reader
      (urdfdom's rules, no code shared with the renderer or the model), plus yourdfpy under
      check --thorough.""",
)

GEN031 = declare(
    "GEN031",
    "srdf-readback-differs",
    "error",
    "The generated SRDF, read back, differs from the spec's semantics (or does not parse).",
    """MoveIt would plan with groups or states other than those specified. Fix the SRDF template.""",
)

GEN032 = declare(
    "GEN032",
    "ros2-control-readback-differs",
    "error",
    "The generated <ros2_control> block, read back, differs from the spec.",
    """The hardware would export other interfaces than specified. Fix the ros2_control template.""",
)

GEN033 = declare(
    "GEN033",
    "controllers-readback-differs",
    "error",
    "The generated controllers YAML, read back, differs from the spec.",
    """controller_manager would load other controllers or parameters than specified. Fix the
      controllers template.""",
)

GEN040 = declare(
    "GEN040",
    "symlink-in-package",
    "error",
    "A symbolic link inside the package folder.",
    """Following it could write outside the output root; it is refused, never followed
      (docs/security.md). Replace the link with the file.""",
)

GEN041 = declare(
    "GEN041",
    "package-folder-unsafe",
    "error",
    "The package folder is a symbolic link, or exists but is not a folder.",
    """generate swaps the package folder as a whole; a link or file there could redirect the write.
      Move it away.""",
)

GEN042 = declare(
    "GEN042",
    "output-root-unsafe",
    "error",
    "The output root is a symbolic link or not a folder.",
    """Writes must stay inside the output root the user named. Name a folder with --out, or replace
      the link with a folder.""",
)

GEN043 = declare(
    "GEN043",
    "special-file-in-package",
    "error",
    "A FIFO, socket or device inside the package folder.",
    """Reading or replacing it could block or touch a device. Remove it from the package folder.""",
)

GEN044 = declare(
    "GEN044",
    "output-root-locked",
    "error",
    "Another descgen run holds the lock on the output root.",
    """Two runs writing one package would mix their files. Wait for the other run, then run again.""",
)

GEN045 = declare(
    "GEN045",
    "package-write-failed",
    "error",
    "The package could not be written (disk full, read-only --out, ...).",
    """Writes are all or nothing, so the previous package is unchanged. Check free space and
      permissions of the output folder.""",
)

GEN060 = declare(
    "GEN060",
    "mesh-copy-stale",
    "error",
    "A mesh copied into the package differs from its source beside the spec (either was edited).",
    """Meshes are copied byte for byte, and binary files carry no header, so check compares each copy
      with its source (and the package's meshes/meshes.sha256 records what was copied). Run descgen
      generate and commit the result; change a mesh at its source, not in the package.""",
)

GEN061 = declare(
    "GEN061",
    "template-failed",
    "error",
    "A template override does not parse or fails to render, or (named by the spec) reaches past the sandbox.",
    """Templates recorded in a spec (templates:) are someone else's code and render in jinja2's
      immutable sandbox, so they cannot walk from a value to Python internals; a refusal or a broken
      override is reported at the template instead of a traceback. Fix the template.""",
)

GEN065 = declare(
    "GEN065",
    "template-not-a-file-in-folder",
    "error",
    "A template override is a symbolic link out of its folder, not a regular file, or too large.",
    """A template is read like any other input: a link to /proc/self/environ would render the
      environment (CI tokens) into the package, and a FIFO would block. Put the template itself in the
      folder, as a regular file of at most 1 MiB.""",
)

GEN070 = declare(
    "GEN070",
    "collision-matrix-unavailable",
    "error",
    "The spec asks for a sampled collision matrix (semantic.collision_matrix) but it cannot be computed: "
    "pinocchio (descgen[collision]) is missing or cannot load the collision geometry.",
    """Writing the SRDF without the matrix the spec asks for would silently leave MoveIt checking
      (or skipping) pairs nobody measured. Install the extra (pip install 'descgen[collision]'),
      fix the geometry pinocchio names, or remove semantic.collision_matrix.""",
)

GEN080 = declare(
    "GEN080",
    "evidence-page-stale",
    "error",
    "The evidence page (evidence/README.md, written by descgen report) no longer matches the proofs it summarises.",
    """A reviewer reads the page instead of re-running every proof, so a page that shows yesterday's
      verdicts is worse than none. check rebuilds it in memory (MuJoCo's machine-dependent lines aside)
      and compares. Run descgen report SPEC and commit the result.""",
)

GEN081 = declare(
    "GEN081",
    "evidence-page-refused",
    "error",
    "descgen report did not write the evidence page: the package is stale, a check failed or a verdict failed.",
    """The page is evidence for a reviewer; written over a failing package it would present a failure
      as a proof. Fix what descgen check reports (or the failed verdict quoted), then run report again.""",
)

GEN090 = declare(
    "GEN090",
    "moveit-readback-mismatch",
    "error",
    "A file of the MoveIt config package, parsed back, does not state what the model says.",
    """joint_limits.yaml, kinematics.yaml, moveit_controllers.yaml, initial_positions.yaml and
      pilz_cartesian_limits.yaml are read back with yaml.safe_load and compared with the model (joint
      names, SI limits, controller joints and action_ns). A mismatch is a descgen or template bug: a
      package that loads but plans with other limits than the spec states. Report it; fix the template.""",
)

GEN091 = declare(
    "GEN091",
    "moveit-integer-value",
    "error",
    "A MoveIt parameter declared double is written so that YAML reads it as an integer.",
    """MoveIt declares limits as PARAMETER_DOUBLE; an integer value (max_velocity: 3) aborts move_group
      with InvalidParameterTypeException (moveit/moveit2#2776). Every such value must read back as a float.""",
)

GEN092 = declare(
    "GEN092",
    "moveit-file-unreadable",
    "error",
    "A file of the MoveIt config package does not parse (YAML, Python launch file, package.xml).",
    """The package is loaded by moveit_configs_utils and colcon; a file that does not parse stops the
      launch. Report it; fix the template that wrote it.""",
)

GEN093 = declare(
    "GEN093",
    "moveit-mock-start-mismatch",
    "error",
    "The MoveIt package's config/<robot>.urdf.xacro, expanded, does not start the mock hardware at the initial state.",
    """MoveItConfigsBuilder loads config/<robot>.urdf.xacro, which passes initial_positions.yaml to the
      description's ros2_control Xacro; each position state's initial_value must then be the initial
      state's value, or the demo starts somewhere else than the spec says (and than MoveIt's start state).
      The file is expanded with xacro (sandboxed, both packages on the package path) and compared with the
      model. Report it; fix the template (robot.ros2_control.xacro.j2, moveit_urdf.xacro.j2) that changed.""",
)

GEN094 = declare(
    "GEN094",
    "frames-drawing-failed",
    "warning",
    "Graphviz's dot failed on evidence/frames.dot or did not finish in time; frames.svg was not drawn.",
    """The drawing is a convenience beside frames.dot and frames.md, which are written and checked as
      always; nothing else depends on it. Draw it by hand (dot -Tsvg evidence/frames.dot), or look at
      what dot printed.""",
)

GEN095 = declare(
    "GEN095",
    "frames-drawing-skipped",
    "info",
    "The frame tree is too large to draw: frames.svg is not drawn (an old one is removed).",
    """Graphviz's layout grows faster than the tree (a 10,000-frame tree takes dot 15-50 s, and no
      reader follows such a drawing); frames.md lists every frame and its publisher, and frames.dot can
      still be drawn by hand (dot -Tsvg, or sfdp for a large tree).""",
)

GEN096 = declare(
    "GEN096",
    "mujoco-model-unbuildable",
    "error",
    "The MJCF model of the mujoco hardware variant cannot be made: a collision mesh that is not an STL or OBJ file "
    "of the robot's own package, or a model MuJoCo refuses.",
    """mujoco_ros2_control loads the MJCF file named by its mujoco_model parameter as it is, with plain mesh paths
      (docs/mujoco_ros2_control.md); nothing converts meshes at launch. descgen simulate SPEC shows why MuJoCo
      refuses a model.""",
)

GEN097 = declare(
    "GEN097",
    "mujoco-model-differs",
    "error",
    "The MJCF model written for hardware:=mujoco, compiled by MuJoCo, is not the URDF's robot: a joint, its range, "
    "an actuator, a mimic equality or the mass differs.",
    """The proof compiles the file as mujoco_ros2_control would and compares it with the model: every moving joint
      with its type and range, one actuator per commanded ros2_control joint of the kind its first command needs, a
      joint equality per mimic joint, and the total mass. A difference is descgen's conversion being wrong.""",
)
