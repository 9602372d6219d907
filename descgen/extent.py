"""How far material can reach: the extreme points of primitive shapes, and the robot's span.

Plausibility rules compare a number with the size of what it belongs to: a principal
moment of inertia cannot exceed what the whole mass would give at the farthest point of
the link's shapes (INER011), and a prismatic joint cannot travel a hundred times the
size of the whole robot (JOINT020). Both need sizes that are upper bounds, so every shape
here is replaced by points whose convex hull contains it (a mesh has no known extent
without reading the file, so a link with a mesh has none here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .model import Box, Collision, Cylinder, Link, Robot, Sphere, Visual
from .transforms import Mat, pose_matrix, rpy_matrix

_SIDES = 64  # a cylinder's rims become 64-gons drawn around the circle, so they contain it
# built once (the audit asks for thousands of hulls): the signs of a box's corners, the unit ring
_CUBE = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
_RING_ANGLES = np.linspace(0.0, 2 * math.pi, _SIDES, endpoint=False)
_RING_COS, _RING_SIN = np.cos(_RING_ANGLES), np.sin(_RING_ANGLES)


@dataclass(frozen=True)
class Hull:
    """Points whose convex hull, grown by ``pad`` in every direction, contains a shape."""

    points: Mat  # (k, 3), in the frame the hull was built in
    pad: float = 0.0  # a sphere is its centre grown by its radius


def shape_hull(shape: Visual | Collision) -> Hull | None:
    """The hull of one primitive in its link's frame; None for a mesh or a missing geometry."""
    g = shape.geometry
    if isinstance(g, Box):
        half = np.array(g.size, dtype=float) / 2
        local = _CUBE * half
        pad = 0.0
    elif isinstance(g, Cylinder):
        # the circumscribed polygon: its corners sit at r / cos(pi / n), so nothing is cut off
        r = g.radius / math.cos(math.pi / _SIDES)
        ring = np.stack([r * _RING_COS, r * _RING_SIN], axis=1)
        local = np.vstack([np.column_stack([ring, np.full(_SIDES, z)]) for z in (-g.length / 2, g.length / 2)])
        pad = 0.0
    elif isinstance(g, Sphere):
        local, pad = np.zeros((1, 3)), g.radius
    else:
        return None
    t = pose_matrix(shape.origin.xyz, shape.origin.rpy)
    return Hull(local @ t[:3, :3].T + t[:3, 3], abs(pad))


def link_hulls(link: Link) -> list[Hull] | None:
    """Hulls of every visual and collision shape of ``link``; None when one of them has no
    known extent (a mesh), since then the others do not bound the link."""
    hulls = [shape_hull(s) for s in link.shapes()]
    if any(h is None for h in hulls):
        return None
    return [h for h in hulls if h is not None]


MARKER = 0.011  # metres: shapes that all fit in about a centimetre mark a point; they do not bound a part


def bounding_hulls(link: Link) -> list[Hull] | None:
    """The hulls of ``link`` when they bound its material: every shape a primitive, and
    together larger than a marker. None otherwise (a mesh, no shapes, a marker)."""
    hulls = link_hulls(link)
    if not hulls:
        return None
    size = max(float(np.ptp(np.vstack([h.points for h in hulls]), axis=0).max()), 2 * max(h.pad for h in hulls))
    return hulls if size >= MARKER else None


def farthest_from_axis(hulls: list[Hull], point: Mat, axis: Mat) -> float:
    """The largest distance from the line through ``point`` along unit ``axis`` to any
    point of the hulls."""
    best = 0.0
    for h in hulls:
        d = h.points - point
        perp = d - np.outer(d @ axis, axis)
        best = max(best, float(np.max(np.linalg.norm(perp, axis=1))) + h.pad)
    return best


def robot_span(robot: Robot) -> float:
    """Diagonal of the box around every link frame and primitive shape at the zero pose
    (root frame): an upper bound on the size of the robot's known parts. 0 when the tree
    cannot be posed."""
    from .kinematics import at_zero

    poses = at_zero(robot)
    if not poses:
        return 0.0
    lows, highs = [], []
    for name, pose in poses.items():
        lows.append(pose[:3, 3])
        highs.append(pose[:3, 3])
        lk = robot.link(name)
        for shape in lk.shapes() if lk is not None else ():
            h = shape_hull(shape)
            if h is None:
                continue
            pts = h.points @ pose[:3, :3].T + pose[:3, 3]
            lows.append(pts.min(axis=0) - h.pad)
            highs.append(pts.max(axis=0) + h.pad)
    return float(np.linalg.norm(np.max(highs, axis=0) - np.min(lows, axis=0)))


@dataclass(frozen=True)
class MomentBound:
    """A moment of inertia (kg*m^2) and the most the link's mass can give at ``reach`` (m)."""

    moment: float
    bound: float
    reach: float

    @property
    def ratio(self) -> float:
        return self.moment / self.bound


def moment_by_shapes(link: Link) -> MomentBound | None:
    """The principal moment that comes closest to (or beyond) its bound: the whole mass at
    the farthest point of the link's own shapes from that principal axis (m * r_max^2, which
    no mass inside the shapes can exceed). None when the shapes do not bound the link."""
    i = link.inertial
    hulls = bounding_hulls(link)
    if i is None or i.inertia is None or i.mass is None or i.mass <= 0 or not hulls:
        return None
    eig, vecs = np.linalg.eigh(np.array(i.inertia.matrix()))
    frame = rpy_matrix(i.origin.rpy)  # the tensor is written in the inertial frame
    com = np.array(i.origin.xyz, dtype=float)
    worst: MomentBound | None = None
    for k in range(3):
        reach = farthest_from_axis(hulls, com, frame @ vecs[:, k])
        found = MomentBound(float(eig[k]), i.mass * reach**2, reach)
        if found.bound > 0 and (worst is None or found.ratio > worst.ratio):
            worst = found
    return worst


def half_trace_by_span(link: Link, span: float) -> MomentBound | None:
    """Half the trace (the sum of m r^2 about the centre of mass) against the whole mass at
    the robot's span: no part reaches farther from its centre of mass than the robot does."""
    i = link.inertial
    if i is None or i.inertia is None or i.mass is None or i.mass <= 0 or span < MARKER:
        return None
    t = i.inertia
    return MomentBound((t.ixx + t.iyy + t.izz) / 2, i.mass * span**2, span)
