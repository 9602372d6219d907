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

from descgen.core.model import Box, Collision, Cylinder, Link, Robot, Sphere, Visual
from descgen.core.record import record
from descgen.physics import principal
from descgen.physics.rigid import Frame, Vec, apply, compose, frame, norm, rotate, rpy_rot

_SIDES = 64  # a cylinder's rims become 64-gons drawn around the circle, so they contain it
_STEP = 2 * math.pi / _SIDES
# the unit ring, built once (the audit asks for thousands of hulls): angle k * 2 pi / 64
_RING = tuple((math.cos(k * _STEP), math.sin(k * _STEP)) for k in range(_SIDES))
_CUBE = tuple((sx, sy, sz) for sx in (-1.0, 1.0) for sy in (-1.0, 1.0) for sz in (-1.0, 1.0))
_SAMPLED = range(0, _SIDES, 8)  # rim corners a quick lower bound on a reach looks at


@record
class Hull:
    """Points whose convex hull, grown by ``pad`` in every direction, contains a shape, in
    the frame the hull was built in: a box's 8 corners, a sphere's centre (``pad`` its
    radius), or a cylinder's two rims, 64-gons of circumradius ``rim`` at heights
    +-``half`` along z of ``at`` (their 128 corners are made only when asked: plain floats,
    and most questions about a rim have a closed form, :func:`extent`)."""

    points: tuple[Vec, ...] = ()
    pad: float = 0.0
    at: Frame | None = None  # a cylinder's frame; None for explicit points
    rim: float = 0.0
    half: float = 0.0


def shape_hull(shape: Visual | Collision) -> Hull | None:
    """The hull of one primitive in its link's frame; None for a mesh or a missing geometry."""
    g = shape.geometry
    if not isinstance(g, (Box, Cylinder, Sphere)):
        return None
    f = frame(shape.origin.xyz, shape.origin.rpy)
    if isinstance(g, Box):
        hx, hy, hz = g.size[0] / 2, g.size[1] / 2, g.size[2] / 2
        return Hull(tuple(apply(f, (sx * hx, sy * hy, sz * hz)) for sx, sy, sz in _CUBE))
    if isinstance(g, Cylinder):
        # the circumscribed polygon: its corners sit at r / cos(pi / n), so nothing is cut off
        return Hull(at=f, rim=g.radius / math.cos(math.pi / _SIDES), half=g.length / 2)
    if isinstance(g, Sphere):
        return Hull((f[1],), abs(g.radius))
    return None


def corners(h: Hull, indices: range = range(_SIDES)) -> tuple[Vec, ...]:
    """The hull's points (a cylinder: the rim corners numbered ``indices``, both rims)."""
    if h.at is None:
        return h.points
    r = h.rim
    return tuple(apply(h.at, (r * _RING[k][0], r * _RING[k][1], z)) for z in (-h.half, h.half) for k in indices)


def extent(h: Hull, placed: Frame | None = None) -> tuple[Vec, Vec]:
    """Least and greatest coordinates of the hull's points (without ``pad``), in the hull's
    frame or moved by ``placed``. A rim corner's coordinate is A cos t + B sin t plus a
    constant, largest at the two grid angles beside atan2(B, A) and least beside the
    opposite one, so four corners per axis are looked at, not 128."""
    if h.at is None:
        pts = h.points if placed is None else tuple(apply(placed, p) for p in h.points)
        return (
            (min(p[0] for p in pts), min(p[1] for p in pts), min(p[2] for p in pts)),
            (max(p[0] for p in pts), max(p[1] for p in pts), max(p[2] for p in pts)),
        )
    f = h.at if placed is None else compose(placed, h.at)
    lo: list[float] = []
    hi: list[float] = []
    for i in range(3):
        row = f[0][i]
        best = -math.inf
        least = math.inf
        for k in _beside(row[0], row[1]) + _beside(-row[0], -row[1]):
            for z in (-h.half, h.half):
                c, s = h.rim * _RING[k][0], h.rim * _RING[k][1]
                v = row[0] * c + row[1] * s + row[2] * z + f[1][i]
                best, least = max(best, v), min(least, v)
        lo.append(least)
        hi.append(best)
    return (lo[0], lo[1], lo[2]), (hi[0], hi[1], hi[2])


def _beside(a: float, b: float) -> tuple[int, int]:
    """The two grid angles on either side of the one where a cos t + b sin t is largest."""
    k = math.floor((math.atan2(b, a) % (2 * math.pi)) / _STEP)
    return k % _SIDES, (k + 1) % _SIDES


def link_hulls(link: Link) -> list[Hull] | None:
    """Hulls of every visual and collision shape of ``link``; None when one of them has no
    known extent (a mesh), since then the others do not bound the link."""
    hulls = []
    for s in link.shapes():
        h = shape_hull(s)
        if h is None:
            return None
        hulls.append(h)
    return hulls


MARKER = 0.011  # metres: shapes that all fit in about a centimetre mark a point; they do not bound a part


def bounding_hulls(link: Link) -> list[Hull] | None:
    """The hulls of ``link`` when they bound its material: every shape a primitive, and
    together larger than a marker. None otherwise (a mesh, no shapes, a marker)."""
    hulls = link_hulls(link)
    if not hulls:
        return None
    boxes = [extent(h) for h in hulls]
    ptp = max(max(hi[k] for _, hi in boxes) - min(lo[k] for lo, _ in boxes) for k in range(3))
    size = max(ptp, 2 * max(h.pad for h in hulls))
    return hulls if size >= MARKER else None


def farthest_from_axis(hulls: list[Hull], point: Vec, axis: Vec, indices: range = range(_SIDES)) -> float:
    """The largest distance from the line through ``point`` along unit ``axis`` to any
    point of the hulls (only rim corners numbered ``indices``: a lower bound otherwise)."""
    # written out (the audit's hottest loop): the same operations, in the same order, as
    # norm(d - dot(d, axis) * axis) with d = p - point, except that the square root is taken
    # once of the largest sum of squares, which is the same float (sqrt is monotone)
    px, py, pz = point
    ax, ay, az = axis
    best = 0.0
    for h in hulls:
        far2 = 0.0
        for x, y, z in corners(h, indices):
            dx, dy, dz = x - px, y - py, z - pz
            along = dx * ax + dy * ay + dz * az
            ex, ey, ez = dx - along * ax, dy - along * ay, dz - along * az
            q = ex * ex + ey * ey + ez * ez
            if q > far2:  # max(far2, q): a nan distance is passed over, as max() does
                far2 = q
        best = max(best, math.sqrt(far2) + h.pad)
    return best


def distinct(hulls: list[Hull]) -> list[Hull]:
    """``hulls`` without repeats (a visual and a collision of the same shape and origin): a
    repeated hull changes no farthest distance, and each costs a pass over its points."""
    return list(dict.fromkeys(hulls)) if len(hulls) > 1 else hulls


_SPANS: list[tuple[Robot, float]] = []  # the spans of the last few robots (INER011 and JOINT020 ask)


def robot_span(robot: Robot) -> float:
    """Diagonal of the box around every link frame and primitive shape at the zero pose
    (root frame): an upper bound on the size of the robot's known parts. 0 when the tree
    cannot be posed. Computed once per robot object (Robot is immutable)."""
    for seen, span in _SPANS:
        if seen is robot:
            return span
    span = _span(robot)
    _SPANS.insert(0, (robot, span))
    del _SPANS[4:]
    return span


def span_floor(robot: Robot) -> float:
    """A lower bound on :func:`robot_span` that poses no shape: the diagonal of the box
    around the link frames alone (forward kinematics is shared with the other rules). Never
    more than the span, in floats too: the span's box holds these same points (so its least
    and greatest coordinates are at least as far apart, min and max being exact), and a
    difference, a square, a sum and a square root each round monotonically."""
    from descgen.physics.zero_pose import at_zero

    poses = at_zero(robot)
    if not poses:
        return 0.0
    ts = [pose[1] for pose in poses.values()]
    lo = [min(t[k] for t in ts) for k in range(3)]
    hi = [max(t[k] for t in ts) for k in range(3)]
    return norm((hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]))


def _span(robot: Robot) -> float:
    from descgen.physics.zero_pose import at_zero

    poses = at_zero(robot)
    if not poses:
        return 0.0
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for name, pose in poses.items():
        t = pose[1]
        boxes = [(t, t, 0.0)]
        lk = robot.link(name)
        for shape in lk.shapes() if lk is not None else ():
            h = shape_hull(shape)
            if h is not None:
                low, high = extent(h, pose)
                boxes.append((low, high, h.pad))
        for low, high, pad in boxes:
            for k in range(3):
                lo[k] = min(lo[k], low[k] - pad)
                hi[k] = max(hi[k], high[k] + pad)
    return norm((hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]))


@record
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
    eig, vecs = principal.axes(i.inertia)  # once per tensor, shared with INER003/INER004
    turn = rpy_rot(i.origin.rpy)  # the tensor is written in the inertial frame
    hulls = distinct(hulls)
    worst: MomentBound | None = None
    for k in range(3):
        reach = farthest_from_axis(hulls, i.origin.xyz, rotate(turn, vecs[k]))
        found = MomentBound(eig[k], i.mass * reach * reach, reach)  # x*x: inf past the floats
        if found.bound > 0 and (worst is None or found.ratio > worst.ratio):
            worst = found
    return worst


def within_shapes(link: Link, hulls: list[Hull], margin: float) -> bool:
    """True when no principal moment of ``link`` can exceed ``margin`` times its bound by
    shapes (so :func:`moment_by_shapes` gives a ratio of at most ``margin``), decided from
    a few points of each rim: their farthest distance is at most the true reach, so the
    bound it gives is at most the true one. False means "compute it" (never "too large")."""
    i = link.inertial
    if i is None or i.inertia is None or i.mass is None or i.mass <= 0:
        return False
    if not principal.axes_without_numpy(i.inertia) and _within_for_every_axis(link, hulls, margin):
        return True
    eig, vecs = principal.axes(i.inertia)
    turn = rpy_rot(i.origin.rpy)
    hulls = distinct(hulls)
    for k in range(3):
        reach = farthest_from_axis(hulls, i.origin.xyz, rotate(turn, vecs[k]), _SAMPLED)
        bound = i.mass * reach * reach
        # a relative slack far above rounding: the exact reach is computed in another order
        if not (bound > 0 and eig[k] <= margin * bound * (1 - 1e-9)):
            return False
    return True


def _within_for_every_axis(link: Link, hulls: list[Hull], margin: float) -> bool:
    """:func:`within_shapes` without eigenvectors (they need numpy for a full tensor): True
    when u^T I u <= margin * m * reach(u)^2 for every unit axis u through the centre of
    mass, hence for the principal ones whatever numpy's vectors are. reach(u)^2 is at least
    the mean over the sampled points p of their squared distance from the axis, tr S - u^T S u
    with S the mean of r r^T (r = p - com), plus pad^2 for the least pad of the hulls (a
    sphere's radius: every point of a hull is that much farther out, and (a + b)^2 >= a^2 + b^2
    for a, b >= 0); so it holds when the largest eigenvalue of I' + k S is at most
    k (tr S + pad^2) (k = margin * m, I' the tensor turned into the link frame), with that
    eigenvalue's upper bound from principal.bounded and a relative slack of 1e-9 over
    everything rounding could move (numpy's vectors are unit and eigen to ~1e-15)."""
    i = link.inertial
    assert i is not None and i.inertia is not None and i.mass is not None
    com = i.origin.xyz
    rs = [(p[0] - com[0], p[1] - com[1], p[2] - com[2]) for h in hulls for p in corners(h, _SAMPLED)]
    if not rs:
        return False
    n = len(rs)
    s = [[sum(r[a] * r[b] for r in rs) / n for b in range(3)] for a in range(3)]
    pad = min(h.pad for h in hulls)
    turn = rpy_rot(i.origin.rpy)
    tensor = i.inertia.matrix()
    # I' = R I R^T: the tensor is written in the inertial frame, the points in the link frame
    ri = [[sum(turn[a][c] * tensor[c][b] for c in range(3)) for b in range(3)] for a in range(3)]
    turned = [[sum(ri[a][c] * turn[b][c] for c in range(3)) for b in range(3)] for a in range(3)]
    k = margin * i.mass * (1 - 1e-9)
    total = k * (s[0][0] + s[1][1] + s[2][2] + pad * pad)
    both = tuple(tuple(turned[a][b] + k * s[a][b] for b in range(3)) for a in range(3))
    found = principal.bounded_matrix(both)
    if found is None or not math.isfinite(total):
        return False
    size = math.sqrt(sum(v * v for row in tensor for v in row))
    return found.high(2) + 1e-9 * (size + total) <= total


def half_trace_by_span(link: Link, span: float) -> MomentBound | None:
    """Half the trace (the sum of m r^2 about the centre of mass) against the whole mass at
    the robot's span: no part reaches farther from its centre of mass than the robot does."""
    i = link.inertial
    if i is None or i.inertia is None or i.mass is None or i.mass <= 0 or span < MARKER:
        return None
    t = i.inertia
    return MomentBound((t.ixx + t.iyy + t.izz) / 2, i.mass * span * span, span)
