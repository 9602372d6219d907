"""What descgen measures in a mesh file: read by descgen/meshes/load.py, kept across runs by
descgen/meshes/cache.py."""

from __future__ import annotations

from descgen.core.model import Vec3
from descgen.core.record import record

MAX_TRIANGLES = 4_000_000  # ~10x the densest real robot mesh; beyond it memory, not detail, grows


@record
class MeshFacts:
    """What was measured in a mesh file, in the file's own units; ``problem`` says why it
    could not be measured (then the rest is empty)."""

    lower: Vec3 | None = None  # bounding box corners
    upper: Vec3 | None = None
    volume: float | None = None  # only for a watertight mesh: otherwise it means nothing
    watertight: bool = False
    triangles: int = 0
    unit_meter: float | None = None  # COLLADA <unit meter>; STL and OBJ declare none
    open_edges: int = 0  # edges of one triangle only: why it is not watertight
    problem: str | None = None
