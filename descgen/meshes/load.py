"""Mesh files, measured: each read once (cached by content hash, in memory and on disk:
descgen/meshes/cache.py) with numpy (binary STL) or trimesh.

What a rule or the inertia derivation needs from a mesh: its bounding box, volume,
watertightness and triangle count in the file's own units, and the unit the file declares
where the format has one (COLLADA ``<unit meter=...>``; STL and OBJ carry none).

A mesh named by a description is someone else's data (docs/security.md): its type and size
are checked before it is read, a COLLADA file with a DTD is refused before any XML parser
sees it (no entities, no external files), a binary STL's triangle count is read from its
header before it is parsed, and every failure becomes a :class:`MeshError`, never a
traceback. Formats: STL (binary and ASCII), OBJ, and DAE (COLLADA, through pycollada).
"""

from __future__ import annotations

import hashlib
import io
import math
import os
import re
import stat
import struct
import threading
import time
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from descgen.core.findings import InputError
from descgen.core.model import Collision, Link, Mesh, Robot, Visual
from descgen.core.record import record
from descgen.infra.safeio import MIB, read_bounded
from descgen.infra.stat_index import stat_of
from descgen.meshes.facts import MAX_TRIANGLES, MeshFacts

if TYPE_CHECKING:  # numpy only where a mesh is parsed: a warm audit answers from the cache without it
    import numpy as np

FORMATS = ("stl", "obj", "dae")
MAX_MESH_BYTES = 64 * MIB  # the largest example-robot-data mesh is 29 MB (go1 trunk.dae)
_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([^\"']+)[\"']", re.IGNORECASE)
_DTD = re.compile(rb"<!(DOCTYPE|ENTITY)", re.IGNORECASE)


class MeshError(Exception):
    """A mesh that cannot be measured; ``str()`` says why, in one line."""


@record
class Loaded:
    """A mesh built from its file by trimesh: vertices (file units) and triangles, its facts,
    and what only the built mesh tells (for the spec's inertia from a mesh)."""

    vertices: np.ndarray  # (n, 3) float64
    faces: np.ndarray  # (m, 3) int64
    facts: MeshFacts
    watertight: bool  # every edge in two triangles, wound consistently: it bounds a solid
    volume: float | None  # only for a watertight mesh: otherwise it means nothing
    open_edges: int  # edges of one triangle only: why it is not watertight


_CACHE: dict[str, Loaded | MeshError] = {}  # sha256 of the bytes -> what they gave
_BY_STAT: dict[tuple[str, int, int, int, int], str] = {}  # (path, inode, size, mtime, ctime) -> sha256
_LOCK = threading.Lock()


def load(path: Path) -> Loaded:
    """The mesh at ``path``, measured. Raises :class:`MeshError` with the reason."""
    kind = path.suffix.lower().lstrip(".")
    if kind not in FORMATS:
        raise MeshError(f"'.{kind}' is not a mesh format descgen reads (STL, OBJ, DAE)")
    seen = _stat_key(path)
    with _LOCK:
        key = _BY_STAT.get(seen) if seen is not None else None
        hit = _CACHE.get(key) if key is not None else None
    if hit is None:
        try:
            data = read_bounded(path, "mesh", MAX_MESH_BYTES)
        except InputError as exc:
            raise MeshError(exc.findings[0].message) from None
        key = _content_key(data, kind)
        with _LOCK:
            hit = _CACHE.get(key)
        if hit is None:
            hit = _parsed(data, kind)
        with _LOCK:
            if seen is not None:
                _BY_STAT[seen] = key
            _CACHE[key] = hit
    if isinstance(hit, MeshError):
        raise MeshError(str(hit))
    return hit


def _parsed(data: bytes, kind: str) -> Loaded | MeshError:
    try:
        return _parse(data, kind)
    except MeshError as exc:
        return exc


_FACTS: dict[str, MeshFacts] = {}  # content key -> facts, for measure() (no arrays kept)


def measure(path: Path | str) -> MeshFacts:
    """The facts of the mesh at ``path``; a mesh that cannot be read gives facts with a ``problem``.

    Looked up by content: in this process, then in the persistent cache (descgen/meshes/cache.py),
    and only then measured: the bounding box in one pass over the file (descgen/meshes/bounds.py),
    trimesh only for what that reader leaves to it. Hashing the bytes is ~10x cheaper than that."""
    from descgen.meshes import cache as mesh_cache  # the persistent cache only when a mesh is measured

    kind = os.path.splitext(path)[1].lower().lstrip(".")  # Path.suffix, without making a Path
    if kind not in FORMATS:
        return MeshFacts(problem=f"'.{kind}' is not a mesh format descgen reads (STL, OBJ, DAE)")
    st = _stat(path)
    seen = _seen(path, st)
    with _LOCK:
        key = _BY_STAT.get(seen) if seen is not None else None
        known = _FACTS.get(key) if key is not None else None
    if known is not None:
        return known
    if key is None and st is not None and stat.S_ISREG(st.st_mode) and st.st_size <= MAX_MESH_BYTES:
        # unchanged since a run hashed it (the stat index): its facts without reading its bytes
        row = mesh_cache.known(str(path), stat_of(st), kind)
        indexed, facts = row if row is not None else (None, None)
        if indexed is not None and facts is None:
            facts = _FACTS.get(indexed) or mesh_cache.get(indexed, kind)
        if indexed is not None and facts is not None:
            with _LOCK:
                if seen is not None:
                    _BY_STAT[seen] = indexed
                _FACTS[indexed] = facts
            return facts
    hashed_at = time.time_ns()
    try:
        data = read_bounded(Path(path), "mesh", MAX_MESH_BYTES)
    except InputError as exc:
        return MeshFacts(problem=exc.findings[0].message)
    # the content hash names the entry of the persistent cache; with that cache off, this
    # process knows the file by its stat data alone (hashing the corpus's meshes is ~0.3 s)
    caching = mesh_cache.folder() is not None or seen is None
    key = _content_key(data, kind) if caching else f"unhashed:{seen}"
    facts = _FACTS.get(key) or mesh_cache.get(key, kind)
    if facts is None:
        facts = _measured(data, kind)
        mesh_cache.put(key, kind, facts)
    if st is not None:
        mesh_cache.remember(str(path), stat_of(st), key, hashed_at, kind, facts)
    with _LOCK:
        if seen is not None:
            _BY_STAT[seen] = key
        _FACTS[key] = facts
    return facts


def _measured(data: bytes, kind: str) -> MeshFacts:
    from descgen.meshes.bounds import bounds

    try:
        unit = _checked(data, kind)
        fast = bounds(data, kind, unit)
        return fast if fast is not None else _parse(data, kind).facts
    except MeshError as exc:
        return MeshFacts(problem=str(exc))


def _stat(path: Path | str) -> os.stat_result | None:
    try:
        return os.stat(path)
    except (OSError, ValueError):
        return None


def _seen(path: Path | str, st: os.stat_result | None) -> tuple[str, int, int, int, int] | None:
    """The same file, unchanged since it was hashed in this process: no re-read."""
    return None if st is None else (str(path), st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns)


def _stat_key(path: Path) -> tuple[str, int, int, int, int] | None:
    return _seen(path, _stat(path))


def _content_key(data: bytes, kind: str) -> str:
    digest = hashlib.sha256(kind.encode() + b"\0")
    digest.update(data)  # not kind + data: that copies every byte once more
    return digest.hexdigest()


def _checked(data: bytes, kind: str) -> float | None:
    """Refuse what no parser should see (an absurd STL triangle count, a COLLADA DTD); the
    unit a COLLADA file declares."""
    if kind == "stl":
        _check_stl(data)
    return _check_dae(data) if kind == "dae" else None


def _parse(data: bytes, kind: str) -> Loaded:
    import numpy as np

    unit = _checked(data, kind)
    mesh = _trimesh(data, kind)
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(faces) > MAX_TRIANGLES:
        raise MeshError(f"{len(faces)} triangles; descgen reads meshes of at most {MAX_TRIANGLES}")
    if len(faces) == 0 or not np.all(np.isfinite(vertices)):
        raise MeshError("the reader found no triangles with finite vertices in it")
    watertight = bool(mesh.is_watertight and mesh.is_winding_consistent)
    volume = abs(float(mesh.volume)) if watertight else None
    lo, hi = vertices[faces].reshape(-1, 3).min(axis=0), vertices[faces].reshape(-1, 3).max(axis=0)
    facts = MeshFacts(
        lower=(float(lo[0]), float(lo[1]), float(lo[2])),
        upper=(float(hi[0]), float(hi[1]), float(hi[2])),
        unit_meter=unit,
    )
    return Loaded(vertices, faces, facts, watertight, volume, _open_edges(faces))


def _trimesh(data: bytes, kind: str) -> Any:  # trimesh.Trimesh (untyped)
    import trimesh

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # trimesh and pycollada warn about what we report ourselves
            # file_obj without a resolver: an OBJ's .mtl or a DAE's textures are never opened
            mesh = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh", process=True)
    except ImportError as exc:
        raise MeshError(f"reading .{kind} needs {exc.name or 'an extra package'} (pip install pycollada)") from None
    except Exception as exc:  # any parser failure on foreign bytes is a finding, not a crash
        raise MeshError(f"cannot read the mesh: {type(exc).__name__}: {str(exc)[:120]}") from None
    if not isinstance(mesh, trimesh.Trimesh):
        raise MeshError("the file holds no triangle mesh")
    return mesh


def _check_stl(data: bytes) -> None:
    """A binary STL says how many triangles it has: refuse an absurd count before parsing."""
    if len(data) >= 84 and data[:5].lower() != b"solid":
        (count,) = struct.unpack_from("<I", data, 80)
        if count > MAX_TRIANGLES:
            raise MeshError(f"the STL header declares {count} triangles; at most {MAX_TRIANGLES} are read")


def _check_dae(data: bytes) -> float | None:
    """COLLADA is XML read by pycollada's own parser: refuse a DTD (entities could read local
    files or expand without bound) before it sees the bytes. Returns ``<unit meter>``."""
    if _DTD.search(data):
        raise MeshError("the COLLADA file has a DTD (<!DOCTYPE or <!ENTITY); descgen refuses DTDs")
    found = _UNIT.search(data[: 64 * 1024])  # <asset> comes first in a COLLADA file
    if found is None:
        return None
    try:
        meter = float(found.group(1))
    except ValueError:
        raise MeshError(f'<unit meter="{found.group(1).decode("ascii", "replace")}"> is not a number') from None
    if not math.isfinite(meter) or meter <= 0:
        raise MeshError(f'<unit meter="{meter}"> is not a positive length')
    return meter


def _open_edges(faces: np.ndarray) -> int:
    """Edges used by one triangle only: why a mesh is not watertight, counted for the message."""
    import numpy as np

    if len(faces) == 0:
        return 0
    edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    # one int64 key per edge, sorted: np.unique(axis=0) on rows is several times slower
    # (at most 12 M vertices, so the key stays below 2**63)
    lo = int(edges.min())
    span = int(edges.max()) - lo + 1
    keys = np.sort((edges[:, 0] - lo) * span + (edges[:, 1] - lo))
    differs = np.diff(keys) != 0
    single = np.concatenate(([True], differs)) & np.concatenate((differs, [True]))  # unlike both neighbours
    return int(np.count_nonzero(single))


# -- the meshes of a robot ----------------------------------------------------------------------


_ROBOT_FACTS: list[tuple[Robot, dict[str, MeshFacts]]] = []  # the last few robots' facts


def facts_of_robot(robot: Robot) -> dict[str, MeshFacts]:
    """Mesh filename -> facts, for every mesh the loaders resolved to a file
    (``Robot.mesh_files``, descgen/meshes/paths.py); read once per content (cached), and
    gathered once per robot object for the four rules that ask (do not change the dict)."""
    with _LOCK:
        for seen, facts in _ROBOT_FACTS:
            if seen is robot:
                return facts
    from descgen.meshes import cache as mesh_cache  # the persistent cache only when a mesh is measured

    out: dict[str, MeshFacts] = {}
    for name, file in robot.mesh_files:
        out[name] = measure(file)
    mesh_cache.save_index()  # what was hashed here is known to the next run, even if this one is killed
    with _LOCK:
        _ROBOT_FACTS.insert(0, (robot, out))
        del _ROBOT_FACTS[4:]
    return out


MeshShape = tuple[Link, Visual | Collision, Mesh, MeshFacts]
_ROBOT_SHAPES: list[tuple[Robot, list[MeshShape]]] = []  # the last few robots' measured mesh shapes


def mesh_shapes(robot: Robot) -> list[MeshShape]:
    """(link, visual or collision, its mesh, the mesh's facts) for every shape whose mesh
    was measured, in link and shape order; gathered once per robot object for the rules
    that all walk them (do not change the list)."""
    with _LOCK:
        for seen, shapes in _ROBOT_SHAPES:
            if seen is robot:
                return shapes
    facts = facts_of_robot(robot)
    out: list[MeshShape] = []
    if facts:
        for lk in robot.links:
            for shape in lk.shapes():
                g = shape.geometry
                if isinstance(g, Mesh):
                    found = facts.get(g.filename)
                    if found is not None:
                        out.append((lk, shape, g, found))
    with _LOCK:
        _ROBOT_SHAPES.insert(0, (robot, out))
        del _ROBOT_SHAPES[4:]
    return out


def size_in_metres(facts: MeshFacts, scale: Sequence[float]) -> tuple[float, float, float] | None:
    """The scaled bounding box extents in metres, as RViz and Gazebo show the mesh: file units
    times the COLLADA unit (both apply it) times the URDF ``scale``."""
    if facts.lower is None or facts.upper is None:
        return None
    unit = facts.unit_meter or 1.0
    e = [abs((hi - lo) * unit * s) for lo, hi, s in zip(facts.lower, facts.upper, scale, strict=True)]
    return (e[0], e[1], e[2])


def box_in_metres(
    facts: MeshFacts, scale: Sequence[float]
) -> tuple[tuple[float, float, float], tuple[float, float, float]] | None:
    """Two opposite corners of the scaled bounding box in the mesh frame (metres), or None;
    a negative scale mirrors the box, so a "low" coordinate may exceed its "high" one."""
    if facts.lower is None or facts.upper is None:
        return None
    unit = facts.unit_meter or 1.0
    lo = [v * unit * s for v, s in zip(facts.lower, scale, strict=True)]
    hi = [v * unit * s for v, s in zip(facts.upper, scale, strict=True)]
    return (lo[0], lo[1], lo[2]), (hi[0], hi[1], hi[2])
