"""Forward kinematics on the SI model (numpy).

A joint's transform is ``origin * motion(q)``: rotation by q about the joint axis (in the
joint frame) for revolute and continuous joints, translation by q along it for prismatic
joints; fixed, floating and planar joints sit at their origin (known poses set only
one-degree-of-freedom joints). Mimic joints follow their leaders (``descgen.mimic``), as
in robot_state_publisher, MoveIt, yourdfpy and pinocchio. The axis is normalised (urdfdom does not; JOINT002 flags
an axis that is not unit length). Origins use URDF's fixed-axis roll-pitch-yaw.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from . import mimic
from .model import ROTATING, Joint, Robot
from .transforms import Mat, axis_angle_matrix, pose_matrix


def motion(j: Joint, q: float) -> Mat:
    t = np.eye(4)
    if q == 0 or j.axis is None:
        return t
    axis = np.asarray(j.axis, dtype=float)
    n = float(np.linalg.norm(axis))
    if n == 0:
        return t
    if j.type in ROTATING:
        t[:3, :3] = axis_angle_matrix(tuple(float(c) for c in axis / n), q)
    elif j.type == "prismatic":
        t[:3, 3] = q * axis / n
    return t


def joint_transform(j: Joint, q: float = 0.0) -> Mat:
    """Pose of the child link frame in the parent link frame."""
    return pose_matrix(j.origin.xyz, j.origin.rpy) @ motion(j, q)


def forward(robot: Robot, q: Mapping[str, float] | None = None) -> dict[str, Mat]:
    """Pose of every link reachable from the root, in the root frame.

    Joints not in ``q`` are at zero; a mimic joint is always set from its leader (a value
    given for it is replaced: it is not a free variable)."""
    values = mimic.resolve(robot, q or {})
    root = robot.root()
    if root is None:
        return {}
    poses: dict[str, Mat] = {root: np.eye(4)}
    todo = [root]
    while todo:
        parent = todo.pop()
        for j in robot.child_joints(parent):
            if j.child is None or j.child in poses:
                continue
            poses[j.child] = poses[parent] @ joint_transform(j, values.get(j.name, 0.0))
            todo.append(j.child)
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
