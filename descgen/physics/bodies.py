"""Physics and derivations that several parts share: the audit rules, the fault catalogue
and the proofs ask here, so a rule module holds rules only.

- rigid bodies: which links move, which are bodies of their own, what a welded body holds;
- sizes: a primitive shape's dimensions, and the size below which shapes are markers;
- gravity: the static torque (or force) a joint holds against the mass it carries.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from descgen.core.model import Box, Cylinder, Geometry, Joint, Link, Robot, Sphere
from descgen.physics.extent import MARKER
from descgen.physics.rigid import Frame, Vec, apply, cross, dot, rotate

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


def subtree_loads(robot: Robot, poses: dict[str, Frame]) -> dict[str, tuple[float, Vec]]:
    """For every link: the mass of it and everything below it, and the sum of m * centre of
    mass (root frame), from the zero-pose frames (descgen/physics/zero_pose.py). One pass from the
    leaves up, so a 1000-link chain stays linear. Plain floats: the audit asks for every robot."""
    own: dict[str, tuple[float, Vec]] = {}
    for name, pose in poses.items():
        lk = robot.link(name)
        if lk is not None and lk.inertial is not None and lk.inertial.mass and lk.inertial.mass > 0:
            m = lk.inertial.mass
            com = apply(pose, lk.inertial.origin.xyz)  # the inertial frame's origin; its rpy moves no point
            own[name] = (m, (m * com[0], m * com[1], m * com[2]))
        else:
            own[name] = (0.0, (0.0, 0.0, 0.0))
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
    total: dict[str, tuple[float, Vec]] = {}
    for name in reversed(order):  # children before parents
        mass, moment = own[name]
        for j in robot.child_joints(name):
            if j.child in total:
                cm, cmo = total[j.child]
                mass, moment = mass + cm, (moment[0] + cmo[0], moment[1] + cmo[1], moment[2] + cmo[2])
        total[name] = (mass, moment)
    return total


def max_abs_harmonic(a: float, b: float, lo: float, hi: float) -> float:
    """max |a cos q + b sin q| over [lo, hi]: the ends and every stationary point inside."""
    candidates = [lo, hi]
    if hi - lo >= 2 * math.pi:
        return math.hypot(a, b)
    if not (math.isfinite(a) and math.isfinite(b) and math.isfinite(lo) and math.isfinite(hi)):
        # a load at a pose beyond the floats (two offsets of 1e308: inf - inf = nan): no
        # stationary point to find; hypot bounds what is finite and is nan for the rest
        return math.hypot(a, b)
    base = math.atan2(b, a)
    k = math.floor((lo - base) / math.pi)
    while base + k * math.pi <= hi:
        q = base + k * math.pi
        if q >= lo:
            candidates.append(q)
        k += 1
    return max(abs(a * math.cos(q) + b * math.sin(q)) for q in candidates)


def static_load(j: Joint, frame: Frame, mass: float, moment: Vec) -> float:
    """The largest static torque (N*m; force in N for a prismatic joint) that joint ``j``
    holds against gravity (-z of the root) over its own range, the other joints at zero.

    ``frame`` is the child link's pose at zero (the axis is in child coordinates), ``mass``
    and ``moment`` what :func:`subtree_loads` gives for the child. The axis must be non-zero."""
    assert j.axis is not None
    g = (0.0, 0.0, -G)
    n = math.hypot(*j.axis)
    axis = rotate(frame[0], (j.axis[0] / n, j.axis[1] / n, j.axis[2] / n))
    if j.type == "prismatic":
        return abs(dot((mass * g[0], mass * g[1], mass * g[2]), axis))
    # turning the load by q about the axis: torque(q) = A cos q + B sin q (Rodrigues;
    # the axis-parallel part of the lever gives none, since a x g is normal to a)
    p = frame[1]
    lever = (moment[0] - mass * p[0], moment[1] - mass * p[1], moment[2] - mass * p[2])  # sum m (c - p)
    k = cross(axis, g)
    a = dot(lever, k)
    b = dot(cross(axis, lever), k)
    lm = j.limit
    lo = lm.lower if lm is not None and lm.lower is not None else -math.pi
    hi = lm.upper if lm is not None and lm.upper is not None else math.pi
    return max_abs_harmonic(a, b, min(lo, hi), max(lo, hi))


def robot_scale(robot: Robot) -> float:
    """Median length of the non-zero joint offsets: the size of a typical link."""
    lengths = [math.hypot(*j.origin.xyz) for j in robot.joints]
    lengths = sorted(x for x in lengths if x > 1e-4)
    if not lengths:
        return 0.1
    # statistics.median, written out: its import (random, decimal, fractions) cost more than the audit's use
    mid = len(lengths) // 2
    return lengths[mid] if len(lengths) % 2 else (lengths[mid - 1] + lengths[mid]) / 2
