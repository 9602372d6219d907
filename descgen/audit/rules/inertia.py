"""INER: masses and inertia tensors that a simulator can use."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding, Severity
from descgen.core.model import Collision, Inertia, Link, Robot
from descgen.physics import principal
from descgen.physics.bodies import moving_links, own_bodies, welded_count
from descgen.physics.extent import (
    MomentBound,
    bounding_hulls,
    half_trace_by_span,
    moment_by_shapes,
    robot_span,
    span_floor,
    within_shapes,
)
from descgen.physics.rigid import Vec, norm, rpy_rot


def _carries_geometry(robot: Robot, link: str) -> bool:
    lk = robot.link(link)
    return bool(lk and (lk.visuals or lk.collisions))


@rule("INER001", "non-positive-mass", "error")
def non_positive_mass(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a link whose mass is missing or negative, or zero on a link that moves on its own
    joint or that has an inertia tensor (a massless, tensorless frame is fine).
    ## Why is this bad?
    urdfdom accepts negative mass; physics engines reject it or explode.
    """
    moving = own_bodies(robot)
    for lk in robot.links:
        if lk.inertial is None:
            continue
        mass = lk.inertial.mass
        if mass is None:
            yield at(
                "INER001", lk.inertial, f"link '{lk.name}' inertial has no mass", "add <mass value>", subject=lk.subject
            )
        elif mass < 0 or (mass == 0 and (lk.name in moving or _has_tensor(lk))):
            why = "" if mass < 0 else " but it moves" if lk.name in moving else " but it has an inertia tensor"
            yield at(
                "INER001",
                lk.inertial,
                f"link '{lk.name}' mass is {mass:.6g} kg{why}",
                "write the measured mass (> 0)",
                severity="error" if mass < 0 else _severity(robot, lk, moving),
                subject=lk.subject,
            )


def _has_tensor(lk: Link) -> bool:
    t = lk.inertial.inertia if lk.inertial else None
    return t is not None and any(abs(v) > 0 for v in (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz))


def _weighed(lk: Link) -> bool:
    """A link that carries mass (a massless, tensorless inertial is a placeholder)."""
    i = lk.inertial
    return i is not None and i.inertia is not None and i.mass is not None and i.mass > MASSLESS


def _severity(robot: Robot, lk: Link, bodies: set[str]) -> Severity:
    """Inertia defects break simulation of a body that moves on its own joint; a link welded
    on by a fixed joint is merged into its parent, so there it is a warning."""
    return "error" if lk.name in bodies else "warning"


@rule("INER002", "moving-link-without-mass", "error")
def moving_link_without_mass(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a link with geometry that a moving joint carries when neither it nor any link
    welded to it by fixed joints has an inertial.
    ## Why is this bad?
    Simulators drop or mis-simulate massless bodies; gravity compensation and the
    static-torque check ignore it.
    """
    bodies = own_bodies(robot)
    with_inertial = welded_count(robot, lambda other: other.inertial is not None)
    for name in sorted(moving_links(robot)):
        lk = robot.link(name)
        weighed = with_inertial.get(name, 0) > 0
        if lk is not None and not weighed and _carries_geometry(robot, name):
            welded = "" if name in bodies else " (welded to a moving link)"
            yield at(
                "INER002",
                lk,
                f"moving link '{name}'{welded} has geometry but no inertial",
                "add mass and inertia",
                severity=_severity(robot, lk, bodies),
            )


@rule("INER003", "inertia-not-positive-definite", "error")
def inertia_not_positive_definite(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks that each inertia tensor has positive principal moments. A moment within 1e-10 of
    the tensor's largest entry counts as zero (and is printed as 0).
    ## Why is this bad?
    A tensor with a zero or negative eigenvalue is not a rigid body; urdfdom accepts it.
    """
    moving = own_bodies(robot)
    for lk in robot.links:
        if not _weighed(lk) or lk.inertial is None or lk.inertial.inertia is None:
            continue
        shown = _verdict(lk.inertial.inertia, _not_positive_definite, _settled_not_pd)
        if shown is not None:
            yield at(
                "INER003",
                lk.inertial,
                f"link '{lk.name}' inertia has principal moments {shown}: not positive definite",
                "recompute the tensor (or use from: collision)",
                severity=_severity(robot, lk, moving),
                subject=lk.subject,
            )


@rule("INER004", "inertia-triangle-inequality", "error")
def inertia_triangle_inequality(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks the principal moments of a positive definite tensor (INER003 reports the others)
    satisfy A + B >= C for every ordering.
    ## Why is this bad?
    No real mass distribution violates it; the numbers were mistyped or mixed units.
    """
    moving = own_bodies(robot)
    for lk in robot.links:
        if not _weighed(lk) or lk.inertial is None or lk.inertial.inertia is None:
            continue
        shown = _verdict(lk.inertial.inertia, _breaks_triangle, _settled_triangle)
        if shown is not None:
            yield at(
                "INER004",
                lk.inertial,
                f"link '{lk.name}' principal moments {shown} break the triangle inequality",
                "recompute the tensor; a value may be in the wrong unit",
                severity=_severity(robot, lk, moving),
                subject=lk.subject,
            )


# A principal moment within this fraction of the tensor's largest entry is zero at any
# precision a CAD export or a hand computation has (a body that thin is a line: a 1 m rod of
# 1 um radius): such a tensor is not positive definite (INER003), and the moment is printed as
# 0, not as the rounding noise LAPACK leaves there (-1.993e-22 on one BLAS build, +8.5e-23 on
# another). One threshold for both, so a printed 0 is always INER003's.
ZERO_MOMENT = 1e-10


def _zero_moment(t: Inertia) -> float:
    """The magnitude at or below which a principal moment of ``t`` is zero."""
    return ZERO_MOMENT * max(abs(t.ixx), abs(t.ixy), abs(t.ixz), abs(t.iyy), abs(t.iyz), abs(t.izz))


def _printer(zero: float) -> Callable[[float], str]:
    def one(v: float) -> str:
        return "0" if abs(v) <= zero else f"{float(v):.4g}"

    return one


def _not_positive_definite(eig: principal.Moments, zero: float) -> bool:
    return min(eig) <= zero


def _breaks_triangle(eig: principal.Moments, zero: float) -> bool:
    # only for a positive definite tensor: INER003 reports the others, and whether a moment
    # that is zero in truth came out as +1e-22 or -1e-22 must not decide a second finding
    return not _not_positive_definite(eig, zero) and eig[2] > 1e-12 and eig[0] + eig[1] < eig[2] * (1 - 1e-9)


# The two tests above, decided over intervals: True or False when every value numpy may give
# decides alike, None when not. Sound because each float comparison, sum, product and max
# is monotone in its arguments, so the ends of the intervals bound every case (eigenvalues
# ascending; ``zero`` is the tensor's own, exact).
def _settled_not_pd(b: principal.Bounded, zero: float) -> bool | None:
    if b.low(0) > zero:
        return False
    if b.high(0) <= zero:
        return True
    return None


def _settled_triangle(b: principal.Bounded, zero: float) -> bool | None:
    if b.high(2) <= 1e-12 or b.low(0) + b.low(1) >= b.high(2) * (1 - 1e-9):
        return False
    definite = _settled_not_pd(b, zero)
    if definite is not False:
        return None if definite is None else False
    if b.low(2) > 1e-12 and b.high(0) + b.high(1) < b.low(2) * (1 - 1e-9):
        return True
    return None


def _verdict(
    t: Inertia,
    test: Callable[[principal.Moments, float], bool],
    settled: Callable[[principal.Bounded, float], bool | None],
) -> str | None:
    """The printed principal moments when ``test`` holds for numpy's eigenvalues of ``t``,
    else None. Plain-float eigenvalues (principal.bounded) answer when their interval
    settles the test and prints alike; numpy only when it does not (a tensor on the edge)."""
    zero = _zero_moment(t)
    one = _printer(zero)
    b = principal.bounded(t)
    decided = settled(b, zero) if b is not None else None
    if decided is False:
        return None
    if decided and b is not None:
        shown = principal.text(b, one)
        if shown is not None:
            return "[" + ", ".join(shown) + "]"
    eig = principal.moments(t)
    return "[" + ", ".join(one(v) for v in eig) + "]" if test(eig, zero) else None


MASSLESS = 1e-6  # kg: a "mass" this small is a frame's placeholder, not a body
DENSEST = 22_600.0  # kg/m^3, osmium: no solid part is denser


@rule("INER006", "inertia-too-small-for-mass", "error")
def inertia_too_small_for_mass(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks the tensor against the most compact body the mass could be: a solid sphere of
    the densest metal. Half the trace of the tensor (the sum of m r^2) cannot be smaller
    than that sphere's 3/5 m r^2.
    ## Why is this bad?
    A tensor that small cannot belong to that mass: either the mass is in the wrong unit
    (grams written as kilograms) or the tensor is a placeholder. Simulators then spin
    the link far too easily.
    """
    moving = own_bodies(robot)
    for lk in robot.links:
        i = lk.inertial
        if i is None or i.inertia is None or i.mass is None or i.mass <= MASSLESS:
            continue
        t = i.inertia
        half_trace = (t.ixx + t.iyy + t.izz) / 2
        r_min = (3 * i.mass / (4 * math.pi * DENSEST)) ** (1 / 3)
        least = 0.6 * i.mass * r_min * r_min
        if half_trace < least * (1 - 1e-9):
            yield at(
                "INER006",
                i,
                f"link '{lk.name}' inertia (sum of m r^2 = {half_trace:.3g} kg*m^2) is too small for "
                f"{i.mass:.4g} kg: even a solid osmium sphere has {least:.3g}",
                "check the mass unit (g vs kg) and recompute the tensor",
                severity=_severity(robot, lk, moving),
                subject=lk.subject,
            )


def _box_of(collisions: tuple[Collision, ...]) -> tuple[Vec, Vec] | None:
    """Axis-aligned box around a link's collision primitives, in the link frame."""
    from descgen.core.model import Box, Cylinder, Sphere

    lows: list[Vec] = []
    highs: list[Vec] = []
    for c in collisions:
        g = c.geometry
        if isinstance(g, Box):
            half = (g.size[0] / 2, g.size[1] / 2, g.size[2] / 2)
        elif isinstance(g, Cylinder):
            half = (g.radius, g.radius, g.length / 2)
        elif isinstance(g, Sphere):
            half = (g.radius, g.radius, g.radius)
        else:
            return None  # a mesh: extent unknown without reading it
        r = rpy_rot(c.origin.rpy)
        extent = [abs(row[0]) * half[0] + abs(row[1]) * half[1] + abs(row[2]) * half[2] for row in r]
        centre = c.origin.xyz
        lows.append((centre[0] - extent[0], centre[1] - extent[1], centre[2] - extent[2]))
        highs.append((centre[0] + extent[0], centre[1] + extent[1], centre[2] + extent[2]))
    return (
        (min(v[0] for v in lows), min(v[1] for v in lows), min(v[2] for v in lows)),
        (max(v[0] for v in highs), max(v[1] for v in highs), max(v[2] for v in highs)),
    )


@rule("INER005", "com-outside-geometry", "warning")
def com_outside_geometry(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a centre of mass outside the box around the link's collision primitives by more
    than a quarter of that box's size.
    ## Why is this bad?
    The mass sits where there is no material: usually an origin in the wrong frame or unit.
    """
    colliding = welded_count(robot, lambda other: other.collisions)
    boxes: dict[tuple[tuple[object, object], ...], tuple[Vec, Vec] | None] = {}
    for lk in robot.links:
        i = lk.inertial
        if i is None or i.mass is None or i.mass <= 0:
            continue
        first = robot.link(lk.name)  # the body counts names, and a repeated name is its first link
        if colliding.get(lk.name, 0) - (1 if first is not None and first.collisions else 0) > 0:
            continue  # the body's material is partly on welded links: one box says too little
        if first is None or not first.collisions:
            continue
        key = tuple((c.geometry, c.origin) for c in first.collisions)  # a repeated part: boxed once
        if key in boxes:
            box = boxes[key]
        else:
            box = boxes[key] = _box_of(first.collisions)
        if box is None:
            continue
        low, high = box
        size = norm([high[k] - low[k] for k in range(3)])
        com = i.origin.xyz
        outside = norm([max(low[k] - com[k], 0.0) + max(com[k] - high[k], 0.0) for k in range(3)])
        if outside > 0.25 * size and outside > 1e-3:
            yield at(
                "INER005",
                i,
                f"link '{lk.name}' centre of mass is {outside * 1000:.1f} mm outside its collision geometry",
                "check the inertial origin (frame and unit)",
                subject=lk.subject,
            )


GEOMETRY_MARGIN = 2.0  # a moment over twice the shell bound: the material would reach 1.4x beyond every shape
SPAN_MARGIN = 3.0  # the whole-robot bound is loose already; only unit slips land beyond it


@rule("INER011", "inertia-too-large-for-size", "error")
def inertia_too_large_for_size(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks each principal moment against the largest value the link's mass could give:
    all of it at the farthest point of the link's own visual and collision primitives from
    that axis (m * r_max^2). A moment over twice that bound is reported. A link whose
    shapes include a mesh (extent unknown) or that has none is checked against the whole
    robot instead: half the trace (the sum of m r^2) over three times m * span^2, where the
    span is the diagonal of the box around every link frame and primitive at zero pose.
    ## Why is this bad?
    No body fits a larger tensor into that space: the tensor is in the wrong unit
    (kg*cm^2 or g*mm^2 written as kg*m^2), copied from a bigger part, or the mass is too
    small. Simulators then turn the link far too sluggishly and controllers tuned on it
    misbehave on the real robot; urdfdom and every parser accept it.
    ## Example
    A caster, a 0.3 kg sphere of 30 mm radius, with ixx = iyy = izz = 0.2 kg*m^2: the
    bound about any axis is 0.3 * 0.03^2 = 2.7e-4.
    ## Use instead
    The tensor of the part (CAD, or computed from the collision shape: `from: collision`
    in a spec), in kg*m^2.
    """
    moving = own_bodies(robot)
    span: list[float] = []  # the robot's span, computed once and only when a link needs it
    floor: list[float] = []  # a lower bound on it that poses no shape (extent.span_floor): most links stop there
    # a repeated part (wheels, fingers, a synthetic chain) has equal keys: decided once
    decided: dict[tuple[object, ...], MomentBound | bool | None] = {}
    for lk in robot.links:
        i = lk.inertial
        if i is None or i.inertia is None or i.mass is None or i.mass <= MASSLESS:
            continue
        key = (i.mass, i.origin, i.inertia, *((s.geometry, s.origin) for s in lk.shapes()))
        if key in decided:
            found = decided[key]
        else:
            found = decided[key] = _by_shapes(lk)
        if found is True:
            continue
        if isinstance(found, MomentBound):
            if found.ratio <= GEOMETRY_MARGIN:
                continue
            why = (
                f"principal moment {found.moment:.3g} kg*m^2 is {found.ratio:.3g} times the most its mass can "
                f"give inside its shapes ({found.bound:.3g}: all {i.mass:.4g} kg at {found.reach * 1000:.4g} mm "
                "from the axis)"
            )
        else:
            if not floor:
                floor.append(span_floor(robot))
            rough = half_trace_by_span(lk, floor[0]) if math.isfinite(floor[0]) else None
            if rough is not None and rough.ratio <= SPAN_MARGIN:
                continue  # within the margin at a span no larger than the robot's: so within at its span
            if not span:
                span.append(robot_span(robot))
            found = half_trace_by_span(lk, span[0])
            if found is None or found.ratio <= SPAN_MARGIN:
                continue
            why = (
                f"the sum of m r^2 ({found.moment:.3g} kg*m^2) is {found.ratio:.3g} times what {i.mass:.4g} kg "
                f"gives at the span of the whole robot ({found.bound:.3g}: {found.reach:.3g} m; its own shapes "
                "have no known size)"
            )
        yield at(
            "INER011",
            i,
            f"link '{lk.name}' inertia is too large for its mass and size: {why}",
            "check the tensor's unit (kg*m^2, not kg*cm^2 or g*mm^2) and the mass; recompute the tensor from the part",
            severity=_severity(robot, lk, moving),
            subject=lk.subject,
        )


def _by_shapes(lk: Link) -> MomentBound | bool | None:
    """INER011's answer from the link's own shapes: True when within GEOMETRY_MARGIN, else the
    moment that comes closest to (or beyond) its bound, None when the shapes bound nothing
    (then the robot's span decides). It depends only on the inertial's mass, origin and
    tensor and on each shape's geometry and origin, the key the rule keeps it under (equal
    keys differ at most in the sign of a zero, which changes no verdict and no printed value:
    distances and bounds are square roots of sums of squares)."""
    hulls = bounding_hulls(lk)
    if hulls is None:
        return None
    if within_shapes(lk, hulls, GEOMETRY_MARGIN):
        return True  # a few rim corners settle it: the common case, without all 128 per cylinder
    return moment_by_shapes(lk)
