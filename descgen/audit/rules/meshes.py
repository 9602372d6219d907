"""GEOM (mesh contents): what the mesh files say, once they resolve and are read.

The facts come from ``descgen.meshes.load``, for the files in ``Robot.mesh_files``: a mesh that did not resolve
has none, and these rules stay silent about it (GEOM003-GEOM005 report the path).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import Collision, Link, Mesh, Robot, Visual
from descgen.meshes.facts import MeshFacts
from descgen.meshes.load import (
    MeshShape,
    box_in_metres,
    facts_of_robot,
    mesh_shapes,
    size_in_metres,
)
from descgen.physics.bodies import PLACEHOLDER_MASS, dims, robot_scale
from descgen.physics.rigid import Vec, frame, norm, placed_box

Box3 = tuple[Vec, Vec]  # (low, high) corners of an axis-aligned box

TOO_LARGE = 30.0  # a mesh this many times the link's other evidence is in the wrong unit
FLOOR = 1.0  # metres: a mesh smaller than this is never called too large
WATER = 1000.0  # kg/m^3: the side of a cube of water of the link's mass is one more length
# Unit slips between CAD and URDF (file unit in metres -> how many times too large);
# a ratio within 15 % of one of these is named.
_FACTORS = ((1000.0, "millimetres"), (100.0, "centimetres"), (1 / 0.0254, "inches"), (0.001, "metres scaled as mm"))


def _shapes_with_facts(robot: Robot) -> list[MeshShape]:
    return mesh_shapes(robot)  # gathered once per robot for the rules below


def _kind(shape: Visual | Collision) -> str:
    return "visual" if isinstance(shape, Visual) else "collision"


def _mm(v: tuple[float, float, float]) -> str:
    return " x ".join(f"{c * 1000:.6g}" for c in v) + " mm"


def _scale_fix(factor: float, mesh: Mesh) -> str:
    s = [c / factor for c in mesh.scale]
    return 'scale="' + " ".join(f"{c:g}" for c in s) + '"'


@rule("GEOM030", "mesh-size-mismatch", "error")
def mesh_size_mismatch(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares the bounding box of a scaled mesh (file units, times a COLLADA file's
    `<unit meter>`, times `scale`) with the size the spec states for it (`mesh: {size: [...],
    tolerance: ...}`, default tolerance 1 mm), axis by axis.
    ## Why is this bad?
    The mesh is what RViz, planners and simulators see. A CAD export in millimetres is a
    thousand times the measured part; one in inches is 25.4 times; a wrong part file has
    the wrong size. Every parser accepts all of them.
    """
    for lk, shape, mesh, facts in _shapes_with_facts(robot):
        if mesh.size is None:
            continue  # the common case: no stated size (so no need to scale the box)
        size = size_in_metres(facts, mesh.scale)
        if size is None:
            continue
        tol = mesh.size_tolerance if mesh.size_tolerance is not None else 0.001
        if all(abs(a - b) <= tol for a, b in zip(size, mesh.size, strict=True)):
            continue
        ratio = max(size) / max(mesh.size) if max(mesh.size) > 0 else math.inf
        named = _named_factor(ratio)
        why = f"; {ratio:.4g} times the stated size (a file in {named[1]}?)" if named else ""
        fix = _scale_fix(named[0], mesh) if named else "the measured size, or check the file"
        yield at(
            "GEOM030",
            shape,
            f"link '{lk.name}' {_kind(shape)} mesh '{mesh.filename}' measures {_mm(size)} at scale "
            f"{' '.join(f'{c:g}' for c in mesh.scale)}, not the stated {_mm(mesh.size)} "
            f"(tolerance {tol * 1000:g} mm){why}",
            f"set {fix}" if named else f"fix {fix}",
            subject=lk.subject,
        )


def _named_factor(ratio: float) -> tuple[float, str] | None:
    for factor, unit in _FACTORS:
        if math.isfinite(ratio) and abs(ratio / factor - 1) <= 0.15:
            return factor, unit
    return None


def _evidence(robot: Robot, lk: Link) -> list[tuple[float, str]]:
    """Lengths (m) that say how big link ``lk`` is, other than its meshes: its primitives,
    the joint offsets that touch it, and the side of a cube of water of its mass."""
    out: list[tuple[float, str]] = []
    prim = max((d for shape in lk.shapes() for d in dims(shape.geometry)), default=0.0)
    if prim > 0:
        out.append((prim, f"its primitives up to {prim:.3g} m"))
    joints = [j for j in robot.joints if lk.name in (j.parent, j.child)]
    offset = max((math.hypot(*j.origin.xyz) for j in joints), default=0.0)
    if offset > 1e-4:
        out.append((offset, f"joint offsets up to {offset:.3g} m"))
    mass = lk.inertial.mass if lk.inertial else None
    if mass is not None and math.isfinite(mass) and mass > PLACEHOLDER_MASS:
        side = (mass / WATER) ** (1 / 3)
        out.append((side, f"{mass:.3g} kg (a {side:.3g} m cube of water)"))
    if not out:
        scale = robot_scale(robot)
        out.append((scale, f"typical joint offsets of {scale:.3g} m"))
    return out


@rule("GEOM031", "mesh-in-wrong-unit", "error")
def mesh_in_wrong_unit(robot: Robot) -> Iterator[Finding]:
    """## What it does
    For a mesh without a stated size: flags a scaled mesh over 1 m across that is more than
    30 times every other length the link has (its box/cylinder/sphere shapes, the joint
    offsets to its parent and children, the side of a cube of water of its mass), and
    names the likely factor (1000: a file in millimetres; 100: centimetres).
    ## Why is this bad?
    CAD exports in millimetres with `scale="1"` give a robot a thousand times too large in
    RViz and a collision model that hits everything; nothing else in the URDF is wrong, so
    no parser notices.
    """
    for lk, shape, mesh, facts in _shapes_with_facts(robot):
        if mesh.size is not None:
            continue
        size = size_in_metres(facts, mesh.scale)
        if size is None or max(size) <= FLOOR:
            continue
        evidence = _evidence(robot, lk)
        longest = max(length for length, _ in evidence)
        ratio = max(size) / longest
        if ratio < TOO_LARGE:
            continue
        # real parts are 0.2-5 times their link's longest other length: the factor is the
        # unit slip nearest (in log) to the ratio, 316 being between 100 and 1000
        factor = 1000.0 if ratio >= math.sqrt(1000.0 * 100.0) else 100.0
        unit = "millimetres" if factor == 1000.0 else "centimetres"
        yield at(
            "GEOM031",
            shape,
            f"link '{lk.name}' {_kind(shape)} mesh '{mesh.filename}' is {max(size):.4g} m across "
            f"({ratio:.0f} times {'; '.join(text for _, text in evidence)}): "
            f"about {factor:g}x too large, as a file in {unit} with scale "
            f"{' '.join(f'{c:g}' for c in mesh.scale)} would be",
            f"set {_scale_fix(factor, mesh)} on the mesh (or re-export it in metres)",
            subject=lk.subject,
        )


def _box_in_link(shape: Visual | Collision, facts: MeshFacts | None) -> Box3 | None:
    """Axis-aligned box (link frame) around a shape: a mesh's scaled bounding box or a primitive."""
    g = shape.geometry
    if isinstance(g, Mesh):
        bounds = box_in_metres(facts, g.scale) if facts is not None else None
    elif g is not None and dims(g):
        h = _half_extents(shape)
        bounds = (-h[0], -h[1], -h[2]), h
    else:
        bounds = None
    if bounds is None:
        return None
    return placed_box(bounds[0], bounds[1], frame(shape.origin.xyz, shape.origin.rpy))


def _half_extents(shape: Visual | Collision) -> tuple[float, float, float]:
    d = dims(shape.geometry)
    if len(d) == 3:
        return (d[0] / 2, d[1] / 2, d[2] / 2)
    if len(d) == 2:  # cylinder: diameter, length along z
        return (d[0] / 2, d[0] / 2, d[1] / 2)
    return (d[0] / 2, d[0] / 2, d[0] / 2)


@rule("GEOM032", "visual-far-from-collision", "warning")
def visual_far_from_collision(robot: Robot) -> Iterator[Finding]:
    """## What it does
    On a link whose visual or collision geometry is a mesh, compares the box around its
    visuals with the box around its collisions (link frame, meshes measured from their files)
    and flags them when the gap between the two boxes is larger than both boxes.
    ## Why is this bad?
    The collision model is not where the robot is drawn: a planner avoids empty space and
    drives through the part you see. Usually an origin in the wrong unit or frame, or a
    mesh exported about a different origin.
    """
    facts = facts_of_robot(robot)
    if not facts:
        return
    for lk in robot.links:
        if not any(isinstance(s.geometry, Mesh) for s in lk.shapes()):
            continue
        vis = _union([_box_in_link(s, _facts_of(s, facts)) for s in lk.visuals])
        col = _union([_box_in_link(s, _facts_of(s, facts)) for s in lk.collisions])
        if vis is None or col is None:
            continue
        gap = norm([max(0.0, vis[0][k] - col[1][k], col[0][k] - vis[1][k]) for k in range(3)])
        larger = max(norm(_sub(vis[1], vis[0])), norm(_sub(col[1], col[0])))
        if gap > larger and gap > 0.01:
            yield at(
                "GEOM032",
                lk.visuals[0],
                f"link '{lk.name}' visual is {gap:.3g} m away from its collision geometry "
                f"(visual centre {_mm(_centre(vis))}, collision centre {_mm(_centre(col))} in the link frame)",
                "give the visual and the collision the same origin and unit",
                subject=lk.subject,
            )


def _facts_of(shape: Visual | Collision, facts: dict[str, MeshFacts]) -> MeshFacts | None:
    g = shape.geometry
    return facts.get(g.filename) if isinstance(g, Mesh) else None


def _union(boxes: list[Box3 | None]) -> Box3 | None:
    if not boxes or any(b is None for b in boxes):
        return None  # a shape we cannot place: no judgement
    if len(boxes) == 1:
        return boxes[0]  # what min and max of one value give: the value itself
    lows = [b[0] for b in boxes if b is not None]
    highs = [b[1] for b in boxes if b is not None]
    (lx, ly, lz), (hx, hy, hz) = zip(*lows, strict=True), zip(*highs, strict=True)
    return (min(lx), min(ly), min(lz)), (max(hx), max(hy), max(hz))


def _sub(a: Vec, b: Vec) -> Vec:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _centre(box: Box3) -> Vec:
    return ((box[0][0] + box[1][0]) / 2, (box[0][1] + box[1][1]) / 2, (box[0][2] + box[1][2]) / 2)


@rule("GEOM033", "mesh-not-measured", "info")
def mesh_not_measured(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Reports a mesh file that exists but that descgen could not measure: not STL, OBJ or
    DAE, larger than 64 MiB or 4 million triangles, a COLLADA file with a DTD, or bytes
    from which trimesh (pycollada for DAE) got no triangles.
    ## Why is this bad?
    Its size, unit and placement go unchecked (GEOM030-GEOM032 skip it). Other readers may
    fail on it too (a parser error) or may not (pycollada drops geometry whose material
    references are broken, RViz's assimp does not), so it is information, not a defect.
    """
    seen: set[tuple[str, str]] = set()
    for lk, shape, mesh, facts in _shapes_with_facts(robot):
        if facts.problem is None or (lk.name, mesh.filename) in seen:
            continue
        seen.add((lk.name, mesh.filename))
        yield at(
            "GEOM033",
            shape,
            f"link '{lk.name}' mesh '{mesh.filename}' cannot be read: {facts.problem}",
            "check the file opens in a mesh viewer; re-export it as binary STL to have it checked",
            subject=lk.subject,
        )
