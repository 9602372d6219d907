"""Mass properties of primitive shapes (uniform density).

Formulas: solid box, solid cylinder about its centroid with length along z (URDF's
cylinder axis), solid sphere. These are the textbook values; tests check them against
pinocchio's ``Inertia.FromBox/FromCylinder/FromSphere``.
"""

from __future__ import annotations

import math

import numpy as np

from .model import Box, Cylinder, Geometry, Inertia, Mesh, Pose, Sphere
from .transforms import Mat, rpy_matrix


def volume(g: Geometry) -> float | None:
    """Volume in m^3, or None for a mesh (unknown without reading the file)."""
    if isinstance(g, Box):
        return g.size[0] * g.size[1] * g.size[2]
    if isinstance(g, Cylinder):
        return math.pi * g.radius**2 * g.length
    if isinstance(g, Sphere):
        return 4.0 / 3.0 * math.pi * g.radius**3
    return None


def centroidal(g: Geometry, mass: float) -> Mat | None:
    """Inertia tensor about the centroid, in the geometry frame; None for a mesh."""
    if isinstance(g, Box):
        x, y, z = g.size
        return np.diag([mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12, mass * (x * x + y * y) / 12])
    if isinstance(g, Cylinder):
        r, h = g.radius, g.length
        side = mass * (3 * r * r + h * h) / 12
        return np.diag([side, side, mass * r * r / 2])
    if isinstance(g, Sphere):
        return np.eye(3) * (2.0 / 5.0 * mass * g.radius**2)
    if isinstance(g, Mesh):
        return None
    return None


def in_link_frame(g: Geometry, mass: float, origin: Pose) -> Inertia | None:
    """The primitive's centroidal tensor rotated into link-frame axes."""
    tensor = centroidal(g, mass)
    if tensor is None:
        return None
    r = rpy_matrix(origin.rpy)
    t = r @ tensor @ r.T
    scale = float(np.max(np.abs(t))) or 1.0
    t[np.abs(t) < scale * 1e-12] = 0.0  # rotation round-off, not physics

    def v(i: int, j: int) -> float:
        return float(t[i, j]) + 0.0

    return Inertia(v(0, 0), v(0, 1), v(0, 2), v(1, 1), v(1, 2), v(2, 2))
