"""The audit's findings cache (descgen/audit/findings_cache.py): a description audited again
unchanged gives the findings of an audit without the cache, without running a rule; any
changed input (the URDF, the SRDF, a mesh's bytes, where a mesh resolves, a launch argument)
is audited again; an entry that is not as written is ignored; Xacro, specs and MoveIt config
folders are never kept.

The expected findings come from tests/rules/GEOM031/bad.expected (hand-checked: an arm
exported in millimetres) and from the same audit with the cache switched off."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from descgen.audit import findings_cache, registry
from descgen.core.findings import Finding
from descgen.infra import result_cache, stat_index
from descgen.read.description import Options, audit
from tests.helpers import ROOT

GEOM031 = ROOT / "tests" / "rules" / "GEOM031"


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A cache folder of the test's own. The meshes the tests copy are seconds old at most, so
    the 2-second racy window is closed here (test_a_mesh_changed_just_before_is_not_kept
    opens it); a change during the audit is still caught."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(folder))
    monkeypatch.setattr(stat_index, "RACY_NS", 0)
    yield folder


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    """The GEOM031 fixture (a URDF whose mesh is in millimetres) in a folder of its own."""
    folder = tmp_path / "arm"
    shutil.copytree(GEOM031, folder)
    return folder / "bad.urdf"


def _uncached(path: Path, options: Options, monkeypatch: pytest.MonkeyPatch) -> list[Finding]:
    with monkeypatch.context() as m:
        m.setenv("DESCGEN_CACHE_DIR", "")
        return audit(path, options)


def _no_rules(monkeypatch: pytest.MonkeyPatch) -> None:
    """Make running any rule fail the test: a hit must not audit."""

    def refuse(*args: object, **kwargs: object) -> list[Finding]:
        raise AssertionError("the rules ran: not answered from the cache")

    monkeypatch.setattr(registry, "run", refuse)


def _codes(found: list[Finding]) -> list[tuple[str, int]]:
    return [(f.code, f.where.line) for f in found if f.code.startswith("GEOM03")]


def _entries(cache: Path) -> list[Path]:
    return sorted((cache / "results" / findings_cache.KIND).glob("*.json"))


def test_a_second_audit_is_answered_from_the_cache(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rows = [ln.split("\t") for ln in (GEOM031 / "bad.expected").read_text().splitlines()]
    expected = [(r[0], int(r[3])) for r in rows]
    first = audit(arm, Options())
    assert _codes(first) == expected  # the hand-checked fixture: two GEOM031 at lines 5 and 6
    assert first == _uncached(arm, Options(), monkeypatch)
    assert len(_entries(cache)) == 1
    _no_rules(monkeypatch)
    assert audit(arm, Options()) == first  # every field: code, severity, message, hint, subject, where


def test_a_changed_mesh_is_audited_again(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert _codes(audit(arm, Options()))
    # the arm exported in metres instead: a new file put in place (as an exporter or git does)
    fresh = arm.parent / "meshes" / "fresh.stl"
    shutil.copyfile(arm.parent / "meshes" / "arm_m.stl", fresh)
    os.replace(fresh, arm.parent / "meshes" / "arm_mm.stl")
    again = audit(arm, Options())
    assert _codes(again) == []  # the metre mesh fits the arm: GEOM031 is gone
    assert again == _uncached(arm, Options(), monkeypatch)


def test_a_removed_mesh_is_audited_again(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    audit(arm, Options())
    (arm.parent / "meshes" / "arm_mm.stl").unlink()
    again = audit(arm, Options())
    assert again == _uncached(arm, Options(), monkeypatch)
    assert not _codes(again)  # no mesh, no size to compare


def test_a_package_that_now_resolves_elsewhere_is_audited_again(
    cache: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """package://arm_pkg/... is searched in --package-path order: a package that appears in an
    earlier folder takes over, though no file the first audit read has changed."""
    late, early = tmp_path / "late", tmp_path / "early"
    for root, mesh in ((late, "arm_mm.stl"), (early, "arm_m.stl")):
        (root / "arm_pkg" / "meshes").mkdir(parents=True)
        (root / "arm_pkg" / "package.xml").write_text("<package format='3'><name>arm_pkg</name></package>")
        shutil.copyfile(GEOM031 / "meshes" / mesh, root / "arm_pkg" / "meshes" / "arm.stl")
    urdf = tmp_path / "arm.urdf"
    urdf.write_text((GEOM031 / "bad.urdf").read_text().replace("meshes/arm_mm.stl", "package://arm_pkg/meshes/arm.stl"))
    hidden = tmp_path / "hidden"
    early.rename(hidden)
    options = Options(package_paths=(early, late))
    assert len(_codes(audit(urdf, options))) == 2  # only the millimetre package exists
    hidden.rename(early)
    again = audit(urdf, options)
    assert _codes(again) == []
    assert again == _uncached(urdf, options, monkeypatch)


def test_an_edited_urdf_or_srdf_is_a_new_key(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    srdf = arm.parent / "arm.srdf"
    srdf.write_text('<robot name="arm"><group name="g"><joint name="shoulder"/></group></robot>')
    audit(arm, Options(srdf=srdf))
    srdf.write_text('<robot name="arm"><group name="g"><joint name="no_such_joint"/></group></robot>')
    again = audit(arm, Options(srdf=srdf))
    assert again == _uncached(arm, Options(srdf=srdf), monkeypatch)
    assert any("no_such_joint" in f.message for f in again)
    arm.write_text(arm.read_text().replace('name="tool_link"', 'name="tool link"'))
    edited = audit(arm, Options(srdf=srdf))
    assert edited == _uncached(arm, Options(srdf=srdf), monkeypatch)
    assert any(f.subject == "link:tool link" for f in edited)
    assert len(_entries(cache)) == 3


def test_launch_arguments_are_part_of_the_key(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    yaml_file = arm.parent / "controllers.yaml"
    yaml_file.write_text(
        "controller_manager:\n  ros__parameters:\n    update_rate: 100\n"
        "    arm:\n      type: joint_trajectory_controller/JointTrajectoryController\n"
        "arm:\n  ros__parameters:\n    joints: [$(var joint)]\n"
        "    command_interfaces: [position]\n    state_interfaces: [position]\n"
    )
    good, bad = (Options(controllers=yaml_file, launch_args={"joint": j}) for j in ("shoulder", "elbow"))
    audit(arm, good)
    assert audit(arm, bad) == _uncached(arm, bad, monkeypatch)
    assert any("elbow" in f.message for f in audit(arm, bad))
    assert not any("elbow" in f.message for f in audit(arm, good))


def test_the_urdf_is_audited_from_the_bytes_its_key_was_computed_from(
    cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A -> B -> A: the URDF is edited right after its key was computed and put back before
    the audit ends (a branch switched and back). The findings stored under A's key are A's."""
    a = arm.read_text()
    real_inputs, real_run = findings_cache.inputs, registry.run

    def key_then_edit(*args: object, **kwargs: object) -> object:
        found = real_inputs(*args, **kwargs)  # type: ignore[arg-type]
        arm.write_text(a.replace('name="tool_link"', 'name="tool link"'))  # B, before the audit reads
        return found

    def run_then_restore(robot: object, *args: object, **kwargs: object) -> list[Finding]:
        try:
            return real_run(robot, *args, **kwargs)  # type: ignore[arg-type]
        finally:
            arm.write_text(a)

    with monkeypatch.context() as m:
        m.setattr(findings_cache, "inputs", key_then_edit)
        m.setattr(registry, "run", run_then_restore)
        first = audit(arm, Options())
    assert not any("tool link" in f.subject for f in first)  # A's findings, from A's bytes
    assert first == _uncached(arm, Options(), monkeypatch)
    _no_rules(monkeypatch)
    assert audit(arm, Options()) == first


def test_a_mesh_edited_during_the_audit_is_not_kept(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The mesh is measured in millimetres, then replaced by the metre file before the entry is
    written: stored, its new stat data would vouch for the old findings."""
    real = registry.run
    mesh = arm.parent / "meshes" / "arm_mm.stl"

    def run_then_edit(robot: object, *args: object, **kwargs: object) -> list[Finding]:
        found = real(robot, *args, **kwargs)  # type: ignore[arg-type]
        fresh = mesh.with_name("fresh.stl")
        shutil.copyfile(mesh.with_name("arm_m.stl"), fresh)
        os.replace(fresh, mesh)
        return found

    with monkeypatch.context() as m:
        m.setattr(registry, "run", run_then_edit)
        assert _codes(audit(arm, Options()))  # audited with the millimetre mesh
    assert _entries(cache) == []
    assert _codes(audit(arm, Options())) == []  # the metre mesh, audited afresh


def test_a_mesh_changed_just_before_is_not_kept(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Within the racy window a rewrite may keep every stat field (coarse time stamps): the
    entry waits until the mesh is older. Oracle: the copy's own ctime, just now."""
    monkeypatch.setattr(stat_index, "RACY_NS", 2_000_000_000)
    audit(arm, Options())
    assert _entries(cache) == []
    monkeypatch.setattr(stat_index, "RACY_NS", 0)
    audit(arm, Options())
    assert len(_entries(cache)) == 1


def test_an_unreadable_mesh_is_not_kept(cache: Path, arm: Path) -> None:
    """GEOM033 (a mesh that could not be read) may have a passing cause: audited every time."""
    (arm.parent / "meshes" / "arm_mm.stl").write_bytes(b"solid nothing\nendsolid nothing\n")
    assert any(f.code == "GEOM033" for f in audit(arm, Options()))
    assert _entries(cache) == []


@pytest.mark.parametrize(
    "value",
    [
        "findings",
        {"meshes": [], "findings": [["GEOM031", "fatal", "m", "h", "s", ["f", 1, 1, []]]]},  # no such severity
        {"meshes": [], "findings": [["GEOM031", "error", "m", "h", "s", ["f", -1, 1, []]]]},
        {"meshes": [], "findings": [["GEOM031", "error", "m", "h", "s", ["f", 1, 1.5, []]]]},
        {"meshes": [], "findings": [["GEOM031", "error", "m", "h", "s"]]},
        {"meshes": [["x"]], "findings": []},
        {"meshes": [["meshes/arm_mm.stl", "ok", "/elsewhere.stl", [1, 2, 3, 4]]], "findings": []},
        {"meshes": [], "findings": [["GEOM031\nforged: error", "error", "m", "h", "s", ["f", 1, 1, []]]]},
    ],
)
def test_an_entry_not_as_written_is_ignored(
    cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch, value: object
) -> None:
    first = audit(arm, Options())
    (entry,) = _entries(cache)
    doc = json.loads(entry.read_text())
    entry.write_text(json.dumps({**doc, "value": value}))
    assert audit(arm, Options()) == first


def test_an_entry_under_another_urdfs_key_is_a_miss(cache: Path, arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An entry copied over another description's (same meshes, other URDF) is refused by
    the key written inside it: the copied findings are never served."""
    first = audit(arm, Options())
    (entry,) = _entries(cache)
    other = arm.parent / "good.urdf"
    audit(other, Options())
    moved = next(p for p in _entries(cache) if p != entry)
    moved.write_text(entry.read_text())  # the bad URDF's findings under the good URDF's name
    assert audit(other, Options()) == _uncached(other, Options(), monkeypatch)
    assert audit(arm, Options()) == first


def test_xacro_spec_and_moveit_config_are_not_kept(cache: Path, tmp_path: Path) -> None:
    xacro = tmp_path / "arm.urdf.xacro"
    xacro.write_text('<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base_link"/></robot>')
    audit(xacro, Options())
    spec = ROOT / "specs" / "warehouse_arm.yaml"
    audit(spec, Options())
    assert _entries(cache) == []


def test_nothing_is_read_or_kept_when_caching_is_off(arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")

    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("the result cache was used with caching off")

    monkeypatch.setattr(result_cache, "get", refuse)
    monkeypatch.setattr(result_cache, "put", refuse)
    assert _codes(audit(arm, Options()))


def test_a_kind_with_its_own_bounds_is_pruned_by_count_and_size(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    keys = [result_cache.key("probe", i) for i in range(6)]
    for i, k in enumerate(keys):
        result_cache.put("probe", k, i, keep=4, most_bytes=1024)
        os.utime(cache / "results" / "probe" / f"{k}.json", ns=(i * 10**9, i * 10**9))
    assert [result_cache.get("probe", k) for k in keys] == [None, None, 2, 3, 4, 5]
    result_cache.put("probe", result_cache.key("probe", "big"), "x" * 2048, keep=4, most_bytes=1024)
    assert result_cache.get("probe", result_cache.key("probe", "big")) is None  # over most_bytes: not kept


@pytest.mark.e2e
def test_a_hit_imports_neither_lxml_nor_the_rules(arm: Path, tmp_path: Path) -> None:
    probe = (
        "import json, sys\n"
        "from pathlib import Path\n"
        "from descgen.infra import stat_index\n"
        "from descgen.read.description import Options, audit\n"
        "stat_index.RACY_NS = 0  # the fixture's meshes were copied a moment ago\n"
        "found = audit(Path(sys.argv[1]), Options())\n"
        "print('PROBE' + json.dumps([len(found), sorted(m for m in sys.modules if m.startswith(('lxml', 'numpy', "
        "'descgen.audit.rules', 'descgen.read.urdf', 'descgen.read.xacro', 'descgen.read.srdf')))]))\n"
    )
    env = {**os.environ, "DESCGEN_CACHE_DIR": str(tmp_path / "cache")}
    runs = []
    for _ in range(2):
        done = subprocess.run(
            [sys.executable, "-c", probe, str(arm)], capture_output=True, text=True, env=env, cwd=ROOT, timeout=120
        )
        line = next(x for x in done.stdout.splitlines() if x.startswith("PROBE"))
        runs.append(json.loads(line[len("PROBE") :]))
    (first_count, first_modules), (second_count, second_modules) = runs
    assert "lxml.etree" in first_modules and "descgen.audit.rules" in first_modules  # the probe sees imports
    assert second_count == first_count > 0
    assert second_modules == []
