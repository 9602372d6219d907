"""Physics and derivations that several parts share: the audit rules, the fault catalogue
and the proofs ask here, so a rule module holds rules only.

- rigid bodies: which links move, which are bodies of their own, what a welded body holds;
- sizes: a primitive shape's dimensions, and the size below which shapes are markers;
- gravity: the static torque (or force) a joint holds against the mass it carries.
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable

import numpy as np

from .extent import MARKER
from .model import Box, Cylinder, Geometry, Joint, Link, Robot, Sphere
from .transforms import Mat, pose_matrix

G = 9.80665  # m/s^2, standard gravity

# A link whose shapes all fit within about a centimetre is a marker or a contact point, not
# the part's shape (one threshold with extent.MARKER, so the rules agree on what a marker is).
PLACEHOLDER = MARKER
PLACEHOLDER_MASS = 0.001  # kg: dummy masses (the real one sits on a welded link)


# -- rigid bodies ---------------------------------------------------------------------------


def moving_links(robot: Robot) -> set[str]:
    """Links that some non-fixed joint moves (that joint's child and everything below)."""
    moving: set[str] = set()
    todo = [j.child for j in robot.joints if j.type != "fixed" and j.child]
    while todo:
        name = todo.pop()
        if name in moving:
            continue  # also ends cycles
        moving.add(name)
        todo += [j.child for j in robot.child_joints(name) if j.child]
    return moving


def own_bodies(robot: Robot) -> set[str]:
    """Links that are rigid bodies of their own: the child of a joint that moves. A link
    welded on by a fixed joint is merged into its parent by simulators and by KDL."""
    return {j.child for j in robot.joints if j.type != "fixed" and j.child}


def welded_count(robot: Robot, has: Callable[[Link], object]) -> dict[str, int]:
    """Per link name: how many links of its rigid body (welded by fixed joints) satisfy ``has``.

    Each body is visited once, so 10,000 welded links cost linear time, not a scan of the
    whole body per link."""
    counts: dict[str, int] = {}
    for lk in robot.links:
        if lk.name in counts:
            continue
        body = robot.body_of(lk.name)
        n = sum(1 for name in body if (other := robot.link(name)) is not None and has(other))
        for name in body:
            counts[name] = n
    return counts


# -- sizes ----------------------------------------------------------------------------------


def dims(g: Geometry | None) -> list[float]:
    """The dimensions of a primitive (box sides, cylinder diameter and length, sphere
    diameter); none for a mesh, whose size is unknown without reading it."""
    if isinstance(g, Box):
        return list(g.size)
    if isinstance(g, Cylinder):
        return [2 * g.radius, g.length]
    if isinstance(g, Sphere):
        return [2 * g.radius]
    return []


# -- gravity --------------------------------------------------------------------------------


def subtree_loads(robot: Robot, poses: dict[str, Mat]) -> dict[str, tuple[float, Mat]]:
    """For every link: the mass of it and everything below it, and the sum of m * centre of
    mass (root frame). One pass from the leaves up, so a 1000-link chain stays linear."""
    own: dict[str, tuple[float, Mat]] = {}
    for name, pose in poses.items():
        lk = robot.link(name)
        if lk is not None and lk.inertial is not None and lk.inertial.mass and lk.inertial.mass > 0:
            com = pose @ pose_matrix(lk.inertial.origin.xyz, lk.inertial.origin.rpy)
            own[name] = (lk.inertial.mass, lk.inertial.mass * com[:3, 3])
        else:
            own[name] = (0.0, np.zeros(3))
    order: list[str] = []
    root = robot.root()
    todo = [root] if root in poses else []
    seen: set[str] = set()
    while todo:
        name = todo.pop()
        if name is None or name in seen:
            continue
        seen.add(name)
        order.append(name)
        todo += [j.child for j in robot.child_joints(name) if j.child in poses]
    total: dict[str, tuple[float, Mat]] = {}
    for name in reversed(order):  # children before parents
        mass, moment = own[name]
        for j in robot.child_joints(name):
            if j.child in total:
                cm, cmo = total[j.child]
                mass, moment = mass + cm, moment + cmo
        total[name] = (mass, moment)
    return total


def max_abs_harmonic(a: float, b: float, lo: float, hi: float) -> float:
    """max |a cos q + b sin q| over [lo, hi]: the ends and every stationary point inside."""
    candidates = [lo, hi]
    if hi - lo >= 2 * math.pi:
        return math.hypot(a, b)
    base = math.atan2(b, a)
    k = math.floor((lo - base) / math.pi)
    while base + k * math.pi <= hi:
        q = base + k * math.pi
        if q >= lo:
            candidates.append(q)
        k += 1
    return max(abs(a * math.cos(q) + b * math.sin(q)) for q in candidates)


def static_load(j: Joint, frame: Mat, mass: float, moment: Mat) -> float:
    """The largest static torque (N*m; force in N for a prismatic joint) that joint ``j``
    holds against gravity (-z of the root) over its own range, the other joints at zero.

    ``frame`` is the child link's pose at zero (the axis is in child coordinates), ``mass``
    and ``moment`` what :func:`subtree_loads` gives for the child. The axis must be non-zero."""
    assert j.axis is not None
    g = np.array([0.0, 0.0, -G])
    axis = frame[:3, :3] @ (np.array(j.axis) / math.hypot(*j.axis))
    if j.type == "prismatic":
        return abs(float(np.dot(mass * g, axis)))
    # turning the load by q about the axis: torque(q) = A cos q + B sin q (Rodrigues;
    # the axis-parallel part of the lever gives none, since a x g is normal to a)
    lever = moment - mass * frame[:3, 3]  # sum m (c - p)
    k = _cross(axis, g)
    a = float(np.dot(lever, k))
    b = float(np.dot(_cross(axis, lever), k))
    lm = j.limit
    lo = lm.lower if lm is not None and lm.lower is not None else -math.pi
    hi = lm.upper if lm is not None and lm.upper is not None else math.pi
    return max_abs_harmonic(a, b, min(lo, hi), max(lo, hi))


def _cross(u: Mat, v: Mat) -> Mat:
    """np.cross of two 3-vectors, term for term the same floats, without its axis handling
    (ten times its cost on 3-vectors: it ran once per joint of every audited robot)."""
    return np.array([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]])


def robot_scale(robot: Robot) -> float:
    """Median length of the non-zero joint offsets: the size of a typical link."""
    lengths = [math.hypot(*j.origin.xyz) for j in robot.joints]
    lengths = [x for x in lengths if x > 1e-4]
    return statistics.median(lengths) if lengths else 0.1
