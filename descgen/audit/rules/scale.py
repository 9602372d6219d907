"""UNIT (scale): offsets and sizes that cannot belong to a robot of this size."""

from __future__ import annotations

import math
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import Mesh, Robot
from descgen.physics.bodies import dims, robot_scale

FACTOR = 50.0  # ×1000 mistakes land far beyond this; real designs stay far below it
FLOOR = 1.0  # metres: never flag anything shorter
_PRIMITIVES = ("cube", "box", "cylinder", "sphere")  # unit shapes scaled to size: the scale is the size


@rule("UNIT011", "implausible-offset", "error")
def implausible_offset(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a joint origin more than 50 times the robot's typical link length (the median
    joint offset) and over 1 m.
    ## Why is this bad?
    That is the millimetre-as-metre mistake: a camera 25 m from the wrist instead of 25 mm.
    Every parser accepts it.
    """
    scale = robot_scale(robot)
    for j in robot.joints:
        d = math.hypot(*j.origin.xyz)
        if d > FLOOR and d > FACTOR * scale:
            yield at(
                "UNIT011",
                j,
                f"joint '{j.name}' origin is {d:.4g} m from its parent; typical offsets here are {scale:.3g} m",
                "was it written in millimetres? divide by 1000",
            )


@rule("UNIT012", "implausible-size", "error")
def implausible_size(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a box, cylinder or sphere dimension more than 50 times the robot's typical link
    length and over 1 m.
    ## Why is this bad?
    A geometry a thousand times too large breaks collision checking and planning (every
    pose collides) and the inertia computed from it.
    """
    scale = robot_scale(robot)
    for lk in robot.links:
        for shape in lk.shapes():
            big = max(dims(shape.geometry), default=0.0)
            if big > FLOOR and big > FACTOR * scale:
                yield at(
                    "UNIT012",
                    shape,
                    f"link '{lk.name}' geometry is {big:.4g} m across; typical links here are {scale:.3g} m",
                    "was it written in millimetres? divide by 1000",
                    subject=lk.subject,
                )


@rule("UNIT013", "suspicious-mesh-scale", "warning")
def suspicious_mesh_scale(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a mesh scale component other than 1 or 0.001 (either sign), except on meshes
    named as unit primitives (cube, box, cylinder, sphere), whose scale is their size.
    ## Why is this bad?
    Meshes are exported in metres (1) or millimetres (0.001); any other factor usually
    means a unit guess (0.01, 0.0254) that deserves a second look.
    """
    for lk in robot.links:
        for shape in lk.shapes():
            g = shape.geometry
            # the scale first: it is 1 or 0.001 on almost every mesh, and the name test is dearer
            if (
                isinstance(g, Mesh)
                and any(not math.isclose(abs(s), 1.0) and not math.isclose(abs(s), 0.001) for s in g.scale)
                and not any(word in g.filename.lower().rsplit("/", 1)[-1] for word in _PRIMITIVES)
            ):
                yield at(
                    "UNIT013",
                    shape,
                    f"link '{lk.name}' mesh {g.filename} has scale {list(g.scale)}",
                    "export the mesh in metres, or use 0.001 for millimetres",
                    subject=lk.subject,
                )
