"""Forward kinematics on the SI model (numpy).

A joint's transform is ``origin * motion(q)``: rotation by q about the joint axis (in the
joint frame) for revolute and continuous joints, translation by q along it for prismatic
joints; fixed, floating and planar joints sit at their origin (known poses set only
one-degree-of-freedom joints). Mimic joints follow their leaders (``descgen.physics.mimic``), as
in robot_state_publisher, MoveIt, yourdfpy and pinocchio. The axis is normalised (urdfdom does not; JOINT002 flags
an axis that is not unit length). Origins use URDF's fixed-axis roll-pitch-yaw.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from descgen.core.model import ROTATING, Joint, Robot
from descgen.physics import mimic
from descgen.physics.transforms import Mat, axis_angle_matrix, pose_matrix

# what a joint's motion needs that does not depend on q: its axis as an array, the axis's
# norm, and the unit axis; None for no axis or a zero one
_Axis = tuple[np.ndarray, float, tuple[float, float, float]] | None


def _axis(j: Joint) -> _Axis:
    if j.axis is None:
        return None
    axis = np.asarray(j.axis, dtype=float)
    n = float(np.linalg.norm(axis))
    if n == 0:
        return None
    unit = axis / n
    return axis, n, (float(unit[0]), float(unit[1]), float(unit[2]))


def _motion(j: Joint, q: float, ax: _Axis) -> Mat:
    t = np.eye(4)
    if q == 0 or ax is None:
        return t
    axis, n, unit = ax
    if j.type in ROTATING:
        t[:3, :3] = axis_angle_matrix(unit, q)
    elif j.type == "prismatic":
        t[:3, 3] = q * axis / n
    return t


def motion(j: Joint, q: float) -> Mat:
    return _motion(j, q, _axis(j))


def joint_transform(j: Joint, q: float = 0.0) -> Mat:
    """Pose of the child link frame in the parent link frame."""
    return pose_matrix(j.origin.xyz, j.origin.rpy) @ motion(j, q)


_PARTS: list[tuple[Robot, dict[int, tuple[Mat, _Axis]]]] = []  # the last few robots' joint parts
_PARTS_KEPT = 4


def _parts(robot: Robot) -> dict[int, tuple[Mat, _Axis]]:
    """Each joint's origin matrix and axis (by the joint object's identity: a broken description
    may repeat a name), once per robot object: the sweep and the known poses call
    :func:`forward` hundreds of times on one robot, and the origins were a third of it. The same
    arithmetic as :func:`joint_transform`, so the same poses to the last bit."""
    for seen, known in _PARTS:
        if seen is robot:
            return known
    parts: dict[int, tuple[Mat, _Axis]] = {}
    for j in robot.joints:
        origin = pose_matrix(j.origin.xyz, j.origin.rpy)
        origin.flags.writeable = False
        parts[id(j)] = (origin, _axis(j))
    _PARTS.insert(0, (robot, parts))  # holds the robot, so the ids stay its joints'
    del _PARTS[_PARTS_KEPT:]
    return parts


def forward(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, Mat]:
    """Pose of every link reachable from the root, in the root frame.

    Joints not in ``q`` are at zero; a mimic joint is always set from its leader (a value
    given for it is replaced: it is not a free variable)."""
    values = mimic.resolve(robot, q or {})
    root = robot.root()
    if root is None:
        return {}
    parts = _parts(robot)
    poses: dict[str, Mat] = {root: np.eye(4)}
    for j in robot.tree_joints():
        assert j.parent is not None and j.child is not None  # tree_joints yields only linked joints
        known = parts.get(id(j))
        value = values.get(j.name, 0.0)
        local = joint_transform(j, value) if known is None else known[0] @ _motion(j, value, known[1])
        poses[j.child] = poses[j.parent] @ local
    return poses


_AT_ZERO: list[tuple[Robot, dict[str, Mat]]] = []  # the zero poses of the last few robots
_AT_ZERO_KEPT = 4


def at_zero(robot: Robot) -> dict[str, Mat]:
    """``forward(robot)`` at the zero pose, computed once per robot object and shared by the
    audit rules, the span and the load estimates that all need it (read-only matrices: a
    caller cannot change what the next one sees; do not add to the dict). Keyed by
    identity, as Robot is immutable."""
    for seen, poses in _AT_ZERO:
        if seen is robot:
            return poses
    poses = forward(robot)
    for m in poses.values():
        m.flags.writeable = False
    _AT_ZERO.insert(0, (robot, poses))
    del _AT_ZERO[_AT_ZERO_KEPT:]
    return poses


def relative(poses: Mapping[str, Mat], frame: str, base: str | None) -> Mat | None:
    """Pose of ``frame`` in ``base`` (the root when None)."""
    if frame not in poses or (base is not None and base not in poses):
        return None
    if base is None:
        return poses[frame]
    return np.linalg.inv(poses[base]) @ poses[frame]
