"""Results of pure computations kept between runs, keyed by the hash of every input.

``check`` runs on every commit, and most commits change nothing a proof reads: the sandboxed
Xacro expansions, catkin_pkg's reading of package.xml and the sweep's table would give the
same result as last time. Each is a pure function of what its key holds:

- the inputs themselves, by content (the files an expansion reads, the arguments, the
  environment variables the sandbox lets through; the model values the sweep reads);
- descgen's identity as a local cache takes it (descgen/infra/keys.py ``LOCAL``: the release, a
  hash of every source file, the Python version to its patch release), so any edit to descgen
  computes again;
- the versions of the libraries that compute it (xacro, catkin_pkg, numpy, ...).

The key is :func:`descgen.infra.keys.key`'s, as every cache's and every evidence record's.

A changed input is a different key, so nothing stale is ever served: the result is computed
exactly as without the cache. A proof that reads a cached tool output still does its own
comparison every time; only the tool's work is skipped.

One JSON file per result under ``<cache>/results/<kind>/`` (descgen/core/cache_dir.py: the user
cache folder, ``DESCGEN_CACHE_DIR=`` switches caching off, as the test suite does). An entry
is data (docs/security.md): read with a size bound, its schema, kind and key must match, and
each user checks the value's shape; anything else is a miss. Writes go through a temporary
file renamed into place. A folder holding more than :data:`KEEP` entries drops those used
least recently (a hit touches its entry).
Nothing here raises: a cache that cannot be read or written only costs time.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import time
from pathlib import Path
from typing import Any

from descgen.core.cache_dir import cache_root, read_at_most, write_atomic
from descgen.infra import keys

SCHEMA = 1  # bump when an entry's layout changes
MAX_ENTRY_BYTES = 64 * 1024 * 1024  # a 1000-link expansion is a few MB
STALE_TMP_NS = 3600 * 10**9  # a write takes milliseconds: an hour-old temporary file is left over
KEEP = 128  # entries per kind: a few robots' worth of recent edits
KEEP_BYTES = 256 * 1024 * 1024  # and at most this much per kind (1000-link expansions are MBs each)
_KEY = re.compile(r"[0-9a-f]{64}")
_KIND = re.compile(r"[a-z][a-z0-9-]{0,40}")


def key(kind: str, inputs: object, tools: tuple[str, ...] = (), version: int = 1) -> str:
    """The key (descgen/infra/keys.py) of computing ``kind`` (its ``version``) from ``inputs``
    (JSON-able): with descgen's whole source and the ``tools``' versions, as a local cache is."""
    return keys.key(kind, version, inputs, tools, keys.LOCAL)


def _folder(kind: str) -> Path | None:
    root = cache_root()
    return None if root is None or not _KIND.fullmatch(kind) else root / "results" / kind


def get(kind: str, k: str, most_bytes: int | None = None) -> Any:
    """The value stored for key ``k``, or None on a miss (or an entry not as :func:`put` wrote
    it; one over ``most_bytes``, the bound its :func:`put` was given, is not read)."""
    folder = _folder(kind)
    if folder is None or not _KEY.fullmatch(k):
        return None
    entry = folder / f"{k}.json"
    raw = read_at_most(entry, MAX_ENTRY_BYTES if most_bytes is None else min(most_bytes, MAX_ENTRY_BYTES))
    if raw is None:
        return None
    try:
        doc = json.loads(raw, parse_constant=_no_constant)
    except (ValueError, RecursionError):  # bad JSON, NaN/Infinity, bad UTF-8
        return None
    if not isinstance(doc, dict) or doc.get("schema") != SCHEMA or doc.get("kind") != kind or doc.get("key") != k:
        return None
    with contextlib.suppress(OSError):  # a read-only cache still answers
        os.utime(entry)  # used now: the prune keeps the entries used last, not those written last
    return doc.get("value")


def put(kind: str, k: str, value: object, keep: int | None = None, most_bytes: int | None = None) -> None:
    """Store ``value`` (JSON-able) under key ``k``, keeping the newest ``keep`` entries of the
    kind (:data:`KEEP` when None); an entry over ``most_bytes`` (:data:`MAX_ENTRY_BYTES`) is not
    stored. Silently nothing when caching is off or fails."""
    keep = KEEP if keep is None else keep
    most_bytes = MAX_ENTRY_BYTES if most_bytes is None else min(most_bytes, MAX_ENTRY_BYTES)
    folder = _folder(kind)
    if folder is None or not _KEY.fullmatch(k):
        return
    try:
        text = json.dumps(
            {"schema": SCHEMA, "kind": kind, "key": k, "value": value}, allow_nan=False, separators=(",", ":")
        )
    except (TypeError, ValueError):
        return
    if len(text.encode("utf-8")) > most_bytes:
        return
    write_atomic(folder / f"{k}.json", text)
    _prune(folder, keep, most_bytes)


def _stale_temporary(e: os.DirEntry[str], stale: int) -> bool:
    """A ``.tmp-`` entry a writer left over an hour ago: a regular file or a link (unlinked,
    never followed); a folder of that name is no writer's and is left alone. One that is gone
    already (its writer renamed it) is not left over."""
    try:
        if e.is_dir(follow_symlinks=False):
            return False
        return e.stat(follow_symlinks=False).st_mtime_ns < stale
    except FileNotFoundError:
        return False


def _no_constant(name: str) -> None:
    raise ValueError(f"{name} is not a number descgen writes")


def _prune(folder: Path, keep: int, most_bytes: int) -> None:
    """Keep the newest entries, at most ``keep`` of them and :data:`KEEP_BYTES` in all, and
    drop temporary files a killed writer left over an hour ago (only after a write, so a read
    never lists the folder). Entries are stat()ed only when some may have to go (too many, or
    possibly too large at ``most_bytes`` each, or a temporary file): an audit writes one small
    entry per description, and stat()ing thousands after each would cost more than the audit."""
    try:
        listed = list(os.scandir(folder))
        stale = time.time_ns() - STALE_TMP_NS
        # a young temporary file is a live writer's: only a stale one makes the entries worth a stat
        left_over = any(_stale_temporary(e, stale) for e in listed if e.name.startswith(".tmp-"))
        if len(listed) <= keep and len(listed) * most_bytes <= KEEP_BYTES and not left_over:
            return
        entries = []
        for e in listed:
            if e.name.startswith(".tmp-"):
                if _stale_temporary(e, stale):  # a live writer's is younger
                    with contextlib.suppress(FileNotFoundError):
                        os.unlink(e.path)
                continue
            if not e.is_file(follow_symlinks=False):
                continue
            try:
                st = e.stat(follow_symlinks=False)
            except FileNotFoundError:  # another process pruned it
                continue
            if e.name.endswith(".json"):
                entries.append((st.st_mtime_ns, st.st_size, e.path))
        entries.sort(reverse=True)  # newest first
        kept = 0
        for i, (_, size, path) in enumerate(entries):
            kept += size
            if i >= keep or kept > KEEP_BYTES:
                os.unlink(path)
    except OSError:
        return
