"""Values the outputs need that are derived from the model, never typed twice.

Templates only format; everything computed for an output is computed here and tested here.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from descgen.core.model import WITH_LIMITS, Controller, Cylinder, Interface, Joint, Robot, Sphere
from descgen.core.record import record

if TYPE_CHECKING:
    from descgen.physics.rigid import Frame


def _wheel_names(c: Controller, key: str) -> list[str]:
    v = c.param(key)
    return [str(x) for x in v] if isinstance(v, list | tuple) else []


@record
class DiffDriveGeometry:
    wheel_separation: float | None
    wheel_radius: float | None
    problems: tuple[str, ...] = ()


def diff_drive_geometry(robot: Robot, c: Controller) -> DiffDriveGeometry:
    """``wheel_separation``: distance between the left and right wheel joint origins, along
    the wheel axis; ``wheel_radius``: the radius of the wheel link's collision cylinder
    (or sphere). With several wheels per side, the first of each side is used and the
    others must agree."""
    problems: list[str] = []
    left, right = _wheel_names(c, "left_wheel_names"), _wheel_names(c, "right_wheel_names")
    if not left or not right:
        return DiffDriveGeometry(None, None, ("left_wheel_names and right_wheel_names are required",))
    joints = [robot.joint(n) for n in (left[0], right[0])]
    lj, rj = joints
    if lj is None or rj is None:
        missing = [n for n, j in zip((left[0], right[0]), joints, strict=True) if j is None]
        return DiffDriveGeometry(None, None, (f"wheel joint '{missing[0]}' does not exist",))
    separation = None
    # both wheel joints in the root's frame, every joint at zero: a wheel may hang from its own
    # link (a wheel-drop suspension, iRobot Create 3), the controller sees only the two wheels'
    # contact line; from one parent link this is the distance in that link's frame
    fl, fr = _frame_in_root(robot, lj), _frame_in_root(robot, rj)
    if lj.axis is None:
        problems.append(f"wheel joint '{lj.name}' has no axis")
    elif fl is None or fr is None:
        problems.append(f"wheels '{lj.name}' and '{rj.name}' are not in one tree with the robot's root")
    else:
        # plain floats (descgen/physics/rigid.py): validate and check run this for every diff drive,
        # and numpy costs more to import than the whole computation
        from descgen.physics import rigid

        axis = rigid.rotate(fl[0], lj.axis)
        n = rigid.norm(axis)
        if n > 0:
            gap = tuple(a - b for a, b in zip(fl[1], fr[1], strict=True))
            separation = abs(rigid.dot(gap, tuple(c / n for c in axis)))
    radii = [wheel_radius(robot, j) for j in (lj, rj)]
    radius = radii[0]
    if radius is None:
        problems.append(f"wheel link '{lj.child}' has no collision cylinder or sphere to take the radius from")
    elif radii[1] is not None and not math.isclose(radii[0] or 0, radii[1], rel_tol=1e-9):
        problems.append(f"left and right wheel radii differ ({radii[0]:.6g} m, {radii[1]:.6g} m)")
    return DiffDriveGeometry(separation, radius, tuple(problems))


def _frame_in_root(robot: Robot, j: Joint) -> Frame | None:
    """The frame of joint ``j`` (its origin) in the root link's frame with every joint at zero;
    None when its parent link does not lead to the root."""
    from descgen.physics import rigid

    f = rigid.frame(j.origin.xyz, j.origin.rpy)
    link, seen = j.parent, set()
    root = robot.root()
    while link is not None and link != root:
        above = robot.parent_joint(link)
        if above is None or link in seen:
            return None
        seen.add(link)
        f = rigid.compose(rigid.frame(above.origin.xyz, above.origin.rpy), f)
        link = above.parent
    return f if link is not None else None


def wheel_params(robot: Robot, c: Controller) -> dict[str, float]:
    """``wheel_separation``/``wheel_radius`` for the controllers file: the spec's calibrated
    value where it states one (measured on the robot), else the URDF-derived one."""
    geo = diff_drive_geometry(robot, c)
    derived = (("wheel_separation", geo.wheel_separation), ("wheel_radius", geo.wheel_radius))
    out = {k: v for k, v in derived if v is not None}
    out.update({cal.param: cal.value for cal in c.calibrated})
    return out


def wheel_radius(robot: Robot, j: Joint) -> float | None:
    link = robot.link(j.child) if j.child else None
    if link is None:
        return None
    shapes = [c.geometry for c in link.collisions] + [v.geometry for v in link.visuals]
    for g in shapes:
        if isinstance(g, Cylinder | Sphere):
            return g.radius
    return None


def command_limits(j: Joint | None, interface: str) -> tuple[float | None, float | None]:
    """``min``/``max`` of a command interface, from the joint's URDF limits."""
    if j is None or j.limit is None:
        return None, None
    lm = j.limit
    if interface == "position" and j.type in WITH_LIMITS:
        return lm.lower, lm.upper
    if interface == "velocity" and lm.velocity is not None:
        return -abs(lm.velocity), abs(lm.velocity)
    if interface == "effort" and lm.effort is not None:
        return -abs(lm.effort), abs(lm.effort)
    return None, None


def initial_position(j: Joint | None, given: float | None) -> float:
    """The given initial position, else 0 when inside the limits, else the middle of the
    range (what joint_state_publisher does)."""
    if given is not None:
        return given
    if j is not None and j.outside_limits(0.0) and j.limit and j.limit.lower is not None and j.limit.upper is not None:
        return (j.limit.lower + j.limit.upper) / 2
    return 0.0


def interfaces_with_limits(robot: Robot) -> list[tuple[str, list[Interface], list[Interface]]]:
    """Per ros2_control joint: command interfaces with min/max from the joint limits, and
    state interfaces with their initial values."""
    rc = robot.ros2_control
    out: list[tuple[str, list[Interface], list[Interface]]] = []
    if rc is None:
        return out
    for cj in rc.joints:
        j = robot.joint(cj.name)
        commands = []
        for i in cj.command:  # a spec's own min/max win over the joint limits (CTRL008 checks them)
            lo, hi = command_limits(j, i.name)
            lo, hi = (lo if i.min is None else i.min), (hi if i.max is None else i.max)
            commands.append(Interface(i.name, lo, hi, data_type=i.data_type))
        states = []
        for i in cj.state:
            if i.name == "position":
                value = initial_position(j, i.initial_value)
            else:
                value = 0.0 if i.initial_value is None else i.initial_value
            states.append(Interface(i.name, initial_value=value, data_type=i.data_type))
        out.append((cj.name, commands, states))
    return out


def adjacent_pairs(robot: Robot) -> list[tuple[str, str]]:
    """Links that touch through a joint: each link with collision geometry paired with its
    nearest ancestor that has collision geometry (MoveIt's "Adjacent")."""
    with_geometry = {lk.name for lk in robot.links if lk.collisions}
    pairs: list[tuple[str, str]] = []
    for lk in robot.links:
        if lk.name not in with_geometry:
            continue
        for j in reversed(robot.path_to_root(lk.name)):
            if j.parent in with_geometry:
                pairs.append((j.parent, lk.name))
                break
    return pairs
