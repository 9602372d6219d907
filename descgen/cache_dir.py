"""The user cache folder descgen keeps derived data in (pint's parsed definitions, compiled
templates, mesh facts, the result cache of descgen/result_cache.py).

``DESCGEN_CACHE_DIR=DIR`` moves it, ``DESCGEN_CACHE_DIR=`` (empty) switches caching off (the test
suite does). Everything in it is derived from inputs it is keyed by, so deleting it only costs
time; each user validates what it reads back (docs/security.md)."""

from __future__ import annotations

import os
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
