"""Mass properties of primitive shapes (uniform density).

Formulas: solid box, solid cylinder about its centroid with length along z (URDF's
cylinder axis), solid sphere. These are the textbook values; tests check them against
pinocchio's ``Inertia.FromBox/FromCylinder/FromSphere``.

A primitive's tensor is plain Python: the spec loader derives one per ``from:`` link, and
importing numpy for a few 3x3 products was ~60 ms of every cold ``validate``. It is also the
same on every machine (numpy hands 3x3 products to the BLAS, whose kernel, and with it the
rounding of the last bit, depends on the CPU). Mesh integrals stay numpy, imported when a
mesh is integrated.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from descgen.core.model import Box, Cylinder, Geometry, Inertia, Pose, Sphere, Vec3
from descgen.physics import rigid

if TYPE_CHECKING:
    import numpy as np

    from descgen.physics.transforms import Mat

Rows = tuple[Vec3, Vec3, Vec3]


def volume(g: Geometry) -> float | None:
    """Volume in m^3, or None for a mesh (unknown without reading the file)."""
    if isinstance(g, Box):
        return g.size[0] * g.size[1] * g.size[2]
    if isinstance(g, Cylinder):
        return math.pi * g.radius * g.radius * g.length  # x*x: inf past the floats, where ** raises
    if isinstance(g, Sphere):
        return 4.0 / 3.0 * math.pi * g.radius * g.radius * g.radius
    return None


def principal_moments(g: Geometry, mass: float) -> Vec3 | None:
    """The diagonal of the centroidal tensor (a primitive's axes are its principal axes)."""
    if isinstance(g, Box):
        x, y, z = g.size
        return (mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12, mass * (x * x + y * y) / 12)
    if isinstance(g, Cylinder):
        r, h = g.radius, g.length
        side = mass * (3 * r * r + h * h) / 12
        return (side, side, mass * r * r / 2)
    if isinstance(g, Sphere):
        s = 2.0 / 5.0 * mass * g.radius * g.radius
        return (s, s, s)
    return None


def in_link_frame(g: Geometry, mass: float, origin: Pose) -> Inertia | None:
    """The primitive's centroidal tensor rotated into link-frame axes: R·diag(a, b, c)·Rᵀ."""
    principal = principal_moments(g, mass)
    if principal is None:
        return None
    r = rigid.rpy_rot(origin.rpy)
    # (R·D) first, then ·Rᵀ, each sum left to right: R·D scales R's columns
    rd = [(row[0] * principal[0], row[1] * principal[1], row[2] * principal[2]) for row in r]
    t = [[rd[i][0] * r[j][0] + rd[i][1] * r[j][1] + rd[i][2] * r[j][2] for j in range(3)] for i in range(3)]
    scale = max(abs(x) for row in t for x in row) or 1.0
    floor = scale * 1e-12  # rotation round-off, not physics

    def v(i: int, j: int) -> float:
        x = t[i][j]
        return 0.0 if abs(x) < floor else x + 0.0

    return Inertia(v(0, 0), v(0, 1), v(0, 2), v(1, 1), v(1, 2), v(2, 2))


def mesh_properties(vertices: np.ndarray, faces: np.ndarray) -> tuple[float, Vec3, Mat]:
    """Volume, centroid and the tensor about the centroid per unit density (so multiply by
    mass / volume) of the solid a closed triangle mesh bounds, in the mesh's frame.

    The divergence theorem turns each volume integral into a sum over the triangles
    (D. Eberly, "Polyhedral Mass Properties (Revisited)", 2002). Only meaningful for a
    watertight mesh with consistent winding; an inward-wound mesh gives a negative volume,
    which is flipped."""
    import numpy as np

    v0, v1, v2 = (np.asarray(vertices, dtype=np.float64)[np.asarray(faces)[:, i]] for i in range(3))
    d = np.cross(v1 - v0, v2 - v0)
    f1, f2, f3, g0, g1, g2 = _subexpressions(v0, v1, v2)
    x, y, z = 0, 1, 2
    integral = np.array(
        [
            np.sum(d[:, x] * f1[:, x]) / 6,
            np.sum(d[:, x] * f2[:, x]) / 24,
            np.sum(d[:, y] * f2[:, y]) / 24,
            np.sum(d[:, z] * f2[:, z]) / 24,
            np.sum(d[:, x] * f3[:, x]) / 60,
            np.sum(d[:, y] * f3[:, y]) / 60,
            np.sum(d[:, z] * f3[:, z]) / 60,
            np.sum(d[:, x] * (v0[:, y] * g0[:, x] + v1[:, y] * g1[:, x] + v2[:, y] * g2[:, x])) / 120,
            np.sum(d[:, y] * (v0[:, z] * g0[:, y] + v1[:, z] * g1[:, y] + v2[:, z] * g2[:, y])) / 120,
            np.sum(d[:, z] * (v0[:, x] * g0[:, z] + v1[:, x] * g1[:, z] + v2[:, x] * g2[:, z])) / 120,
        ]
    )
    if integral[0] < 0:
        integral = -integral  # wound inwards: every integral has the opposite sign
    vol = float(integral[0])
    if vol <= 0:
        return 0.0, (0.0, 0.0, 0.0), np.zeros((3, 3))
    cx, cy, cz = integral[1:4] / vol
    # second moments about the origin, moved to the centroid (parallel axis), tensor signs
    ixx = integral[5] + integral[6] - vol * (cy * cy + cz * cz)
    iyy = integral[4] + integral[6] - vol * (cz * cz + cx * cx)
    izz = integral[4] + integral[5] - vol * (cx * cx + cy * cy)
    ixy = -(integral[7] - vol * cx * cy)
    iyz = -(integral[8] - vol * cy * cz)
    ixz = -(integral[9] - vol * cz * cx)
    tensor = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=np.float64)
    return vol, (float(cx), float(cy), float(cz)), tensor


def _subexpressions(
    w0: np.ndarray, w1: np.ndarray, w2: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Eberly's per-triangle polynomial terms, for x, y and z at once (columns)."""
    temp0 = w0 + w1
    f1 = temp0 + w2
    temp1 = w0 * w0
    temp2 = temp1 + w1 * temp0
    f2 = temp2 + w2 * f1
    f3 = w0 * temp1 + w1 * temp2 + w2 * f2
    return f1, f2, f3, f2 + w0 * (f1 + w0), f2 + w1 * (f1 + w1), f2 + w2 * (f1 + w2)


def from_mesh(
    vertices: np.ndarray, faces: np.ndarray, mass: float, scale: Vec3, origin: Pose
) -> tuple[Vec3, Inertia] | None:
    """Centre of mass and centroidal tensor, in link-frame axes, of a watertight mesh of
    uniform density and the given mass, placed by the geometry's ``scale`` and ``origin``.
    None when the mesh bounds no volume."""
    import numpy as np

    from descgen.physics.transforms import rpy_matrix

    scaled = np.asarray(vertices, dtype=np.float64) * np.asarray(scale, dtype=np.float64)
    vol, centroid, per_density = mesh_properties(scaled, faces)
    if vol <= 0:
        return None
    r = rpy_matrix(origin.rpy)
    t = r @ (per_density * (mass / vol)) @ r.T
    size = float(np.max(np.abs(t))) or 1.0
    t[np.abs(t) < size * 1e-12] = 0.0  # rotation round-off, not physics
    com = r @ np.asarray(centroid) + np.asarray(origin.xyz)

    def v(i: int, j: int) -> float:
        return float(t[i, j]) + 0.0

    tensor = Inertia(v(0, 0), v(0, 1), v(0, 2), v(1, 1), v(1, 2), v(2, 2))
    return (float(com[0]), float(com[1]), float(com[2])), tensor
