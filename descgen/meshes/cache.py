"""Mesh facts kept between runs: parsing a mesh costs ~100x hashing its bytes.

One small JSON file per mesh content, in the user cache folder descgen already uses for pint
(``DESCGEN_CACHE_DIR``, default ``~/.cache/descgen``; ``DESCGEN_CACHE_DIR=`` switches it off,
as the test suite does). The key is the sha256 of the mesh's bytes (and its format); the
folder is named by a key (descgen/infra/keys.py) of the schema version and the versions of
trimesh, pycollada and numpy, which decide what a parse gives, so an upgrade starts a fresh
folder.

An entry is data, never code (docs/security.md): JSON read with a size bound, every field
checked for type, range and finiteness, and the key inside it must equal its file name. Any
entry that fails is ignored and the mesh is measured again; writes go to a temporary file
renamed into place, so a reader never sees half an entry. Nothing here raises: a cache that
cannot be read or written is a cache miss.

In front of the hashes sits a stat index (descgen/infra/stat_index.py, the one implementation
of the stat shortcut, shared with the findings cache), as git's index sits in front of its
object hashes: one file (``stat-index``) mapping a mesh's path and stat data (size, mtime,
inode, ctime, all in nanoseconds where the OS has them) to the content key last computed for
it and a copy of that key's entry, so a warm run stats a mesh instead of reading and hashing
its bytes (sha256 of the corpus's 350 MB is ~0.3 s) and reads one file, not one entry per mesh
(~620 opens and JSON parses for the corpus). The copy is checked exactly as an entry file is;
one that fails leaves the key, and the entry file is read instead. A file whose stat data
differs in any field is read and hashed again; one changed less than ``stat_index.RACY_NS``
before it was hashed is never indexed ("racily clean").
"""

from __future__ import annotations

import functools
import json
import math
import os
import re
from pathlib import Path
from typing import Any

from descgen.core.cache_dir import CACHE_ENV, cache_root, write_atomic
from descgen.infra import keys, stat_index
from descgen.infra.safeio import MIB
from descgen.infra.stat_index import Stat
from descgen.meshes.facts import MeshFacts

SCHEMA = 2  # bump when MeshFacts or how it is measured changes (2: the box alone, from meshes/bounds.py)
MAX_ENTRY_BYTES = 4096  # a real entry is ~300 bytes; anything larger is not ours
_KEY = re.compile(r"[0-9a-f]{64}")
_KINDS = ("stl", "obj", "dae")
INDEX = "stat-index"  # beside the entries' subfolders; not *.json: it is no facts entry
MAX_INDEX_BYTES = 32 * MIB  # ~150 bytes per mesh: 200,000 meshes
MAX_INDEX_ENTRIES = 200_000
# what measures a mesh: descgen/meshes/bounds.py (numpy, lxml), and trimesh (with pycollada for
# .dae) for what that reader leaves to it
LIBRARIES = ("trimesh", "pycollada", "numpy", "lxml")
_INDEX = stat_index.StatIndex(INDEX, SCHEMA, MAX_INDEX_BYTES, MAX_INDEX_ENTRIES)


@functools.cache
def _folder_name() -> str:
    # the versions are read from the installed metadata, without importing trimesh (~0.5 s)
    return "meshes-" + keys.key("mesh facts", SCHEMA, None, LIBRARIES, keys.NOTHING)[:16]


_FOLDERS: dict[str | None, Path | None] = {}  # DESCGEN_CACHE_DIR's value -> folder (asked per mesh)


def folder() -> Path | None:
    """The folder of mesh entries, or None when caching is off (``DESCGEN_CACHE_DIR=``)."""
    configured = os.environ.get(CACHE_ENV)  # read each time: a test or caller may change it
    found = _FOLDERS.get(configured, _FOLDERS)
    if found is not _FOLDERS:
        return found  # type: ignore[return-value]
    base = cache_root()
    result = None if base is None else base / _folder_name()
    _FOLDERS[configured] = result
    return result


def _entry(root: Path, key: str) -> Path:
    return root / key[:2] / f"{key}.json"


def get(key: str, kind: str) -> MeshFacts | None:
    """The cached facts of the mesh whose content hash is ``key``; None on a miss or on an
    entry that is not exactly what :func:`put` writes."""
    root = folder()
    if root is None or not _KEY.fullmatch(key):
        return None
    try:
        fd = os.open(_entry(root, key), os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except (OSError, ValueError):
        return None
    try:
        raw = os.read(fd, MAX_ENTRY_BYTES + 1)  # a FIFO gives b"" at once (O_NONBLOCK), a device is cut
    except OSError:
        return None
    finally:
        os.close(fd)
    if len(raw) > MAX_ENTRY_BYTES:
        return None
    try:
        doc = json.loads(raw, parse_constant=_no_constant)
    except (ValueError, RecursionError):  # bad JSON, NaN/Infinity, bad UTF-8
        return None
    return _facts(doc, key, kind)


def put(key: str, kind: str, facts: MeshFacts) -> None:
    """Record ``facts`` for content ``key``; silently does nothing if the folder is unwritable."""
    root = folder()
    if root is None or not _KEY.fullmatch(key) or _facts(_doc(key, kind, facts), key, kind) != facts:
        return  # never write what get() would refuse (a problem message too long, say)
    try:
        text = json.dumps(_doc(key, kind, facts), allow_nan=False, separators=(",", ":"))
    except ValueError:
        return
    write_atomic(_entry(root, key), text)


def _doc(key: str, kind: str, f: MeshFacts) -> dict[str, Any]:
    return {
        "schema": SCHEMA,
        "sha256": key,
        "kind": kind,
        "lower": list(f.lower) if f.lower is not None else None,
        "upper": list(f.upper) if f.upper is not None else None,
        "unit_meter": f.unit_meter,
        "problem": f.problem,
    }


def _no_constant(name: str) -> None:
    raise ValueError(f"{name} is not a number descgen caches")


def _real(v: Any) -> bool:
    return type(v) in (float, int) and math.isfinite(v)  # not bool (a subclass of int)


def _vec(v: Any) -> tuple[float, float, float] | None:
    if type(v) is list and len(v) == 3 and all(_real(x) for x in v):
        return (float(v[0]), float(v[1]), float(v[2]))
    return None


def _facts(doc: Any, key: str, kind: str) -> MeshFacts | None:
    """The facts in a parsed entry, or None unless every field is what put() writes."""
    fields = {"schema", "sha256", "kind", "lower", "upper", "unit_meter", "problem"}
    if type(doc) is not dict or set(doc) != set(fields):
        return None
    if doc["schema"] != SCHEMA or doc["sha256"] != key or doc["kind"] != kind or kind not in _KINDS:
        return None
    problem = doc["problem"]
    if problem is not None:
        if type(problem) is not str or not 0 < len(problem) <= 300 or "\n" in problem:
            return None
        if (doc["lower"], doc["upper"], doc["unit_meter"]) != (None, None, None):
            return None
        return MeshFacts(problem=problem)
    lower, upper, unit = _vec(doc["lower"]), _vec(doc["upper"]), doc["unit_meter"]
    if lower is None or upper is None or any(lo > hi for lo, hi in zip(lower, upper, strict=True)):
        return None
    if unit is not None and not (_real(unit) and unit > 0):
        return None
    return MeshFacts(lower=lower, upper=upper, unit_meter=None if unit is None else float(unit))


# -- the stat index: (path, size, mtime, inode, ctime) -> content key (descgen/infra/stat_index.py) ----


def known_key(path: str, stat: Stat) -> str | None:
    """The content key recorded for ``path`` while its stat data was ``stat``; None when the
    index has none or the file changed since (any field differs)."""
    entry = _row(path, stat)
    return entry[1] if entry is not None else None


def known(path: str, stat: Stat, kind: str) -> tuple[str, MeshFacts | None] | None:
    """The content key recorded for ``path`` while its stat data was ``stat``, and the facts
    the index holds for it (None when its copy is missing or not exactly what put() writes:
    then :func:`get` reads the entry file). None when the file changed since."""
    entry = _row(path, stat)
    if entry is None:
        return None
    return entry[1], None if entry[2] is None else _facts(entry[2], entry[1], kind)


def _row(path: str, stat: Stat) -> stat_index.Row | None:
    root = folder()
    return None if root is None else _INDEX.row(root, path, stat)


def remember(
    path: str, stat: Stat, key: str, hashed_at_ns: int, kind: str = "", facts: MeshFacts | None = None
) -> None:
    """Record that ``path`` with ``stat`` held content ``key`` (of ``kind``, measured as
    ``facts``), read at ``hashed_at_ns`` (``time.time_ns()`` before the read). A file changed
    within ``stat_index.RACY_NS`` of then is left out: a second rewrite in the same time-stamp
    tick would look unchanged."""
    root = folder()
    if root is None:
        return
    doc = _doc(key, kind, facts) if facts is not None and _facts(_doc(key, kind, facts), key, kind) == facts else None
    _INDEX.remember(root, path, stat, key, hashed_at_ns, doc)


def save_index() -> None:
    """Write the entries this process added, merged into the index on disk (another process
    may have added its own since it was read); atomic, and silent when unwritable."""
    _INDEX.save()


def forget() -> None:
    """Drop what this process holds in memory (the tests' fresh process)."""
    _INDEX.forget()
