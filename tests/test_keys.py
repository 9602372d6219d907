"""The one key scheme (descgen/infra/keys.py): a key is the sha256 of a canonical JSON document
(keys sorted) of what is computed (a name and a version), its inputs, descgen's identity as it
applies and the versions of the libraries that compute it; every cache and evidence record
takes its key from it (the collision matrix's and the sweep's included).

Oracles: hashlib and json themselves (the document hashed by hand), importlib.metadata for the
versions, and the SRDF the template writes for the record the matrix reads back."""

from __future__ import annotations

import hashlib
import json
import re
import sys
from dataclasses import replace
from importlib import metadata
from pathlib import Path

import pytest

import descgen
from descgen.infra import evidence_hash, keys
from tests.helpers import ROOT

DESCGEN = ROOT / "descgen"


def test_the_key_is_the_sha256_of_the_sorted_canonical_document() -> None:
    doc = keys.document("probe", 3, {"b": [1, {"y": 2, "x": 1}], "a": "é"}, {"xacro": "2.1"}, keys.NOTHING)
    by_hand = json.dumps(doc, sort_keys=True, separators=(",", ":"), ensure_ascii=True)
    assert keys.key("probe", 3, {"b": [1, {"y": 2, "x": 1}], "a": "é"}, {"xacro": "2.1"}, keys.NOTHING) == (
        hashlib.sha256(by_hand.encode("ascii")).hexdigest()
    )


def test_the_same_inputs_in_another_order_are_the_same_key() -> None:
    one = keys.key("probe", 1, {"a": 1, "b": {"c": 2, "d": 3}}, ("xacro", "lxml"))
    other = keys.key("probe", 1, {"b": {"d": 3, "c": 2}, "a": 1}, ("xacro", "lxml"))
    assert one == other
    assert keys.key("probe", 1, {"a": 1, "b": {"c": 2, "d": 4}}, ("xacro", "lxml")) != one


def test_what_and_its_version_are_part_of_the_key() -> None:
    base = keys.key("probe", 1, {})
    assert keys.key("probe", 2, {}) != base  # a bumped format version
    assert keys.key("other", 1, {}) != base
    with pytest.raises(ValueError):
        keys.key("", 1, {})


def test_library_versions_are_in_the_key(monkeypatch: pytest.MonkeyPatch) -> None:
    doc = keys.document("probe", 1, {}, ("xacro", "lxml", "no-such-distribution-here"))
    assert doc["libraries"] == {
        "xacro": metadata.version("xacro"),
        "lxml": metadata.version("lxml"),
        "no-such-distribution-here": "absent",
    }
    before = keys.key("probe", 1, {}, ("xacro",))
    monkeypatch.setattr(evidence_hash, "versions", lambda *names: {n: "99.0" for n in names})  # an upgrade
    assert keys.key("probe", 1, {}, ("xacro",)) != before
    # a mapping is the versions a record says computed the result: taken as given
    assert keys.document("probe", 1, {}, {"pin": "3.4.0"})["libraries"] == {"pin": "3.4.0"}


def test_descgens_identity_is_in_the_key_as_it_applies(monkeypatch: pytest.MonkeyPatch) -> None:
    evidence_hash.source_digest.cache_clear()
    local = keys.document("probe", 1, {}, (), keys.LOCAL)["descgen"]
    assert local == {
        "descgen": descgen.__version__,
        "source": evidence_hash.source_digest(),
        "python": list(sys.version_info[:3]),
    }
    assert keys.document("probe", 1, {}, (), keys.EVIDENCE)["descgen"] == {
        "descgen": descgen.__version__,
        "python": list(sys.version_info[:2]),
    }
    assert keys.document("probe", 1, {}, (), keys.RELEASE)["descgen"] == {"descgen": descgen.__version__}
    assert keys.document("probe", 1, {}, (), keys.NOTHING)["descgen"] == {}
    scopes = (keys.LOCAL, keys.EVIDENCE, keys.RELEASE, keys.NOTHING)
    before = {s: keys.key("probe", 1, {}, (), s) for s in scopes}
    monkeypatch.setattr(evidence_hash, "source_digest", lambda: "0" * 64)  # any edit to descgen's source
    edited = {s: keys.key("probe", 1, {}, (), s) for s in scopes}
    assert [edited[s] != before[s] for s in scopes] == [True, False, False, False]
    monkeypatch.setattr(descgen, "__version__", "9.9.9")  # another release
    released = {s: keys.key("probe", 1, {}, (), s) for s in scopes}
    assert [released[s] != edited[s] for s in scopes] == [True, True, True, False]
    with pytest.raises(ValueError):
        keys.identity(("sauce",))


def test_recompute_is_read_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(evidence_hash.RECOMPUTE_ENV, raising=False)
    assert not evidence_hash.recompute()
    record = evidence_hash.recorded(evidence_hash.stamp("a" * 64, "text"))
    assert evidence_hash.reusable(record, "a" * 64, "text")
    for value, on in (("1", True), ("yes", True), ("0", False), ("", False)):
        monkeypatch.setenv(evidence_hash.RECOMPUTE_ENV, value)
        assert evidence_hash.recompute() is on
        assert evidence_hash.reusable(record, "a" * 64, "text") is not on


def test_no_key_is_built_by_hand() -> None:
    """Every hash of a JSON document in descgen is a key of keys.py (or a content hash of what
    was written, descgen/commands/control/record.py's ``written_content``); the one primitive
    that hashes canonical JSON is evidence_hash.digest, which keys.key calls."""
    by_hand = re.compile(r"sha256\(\s*json\.dumps|hashlib\.sha256\([^)]*json")
    found = [
        f"{p.relative_to(ROOT)}:{n}"
        for p in sorted(DESCGEN.rglob("*.py"))
        if p != DESCGEN / "infra" / "evidence_hash.py"
        for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
        if by_hand.search(line)
    ]
    assert found == []
    users = sorted(
        p.relative_to(DESCGEN).as_posix()
        for p in DESCGEN.rglob("*.py")
        if re.search(r"\bkeys\.key\(|\bresult_cache\.key\(", p.read_text(encoding="utf-8"))
    )
    assert users == [
        "audit/findings_cache.py",
        "commands/control/record.py",
        "commands/evidence_page.py",
        "infra/result_cache.py",
        "meshes/cache.py",
        "physics/collision.py",
        "physics/sweep/__init__.py",
        "prove/package.py",
        "prove/sweep.py",
        "prove/xacro_expand.py",
        "render/__init__.py",
        "write/pose_images.py",
    ]


# -- the collision matrix and the sweep ------------------------------------------------------------


def _example() -> tuple[object, str, str]:
    from descgen.audit.spec import load_spec
    from descgen.render import header

    pkg = ROOT / "generated" / "warehouse_arm_description"
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    stamp = header.read((pkg / "urdf" / "warehouse_arm.urdf").read_text())
    assert stamp is not None
    return robot, stamp.body, (pkg / "srdf" / "warehouse_arm.srdf").read_text()


def test_the_collision_key_holds_pinocchio_coal_numpy_and_the_release(monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.physics import collision

    robot, urdf, _ = _example()
    settings = robot.semantic.collision_matrix  # type: ignore[attr-defined]
    installed = {n: metadata.version(n) for n in ("pin", "coal", "numpy")}
    key = collision.input_hash(robot, urdf, {}, settings)  # type: ignore[arg-type]
    assert key == collision.input_hash(robot, urdf, {}, settings, installed)  # type: ignore[arg-type]
    for name in installed:
        other = {**installed, name: installed[name] + ".post9"}
        assert collision.input_hash(robot, urdf, {}, settings, other) != key  # type: ignore[arg-type]
    assert collision.input_hash(robot, urdf, {}, replace(settings, seed=settings.seed + 1)) != key  # type: ignore[arg-type]
    monkeypatch.setattr(evidence_hash, "source_digest", lambda: "0" * 64)
    assert collision.input_hash(robot, urdf, {}, settings) == key  # type: ignore[arg-type]  # source edits: no
    monkeypatch.setattr(descgen, "__version__", "9.9.9")
    assert collision.input_hash(robot, urdf, {}, settings) != key  # type: ignore[arg-type]  # a release: yes


def test_the_srdf_records_the_matrix_key_with_its_libraries() -> None:
    from descgen.physics import collision

    robot, urdf, srdf = _example()
    found = collision.recorded(srdf)
    assert found is not None
    key, libraries = found
    assert libraries is not None and list(libraries) == list(collision.LIBRARIES)
    settings = robot.semantic.collision_matrix  # type: ignore[attr-defined]
    assert collision.input_hash(robot, urdf, {}, settings, libraries) == key  # type: ignore[arg-type]
    # a record of the earlier layout names no libraries: its key is taken, never its versions
    assert collision.recorded(f"<!-- collision matrix input-sha256={key} -->") == (key, None)


def test_without_pinocchio_the_committed_matrix_is_reused_by_its_recorded_versions(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from descgen.physics import collision

    robot, urdf, srdf = _example()
    settings = robot.semantic.collision_matrix  # type: ignore[attr-defined]
    real = keys.libraries
    monkeypatch.setattr(
        keys, "libraries", lambda names: {**real(names), "pin": "absent"} if not isinstance(names, dict) else names
    )
    monkeypatch.setitem(sys.modules, "pinocchio", None)  # importing it fails, as when not installed

    def refuse(*_: object) -> None:
        raise AssertionError("sampled")

    monkeypatch.setattr(collision, "_sample", refuse)
    found = collision.recorded(srdf)
    assert found is not None and found[1] is not None
    matrix = collision.compute(robot, urdf, {}, "warehouse_arm_description", settings, srdf)  # type: ignore[arg-type]
    assert matrix.input_hash == found[0] and dict(matrix.libraries) == found[1]
    # and DESCGEN_RECOMPUTE=1 refuses it: nothing can sample here, so that is an error, not a reuse
    monkeypatch.setenv(evidence_hash.RECOMPUTE_ENV, "1")
    with pytest.raises(AssertionError, match="sampled"):
        collision.compute(robot, urdf, {}, "warehouse_arm_description", settings, srdf)  # type: ignore[arg-type]


def test_other_installed_versions_sample_again_and_keep_a_reproduced_record(monkeypatch: pytest.MonkeyPatch) -> None:
    """A machine with another numpy (a fresh CI venv gets the newest): the committed matrix is
    sampled again there; the same pairs keep the committed record (the SRDF is not rewritten),
    other pairs are keyed with the installed versions (the SRDF reads stale)."""
    from descgen.physics import collision
    from descgen.prove import sweep as sweep_evidence

    robot, urdf, srdf = _example()
    settings = robot.semantic.collision_matrix  # type: ignore[attr-defined]
    found = collision.recorded(srdf)
    assert found is not None and found[1] is not None
    newer = {**found[1], "numpy": found[1]["numpy"] + ".post9"}
    monkeypatch.setattr(collision, "installed", lambda: dict(newer))
    real, sampled = collision._sample, []

    def counted(*args: object, **kwargs: object) -> object:
        sampled.append(1)
        return real(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(collision, "_sample", counted)
    monkeypatch.setattr(collision, "_SAMPLED", {})
    matrix = collision.compute(robot, urdf, {}, "warehouse_arm_description", settings, srdf)  # type: ignore[arg-type]
    assert sampled == [1]
    assert matrix.input_hash == found[0] and dict(matrix.libraries) == found[1]  # the record stands
    with_matrix = replace(robot, semantic=replace(robot.semantic, matrix=matrix))  # type: ignore[type-var]
    committed = (ROOT / "generated" / "warehouse_arm_description" / "evidence" / "sweep.md").read_text()
    assert not sweep_evidence.reuse(with_matrix, committed)  # the sweep's runs are computed here too

    monkeypatch.setattr(collision, "_SAMPLED", {})
    monkeypatch.setattr(collision, "_sample", lambda *_: matrix.pairs[1:])  # pinocchio disagrees
    other = collision.compute(robot, urdf, {}, "warehouse_arm_description", settings, srdf)  # type: ignore[arg-type]
    assert other.input_hash == collision.input_hash(robot, urdf, {}, settings, newer) != found[0]  # type: ignore[arg-type]
    assert dict(other.libraries) == newer


def test_the_sweep_key_is_keyed_by_the_matrix_and_its_libraries(monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.physics import collision, sweep

    robot, urdf, srdf = _example()
    settings = robot.semantic.collision_matrix  # type: ignore[attr-defined]
    found = collision.recorded(srdf)
    assert found is not None and found[1] is not None
    monkeypatch.setattr(collision, "_sample", lambda *_: pytest.fail("sampled"))  # the committed matrix
    matrix = collision.compute(robot, urdf, {}, "warehouse_arm_description", settings, srdf)  # type: ignore[arg-type]
    with_matrix = replace(robot, semantic=replace(robot.semantic, matrix=matrix))  # type: ignore[type-var]
    state, values = sweep.state_values(with_matrix, None)
    disabled = sweep.disabled_pairs(with_matrix)[0]
    key = sweep.memo_key(with_matrix, state, values, sweep.DEFAULT_STEPS, disabled)
    inputs = {
        "matrix": found[0],
        "state": state,
        "values": sorted(values.items()),
        "steps": sweep.DEFAULT_STEPS,
        "disabled": sorted(sorted(p) for p in disabled),
    }
    assert key == keys.key("sweep collision runs", sweep.ALGORITHM, inputs, found[1], keys.RELEASE)
    # the committed evidence/sweep.md records this very key
    committed = (ROOT / "generated" / "warehouse_arm_description" / "evidence" / "sweep.md").read_text()
    assert f"<!-- sweep input-sha256={key} runs=" in committed
    newer = replace(matrix, libraries=(("pin", "99.0"), *matrix.libraries[1:]))
    other = replace(robot, semantic=replace(robot.semantic, matrix=newer))  # type: ignore[type-var]
    assert sweep.memo_key(other, state, values, sweep.DEFAULT_STEPS, disabled) != key


def test_the_mesh_cache_folder_is_named_by_a_key() -> None:
    from descgen.meshes import cache as mesh_cache

    name = mesh_cache._folder_name()
    libraries = ("trimesh", "pycollada", "numpy", "lxml")  # what measures a mesh: meshes/bounds.py and trimesh
    expected = keys.key("mesh facts", mesh_cache.SCHEMA, None, libraries, keys.NOTHING)
    assert name == "meshes-" + expected[:16]


def test_the_template_cache_folder_is_named_by_a_key(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen import render

    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(tmp_path))
    render._bytecode_cache.cache_clear()
    try:
        assert render._bytecode_cache(True) is not None and render._bytecode_cache(False) is not None
    finally:
        render._bytecode_cache.cache_clear()
    generator = hashlib.sha256(Path(render.escaping.__file__).read_bytes()).hexdigest()
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(
        f"jinja2-{kind}-"
        + keys.key("compiled templates", 1, {"environment": kind, "generator": generator}, ("Jinja2",), keys.NOTHING)[
            :16
        ]
        for kind in ("plain", "sandbox")
    )
