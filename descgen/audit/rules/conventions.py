"""NAME (conventions): REP 105 frames and REP 103 optical frames."""

from __future__ import annotations

import math
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import Robot
from descgen.physics.rigid import IDENTITY, Rot, rpy_rot

# body (x forward, y left, z up) -> optical (z forward, x right, y down): columns are the
# optical axes in body coordinates (docs/reference/conventions.md)
REP103: Rot = ((0.0, 0.0, 1.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0))


def _allclose(a: Rot, b: Rot, atol: float) -> bool:
    """``numpy.allclose(a, b, atol=atol)`` on two rotations (its default rtol=1e-5 included)."""
    return all(
        abs(x - y) <= atol + 1e-5 * abs(y) for ra, rb in zip(a, b, strict=True) for x, y in zip(ra, rb, strict=True)
    )


def is_mobile_base(robot: Robot) -> bool:
    rc = robot.ros2_control
    if rc is not None and any(c.type.startswith("diff_drive_controller/") for c in rc.controllers):
        return True
    wheels = [j for j in robot.joints if j.type == "continuous" and "wheel" in j.name.lower()]
    return len(wheels) >= 2


@rule("NAME010", "no-base-link", "warning")
def no_base_link(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a wheeled robot (REP 105 is about mobile platforms) without a `base_link` frame
    (behind its prefix, where it declares one: NAME014).
    ## Why is this bad?
    REP 105 names the frame rigidly attached to the base `base_link`; navigation,
    odometry and most tools look it up by that name.
    """
    name = _prefixed(robot, "base_link")
    if robot.links and not _has(robot, "base_link") and is_mobile_base(robot):
        yield at(
            "NAME010",
            robot,
            f"no link named '{name}' (REP 105)",
            f"name the base's rigid frame {name}",
            subject="robot",
        )


@rule("NAME011", "mobile-base-without-footprint", "info")
def mobile_base_without_footprint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a wheeled base (diff-drive controller or two wheel joints) without `base_footprint`.
    ## Why is this bad?
    Common practice for wheeled robots is `base_footprint` on the floor under `base_link`;
    2D navigation stacks default to it. (A convention, not a REP rule.)
    """
    name = _prefixed(robot, "base_footprint")
    if is_mobile_base(robot) and not _has(robot, "base_footprint"):
        yield at(
            "NAME011",
            robot,
            f"wheeled base without a '{name}' frame",
            f"add {name} on the floor under {_prefixed(robot, 'base_link')}",
            subject="robot",
        )


def _has(robot: Robot, name: str) -> bool:
    """Every base of the robot has the REP 105 frame ``name``, behind its prefix: each diff drive's
    base frame says where a base is (``left_base_footprint``: ``left_``), else each robot a spec
    composed, else the robot's own declared prefix."""
    prefixes = _drive_prefixes(robot) or {mt.prefix for mt in robot.mounted} or {_prefixed(robot, "")}
    return all(robot.link(p + name) is not None for p in prefixes)


def _drive_prefixes(robot: Robot) -> set[str]:
    out = set()
    for c in robot.ros2_control.controllers if robot.ros2_control else ():
        base = c.param("base_frame_id") if c.type.startswith("diff_drive_controller/") else None
        for suffix in ("base_footprint", "base_link"):
            if isinstance(base, str) and base.endswith(suffix):
                out.add(base[: -len(suffix)])
    return out


def _prefixed(robot: Robot, name: str) -> str:
    """A REP 105 frame name as a robot with a declared prefix writes it (left_base_link)."""
    return robot.prefix.value + name if robot.prefix is not None else name


def _optical_links(robot: Robot) -> list[str]:
    return [lk.name for lk in robot.links if "optical" in lk.name.lower()]


@rule("NAME012", "camera-without-optical-frame", "warning")
def camera_without_optical_frame(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a camera frame (a link named like `*camera*`) with no `*optical*` frame below it.
    ## Why is this bad?
    Images are expressed in the optical frame (z forward, x right, y down, REP 103);
    without it, image geometry ends up in the body frame, rotated 90 degrees twice.
    """
    optical = set(_optical_links(robot))
    for lk in robot.links:
        name = lk.name.lower()
        if "camera" not in name or "optical" in name:
            continue
        parent = robot.parent_joint(lk.name)
        if parent is not None and parent.parent and "camera" in parent.parent.lower():
            continue  # a sub-frame of a camera already considered
        below = set(robot.descendants(lk.name))
        if not below & optical:
            yield at(
                "NAME012",
                lk,
                f"camera frame '{lk.name}' has no optical frame below it",
                f"add {lk.name.removesuffix('_link')}_optical_frame with rpy (-pi/2, 0, -pi/2)",
            )


@rule("NAME013", "optical-frame-not-rotated", "error")
def optical_frame_not_rotated(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks that each `*optical*` frame is turned from its parent body frame by the REP 103
    rotation (rpy -pi/2, 0, -pi/2: z forward, x right, y down).
    ## Why is this bad?
    An optical frame without that rotation makes every detection, point cloud and
    calibration land 90 degrees off, with no error anywhere.
    """
    for name in _optical_links(robot):
        j = robot.parent_joint(name)
        if j is None or j.type != "fixed" or (j.parent and "optical" in j.parent.lower()):
            continue
        r = rpy_rot(j.origin.rpy)
        if _allclose(r, REP103, atol=1e-3):
            continue
        if _allclose(r, IDENTITY, atol=1e-6):
            yield at(
                "NAME013",
                j,
                f"optical frame '{name}' is not rotated from '{j.parent}'",
                "set the joint's rpy to (-pi/2, 0, -pi/2) (REP 103)",
            )
        else:
            trace = -r[1][0] - r[2][1] + r[0][2]  # trace(REP103^T r): REP103's three non-zero entries
            angle = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1) / 2))))
            yield at(
                "NAME013",
                j,
                f"optical frame '{name}' is {angle:.1f} deg away from the REP 103 rotation",
                "if the parent is a body frame (x forward), use rpy (-pi/2, 0, -pi/2)",
                severity="warning",
            )
