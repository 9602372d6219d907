"""The one stat shortcut (descgen/infra/stat_index.py) that the mesh cache's index and the
findings cache share: a row is trusted only while every stat field is what it was, and a file
written within RACY_NS of being read is never vouched for by its stat data (git's "racily
clean"). Oracle: os.stat and the clock, and the file's own time stamps set by hand."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import pytest

from descgen.audit import findings_cache
from descgen.infra import stat_index
from descgen.meshes import cache as mesh_cache

KEY = "ab" * 32


def _index(tmp_path: Path) -> tuple[stat_index.StatIndex, Path]:
    folder = tmp_path / "cache"
    folder.mkdir()
    return stat_index.StatIndex("probe-index", 1, 1 << 20, 100), folder


def _file(tmp_path: Path, age_ns: int) -> tuple[Path, stat_index.Stat]:
    """A file whose mtime is ``age_ns`` before now (its ctime is now: the write itself)."""
    path = tmp_path / "mesh.stl"
    path.write_bytes(b"solid x\nendsolid x\n")
    then = time.time_ns() - age_ns
    os.utime(path, ns=(then, then))
    stat = stat_index.stat_path(path)
    assert stat is not None
    return path, stat


def test_a_write_within_racy_ns_is_not_trusted(tmp_path: Path) -> None:
    index, folder = _index(tmp_path)
    path, stat = _file(tmp_path, 0)  # written just now: mtime and ctime inside the window
    assert stat_index.racy(stat, time.time_ns())
    assert not index.remember(folder, str(path), stat, KEY, time.time_ns())
    assert index.row(folder, str(path), stat) is None
    index.save()
    assert not (folder / "probe-index").exists()  # nothing to write: nothing was trusted


def test_a_recent_ctime_alone_is_racy(tmp_path: Path) -> None:
    _, stat = _file(tmp_path, 60 * 10**9)  # an mtime a minute old, set by hand just now (ctime: now)
    assert stat[1] < time.time_ns() - stat_index.RACY_NS <= stat[3]
    assert stat_index.racy(stat, time.time_ns())


def test_a_file_older_than_the_window_is_trusted_while_unchanged(tmp_path: Path) -> None:
    index, folder = _index(tmp_path)
    path, stat = _file(tmp_path, 0)
    read_at = time.time_ns() + stat_index.RACY_NS + 10**9  # as if read three seconds after the write
    assert not stat_index.racy(stat, read_at)
    assert index.remember(folder, str(path), stat, KEY, read_at)
    assert index.row(folder, str(path), stat) == (stat, KEY, None)
    for field in range(4):
        changed = tuple(v + 1 if k == field else v for k, v in enumerate(stat))
        assert index.row(folder, str(path), changed) is None  # size, mtime, inode, ctime: each counts
    index.save()
    fresh = stat_index.StatIndex("probe-index", 1, 1 << 20, 100)  # the next process
    assert fresh.row(folder, str(path), stat) == (stat, KEY, None)
    rows = json.loads((folder / "probe-index").read_text())["entries"]
    assert rows == [[str(path), *stat, KEY, None]]


def test_the_window_is_the_one_constant(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Both caches take RACY_NS from stat_index: closing it there closes it for both."""
    assert not hasattr(mesh_cache, "RACY_NS") and not hasattr(findings_cache, "RACY_NS")
    assert isinstance(mesh_cache._INDEX, stat_index.StatIndex)
    path, stat = _file(tmp_path, 0)
    monkeypatch.setattr(stat_index, "RACY_NS", 0)
    assert not stat_index.racy(stat, time.time_ns() + 1)
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(tmp_path / "cache"))
    mesh_cache.forget()
    try:
        mesh_cache.remember(str(path), stat, KEY, time.time_ns() + 1)
        assert mesh_cache.known_key(str(path), stat) == KEY
        monkeypatch.setattr(stat_index, "RACY_NS", 2_000_000_000)
        mesh_cache.forget()
        mesh_cache.remember(str(path), stat, KEY, time.time_ns())
        assert mesh_cache.known_key(str(path), stat) is None
    finally:
        mesh_cache.forget()


def test_a_row_as_the_index_never_writes_it_is_refused() -> None:
    good = (1, 2, 3, 4)
    assert stat_index.valid("/a", good, KEY)
    for path, stat, key in (
        ("a", good, KEY),  # relative
        ("/a\0b", good, KEY),
        ("/a", (1, 2, 3), KEY),
        ("/a", (1, 2, 3, True), KEY),
        ("/a", (-1, 2, 3, 4), KEY),
        ("/a", (1, 2, 1 << 63, 4), KEY),
        ("/a", good, "AB" * 32),
        ("/a", good, KEY[:10]),
    ):
        assert not stat_index.valid(path, stat, key), (path, stat, key)
