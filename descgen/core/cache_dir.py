"""The user cache folder descgen keeps derived data in (pint's parsed definitions, compiled
templates, mesh facts, the result cache of descgen/infra/result_cache.py).

``DESCGEN_CACHE_DIR=DIR`` moves it, ``DESCGEN_CACHE_DIR=`` (empty) switches caching off (the test
suite does). Everything in it is derived from inputs it is keyed by, so deleting it only costs
time; each user validates what it reads back (docs/security.md)."""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

CACHE_ENV = "DESCGEN_CACHE_DIR"


def cache_root() -> Path | None:
    """The cache folder, or None when caching is off."""
    configured = os.environ.get(CACHE_ENV)
    if configured == "":
        return None
    if configured is not None:
        return Path(configured)
    import platformdirs  # only when a cache is used: its import is not free on a cold start

    return platformdirs.user_cache_path("descgen", appauthor=False)


def cache_folder(name: str) -> Path | None:
    """``<cache>/<name>``, made if missing; None when caching is off or it cannot be made (a
    cache that cannot be written only costs time)."""
    root = cache_root()
    if root is None:
        return None
    folder = root / name
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return folder


def read_at_most(path: Path, limit: int) -> bytes | None:
    """At most ``limit`` bytes of the cache file ``path`` without blocking on a FIFO; None when
    it cannot be opened, is no regular file, or holds more (a cache entry is data: a miss, never
    an error)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except (OSError, ValueError):
        return None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, limit + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError:
        return None
    finally:
        os.close(fd)
    data = b"".join(chunks)
    return None if len(data) > limit else data


def write_atomic(path: Path, text: str) -> None:
    """``text`` to the cache file ``path`` through a temporary file and a rename: a concurrent
    reader sees the old entry or the new one, never half of one. Any failure is a miss later,
    never an error now."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as out:
                out.write(text)
            os.replace(tmp, path)
        except BaseException:
            os.unlink(tmp)
            raise
    except (OSError, ValueError):
        return
