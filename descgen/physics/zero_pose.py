"""Forward kinematics in plain floats (descgen/physics/rigid.py frames), for the audit rules and the
known poses (POSE010, evidence/known_poses.md) that every ``check`` evaluates.

The same kinematics as :mod:`descgen.physics.kinematics` (a joint's frame is ``origin * motion(q)``,
mimic joints follow their leaders, the axis is normalised), without numpy: the audit poses
every robot at zero once and reads a few thousand 3-vectors from it, where numpy's import
(~60 ms) and per-call cost on 4x4 matrices are most of the work. tests/test_audit_plain_floats.py
holds the frames to :func:`descgen.physics.kinematics.forward`.
"""

from __future__ import annotations

from collections.abc import Mapping

from descgen.core.model import ROTATING, Joint, Robot
from descgen.physics import mimic
from descgen.physics.rigid import IDENTITY, ORIGIN, Frame, axis_angle_rot, compose, frame, inverse, norm


def motion(j: Joint, q: float) -> Frame:
    """The joint's own motion by ``q``: a turn about its axis, or a slide along it."""
    if q == 0 or j.axis is None:
        return ORIGIN
    n = norm(j.axis)
    if n == 0:
        return ORIGIN
    if j.type in ROTATING:
        return axis_angle_rot(j.axis, q), (0.0, 0.0, 0.0)
    if j.type == "prismatic":
        return IDENTITY, (q * j.axis[0] / n, q * j.axis[1] / n, q * j.axis[2] / n)
    return ORIGIN


def joint_frame(j: Joint, q: float = 0.0) -> Frame:
    """Pose of the child link frame in the parent link frame."""
    placed = frame(j.origin.xyz, j.origin.rpy)
    moved = motion(j, q)
    return placed if moved is ORIGIN else compose(placed, moved)


def forward(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, Frame]:
    """Pose of every link reachable from the root, in the root frame (joints not in ``q`` at
    zero; a mimic joint always set from its leader), as :func:`descgen.physics.kinematics.forward`."""
    values = mimic.resolve(robot, q or {})
    root = robot.root()
    if root is None:
        return {}
    poses: dict[str, Frame] = {root: ORIGIN}
    for j in robot.tree_joints():
        assert j.parent is not None and j.child is not None  # tree_joints yields only linked joints
        poses[j.child] = compose(poses[j.parent], joint_frame(j, values.get(j.name, 0.0)))
    return poses


def forward_from(
    robot: Robot, q: Mapping[str, float], base: Mapping[str, Frame], base_q: Mapping[str, float]
) -> dict[str, Frame]:
    """``forward(robot, q)`` given ``base = forward(robot, base_q)``: a link is composed again
    only below a joint whose value differs (a sweep moves one joint and its followers); every
    other link keeps base's frame, the very floats forward would compute again."""
    values = mimic.resolve(robot, q)
    before = mimic.resolve(robot, base_q)
    poses = dict(base)
    moved: set[str] = set()
    for j in robot.tree_joints():
        assert j.parent is not None and j.child is not None  # tree_joints yields only linked joints
        v = values.get(j.name, 0.0)
        if j.parent in moved or v != before.get(j.name, 0.0):
            poses[j.child] = compose(poses[j.parent], joint_frame(j, v))
            moved.add(j.child)
    return poses


_AT_ZERO: list[tuple[Robot, dict[str, Frame]]] = []  # the zero poses of the last few robots
_AT_ZERO_KEPT = 4


def at_zero(robot: Robot) -> dict[str, Frame]:
    """``forward(robot)``, computed once per robot object for the rules that all need it
    (frames are tuples, so no caller can change them; do not add to the dict). Keyed by
    identity, as Robot is immutable."""
    for seen, poses in _AT_ZERO:
        if seen is robot:
            return poses
    poses = forward(robot)
    _AT_ZERO.insert(0, (robot, poses))
    del _AT_ZERO[_AT_ZERO_KEPT:]
    return poses


def relative(poses: Mapping[str, Frame], frame_: str, base: str | None) -> Frame | None:
    """Pose of ``frame_`` in ``base`` (the root when None), as :func:`descgen.physics.kinematics.relative`;
    None when either is not in ``poses``."""
    if frame_ not in poses or (base is not None and base not in poses):
        return None
    if base is None:
        return poses[frame_]
    return compose(inverse(poses[base]), poses[frame_])
