"""Rigid transforms as numpy 4x4 matrices, with URDF's conventions.

URDF ``rpy`` is roll, pitch, yaw about the fixed X, Y, Z axes: R = Rz(yaw) Ry(pitch) Rx(roll)
(urdfdom ``Rotation::setFromRPY``; docs/reference/urdf.md).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

Mat = NDArray[np.float64]


def rpy_matrix(rpy: Sequence[float]) -> Mat:
    r, p, y = rpy
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def pose_matrix(xyz: Sequence[float], rpy: Sequence[float]) -> Mat:
    t = np.eye(4)
    t[:3, :3] = rpy_matrix(rpy)
    t[:3, 3] = xyz
    return t


def axis_angle_matrix(axis: Sequence[float], angle: float) -> Mat:
    """Rotation by ``angle`` about the unit vector ``axis`` (Rodrigues)."""
    a = np.asarray(axis, dtype=float)
    n = float(np.linalg.norm(a))
    if n == 0:
        return np.eye(3)
    x, y, z = a / n
    c, s = math.cos(angle), math.sin(angle)
    k = 1 - c
    return np.array(
        [
            [c + x * x * k, x * y * k - z * s, x * z * k + y * s],
            [y * x * k + z * s, c + y * y * k, y * z * k - x * s],
            [z * x * k - y * s, z * y * k + x * s, c + z * z * k],
        ]
    )


def matrix_rpy(r: Mat) -> tuple[float, float, float]:
    """URDF roll, pitch, yaw of a rotation matrix (the inverse of :func:`rpy_matrix`). At pitch
    ±90° roll and yaw turn about one axis; roll is then 0 and yaw carries the rotation."""
    pitch = math.atan2(-float(r[2, 0]), math.hypot(float(r[0, 0]), float(r[1, 0])))
    if math.hypot(float(r[0, 0]), float(r[1, 0])) < 1e-12:
        return 0.0, pitch, math.atan2(-float(r[0, 1]), float(r[1, 1]))
    return math.atan2(float(r[2, 1]), float(r[2, 2])), pitch, math.atan2(float(r[1, 0]), float(r[0, 0]))
