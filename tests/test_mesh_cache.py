"""The persistent mesh-facts cache (descgen/meshes/cache.py): a cache hit answers as a
measurement would, a tampered entry is never trusted, a changed file is measured again. The
one-pass box reader is held to trimesh in tests/test_mesh_bounds.py."""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from pathlib import Path

import pytest
import trimesh

from descgen.infra import stat_index
from descgen.meshes import cache as mesh_cache
from descgen.meshes import load as meshes
from descgen.read.description import Options, audit

from .corpus import descriptions, share


def _forget() -> None:
    """What a fresh process knows: nothing in memory."""
    for memo in (meshes._FACTS, meshes._BY_STAT, meshes._CACHE):
        memo.clear()
    meshes._ROBOT_FACTS.clear()
    mesh_cache.forget()


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    folder = tmp_path / "cache"
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(folder))
    _forget()
    yield folder
    _forget()


def _no_parsing(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*_: object) -> None:
        raise AssertionError("a mesh was parsed although its facts were cached")

    monkeypatch.setattr(meshes, "_parse", refuse)
    monkeypatch.setattr(meshes, "_measured", refuse)


def _box(path: Path, extents: tuple[float, float, float]) -> Path:
    path.write_bytes(trimesh.creation.box(extents=extents).export(file_type="stl"))  # binary STL
    return path


def _entries(folder: Path) -> list[Path]:
    return sorted(folder.rglob("*.json"))


# -- the cache ------------------------------------------------------------------------------------


def test_a_cache_hit_answers_without_parsing_and_equals_the_parse(cache: Path, tmp_path: Path, monkeypatch) -> None:
    mesh = _box(tmp_path / "box.stl", (0.1, 0.2, 0.3))
    cold = meshes.measure(mesh)
    assert cold.upper == pytest.approx((0.05, 0.1, 0.15), rel=1e-6)  # hand value (float32 corners)
    (entry,) = _entries(cache)
    assert json.loads(entry.read_text())["lower"] == pytest.approx([-0.05, -0.1, -0.15], rel=1e-6)
    _forget()
    _no_parsing(monkeypatch)
    assert meshes.measure(mesh) == cold


def test_the_cache_is_off_when_the_variable_is_empty(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    _forget()
    assert mesh_cache.folder() is None
    meshes.measure(_box(tmp_path / "box.stl", (1, 2, 3)))
    assert not (tmp_path / "home").exists() and not (tmp_path / "xdg").exists()
    _forget()


def test_a_changed_file_is_measured_again(cache: Path, tmp_path: Path) -> None:
    mesh = tmp_path / "part.stl"
    small = meshes.measure(_box(mesh, (1.0, 1.0, 1.0))).upper
    stat = mesh.stat()
    _box(mesh, (2.0, 2.0, 2.0))  # same name, same size (12 triangles), other bytes
    os.utime(mesh, ns=(stat.st_atime_ns, stat.st_mtime_ns))  # even with the old time stamp
    _forget()  # a new process: the content is hashed, so the old entry does not match
    assert small == (0.5, 0.5, 0.5)
    assert meshes.measure(mesh).upper == (1.0, 1.0, 1.0)
    assert len(_entries(cache)) == 2


def _tamper(entry: Path, how: str) -> None:
    doc = json.loads(entry.read_text())
    if how == "bad json":
        entry.write_text(entry.read_text()[:-5])
    elif how == "nan":
        entry.write_text(entry.read_text().replace(str(doc["upper"][0]), "NaN", 1))
    elif how == "infinity coordinate":
        entry.write_text(entry.read_text().replace(json.dumps(doc["upper"][1]), "1e999", 1))
    elif how == "string coordinate":
        entry.write_text(json.dumps({**doc, "lower": ["0", 0, 0]}))
    elif how == "bool unit":
        entry.write_text(json.dumps({**doc, "unit_meter": True}))
    elif how == "negative unit":
        entry.write_text(json.dumps({**doc, "unit_meter": -0.001}))
    elif how == "old schema's fields":
        entry.write_text(json.dumps({**doc, "volume": None, "watertight": False, "triangles": 12, "open_edges": 0}))
    elif how == "lower above upper":
        entry.write_text(json.dumps({**doc, "lower": doc["upper"], "upper": doc["lower"]}))
    elif how == "extra key":
        entry.write_text(json.dumps({**doc, "__class__": "os.system"}))
    elif how == "other schema":
        entry.write_text(json.dumps({**doc, "schema": 0}))
    elif how == "other key inside":
        entry.write_text(json.dumps({**doc, "sha256": "0" * 64}))
    elif how == "problem beside facts":
        entry.write_text(json.dumps({**doc, "problem": "x"}))
    elif how == "huge":
        entry.write_text(json.dumps({**doc, "pad": "x" * 10_000_000}))
    elif how == "list":
        entry.write_text("[1, 2, 3]")
    elif how == "deep":
        entry.write_text("[" * 100_000 + "]" * 100_000)
    elif how == "fifo":
        entry.unlink()
        os.mkfifo(entry)  # a read must not block
    else:
        raise AssertionError(how)


HOW = [
    "bad json",
    "nan",
    "infinity coordinate",
    "string coordinate",
    "bool unit",
    "negative unit",
    "old schema's fields",
    "lower above upper",
    "extra key",
    "other schema",
    "other key inside",
    "problem beside facts",
    "huge",
    "list",
    "deep",
    "fifo",
]


@pytest.mark.parametrize("how", HOW)
def test_a_tampered_entry_is_ignored_and_measured_again(cache: Path, tmp_path: Path, how: str) -> None:
    mesh = _box(tmp_path / "box.stl", (0.1, 0.2, 0.3))
    truth = meshes.measure(mesh)
    (entry,) = _entries(cache)
    key = entry.stem
    _tamper(entry, how)
    assert mesh_cache.get(key, "stl") is None
    _forget()
    assert meshes.measure(mesh) == truth  # recomputed, not read from the entry
    assert mesh_cache.get(key, "stl") == truth  # and written back whole


def test_a_plausible_but_wrong_entry_is_what_the_content_key_prevents(cache: Path, tmp_path: Path) -> None:
    # an entry of another mesh copied under this mesh's name carries the other key inside
    a, b = _box(tmp_path / "a.stl", (1, 1, 1)), _box(tmp_path / "b.stl", (3, 3, 3))
    meshes.measure(a), meshes.measure(b)
    first, second = _entries(cache)
    second.write_bytes(first.read_bytes())
    assert mesh_cache.get(second.stem, "stl") is None


def test_an_unreadable_mesh_is_cached_with_its_problem(cache: Path, tmp_path: Path, monkeypatch) -> None:
    bad = tmp_path / "bad.dae"
    bad.write_bytes(b'<?xml version="1.0"?><!DOCTYPE x [<!ENTITY e SYSTEM "/etc/passwd">]><COLLADA/>')
    problem = meshes.measure(bad).problem
    assert problem is not None and "DTD" in problem
    _forget()
    _no_parsing(monkeypatch)
    assert meshes.measure(bad).problem == problem


def test_an_unwritable_cache_folder_is_a_miss_not_an_error(tmp_path: Path, monkeypatch) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(blocker))
    _forget()
    assert meshes.measure(_box(tmp_path / "box.stl", (1, 2, 3))).upper == (0.5, 1.0, 1.5)
    _forget()


# -- the stat index: (path, size, mtime, inode, ctime) -> content key ---------------------------------


def _no_hashing(monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(*_: object) -> None:
        raise AssertionError("a mesh was read and hashed although the stat index knew it")

    monkeypatch.setattr(meshes, "_content_key", refuse)


def _indexed(cache: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[Path, meshes.MeshFacts]:
    """A box measured with the racy window off (a test's files are seconds old), index written."""
    monkeypatch.setattr(stat_index, "RACY_NS", 0)
    mesh = _box(tmp_path / "box.stl", (0.1, 0.2, 0.3))
    truth = meshes.measure(mesh)
    mesh_cache.save_index()
    _forget()
    return mesh, truth


def _index_file(cache: Path) -> Path:
    (index,) = cache.rglob(mesh_cache.INDEX)
    return index


def test_an_unchanged_file_is_answered_from_the_index_without_reading_it(cache, tmp_path, monkeypatch) -> None:
    mesh, truth = _indexed(cache, tmp_path, monkeypatch)
    rows = json.loads(_index_file(cache).read_text())["entries"]
    st = mesh.stat()  # the row is the file's own stat data (an oracle outside descgen)
    (entry,) = _entries(cache)
    # ... and a copy of the mesh's entry file, so a warm run opens one file, not one per mesh
    copy = json.loads(entry.read_text())
    assert rows == [[str(mesh), st.st_size, st.st_mtime_ns, st.st_ino, st.st_ctime_ns, entry.stem, copy]]
    _no_hashing(monkeypatch)
    _no_parsing(monkeypatch)
    assert meshes.measure(mesh) == truth


def test_a_rewritten_file_of_another_size_is_hashed_again(cache, tmp_path, monkeypatch) -> None:
    mesh, _ = _indexed(cache, tmp_path, monkeypatch)
    old = mesh.stat()
    mesh.write_bytes(trimesh.creation.icosphere(subdivisions=1, radius=2.0).export(file_type="stl"))
    os.utime(mesh, ns=(old.st_atime_ns, old.st_mtime_ns))  # even with the old time stamp
    assert mesh.stat().st_size != old.st_size
    facts = meshes.measure(mesh)
    assert facts.upper == pytest.approx((2.0, 2.0, 2.0), abs=1e-6)


def test_a_rewritten_file_with_another_mtime_is_hashed_again(cache, tmp_path, monkeypatch) -> None:
    mesh, _ = _indexed(cache, tmp_path, monkeypatch)
    old = mesh.stat()
    _box(mesh, (1.0, 1.0, 1.0))  # same size in bytes (12 triangles), other corners
    os.utime(mesh, ns=(old.st_atime_ns, old.st_mtime_ns + 1_000_000_000))
    assert mesh.stat().st_size == old.st_size
    assert meshes.measure(mesh).upper == (0.5, 0.5, 0.5)


@pytest.mark.parametrize("field", range(4))
def test_any_stat_field_that_differs_misses(cache, tmp_path, monkeypatch, field: int) -> None:
    mesh, _ = _indexed(cache, tmp_path, monkeypatch)
    stat = stat_index.stat_of(mesh.stat())
    assert mesh_cache.known_key(str(mesh), stat) == _entries(cache)[0].stem
    other = tuple(v + 1 if k == field else v for k, v in enumerate(stat))
    assert mesh_cache.known_key(str(mesh), other) is None  # size, mtime, inode, ctime: each one counts


def test_a_file_changed_just_before_it_was_hashed_is_not_indexed(cache, tmp_path) -> None:
    # git's "racily clean" case: a second rewrite within the time-stamp granularity would keep
    # every stat field, so a file this fresh is hashed again on the next run
    meshes.measure(_box(tmp_path / "box.stl", (1, 2, 3)))
    mesh_cache.save_index()
    assert not list(cache.rglob(mesh_cache.INDEX))


def _tamper_index(index: Path, how: str, mesh: Path) -> None:
    doc = json.loads(index.read_text())
    row = doc["entries"][0]
    if how == "bad json":
        index.write_text(index.read_text()[:-3])
    elif how == "huge":
        index.write_text(json.dumps({**doc, "pad": "x" * (mesh_cache.MAX_INDEX_BYTES + 1)}))
    elif how == "list":
        index.write_text("[]")
    elif how == "deep":
        index.write_text("[" * 100_000 + "]" * 100_000)
    elif how == "other schema":
        index.write_text(json.dumps({**doc, "schema": 0}))
    elif how == "fifo":
        index.unlink()
        os.mkfifo(index)
    elif how == "nan size":
        index.write_text(index.read_text().replace(f",{row[1]},", ",NaN,", 1))
    else:
        bad = {
            "string size": [row[0], str(row[1]), *row[2:]],
            "bool inode": [*row[:3], True, *row[4:]],
            "negative size": [row[0], -1, *row[2:]],
            "relative path": ["box.stl", *row[1:]],
            "short key": [*row[:5], row[5][:10], row[6]],
            "short row": row[:5],
            "old six-field row": row[:6],
        }[how]
        index.write_text(json.dumps({**doc, "entries": [bad]}))


HOW_INDEX = ["bad json", "huge", "list", "deep", "other schema", "fifo", "nan size"]
HOW_INDEX += ["string size", "bool inode", "negative size", "relative path", "short key", "short row"]
HOW_INDEX += ["old six-field row"]


@pytest.mark.parametrize("how", HOW_INDEX)
def test_a_tampered_index_is_ignored(cache, tmp_path, monkeypatch, how: str) -> None:
    mesh, truth = _indexed(cache, tmp_path, monkeypatch)
    index = _index_file(cache)
    _tamper_index(index, how, mesh)
    assert mesh_cache.known_key(str(mesh), stat_index.stat_of(mesh.stat())) is None
    _forget()
    hashed: list[bytes] = []
    real = meshes._content_key
    monkeypatch.setattr(meshes, "_content_key", lambda data, kind: hashed.append(data) or real(data, kind))
    assert meshes.measure(mesh) == truth  # from the file's bytes, not from the index
    assert hashed == [mesh.read_bytes()]


def _damage_copy(doc: dict[str, object], how: str) -> object:
    return {
        "wrong upper": {**doc, "upper": [9.0, 9.0, 9.0], "lower": [8.0, 8.0, 8.0], "sha256": "0" * 64},
        "other kind": {**doc, "kind": "dae"},
        "extra field": {**doc, "extra": 1},
        "lower above upper": {**doc, "lower": doc["upper"], "upper": doc["lower"]},
        "not a dict": ["x"],
        "null": None,
    }[how]


HOW_COPY = ["wrong upper", "other kind", "extra field", "lower above upper", "not a dict", "null"]


@pytest.mark.parametrize("how", HOW_COPY)
def test_a_damaged_facts_copy_in_the_index_falls_back_to_the_entry_file(cache, tmp_path, monkeypatch, how) -> None:
    # a copy that is not exactly what put() writes for this key and kind is a miss, never a
    # wrong fact: the key still stands (the file is not hashed again) and the entry answers
    mesh, truth = _indexed(cache, tmp_path, monkeypatch)
    index = _index_file(cache)
    doc = json.loads(index.read_text())
    doc["entries"][0][6] = _damage_copy(doc["entries"][0][6], how)
    index.write_text(json.dumps(doc))
    key, facts = mesh_cache.known(str(mesh), stat_index.stat_of(mesh.stat()), "stl") or ("", "missing")
    assert key == _entries(cache)[0].stem and facts is None
    _forget()
    _no_hashing(monkeypatch)
    _no_parsing(monkeypatch)
    opened: list[str] = []
    real_get = mesh_cache.get
    monkeypatch.setattr(mesh_cache, "get", lambda k, kind: opened.append(k) or real_get(k, kind))
    assert meshes.measure(mesh) == truth
    assert opened == [key]


def test_a_warm_run_reads_no_entry_file(cache, tmp_path, monkeypatch) -> None:
    mesh, truth = _indexed(cache, tmp_path, monkeypatch)
    _no_hashing(monkeypatch)
    _no_parsing(monkeypatch)
    monkeypatch.setattr(mesh_cache, "get", lambda *_: pytest.fail("an entry file was read"))
    assert meshes.measure(mesh) == truth


def test_an_index_entry_pointing_at_another_meshes_key_is_what_stat_data_prevents(cache, tmp_path, monkeypatch):
    # the index says which content a path held; once the file changes, the entry is not used
    mesh, _ = _indexed(cache, tmp_path, monkeypatch)
    index = _index_file(cache)
    doc = json.loads(index.read_text())
    doc["entries"][0][2] -= 5_000_000_000  # an mtime the file does not have
    index.write_text(json.dumps(doc))
    assert mesh_cache.known_key(str(mesh), stat_index.stat_of(mesh.stat())) is None


# GEOM032 on alex_nub_hands needs its meshes' boxes; allegro's palm mesh bounds INER005; go1 has DAE
CORPUS_FEW = [
    "alex_description/urdf/alex_nub_hands.urdf",
    "allegro_hand_description/urdf/allegro_left_hand.urdf",
    "go1_description/urdf/go1.urdf",
]


@pytest.mark.skipif(share() is None, reason="example-robot-data is not installed")
def test_cached_facts_give_the_findings_of_a_cold_run_on_corpus_robots(cache: Path, monkeypatch) -> None:
    chosen = [d for d in descriptions() if d[0] in CORPUS_FEW]
    assert len(chosen) == len(CORPUS_FEW)
    root = share()

    def findings() -> list[object]:
        return [f for _, urdf, srdf in chosen for f in audit(urdf, Options(srdf=srdf, package_paths=(root,)))]

    cold = findings()
    assert sum(f.code == "GEOM032" for f in cold) == 2  # type: ignore[attr-defined]  # docs/audit-corpus.md
    assert _entries(cache)
    _forget()
    _no_parsing(monkeypatch)
    assert findings() == cold
