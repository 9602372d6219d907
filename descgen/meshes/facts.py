"""What descgen measures in a mesh file: read by descgen/meshes/bounds.py (or trimesh, through
descgen/meshes/load.py), kept across runs by descgen/meshes/cache.py."""

from __future__ import annotations

from descgen.core.model import Vec3
from descgen.core.record import record

MAX_TRIANGLES = 4_000_000  # ~10x the densest real robot mesh; beyond it memory, not detail, grows


@record
class MeshFacts:
    """What the audit's rules read of a mesh file, in the file's own units: its bounding box
    (descgen/meshes/bounds.py, one pass over the file) and the unit it declares; ``problem``
    says why it could not be measured (then the rest is empty). What only a built mesh gives
    (volume, watertightness) is on ``load.Loaded``, for the spec's mesh inertia."""

    lower: Vec3 | None = None  # bounding box corners
    upper: Vec3 | None = None
    unit_meter: float | None = None  # COLLADA <unit meter>; STL and OBJ declare none
    problem: str | None = None
