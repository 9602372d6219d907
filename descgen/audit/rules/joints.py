"""JOINT: axes, limits and mimic relations."""

from __future__ import annotations

import math
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import ONE_DOF, WITH_AXIS, WITH_LIMITS, Joint, Robot
from descgen.core.naming import mirror_name
from descgen.physics import mimic
from descgen.physics.bodies import static_load, subtree_loads
from descgen.physics.rigid import dot, norm, rotate
from descgen.physics.zero_pose import at_zero


@rule("JOINT001", "zero-axis", "error")
def zero_axis(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a moving joint whose axis is (0, 0, 0).
    ## Why is this bad?
    urdfdom accepts `<axis/>` as 0 0 0; the joint then never moves the child.
    """
    for j in robot.joints:
        moving = j.type in WITH_AXIS
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
        if j.axis is not None and j.type in WITH_AXIS:
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
        if j.type in WITH_LIMITS:
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
        if j.type in WITH_LIMITS and lm and lm.lower is not None and lm.upper is not None:
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
    Finds a limit whose effort or velocity is zero or negative; zero is what a passive joint
    (the SRDF's ``passive_joint``, a mimic follower) has, so it is not reported there.
    ## Why is this bad?
    A zero limit lets nothing move; ros2_control takes abs() of a negative one, hiding the typo.
    """
    unpowered = mimic.unactuated(robot)
    for j in robot.joints:
        lm = j.limit
        if lm is None or j.type == "fixed":
            continue
        for field in ("effort", "velocity"):
            if getattr(lm, field) == 0 and j.name in unpowered:
                continue
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
        elif target.mimic is not None and (stuck := _mimic_problem(robot, j)) is not None:
            yield at("JOINT007", j, stuck, "remove the <mimic> of the joint that is really driven")
        elif target.mimic is not None:
            yield at(
                "JOINT007",
                j,
                f"joint '{j.name}' mimics '{target.name}', which mimics '{target.mimic.joint}'",
                "mimic the driving joint directly",
            )
        elif target.type == "fixed":
            yield at("JOINT007", j, f"joint '{j.name}' mimics fixed joint '{target.name}'", "mimic a moving joint")


def _mimic_problem(robot: Robot, j: Joint) -> str | None:
    """Why no joint drives ``j``'s mimic chain (a cycle, a missing joint at its end), or None."""
    from descgen.physics.mimic import problem

    found = problem(robot, j.name)
    return found.message if found is not None and found.joint is j else None


@rule("JOINT008", "effort-below-gravity-load", "error")
def effort_below_gravity_load(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Computes the static gravity torque (or force) each revolute or prismatic joint must
    hold: the mass of everything it carries times the lever arm of their common centre of
    mass, at the worst angle of the joint's own range (other joints at zero, gravity along
    -z of the root), and flags an effort limit below it. Joints with a range under 1 cm
    or about 1 degree (suspensions, compliance) are skipped: they rest on their stops.
    ## Why is this bad?
    The joint cannot hold its own arm up: on the robot it sags or faults; in simulation it
    falls while the description claims it can lift.
    """
    poses = at_zero(robot)
    if not poses:
        return
    loads = subtree_loads(robot, poses)
    unpowered = mimic.unactuated(robot)
    for j in robot.joints:
        if j.type not in WITH_LIMITS or j.limit is None or j.limit.effort is None or j.child is None:
            continue
        if j.name in unpowered:
            continue
        if j.limit.effort == 0:
            continue  # JOINT005 reports a zero effort limit
        lo_, hi_ = j.limit.lower, j.limit.upper
        if lo_ is not None and hi_ is not None and abs(hi_ - lo_) <= (0.01 if j.type == "prismatic" else 0.02):
            continue  # a suspension or compliance joint: it rests on its end stop, it does not hold
        if j.child not in poses or j.axis is None or math.hypot(*j.axis) == 0:
            continue
        mass, moment = loads[j.child]
        if mass <= 0:
            continue
        need = static_load(j, poses[j.child], mass, moment)
        what = f"{need:.4g} N along its axis" if j.type == "prismatic" else f"{need:.4g} N*m"
        if need > abs(j.limit.effort) * (1 + 1e-9) and need > 1e-6:
            yield at(
                "JOINT008",
                j,
                f"joint '{j.name}' must hold {what} against gravity ({mass:.3g} kg carried) but its "
                f"effort limit is {abs(j.limit.effort):.4g}",
                "check the effort limit (and the masses it carries)",
            )


@rule("JOINT009", "mirror-axes-disagree", "warning")
def mirror_axes_disagree(robot: Robot) -> Iterator[Finding]:
    """## What it does
    For left/right joint pairs (names differing only by left/right, l/r, FL/FR, ...) that sit
    mirror-symmetric about the root's x-z plane, checks their axes are mirror images too.
    ## Why is this bad?
    A copied leg or arm with one axis changed turns the wrong way; nothing else notices.
    """
    poses = at_zero(robot)
    done: set[str] = set()
    for j in robot.joints:
        other_name = mirror_name(j.name)
        other = robot.joint(other_name) if other_name else None
        if other is None or j.name in done or j.type not in ONE_DOF:
            continue
        done |= {j.name, other.name}
        if _mounted(robot, j.name) != _mounted(robot, other.name):
            continue  # copies of one robot composed side by side (compose:), not a mirrored limb
        if other.type != j.type or j.axis is None or other.axis is None or not j.child or not other.child:
            continue
        if j.child not in poses or other.child not in poses:
            continue
        (ra, pa), (rb, pb) = poses[j.child], poses[other.child]
        scale = max(norm(pa), 1e-3)
        if norm((pa[0] - pb[0], -pa[1] - pb[1], pa[2] - pb[2])) > 0.01 * scale:
            continue  # not placed as mirror images (about the root's x-z plane): nothing to compare
        na, nb = math.hypot(*j.axis), math.hypot(*other.axis)
        if na == 0 or nb == 0:
            continue
        a = rotate(ra, j.axis)
        a = (a[0] / na, -(a[1] / na), a[2] / na)  # mirrored: y flips
        b = rotate(rb, other.axis)
        b = (b[0] / nb, b[1] / nb, b[2] / nb)
        if abs(abs(dot(a, b)) - 1) > 1e-3:
            angle = math.degrees(math.acos(min(1.0, abs(dot(a, b)))))
            yield at(
                "JOINT009",
                other,
                f"joints '{j.name}' and '{other.name}' mirror each other but their axes are {angle:.1f} deg apart",
                f"check the axis of '{other.name}' (or of '{j.name}')",
            )


def _mounted(robot: Robot, name: str) -> str | None:
    """The prefix of the composed robot ``name`` belongs to (spec ``compose:``), or None."""
    return next((mt.prefix for mt in robot.mounted if name.startswith(mt.prefix)), None)


TRAVEL_FACTOR = 20.0  # a gantry rail may be several robots long; a mm-as-m slip is hundreds
TRAVEL_FLOOR = 2.0  # metres: never flag a shorter travel
_SPAN_FLOOR = 0.01  # metres: a robot of bare frames has no size to compare with


@rule("JOINT020", "implausible-prismatic-travel", "error")
def implausible_prismatic_travel(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares how far each prismatic joint moves its child from zero (the larger of |lower|
    and |upper|) with the span of the whole robot: the diagonal of the box around every
    link frame and primitive shape at zero pose. A travel over 2 m and over 20 times that
    span is reported.
    ## Why is this bad?
    It is a millimetre value typed as metres: a gripper finger with `upper="40"` instead
    of 0.04, a lift of 300 m. Every parser accepts it; planners then sample the finger
    40 m away, ros2_control lets commands through the limit, and simulators throw the
    link off the robot.
    ## Example
    `<limit lower="0" upper="40" .../>` on a finger of a 0.5 m arm.
    ## Use instead
    `<limit lower="0" upper="0.04" .../>` (metres); in a spec, write the unit: `upper: 40 mm`.
    """
    from descgen.physics.extent import robot_span

    travels = [
        (j, lm, max(abs(lm.lower or 0.0), abs(lm.upper or 0.0)))
        for j in robot.joints
        if j.type == "prismatic" and (lm := j.limit) is not None
    ]
    if not any(t > TRAVEL_FLOOR for _, _, t in travels):
        return  # the common case: no need to pose the robot
    span = robot_span(robot)
    if span < _SPAN_FLOOR:
        return
    for j, lm, travel in travels:
        if travel > TRAVEL_FLOOR and travel > TRAVEL_FACTOR * span:
            yield at(
                "JOINT020",
                lm if lm.where.line else j,
                f"prismatic joint '{j.name}' travels {travel:.6g} m, {travel / span:.3g} times the span of the "
                f"whole robot ({span:.3g} m)",
                f"was the limit written in millimetres? {travel:.6g} mm is {travel / 1000:.6g} m",
                subject=j.subject,
            )
