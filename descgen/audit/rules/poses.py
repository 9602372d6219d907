"""POSE: known poses name real joints and frames, within limits."""

from __future__ import annotations

import math
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import ONE_DOF, Joint, KnownPose, Robot
from descgen.physics import mimic


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
    if not robot.known_poses:
        return  # a URDF never has any: no need for the numpy kinematics below
    from descgen.physics.poses import findings

    yield from findings(robot)


# a pose's values are written by hand (often to 4 digits): agreeing to a micrometre or a
# microradian is agreeing; the message shows the exact implied value to copy
MIMIC_TOLERANCE = 1e-6


def _mimic_settings(robot: Robot) -> Iterator[tuple[KnownPose, Joint, float, float, str]]:
    """(pose, mimic joint, value the pose gives, value its leader implies, how) for every
    mimic joint a known pose sets."""
    for kp in robot.known_poses:
        given = dict(kp.joints)
        for name, value in kp.joints:
            rel = mimic.relation(robot, name)
            j = robot.joint(name)
            if rel is None or j is None or math.isnan(value):
                continue
            lead = given.get(rel.leader)
            lead_value = 0.0 if lead is None or math.isnan(lead) else lead
            leader = robot.joint(rel.leader)
            shown = leader.show(lead_value) if leader is not None else f"{lead_value:g}"
            how = f"{mimic.formula(robot, rel)} with {rel.leader} at {shown}" + (
                "" if lead is not None else " (not set by the pose: zero)"
            )
            yield kp, j, value, rel.value(lead_value), how


def _agree(a: float, b: float) -> bool:
    return abs(a - b) <= MIMIC_TOLERANCE * max(1.0, abs(a), abs(b))


@rule("POSE020", "pose-contradicts-mimic", "error")
def pose_contradicts_mimic(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a known pose that sets a mimic joint to a value its leader contradicts:
    `q = multiplier * q_leader + offset` gives something else (a leader the pose does not
    set is at zero).
    ## Why is this bad?
    A mimic joint is not free: robot_state_publisher, MoveIt, pinocchio and GenericSystem
    all compute it from its leader, so the robot could not have been measured in that pose.
    Either the value, the leader's value, or the mimic's multiplier or offset is wrong.
    ## Example
    `finger_right_joint` mimics `finger_left_joint` with multiplier -1 and offset 0; a pose
    sets `finger_left_joint: 20 mm, finger_right_joint: 20 mm`.
    ## Use instead
    Set only the leader (`finger_left_joint: 20 mm`); the follower is at -20 mm by itself.
    """
    for kp, j, value, implied, how in _mimic_settings(robot):
        if not _agree(value, implied):
            yield at(
                "POSE020",
                kp,
                f"known pose '{kp.name}' sets mimic joint '{j.name}' to {j.show(value)}, but its leader puts it at "
                f"{j.show(implied)} ({how})",
                f"remove '{j.name}' from the pose and set its leader, or fix the value or the mimic",
                subject=f"pose:{kp.name}",
            )


@rule("POSE021", "pose-sets-mimic-joint", "info")
def pose_sets_mimic_joint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a known pose that sets a mimic joint to the value its leader implies.
    ## Why is this bad?
    It is consistent but redundant: the follower is computed from the leader anyway, and a
    later change of the mimic's multiplier or offset turns the copy into a contradiction
    (POSE020).
    ## Example
    `finger_left_joint: 20 mm, finger_right_joint: -20 mm` with a multiplier of -1.
    ## Use instead
    `finger_left_joint: 20 mm` alone.
    """
    for kp, j, value, implied, how in _mimic_settings(robot):
        if _agree(value, implied):
            yield at(
                "POSE021",
                kp,
                f"known pose '{kp.name}' sets mimic joint '{j.name}' to {j.show(value)}, "
                f"which its leader implies ({how})",
                f"you may leave '{j.name}' out: it follows its leader",
                subject=f"pose:{kp.name}",
            )


@rule("POSE022", "pose-mimic-outside-limits", "error")
def pose_mimic_outside_limits(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a known pose whose leader values put a mimic joint outside that joint's limits.
    ## Why is this bad?
    The follower's value is computed, not written, so POSE003 cannot see it; yet the robot
    could not have been in that pose: the leader's value, the mimic's multiplier or offset,
    or the follower's limits are wrong.
    ## Example
    `finger_right_joint` (limits 0 to 40 mm) mimics `finger_left_joint` with multiplier 1
    and offset 10 mm; a pose sets `finger_left_joint: 35 mm` (follower at 45 mm).
    ## Use instead
    A leader value whose follower stays inside its limits, or the right offset.
    """
    for kp in robot.known_poses:
        given = dict(kp.joints)
        for name, value in mimic.resolve(robot, given).items():
            rel = mimic.relation(robot, name)
            j = robot.joint(name)
            if rel is None or j is None or name in given or math.isnan(value) or not j.outside_limits(value):
                continue
            yield at(
                "POSE022",
                kp,
                f"known pose '{kp.name}' puts mimic joint '{name}' at {j.show(value)} "
                f"(q = {mimic.formula(robot, rel)}), outside {j.range_text()}",
                "check the leader's value, the mimic's multiplier and offset, and the joint limits",
                subject=f"pose:{kp.name}",
            )
