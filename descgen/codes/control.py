"""Codes of ``descgen control``: the trajectory, its options, the ros2_control model and the run's evidence.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("control")


CTRL011 = declare(
    "CTRL011",
    "tracking-error",
    "error",
    "A joint's measured state did not follow the command within its tolerance.",
    """A joint that does not track its command is reversed, offset or not moving, and a controller
      built on it would fight the hardware. Check the joint's direction, encoder offset and that it
      moves.""",
)

CTRL012 = declare(
    "CTRL012",
    "command-rejected-by-limits",
    "error",
    "The trajectory commanded values beyond the joint limits, which the hardware rejected.",
    """A trajectory that hits the limits does not run as planned. Keep the trajectory inside the
      joint limits.""",
)

CTRL013 = declare(
    "CTRL013",
    "controller-never-active",
    "error",
    "A controller never became active in the ros2_control model.",
    """A controller that fails to configure or claim its interfaces leaves the joints uncommanded.
      See lifecycle.md in the evidence for the failed transition or claim.""",
)

CTRL014 = declare(
    "CTRL014",
    "mock-hardware-echo",
    "info",
    "The measured state is the mock hardware echoing the command.",
    """mock_components/GenericSystem reports what it was told, so the run proves the wiring, not the
      motion. Use --plant sim or real hardware to verify motion.""",
)

CTRL020 = declare(
    "CTRL020",
    "trajectory-malformed",
    "error",
    "The trajectory file is malformed (not a mapping, unknown keys, positions of the wrong length or unit).",
    """A trajectory that cannot be read cannot be run. Fix the trajectory at the given line.""",
)

CTRL021 = declare(
    "CTRL021",
    "package-without-control",
    "error",
    "The generated package has no controllers file or no <ros2_control> block.",
    """control runs the generated files; without them there is nothing to run. Run descgen generate
      first (and point --package at its output).""",
)

CTRL022 = declare(
    "CTRL022",
    "trajectory-controller-unknown",
    "error",
    "No joint_trajectory_controller of the trajectory's name in the controllers file.",
    """The trajectory would be sent to no one. Name the arm's controller.""",
)

CTRL030 = declare(
    "CTRL030",
    "trajectory-empty",
    "error",
    "The trajectory names no joints or has no points.",
    """Nothing would run, so the run would prove nothing. Give joints: and at least one point.""",
)

CTRL031 = declare(
    "CTRL031",
    "trajectory-time-not-increasing",
    "error",
    "A trajectory point's time_from_start is not after the previous point's.",
    """joint_trajectory_controller rejects trajectories whose times do not increase. List points in
      increasing time.""",
)

CTRL032 = declare(
    "CTRL032",
    "bad-fault-option",
    "error",
    "A --plant-fault option is not JOINT:=KIND with a known joint and fault kind.",
    """An unknown joint or fault kind would be silently ignored, and the run would not test what was
      asked. Write JOINT:=KIND with a kind from the list in the hint.""",
)

CTRL033 = declare(
    "CTRL033",
    "trajectory-joint-not-commanded",
    "error",
    "The trajectory names joints that its controller does not command.",
    """The controller would reject the trajectory. Use the controller's joints.""",
)

CTRL034 = declare(
    "CTRL034",
    "evidence-folder-unwritable",
    "error",
    "The evidence folder cannot be created.",
    """The run's evidence would be lost. Choose another --out.""",
)

CTRL035 = declare(
    "CTRL035",
    "evidence-path-not-plain",
    "error",
    "The evidence folder, or a file control writes in it (control_run/, a plot), is a symbolic link, FIFO or device.",
    """Evidence is written only as regular files inside the folder you named; a link would send it
      elsewhere and a FIFO would block. Nothing is written: remove the entry or choose another --out.""",
)
