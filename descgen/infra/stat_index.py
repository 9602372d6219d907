"""The stat shortcut, as git's index: a file whose stat data (size, mtime, inode, ctime, in
nanoseconds where the OS has them) is what it was when its content was read still holds that
content, so a warm run stats the file instead of reading and hashing it.

One implementation for every cache that takes it:

- the mesh cache (descgen/meshes/cache.py) keeps a :class:`StatIndex`: one file per cache folder
  mapping a mesh's path and stat data to the content key last computed for it (and a copy of
  that key's facts), read once per process and merged back on save;
- the findings cache (descgen/audit/findings_cache.py) records the stat data of every mesh an
  audit measured in its entry, and a hit compares them with :func:`stat_path` of each file.

Both refuse what :func:`racy` says: a file changed less than :data:`RACY_NS` before it was read
is never vouched for by its stat data ("racily clean" in git's words: a rewrite within the file
system's time-stamp granularity, 2 s on FAT, could keep every field). Trust as in
docs/security.md: whoever can write the cache folder can make a cache answer what they like.
An index file is data: read with a size bound, every row checked for type and range (a bad
row is skipped, a bad file ignored whole). Nothing here raises: a cache that cannot be read or
written only costs time.
"""

from __future__ import annotations

import atexit
import json
import os
import re
import threading
from pathlib import Path
from typing import Any

from descgen.core.cache_dir import read_at_most, write_atomic

RACY_NS = 2_000_000_000  # a file changed this shortly before it was read is not vouched for (FAT stamps are 2 s)
MAX_PATH_CHARS = 4096  # PATH_MAX on Linux
_INT64 = 1 << 63
_KEY = re.compile(r"[0-9a-f]{64}")

Stat = tuple[int, int, int, int]  # st_size, st_mtime_ns, st_ino, st_ctime_ns
# path -> (stat, content key, what the user keeps beside the key, or None)
Row = tuple[Stat, str, Any]


def stat_of(st: os.stat_result) -> Stat:
    """The stat data the shortcut compares: what changes whenever a file's bytes are rewritten."""
    return (st.st_size, st.st_mtime_ns, st.st_ino, st.st_ctime_ns)


def stat_path(path: str | os.PathLike[str]) -> Stat | None:
    """:func:`stat_of` the file at ``path`` (links followed); None when it cannot be stat()ed."""
    try:
        return stat_of(os.stat(path))
    except (OSError, ValueError):
        return None


def racy(stat: Stat, read_at_ns: int) -> bool:
    """True when the file was changed (mtime or ctime) within :data:`RACY_NS` before
    ``read_at_ns`` (``time.time_ns()`` before its content was read), or after: its stat data
    cannot tell the content read from a rewrite in the same time-stamp tick."""
    return max(stat[1], stat[3]) >= read_at_ns - RACY_NS


def valid(path: Any, stat: Any, key: Any) -> bool:
    """A row as :class:`StatIndex` writes it: an absolute path, four int64 stat fields, a key."""
    if type(path) is not str or not 0 < len(path) <= MAX_PATH_CHARS or not path.startswith("/") or "\0" in path:
        return False
    if type(stat) is not tuple or len(stat) != 4 or any(type(v) is not int for v in stat):
        return False
    if type(key) is not str or not _KEY.fullmatch(key):
        return False
    size, mtime, ino, ctime = stat
    return bool(0 <= size < _INT64 and 0 <= ino < _INT64 and -_INT64 <= mtime < _INT64 and -_INT64 <= ctime < _INT64)


class StatIndex:
    """path + stat data -> content key (and a payload), one file ``name`` per cache folder."""

    def __init__(self, name: str, schema: int, max_bytes: int, max_entries: int) -> None:
        self.name, self.schema, self.max_bytes, self.max_entries = name, schema, max_bytes, max_entries
        self._read: dict[Path, dict[str, Row]] = {}  # cache folder -> its index, read once
        self._added: dict[Path, dict[str, Row]] = {}  # cache folder -> rows not yet written
        self._lock = threading.Lock()
        self._at_exit = False

    def row(self, folder: Path, path: str, stat: Stat) -> Row | None:
        """The row recorded for ``path`` while its stat data was ``stat``; None when there is
        none or the file changed since (any field differs)."""
        with self._lock:
            index = self._read.get(folder)
            if index is None:
                index = self._read[folder] = self.read(folder)
            entry = index.get(path)
        return entry if entry is not None and entry[0] == stat else None

    def remember(self, folder: Path, path: str, stat: Stat, key: str, read_at_ns: int, payload: Any = None) -> bool:
        """Record that ``path`` with ``stat`` held content ``key`` when read at ``read_at_ns``;
        not when :func:`racy` (False then, and for a row :func:`valid` refuses)."""
        if not valid(path, stat, key) or racy(stat, read_at_ns):
            return False
        with self._lock:
            self._read.setdefault(folder, {})[path] = (stat, key, payload)
            self._added.setdefault(folder, {})[path] = (stat, key, payload)
            if not self._at_exit:  # a caller that never calls save() still keeps what it read
                self._at_exit = True
                atexit.register(self.save)
        return True

    def save(self) -> None:
        """Write the rows this process added, merged into the index on disk (another process
        may have added its own since it was read); atomic, and silent when unwritable."""
        with self._lock:
            pending = [(folder, added) for folder, added in self._added.items() if added]
            self._added.clear()
        for folder, added in pending:
            merged = self.read(folder)
            merged.update(added)
            if len(merged) > self.max_entries:  # a cache folder shared by everything: start over
                merged = dict(list(added.items())[-self.max_entries :])
            rows = [[p, *stat, key, payload] for p, (stat, key, payload) in merged.items()]
            try:
                text = json.dumps({"schema": self.schema, "entries": rows}, allow_nan=False, separators=(",", ":"))
            except (TypeError, ValueError):
                continue
            if len(text) <= self.max_bytes:
                write_atomic(folder / self.name, text)

    def forget(self) -> None:
        """Drop what this process holds in memory (the tests' fresh process)."""
        with self._lock:
            self._read.clear()
            self._added.clear()

    def read(self, folder: Path) -> dict[str, Row]:
        """The index in ``folder``: every row that is exactly what :meth:`save` writes; nothing
        when the file is missing, too large, not JSON or not the expected shape."""
        raw = read_at_most(folder / self.name, self.max_bytes)
        if raw is None:
            return {}
        try:
            doc = json.loads(raw, parse_constant=_no_constant)
        except (ValueError, RecursionError):
            return {}
        if type(doc) is not dict or set(doc) != {"schema", "entries"} or doc["schema"] != self.schema:
            return {}
        rows = doc["entries"]
        if type(rows) is not list or len(rows) > self.max_entries:
            return {}
        out: dict[str, Row] = {}
        for row in rows:
            if type(row) is not list or len(row) != 7:
                continue
            path, size, mtime, ino, ctime, key, payload = row
            stat = (size, mtime, ino, ctime)
            if valid(path, stat, key):
                out[path] = (stat, key, payload if type(payload) is dict else None)
        return out


def _no_constant(name: str) -> None:
    raise ValueError(f"{name} is not a number descgen writes")
