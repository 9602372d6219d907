"""The result cache (descgen/infra/result_cache.py) and what check keeps in it: the sandboxed Xacro
expansions, catkin_pkg's reading of package.xml and the sweep's table. A hit gives what the
slow path gives; any changed input is a miss; a stale or edited file is still reported; an
entry that is not as written is ignored; DESCGEN_CACHE_DIR= switches it off. Also the faster
helpers check now uses, against their references: metadata versions (importlib.metadata),
descgen's source hash (the pathlib walk it replaced), libyaml loading (yaml.safe_load)."""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import shutil
import time
from collections.abc import Iterator
from importlib import metadata
from pathlib import Path

import pytest
import yaml

from descgen.core.findings import InputError
from descgen.infra import evidence_hash, result_cache
from tests.helpers import ROOT, cli

EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
DESCRIPTION = "warehouse_arm_description"


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    folder = tmp_path / "cache"
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(folder))
    yield folder


# --- the store ------------------------------------------------------------------------------------


def test_put_then_get_and_nothing_when_off(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    k = result_cache.key("probe", {"a": 1})
    assert result_cache.get("probe", k) is None
    result_cache.put("probe", k, {"x": [1, "two"]})
    assert result_cache.get("probe", k) == {"x": [1, "two"]}
    assert result_cache.get("other", k) is None  # another kind: another folder
    assert result_cache.key("probe", {"a": 2}) != k
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")
    assert result_cache.get("probe", k) is None
    result_cache.put("probe", result_cache.key("probe", {"b": 1}), 1)
    assert len(list(cache.rglob("*.json"))) == 1  # nothing written while off


def test_an_entry_not_as_written_is_a_miss(cache: Path) -> None:
    k = result_cache.key("probe", "x")
    result_cache.put("probe", k, "value")
    (entry,) = cache.rglob(f"{k}.json")
    doc = json.loads(entry.read_text())
    for bad in (
        "{not json",
        json.dumps({**doc, "key": "0" * 64}),  # an entry copied under another name
        json.dumps({**doc, "kind": "other"}),
        json.dumps({**doc, "schema": 0}),
        json.dumps({**doc, "value": float("nan")}),  # NaN: not a value put writes
    ):
        entry.write_text(bad)
        assert result_cache.get("probe", k) is None, bad
    entry.unlink()
    os.mkfifo(entry)  # a FIFO is not read (it would block)
    assert result_cache.get("probe", k) is None


def test_a_folder_keeps_its_newest_entries(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(result_cache, "KEEP", 3)
    keys = [result_cache.key("probe", i) for i in range(5)]
    for i, k in enumerate(keys):
        result_cache.put("probe", k, i)
        os.utime(cache / "results" / "probe" / f"{k}.json", ns=(i * 10**9, i * 10**9))
    assert [result_cache.get("probe", k) for k in keys] == [None, None, 2, 3, 4]
    size = (cache / "results" / "probe" / f"{keys[4]}.json").stat().st_size
    monkeypatch.setattr(result_cache, "KEEP_BYTES", 2 * size + size // 2)  # room for two entries
    result_cache.put("probe", keys[0], 0)  # the newest now
    assert [result_cache.get("probe", k) for k in keys] == [0, None, None, None, 4]


def test_the_prune_keeps_the_entries_used_last(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An entry written long ago but read just now outlives one written later and never read."""
    monkeypatch.setattr(result_cache, "KEEP", 2)
    old, young, newest = (result_cache.key("probe", i) for i in range(3))
    for i, k in enumerate((old, young)):
        result_cache.put("probe", k, i)
        os.utime(cache / "results" / "probe" / f"{k}.json", ns=((i + 1) * 10**9, (i + 1) * 10**9))
    assert result_cache.get("probe", old) == 0  # used now
    result_cache.put("probe", newest, 2)  # three entries: the least recently used goes
    assert [result_cache.get("probe", k) for k in (old, young, newest)] == [0, None, 2]


def test_a_killed_writers_temporary_file_goes_once_it_is_old(cache: Path) -> None:
    """A write that died between mkstemp and rename leaves ``.tmp-*``; the next write's prune
    removes it when it is over an hour old, and leaves a young one (a writer still at work)."""
    folder = cache / "results" / "probe"
    result_cache.put("probe", result_cache.key("probe", 0), 0)
    old, young = folder / ".tmp-old", folder / ".tmp-young"
    old.write_text("{")
    young.write_text("{")
    two_hours_ago = time.time_ns() - 2 * 3600 * 10**9
    os.utime(old, ns=(two_hours_ago, two_hours_ago))
    result_cache.put("probe", result_cache.key("probe", 1), 1)
    assert not old.exists() and young.exists()
    assert result_cache.get("probe", result_cache.key("probe", 0)) == 0  # entries untouched


def test_a_live_writers_temporary_file_does_not_make_every_write_stat_the_folder(
    cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A young ``.tmp-*`` (another process writing now) leaves the prune's shortcut in place:
    only the temporary file is stat()ed, not every entry (an audit writes one entry per file)."""
    folder = cache / "results" / "probe"
    for k in range(5):  # small entries, as the audit's findings are (most_bytes): the shortcut's case
        result_cache.put("probe", result_cache.key("probe", k), k, most_bytes=4096)
    (folder / ".tmp-live").write_text("{")
    stats: list[str] = []
    real = os.scandir

    class Counted:
        def __init__(self, entry: os.DirEntry[str]) -> None:
            self.entry, self.name, self.path = entry, entry.name, entry.path

        def is_file(self, follow_symlinks: bool = True) -> bool:
            return self.entry.is_file(follow_symlinks=follow_symlinks)

        def is_dir(self, follow_symlinks: bool = True) -> bool:
            return self.entry.is_dir(follow_symlinks=follow_symlinks)

        def stat(self, follow_symlinks: bool = True) -> os.stat_result:
            stats.append(self.name)
            return self.entry.stat(follow_symlinks=follow_symlinks)

    monkeypatch.setattr(result_cache.os, "scandir", lambda path: [Counted(e) for e in real(path)])
    result_cache.put("probe", result_cache.key("probe", 5), 5, most_bytes=4096)
    assert stats == [".tmp-live"]
    assert (folder / ".tmp-live").exists()


def test_a_stale_temporary_link_goes_and_a_temporary_folder_is_left_alone(cache: Path) -> None:
    folder = cache / "results" / "probe"
    result_cache.put("probe", result_cache.key("probe", 0), 0, most_bytes=4096)
    target = cache / "target.txt"
    target.write_text("not the cache's")
    link, odd = folder / ".tmp-link", folder / ".tmp-folder"
    link.symlink_to(target)
    odd.mkdir()
    two_hours_ago = time.time_ns() - 2 * 3600 * 10**9
    os.utime(link, ns=(two_hours_ago, two_hours_ago), follow_symlinks=False)
    os.utime(odd, ns=(two_hours_ago, two_hours_ago))
    result_cache.put("probe", result_cache.key("probe", 1), 1, most_bytes=4096)
    assert not os.path.lexists(link) and target.read_text() == "not the cache's"  # unlinked, never followed
    assert odd.is_dir()  # no writer makes a folder: not ours to remove


def test_a_temporary_file_renamed_away_during_the_prune_does_not_stop_it(
    cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # another writer's .tmp- file is listed, then renamed into place before it is stat()ed
    folder = cache / "results" / "probe"
    keys = [result_cache.key("probe", k) for k in range(4)]
    for k, key in enumerate(keys):
        result_cache.put("probe", key, k, keep=2, most_bytes=4096)
        os.utime(folder / f"{key}.json", ns=(10**18 + k * 10**9, 10**18 + k * 10**9))  # an order of use
    real = os.scandir

    class Vanished:
        name, path = ".tmp-gone", str(folder / ".tmp-gone")

        def is_dir(self, follow_symlinks: bool = True) -> bool:
            raise FileNotFoundError(self.path)

        def is_file(self, follow_symlinks: bool = True) -> bool:
            raise FileNotFoundError(self.path)

        def stat(self, follow_symlinks: bool = True) -> os.stat_result:
            raise FileNotFoundError(self.path)

    monkeypatch.setattr(result_cache.os, "scandir", lambda path: [*real(path), Vanished()])
    newest = result_cache.key("probe", 9)
    result_cache.put("probe", newest, 9, keep=2, most_bytes=4096)
    monkeypatch.undo()
    left = sorted(p.name for p in folder.iterdir())
    assert left == sorted([f"{keys[3]}.json", f"{newest}.json"])  # pruned to the 2 used last


def test_the_key_holds_descgen_source_and_tool_versions(monkeypatch: pytest.MonkeyPatch) -> None:
    k = result_cache.key("probe", 1, ("xacro",))
    monkeypatch.setattr(evidence_hash, "source_digest", lambda: "edited")
    assert result_cache.key("probe", 1, ("xacro",)) != k
    monkeypatch.undo()
    monkeypatch.setattr(evidence_hash, "versions", lambda *names: {n: "9.9" for n in names})
    assert result_cache.key("probe", 1, ("xacro",)) != k


# --- the helpers against their references ---------------------------------------------------------


def test_versions_are_importlib_metadatas() -> None:
    names = {d.metadata["Name"] for d in metadata.distributions()}
    assert len(names) > 20
    assert {n: evidence_hash.version(n) for n in names} == {n: metadata.version(n) for n in names}
    assert evidence_hash.version("no-such-distribution-here") == "absent"


def test_source_digest_is_the_pathlib_walks() -> None:
    """The reference: the walk evidence_hash.source_digest did before (pathlib, sorted paths),
    over the whole package (not only descgen/infra/, where evidence_hash.py lives since the layout)."""
    import descgen

    root = Path(descgen.__file__).resolve().parent
    files = sorted(p for p in root.rglob("*") if p.is_file() and "__pycache__" not in p.parts)
    assert root / "audit" / "rules" / "joints.py" in files and root / "templates" / "robot.urdf.j2" in files
    h = hashlib.sha256()
    for path in files:
        h.update(path.relative_to(root).as_posix().encode("utf-8") + b"\0")
        h.update(hashlib.sha256(path.read_bytes()).digest())
    evidence_hash.source_digest.cache_clear()
    assert evidence_hash.source_digest() == h.hexdigest()


def test_libyaml_loading_is_safe_loads() -> None:
    from descgen.prove.controllers import safe_load

    texts = [
        p.read_text()
        for pkg in (DESCRIPTION, "warehouse_arm_moveit_config")
        for p in sorted((ROOT / "generated" / pkg).rglob("*"))
        if p.suffix in (".yaml", ".rviz") or p.name == ".setup_assistant"
    ]
    texts.append("a: 1\nb: 1.0\nc: !!float 1\nd: 0x10\ne: yes\nf: 2001-12-14\ng: [1e3, .5, -.inf]\n")
    assert len(texts) > 5
    for text in texts:
        got, want = safe_load(text), yaml.safe_load(text)
        assert got == want and repr(got) == repr(want)  # same values, same types (1 vs 1.0)
    with pytest.raises(yaml.YAMLError):
        safe_load("a: [1, 2\n")
    with pytest.raises(yaml.YAMLError):  # no Python tags: still a safe loader
        safe_load("!!python/object/apply:os.system ['true']\n")


def test_model_values_leave_out_only_where() -> None:
    from descgen.audit.spec import load_spec
    from descgen.core.findings import Where

    robot = load_spec(EXAMPLE).robot
    moved = dataclasses.replace(robot, joints=tuple(dataclasses.replace(j, where=Where("x", 9)) for j in robot.joints))
    assert evidence_hash.model_values(moved) == evidence_hash.model_values(robot)
    j0 = robot.joints[0]
    other = dataclasses.replace(j0, name=j0.name + "_x")
    renamed = dataclasses.replace(robot, joints=(other, *robot.joints[1:]))
    assert evidence_hash.digest(evidence_hash.model_values(renamed)) != evidence_hash.digest(
        evidence_hash.model_values(robot)
    )
    assert evidence_hash.model_values((1, 1.0, -0.0)) == [1, "1.0", "-0.0"]  # 1 and 1.0 differ
    with pytest.raises(TypeError):
        evidence_hash.model_values(object())


# --- check with the cache: a copy of the example -------------------------------------------------


@pytest.fixture
def project(tmp_path: Path, cache: Path) -> Path:
    """The example spec and its committed packages, made current by ``generate`` (the committed
    packages spare the collision matrix's sampling); without the evidence page and the control
    evidence, whose records hold descgen's source hash and would be stale after any edit."""
    (tmp_path / "specs").mkdir()
    shutil.copy(EXAMPLE, tmp_path / "specs" / EXAMPLE.name)
    for pkg in (DESCRIPTION, "warehouse_arm_moveit_config"):
        shutil.copytree(ROOT / "generated" / pkg, tmp_path / "generated" / pkg)
    evidence = tmp_path / "generated" / DESCRIPTION / "evidence"
    for name in ("README.md", "verdict.json"):
        (evidence / name).unlink(missing_ok=True)
    ran = cli("generate", "specs/warehouse_arm.yaml", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr
    return tmp_path


def _counting(monkeypatch: pytest.MonkeyPatch, module: object, name: str) -> list[int]:
    calls: list[int] = []
    real = getattr(module, name)

    def counted(*args: object, **kwargs: object) -> object:
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, counted)
    return calls


def _check(project: Path) -> tuple[int, str]:
    ran = cli("check", "specs/warehouse_arm.yaml", cwd=project)
    assert "Traceback" not in ran.stderr
    return ran.returncode, ran.stderr


def test_an_unchanged_package_is_checked_without_xacro_or_catkin(
    project: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import catkin_pkg.package

    from descgen.read import xacro_file

    expansions = _counting(monkeypatch, xacro_file, "expand")
    manifests = _counting(monkeypatch, catkin_pkg.package, "parse_package_string")
    code, err = _check(project)
    assert code == 0, err
    assert expansions == [] and manifests == []  # all four expansions and both manifests were cached
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")
    code, err = _check(project)
    assert code == 0, err
    assert len(expansions) == 4 and len(manifests) == 2  # default, gazebo, real, MoveIt's; two packages


def test_a_cached_expansion_is_still_compared(project: Path) -> None:
    """A hit skips xacro, not the proof: with the rendered URDF changed (the Xacro and what it
    reads unchanged, so the same key), the cached expansion no longer matches it."""
    from descgen import prove as checks
    from descgen.commands.generate import plan

    p = plan(project / "specs" / "warehouse_arm.yaml")
    rel = f"urdf/{p.robot.name}.urdf"
    files = dict(p.files)
    assert checks.xacro_matches_urdf(files, p.robot, p.package_dir) == []  # a hit, and equal
    files[rel] = files[rel].replace('<joint name="elbow_joint"', '<joint name="elbow_joint2"', 1)
    assert files[rel] != p.files[rel]
    found = checks.xacro_matches_urdf(files, p.robot, p.package_dir)
    assert [f.code for f in found] == ["GEN001"] and "differs" in found[0].message


def test_an_expansion_is_keyed_by_its_files_args_and_environment(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.prove.xacro_expand import expand_packages
    from descgen.read import xacro_file

    calls = _counting(monkeypatch, xacro_file, "expand")
    xacro = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:arg name="a" default="1"/>'
        '<xacro:include filename="part.xacro"/><link name="l$(arg a)"/><link name="$(optenv ROS_DISTRO none)"/></robot>'
    )
    part = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="p"/></robot>'
    files = {"urdf/r.urdf.xacro": xacro, "urdf/part.xacro": part}
    monkeypatch.delenv("ROS_DISTRO", raising=False)
    first, _ = expand_packages({"pkg": files}, "pkg", "urdf/r.urdf.xacro", {})
    assert 'name="l1"' in first and 'name="p"' in first and 'name="none"' in first and len(calls) == 1
    assert expand_packages({"pkg": files}, "pkg", "urdf/r.urdf.xacro", {})[0] == first and len(calls) == 1
    assert 'name="l2"' in expand_packages({"pkg": files}, "pkg", "urdf/r.urdf.xacro", {"a": "2"})[0]
    changed = {**files, "urdf/part.xacro": part.replace('"p"', '"q"')}  # an included file changed
    assert 'name="q"' in expand_packages({"pkg": changed}, "pkg", "urdf/r.urdf.xacro", {})[0]
    monkeypatch.setenv("ROS_DISTRO", "jazzy")  # what $(optenv) sees in the sandbox
    assert 'name="jazzy"' in expand_packages({"pkg": files}, "pkg", "urdf/r.urdf.xacro", {})[0]
    assert len(calls) == 4
    broken = {**files, "urdf/part.xacro": "<robot"}
    for _ in range(2):  # a failure is never cached: xacro says so every time
        with pytest.raises(InputError):
            expand_packages({"pkg": broken}, "pkg", "urdf/r.urdf.xacro", {})
    assert len(calls) == 6


def test_manifests_are_catkin_pkgs_and_refusals_are_never_cached(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import catkin_pkg.package

    from descgen.prove.package import read_manifest

    text = (ROOT / "generated" / DESCRIPTION / "package.xml").read_text()
    calls = _counting(monkeypatch, catkin_pkg.package, "parse_package_string")
    want = catkin_pkg.package.parse_package_string(text)
    calls.clear()
    for _ in range(2):
        got = read_manifest(text)
        assert (got.format, got.name, got.exec_depends) == (
            want.package_format,
            want.name,
            tuple(d.name for d in want.exec_depends),
        )
    assert len(calls) == 1
    bad = text.replace("<license>", "<licence>", 1)
    for _ in range(2):
        with pytest.raises(catkin_pkg.package.InvalidPackage):
            read_manifest(bad)
    assert len(calls) == 3


def test_a_refused_manifest_still_prints_catkins_warnings(cache: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """catkin_pkg prints its warnings before it raises (validate collects both); read_manifest
    must too, not only for a manifest it accepts. A version with a leading zero is a warning,
    an invalid e-mail an error."""
    import re

    import catkin_pkg.package

    from descgen.prove.package import read_manifest

    text = (ROOT / "generated" / DESCRIPTION / "package.xml").read_text()
    text = re.sub(r"<version>[^<]*</version>", "<version>0.01.0</version>", text)
    text = re.sub(r'email="[^"]*"', 'email="not-an-email"', text, count=1)
    with pytest.raises(catkin_pkg.package.InvalidPackage):
        read_manifest(text)
    assert (
        'WARNING: Package "warehouse_arm_description" does not follow the version conventions'
        in capsys.readouterr().err
    )


def test_sweep_table_reused_recomputed_and_stale_reported(project: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.prove import sweep as evidence

    computed = _counting(monkeypatch, evidence, "compute")
    code, err = _check(project)
    assert code == 0, err
    assert computed == []  # the table came from the cache (generate stored it)
    sweep_md = project / "generated" / DESCRIPTION / evidence.PATH
    committed = sweep_md.read_text()
    sweep_md.write_text(committed.replace("moves tool\\_link", "moves tool\\_link nowhere", 1))
    code, err = _check(project)
    assert code == 1 and "evidence/sweep.md was edited by hand" in err
    assert computed == []
    sweep_md.write_text(committed)
    spec = project / "specs" / "warehouse_arm.yaml"
    old = "limit: {lower: -150 deg, upper: 150 deg, velocity: 120 deg/s"
    spec.write_text(spec.read_text().replace(old, old.replace("upper: 150 deg", "upper: 140 deg"), 1))
    code, err = _check(project)
    assert code == 1 and "evidence/sweep.md is stale: the spec changed" in err
    assert len(computed) >= 1
    # the table the cache gives is the table computed (the slow path, with caching off)
    from descgen.commands.generate import plan

    robot = plan(spec).robot
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")
    slow = evidence.context(robot)
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(project / "cache"))
    before = len(computed)
    assert evidence.context(robot) == slow and len(computed) == before
    # a model value the collision runs' key does not see (the matrix is not sampled again here):
    # the table is computed again, not served for the old robot
    joints = tuple(
        dataclasses.replace(j, limit=dataclasses.replace(j.limit, upper=1.0)) if j.name == "elbow_joint" else j
        for j in robot.joints
    )
    narrower = dataclasses.replace(robot, joints=joints)
    shown = evidence.context(narrower)
    assert len(computed) == before + 1
    elbow = next(j for j in shown["joints"] if j["name"] == "elbow_joint")
    assert elbow["range"].endswith("to 57.3 deg") and shown != slow  # 1 rad, by hand
