"""JOINT: axes, limits and mimic relations."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ...findings import Finding
from ...model import Robot
from ..registry import at, rule


@rule("JOINT001", "zero-axis", "error")
def zero_axis(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a moving joint whose axis is (0, 0, 0).
    ## Why is this bad?
    urdfdom accepts `<axis/>` as 0 0 0; the joint then never moves the child.
    """
    for j in robot.joints:
        moving = j.type in ("revolute", "continuous", "prismatic", "planar")
        if moving and j.axis is not None and math.hypot(*j.axis) == 0:
            yield at("JOINT001", j, f"joint '{j.name}' has a zero axis", "write the unit axis, e.g. +y or [0, 1, 0]")


@rule("JOINT002", "axis-not-unit", "error")
def axis_not_unit(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds an axis whose length is not 1.
    ## Why is this bad?
    urdfdom does not normalise the axis; tools disagree on whether they do, so the same
    joint value moves the child by different amounts.
    """
    for j in robot.joints:
        if j.axis is not None and j.type in ("revolute", "continuous", "prismatic", "planar"):
            n = math.hypot(*j.axis)
            if n > 0 and abs(n - 1) > 1e-6:
                yield at(
                    "JOINT002",
                    j,
                    f"joint '{j.name}' axis {list(j.axis)} has length {n:.6g}",
                    "divide the axis by its length",
                )


@rule("JOINT003", "moving-joint-without-limit", "error")
def moving_joint_without_limit(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a revolute or prismatic joint without limits (or without lower/upper).
    ## Why is this bad?
    urdfdom rejects a missing `<limit>`; a `<limit>` without lower/upper means [0, 0];
    joint_state_publisher raises; ros2_control cannot clamp commands.
    """
    for j in robot.joints:
        if j.type in ("revolute", "prismatic"):
            if j.limit is None:
                yield at(
                    "JOINT003", j, f"{j.type} joint '{j.name}' has no limit", "add lower, upper, effort and velocity"
                )
            elif j.limit.lower is None or j.limit.upper is None:
                yield at(
                    "JOINT003",
                    j,
                    f"{j.type} joint '{j.name}' limit lacks lower or upper",
                    "write both; a missing one is read as 0",
                )


@rule("JOINT004", "limits-out-of-order", "error")
def limits_out_of_order(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds lower > upper (error) and lower == upper on a moving joint.
    ## Why is this bad?
    urdfdom does not check the order; planners and controllers then have no valid position.
    """
    for j in robot.joints:
        lm = j.limit
        if j.type in ("revolute", "prismatic") and lm and lm.lower is not None and lm.upper is not None:
            if lm.lower > lm.upper:
                yield at(
                    "JOINT004",
                    lm if lm.where.line else j,
                    f"joint '{j.name}' lower limit {j.show(lm.lower)} is above upper {j.show(lm.upper)}",
                    "swap lower and upper",
                    subject=j.subject,
                )
            elif lm.lower == lm.upper:
                yield at(
                    "JOINT004",
                    lm if lm.where.line else j,
                    f"joint '{j.name}' lower and upper limits are equal ({j.show(lm.lower)}): it cannot move",
                    "make it fixed, or write the real range",
                    severity="warning",
                    subject=j.subject,
                )


@rule("JOINT005", "non-positive-effort-or-velocity", "error")
def non_positive_effort_or_velocity(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a limit whose effort or velocity is zero or negative.
    ## Why is this bad?
    A zero limit lets nothing move; ros2_control takes abs() of a negative one, hiding the typo.
    """
    for j in robot.joints:
        lm = j.limit
        if lm is None or j.type == "fixed":
            continue
        for field in ("effort", "velocity"):
            v = getattr(lm, field)
            if v is None:
                yield at(
                    "JOINT005",
                    lm if lm.where.line else j,
                    f"joint '{j.name}' limit has no {field}",
                    f"add {field}; urdfdom requires it",
                    subject=j.subject,
                )
            elif v <= 0:
                yield at(
                    "JOINT005",
                    lm if lm.where.line else j,
                    f"joint '{j.name}' {field} limit is {v:.6g}",
                    f"write the positive maximum {field}",
                    subject=j.subject,
                )


@rule("JOINT006", "continuous-with-position-limits", "warning")
def continuous_with_position_limits(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a continuous joint that has lower/upper limits.
    ## Why is this bad?
    ros2_control ignores them (angle wraparound); if the joint really stops, it is revolute.
    """
    for j in robot.joints:
        lm = j.limit
        if j.type == "continuous" and lm and ((lm.lower or 0) != 0 or (lm.upper or 0) != 0):
            yield at(
                "JOINT006",
                j,
                f"continuous joint '{j.name}' has position limits that are ignored",
                "make it revolute, or remove lower/upper",
            )


@rule("JOINT007", "bad-mimic", "error")
def bad_mimic(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a mimic that names a missing joint, itself, or a joint that itself mimics.
    ## Why is this bad?
    urdfdom does not check the mimicked joint exists; ros2_control and
    robot_state_publisher then leave the joint without a value.
    """
    by_name = {j.name: j for j in robot.joints}
    for j in robot.joints:
        if j.mimic is None:
            continue
        target = by_name.get(j.mimic.joint)
        if j.mimic.joint == j.name:
            yield at("JOINT007", j, f"joint '{j.name}' mimics itself", "name the joint it follows")
        elif target is None:
            yield at("JOINT007", j, f"joint '{j.name}' mimics unknown joint '{j.mimic.joint}'", "fix the joint name")
        elif target.mimic is not None:
            yield at(
                "JOINT007",
                j,
                f"joint '{j.name}' mimics '{target.name}', which mimics '{target.mimic.joint}'",
                "mimic the driving joint directly",
            )
        elif target.type == "fixed":
            yield at("JOINT007", j, f"joint '{j.name}' mimics fixed joint '{target.name}'", "mimic a moving joint")
