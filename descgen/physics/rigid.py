"""Rigid transforms in plain floats, for the audit's many tiny 3-vectors.

The audit places a few thousand boxes and frames per corpus pass; numpy costs microseconds
per call on a 3x3, more than the arithmetic itself, so these helpers do the same
arithmetic on tuples. The formulas are those of ``descgen.physics.transforms`` (URDF's fixed-axis
roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll); docs/reference/urdf.md), and the tests hold them
to numpy and to pinocchio.

A rotation is three rows; a frame is (rotation, translation) and maps a point p of the
child to R p + t in the parent.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

Vec = tuple[float, float, float]
Rot = tuple[Vec, Vec, Vec]
Frame = tuple[Rot, Vec]

IDENTITY: Rot = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
ORIGIN: Frame = (IDENTITY, (0.0, 0.0, 0.0))


def rpy_rot(rpy: Sequence[float]) -> Rot:
    """R = Rz(yaw) Ry(pitch) Rx(roll). Remembered per value: descriptions repeat a few
    rotations (zero above all) thousands of times. A zero is looked up only when positive,
    since -0.0 == 0.0 as a key but gives other signed zeros in the matrix."""
    r, p, y = rpy
    key = (r, p, y)
    if (r or math.copysign(1.0, r) > 0) and (p or math.copysign(1.0, p) > 0) and (y or math.copysign(1.0, y) > 0):
        known = _ROTS.get(key)
        if known is None:
            known = _ROTS[key] = _rpy_rot(r, p, y)
            if len(_ROTS) > 65536:  # bounded: one description of random angles must not grow it forever
                _ROTS.clear()
        return known
    return _rpy_rot(r, p, y)


_ROTS: dict[tuple[float, float, float], Rot] = {}


def _rpy_rot(r: float, p: float, y: float) -> Rot:
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def axis_angle_rot(axis: Sequence[float], angle: float) -> Rot:
    """Rotation by ``angle`` about ``axis`` (Rodrigues; normalised here, identity for a zero axis)."""
    n = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    if n == 0:
        return IDENTITY
    x, y, z = axis[0] / n, axis[1] / n, axis[2] / n
    c, s = math.cos(angle), math.sin(angle)
    k = 1 - c
    return (
        (c + x * x * k, x * y * k - z * s, x * z * k + y * s),
        (y * x * k + z * s, c + y * y * k, y * z * k - x * s),
        (z * x * k - y * s, z * y * k + x * s, c + z * z * k),
    )


def rotate(r: Rot, v: Sequence[float]) -> Vec:
    """R v."""
    a, b, c = r
    return (
        a[0] * v[0] + a[1] * v[1] + a[2] * v[2],
        b[0] * v[0] + b[1] * v[1] + b[2] * v[2],
        c[0] * v[0] + c[1] * v[1] + c[2] * v[2],
    )


def matmul(r: Rot, s: Rot) -> Rot:
    """R S."""
    cols = ((s[0][0], s[1][0], s[2][0]), (s[0][1], s[1][1], s[2][1]), (s[0][2], s[1][2], s[2][2]))
    return (
        (_dot(r[0], cols[0]), _dot(r[0], cols[1]), _dot(r[0], cols[2])),
        (_dot(r[1], cols[0]), _dot(r[1], cols[1]), _dot(r[1], cols[2])),
        (_dot(r[2], cols[0]), _dot(r[2], cols[1]), _dot(r[2], cols[2])),
    )


def _dot(u: Sequence[float], v: Sequence[float]) -> float:
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def dot(u: Sequence[float], v: Sequence[float]) -> float:
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def cross(u: Sequence[float], v: Sequence[float]) -> Vec:
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def norm(v: Sequence[float]) -> float:
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


def frame(xyz: Sequence[float], rpy: Sequence[float]) -> Frame:
    return rpy_rot(rpy), (float(xyz[0]), float(xyz[1]), float(xyz[2]))


def compose(a: Frame, b: Frame) -> Frame:
    """A B: the frame ``b`` (given in ``a``) in ``a``'s parent."""
    ra, ta = a
    rb, tb = b
    moved = rotate(ra, tb)
    return matmul(ra, rb), (moved[0] + ta[0], moved[1] + ta[1], moved[2] + ta[2])


def inverse(f: Frame) -> Frame:
    """The frame's inverse: (R^T, -R^T t), exact for a rotation (what ``numpy.linalg.inv`` of
    the 4x4 gives, to rounding)."""
    r, t = f
    rt: Rot = ((r[0][0], r[1][0], r[2][0]), (r[0][1], r[1][1], r[2][1]), (r[0][2], r[1][2], r[2][2]))
    back = rotate(rt, t)
    return rt, (-back[0], -back[1], -back[2])


def apply(f: Frame, p: Sequence[float]) -> Vec:
    """R p + t."""
    r, t = f
    q = rotate(r, p)
    return (q[0] + t[0], q[1] + t[1], q[2] + t[2])


def placed_box(low: Sequence[float], high: Sequence[float], f: Frame) -> tuple[Vec, Vec]:
    """The axis-aligned box (parent frame) around the box [low, high] of a child frame: per
    axis, the least and greatest of R c + t over the 8 corners c, taken term by term (each
    corner coordinate contributes independently, so no corner list is built)."""
    r, t = f
    lo: list[float] = []
    hi: list[float] = []
    for i in range(3):
        row = r[i]
        least = most = t[i]
        for j in range(3):
            a, b = row[j] * low[j], row[j] * high[j]
            if a <= b:
                least += a
                most += b
            else:
                least += b
                most += a
        lo.append(least)
        hi.append(most)
    return (lo[0], lo[1], lo[2]), (hi[0], hi[1], hi[2])
