"""Mesh files, measured: each read once (cached by content hash) with trimesh.

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
import os
import re
import struct
import threading
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .findings import InputError
from .model import Robot, Vec3
from .safeio import MIB, read_bounded

FORMATS = ("stl", "obj", "dae")
MAX_MESH_BYTES = 64 * MIB  # the largest example-robot-data mesh is 29 MB (go1 trunk.dae)
MAX_TRIANGLES = 4_000_000  # ~10x the densest real robot mesh; beyond it memory, not detail, grows
_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([^\"']+)[\"']", re.IGNORECASE)
_DTD = re.compile(rb"<!(DOCTYPE|ENTITY)", re.IGNORECASE)


@dataclass(frozen=True)
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


class MeshError(Exception):
    """A mesh that cannot be measured; ``str()`` says why, in one line."""


@dataclass(frozen=True)
class Loaded:
    """A mesh read from its file: vertices (file units) and triangles, plus its facts."""

    vertices: np.ndarray  # (n, 3) float64
    faces: np.ndarray  # (m, 3) int64
    facts: MeshFacts


_CACHE: dict[str, Loaded | MeshError] = {}  # sha256 of the bytes -> what they gave
_BY_STAT: dict[tuple[str, int, int, int], str] = {}  # (path, inode, size, mtime) -> sha256
_LOCK = threading.Lock()


def load(path: Path) -> Loaded:
    """The mesh at ``path``, measured. Raises :class:`MeshError` with the reason."""
    kind = path.suffix.lower().lstrip(".")
    if kind not in FORMATS:
        raise MeshError(f"'.{kind}' is not a mesh format descgen reads (STL, OBJ, DAE)")
    try:
        st = os.stat(path)
        seen = (str(path), st.st_ino, st.st_size, st.st_mtime_ns)  # the same file, unchanged: no re-read
    except (OSError, ValueError):
        seen = None
    with _LOCK:
        key = _BY_STAT.get(seen) if seen is not None else None
    if key is None:
        try:
            data = read_bounded(path, "mesh", MAX_MESH_BYTES)
        except InputError as exc:
            raise MeshError(exc.findings[0].message) from None
        key = hashlib.sha256(kind.encode() + b"\0" + data).hexdigest()
        with _LOCK:
            if seen is not None:
                _BY_STAT[seen] = key
            hit = _CACHE.get(key)
        if hit is None:
            hit = _parsed(data, kind)
            with _LOCK:
                _CACHE[key] = hit
    else:
        with _LOCK:
            hit = _CACHE[key]
    if isinstance(hit, MeshError):
        raise MeshError(str(hit))
    return hit


def _parsed(data: bytes, kind: str) -> Loaded | MeshError:
    try:
        return _parse(data, kind)
    except MeshError as exc:
        return exc


def measure(path: Path) -> MeshFacts:
    """The facts of the mesh at ``path``; a mesh that cannot be read gives facts with a ``problem``."""
    try:
        return load(path).facts
    except MeshError as exc:
        return MeshFacts(problem=str(exc))


def _parse(data: bytes, kind: str) -> Loaded:
    unit = None
    if kind == "stl":
        _check_stl(data)
    elif kind == "dae":
        unit = _check_dae(data)
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
        volume=volume,
        watertight=watertight,
        triangles=len(faces),
        unit_meter=unit,
        open_edges=_open_edges(faces),
    )
    return Loaded(vertices, faces, facts)


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
    if not np.isfinite(meter) or meter <= 0:
        raise MeshError(f'<unit meter="{meter}"> is not a positive length')
    return meter


def _open_edges(faces: np.ndarray) -> int:
    """Edges used by one triangle only: why a mesh is not watertight, counted for the message."""
    edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return int(np.count_nonzero(counts == 1))


# -- the meshes of a robot ----------------------------------------------------------------------


def facts_of_robot(robot: Robot) -> dict[str, MeshFacts]:
    """Mesh filename -> facts, for every mesh the loaders resolved to a file
    (``Robot.mesh_files``, descgen/mesh_paths.py); read once per content (cached)."""
    out: dict[str, MeshFacts] = {}
    for name, file in robot.mesh_files:
        out[name] = measure(Path(file))
    return out


def size_in_metres(facts: MeshFacts, scale: Sequence[float]) -> tuple[float, float, float] | None:
    """The scaled bounding box extents in metres, as RViz and Gazebo show the mesh: file units
    times the COLLADA unit (both apply it) times the URDF ``scale``."""
    if facts.lower is None or facts.upper is None:
        return None
    unit = facts.unit_meter or 1.0
    e = [abs((hi - lo) * unit * s) for lo, hi, s in zip(facts.lower, facts.upper, scale, strict=True)]
    return (e[0], e[1], e[2])


def corners_in_metres(facts: MeshFacts, scale: Sequence[float]) -> np.ndarray | None:
    """The 8 corners of the scaled bounding box in the mesh frame (metres), or None."""
    if facts.lower is None or facts.upper is None:
        return None
    unit = facts.unit_meter or 1.0
    lo = np.array(facts.lower) * unit * np.array(scale)
    hi = np.array(facts.upper) * unit * np.array(scale)
    return np.array([[(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
