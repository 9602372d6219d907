"""Inertia of a primitive turned into link axes: hand-computed values and pinocchio.

A rotation by 90 degrees, or about an axis of symmetry, cannot tell ``R·I·Rᵀ`` (right) from
``Rᵀ·I·R`` (wrong): both give the same tensor. These cases can.
"""

from __future__ import annotations

import math

import numpy as np

from descgen.core.model import Box, Inertia, Pose
from descgen.physics.inertia import in_link_frame


def as_matrix(i: Inertia) -> np.ndarray:
    return np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])


def test_box_yawed_30_degrees_by_hand() -> None:
    # box 0.6 x 0.2 x 0.1 m, 2 kg: a = m(y²+z²)/12, b = m(x²+z²)/12, c = m(x²+y²)/12
    m, (x, y, z) = 2.0, (0.6, 0.2, 0.1)
    a, b, c = m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12
    t = math.radians(30)
    # the box's long axis turned 30 deg towards +y: Rz(t)·diag(a,b,c)·Rz(t)ᵀ
    want = Inertia(
        ixx=a * math.cos(t) ** 2 + b * math.sin(t) ** 2,
        ixy=(a - b) * math.sin(t) * math.cos(t),
        ixz=0.0,
        iyy=a * math.sin(t) ** 2 + b * math.cos(t) ** 2,
        iyz=0.0,
        izz=c,
    )
    got = in_link_frame(Box((x, y, z)), m, Pose((0.0, 0.0, 0.0), (0.0, 0.0, t)))
    assert got is not None
    np.testing.assert_allclose(as_matrix(got), as_matrix(want), rtol=0, atol=1e-15)
    assert got.ixy < 0  # (a - b) < 0: a long box turned towards +y couples x and y negatively


def test_box_at_a_general_orientation_agrees_with_pinocchio(pin) -> None:  # type: ignore[no-untyped-def]
    m, size, rpy = 3.0, (0.5, 0.3, 0.2), (0.3, -0.7, 1.1)
    got = in_link_frame(Box(size), m, Pose((0.0, 0.0, 0.0), rpy))
    assert got is not None
    rotation = pin.rpy.rpyToMatrix(*rpy)
    want = pin.Inertia.FromBox(m, *size).se3Action(pin.SE3(rotation, np.zeros(3))).inertia
    np.testing.assert_allclose(as_matrix(got), want, rtol=0, atol=1e-14)
    assert abs(got.ixz) > 1e-4 and abs(got.iyz) > 1e-4  # off-diagonal terms really are exercised
