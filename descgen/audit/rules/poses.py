"""POSE: known poses name real joints and frames, within limits."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ...findings import Finding
from ...model import ONE_DOF, Robot
from ..registry import at, rule


def _frames(robot: Robot) -> set[str]:
    return {lk.name for lk in robot.links}


@rule("POSE001", "pose-unknown-joint", "error")
def pose_unknown_joint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a known pose that sets a joint the robot does not have, or a joint without one
    degree of freedom.
    ## Why is this bad?
    The measured pose cannot be reproduced, so it proves nothing.
    """
    for kp in robot.known_poses:
        for name, _ in kp.joints:
            j = robot.joint(name)
            if j is None:
                yield at(
                    "POSE001",
                    kp,
                    f"known pose '{kp.name}' sets unknown joint '{name}'",
                    "fix the joint name",
                    subject=f"pose:{kp.name}",
                )
            elif j.type not in ONE_DOF:
                yield at(
                    "POSE001",
                    kp,
                    f"known pose '{kp.name}' sets {j.type} joint '{name}'",
                    "set only revolute, continuous and prismatic joints",
                    subject=f"pose:{kp.name}",
                )


@rule("POSE002", "pose-unknown-frame", "error")
def pose_unknown_frame(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a known-pose measurement of a frame (or relative to a frame) that does not exist.
    ## Why is this bad?
    The measurement cannot be compared with the model.
    """
    frames = _frames(robot)
    for kp in robot.known_poses:
        for fm in kp.frames:
            for name in (fm.frame, fm.relative_to):
                if name is not None and name not in frames:
                    yield at(
                        "POSE002",
                        fm,
                        f"known pose '{kp.name}' measures unknown frame '{name}'",
                        "name a link of the robot",
                        subject=f"pose:{kp.name}",
                    )


@rule("POSE003", "pose-outside-limits", "error")
def pose_outside_limits(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a known-pose joint value outside that joint's limits.
    ## Why is this bad?
    The robot could not have been in that pose: the value or the limit is wrong.
    """
    for kp in robot.known_poses:
        for name, value in kp.joints:
            j = robot.joint(name)
            if j is not None and not math.isnan(value) and j.outside_limits(value):
                message = f"known pose '{kp.name}' sets '{name}' to {j.show(value)}, outside {j.range_text()}"
                yield at("POSE003", kp, message, "check the value and the joint limits", subject=f"pose:{kp.name}")


@rule("POSE010", "known-pose-mismatch", "error", stage="check")
def known_pose_mismatch(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Computes forward kinematics at each known pose and compares every measured frame
    position with the model, axis by axis, within the measurement's tolerance.
    ## Why is this bad?
    A description that parses can still put the camera 25 m away or turn the elbow about
    the wrong axis; a measured pose is the one claim that catches both.
    """
    from ...poses import findings

    yield from findings(robot)
