"""Audit findings kept between runs, as ruff keeps lint results: a description audited again
unchanged gives last run's findings without being read or checked again.

The findings of a plain URDF (with the SRDF and controllers YAML named beside it) are a pure
function of

- the bytes of those files, the names they are shown by (every finding carries one) and the
  launch arguments the controllers YAML is read with;
- where each mesh reference resolves (descgen/meshes/paths.py: the description's real folder,
  the package paths, the package.xml files on the way) and the content of each mesh found;
- descgen itself (the whole of its source, as every local cache: descgen/infra/keys.py ``LOCAL``)
  and the libraries that read the files and measure the meshes.

The key (descgen/infra/result_cache.py) holds the first and the last. The entry records the second:
every mesh name with its state, the file it resolved to and that file's stat data. A hit
resolves the recorded names again and stats the files; any difference is a miss, and the
description is audited as without the cache. Stat data stands for a mesh's content through the
one stat shortcut the mesh cache's index uses too (descgen/infra/stat_index.py: the same fields,
the same racy window), with the same trust (docs/security.md): whoever can write the cache folder
can make audit print what they like.

A Xacro (includes, arguments, ``$(find)``), a spec and a MoveIt config folder read an
open-ended set of files, so their audits are not kept. An entry is data: read with a bound,
checked for shape, decoded into findings field by field; anything else is a miss.
"""

from __future__ import annotations

import re
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, cast

from descgen.core.cache_dir import cache_root
from descgen.core.findings import SEVERITIES, Finding, InputError, Severity, Where
from descgen.core.model import Robot
from descgen.core.record import record
from descgen.infra import result_cache, stat_index
from descgen.infra.evidence_hash import sha256
from descgen.infra.safeio import read_bounded
from descgen.meshes.paths import resolve_names

KIND = "audit"
KEEP = 1024  # entries: a workspace of a few hundred descriptions, audited with a few option sets
MOST_BYTES = 256 * 1024  # an entry of the corpus is 1-40 kB (talos: ~100 findings); a larger one is not kept
# what reads the files and measures the meshes (the rules are descgen's source)
TOOLS = ("lxml", "PyYAML", "numpy", "trimesh", "pycollada")
MAX_VIA = 64  # macro call depth recorded per location; a plain URDF has none
UNMEASURED = "GEOM033"  # a mesh that could not be read may have failed for a passing reason (EIO, EMFILE)
_CODE = re.compile(r"[A-Z]{2,10}[0-9]{3}")  # every code of the catalogue (descgen/codes/__init__.py)


@record
class Inputs:
    """One audit's key, the bytes it was computed from (the audit reads these, not the files
    again: an edit meanwhile cannot pair one file's findings with another's key), when it
    began, and what a hit must check again."""

    key: str
    description: Path
    package_paths: tuple[Path, ...]
    data: dict[Path, bytes]
    started_ns: int


def inputs(
    description: Path,
    srdf: Path | None,
    controllers: Path | None,
    launch_args: Mapping[str, str],
    package_paths: Sequence[Path],
) -> Inputs | None:
    """The key of auditing ``description`` (a plain URDF) with these files; None when caching
    is off or a file cannot be read (the audit itself then says why)."""
    if cache_root() is None:
        return None
    started = time.time_ns()
    data: dict[Path, bytes] = {}
    files = []
    try:
        for what, path in (("URDF", description), ("SRDF", srdf), ("controllers YAML", controllers)):
            if path is not None:
                data[path] = read_bounded(path, what, display=str(path))
                files.append([what, str(path), sha256(data[path])])
    except InputError:
        return None
    given = {
        "files": files,
        "launch_args": sorted(launch_args.items()),
        "package_paths": [str(p) for p in package_paths],
    }
    return Inputs(result_cache.key(KIND, given, TOOLS), description, tuple(package_paths), data, started)


def get(found: Inputs) -> list[Finding] | None:
    """The findings recorded for ``found``, when every mesh still resolves to the same
    unchanged file; None otherwise."""
    value = result_cache.get(KIND, found.key, MOST_BYTES)
    if not isinstance(value, dict):
        return None
    meshes, findings = value.get("meshes"), value.get("findings")
    if not isinstance(meshes, list) or not isinstance(findings, list) or not _same_meshes(found, meshes):
        return None
    out = [_finding(f) for f in findings]
    return None if any(f is None for f in out) else [f for f in out if f is not None]


def put(found: Inputs, robot: Robot, findings: Sequence[Finding]) -> None:
    """Record ``findings`` of ``robot`` (audited from ``found``'s bytes). Not when a mesh
    changed during the audit or just before it (its stat data cannot tell the content it was
    measured with from the content now, git's "racily clean": ``stat_index.racy``), nor when a
    mesh could not be read (the reason may pass)."""
    if any(f.code == UNMEASURED for f in findings):
        return
    files = dict(robot.mesh_files)
    meshes = []
    for name, state in robot.mesh_status:
        file = files.get(name)
        stat = stat_index.stat_path(file) if file is not None else None
        if file is not None and (stat is None or stat_index.racy(stat, found.started_ns)):
            return  # gone, or changed too recently (mtime, ctime) to be told apart by its stat
        meshes.append([name, state, file, list(stat) if stat is not None else None])
    result_cache.put(KIND, found.key, {"meshes": meshes, "findings": [_row(f) for f in findings]}, KEEP, MOST_BYTES)


def _same_meshes(found: Inputs, meshes: list[Any]) -> bool:
    if not all(isinstance(m, list) and len(m) == 4 and isinstance(m[0], str) for m in meshes):
        return False
    status, files = resolve_names([m[0] for m in meshes], found.description, found.package_paths)
    if len(status) != len(meshes):
        return False  # a name twice: not what put() writes
    for name, state, file, stat in meshes:
        now = files.get(name)
        if status.get(name) != state or (str(now) if now is not None else None) != file:
            return False
        if now is not None and (not isinstance(stat, list) or list(stat_index.stat_path(str(now)) or ()) != stat):
            return False
    return True


def _row(f: Finding) -> list[Any]:
    return [f.code, f.severity, f.message, f.hint, f.subject, _where_row(f.where)]


def _where_row(w: Where) -> list[Any]:
    return [w.file, w.line, w.col, [_where_row(v) for v in w.via]]


def _finding(row: Any) -> Finding | None:
    if not isinstance(row, list) or len(row) != 6 or not all(isinstance(v, str) for v in row[:5]):
        return None
    code, severity, message, hint, subject, where = row
    at = _where(where, 0)
    if severity not in SEVERITIES or at is None or not _CODE.fullmatch(code):
        return None
    return Finding(code, cast(Severity, severity), message, hint, subject, at)


def _where(row: Any, depth: int) -> Where | None:
    if not isinstance(row, list) or len(row) != 4 or depth > MAX_VIA:
        return None
    file, line, col, via = row
    if not isinstance(file, str) or not _count(line) or not _count(col) or not isinstance(via, list):
        return None
    calls = [_where(v, depth + 1) for v in via]
    if any(c is None for c in calls):
        return None
    return Where(file, line, col, tuple(c for c in calls if c is not None))


def _count(v: Any) -> bool:
    return type(v) is int and 0 <= v < 1 << 31
