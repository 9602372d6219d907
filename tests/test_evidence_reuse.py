"""``descgen check`` takes the committed evidence page and control evidence without computing
them again when their recorded inputs are unchanged (descgen/infra/evidence_hash.py), computes them
exactly as before when an input changed, and never takes a result edited with its hash kept.

The expensive functions are replaced by ones that raise (or count): a check that passes with
them raising did not compute; one that reports a stale file after an input changed did."""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from descgen.commands import evidence_page
from descgen.commands.control import evidence_check
from descgen.commands.generate import check
from descgen.infra import evidence_hash

from .conftest import ROOT
from .helpers import cli

PKG = "warehouse_arm_description"
MOVEIT = "warehouse_arm_moveit_config"
SPEC = "specs/warehouse_arm.yaml"
TRAJECTORY = "specs/trajectories/ready.yaml"


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy of the repository's example (spec, trajectory, both packages) whose control
    evidence and page were written again here, so they record this descgen's inputs (the
    committed records may be of other library versions, or of a format version bumped since)."""
    root = tmp_path_factory.mktemp("recorded")
    (root / "specs" / "trajectories").mkdir(parents=True)
    shutil.copy(ROOT / SPEC, root / SPEC)
    shutil.copy(ROOT / TRAJECTORY, root / TRAJECTORY)
    shutil.copytree(ROOT / "generated" / PKG, root / "generated" / PKG)
    shutil.copytree(ROOT / "generated" / MOVEIT, root / "generated" / MOVEIT)
    verdict = root / "generated" / PKG / "evidence" / "verdict.json"
    data = json.loads(verdict.read_text())
    data["reuse"] = {"input-sha256": "0" * 64, "content-sha256": "0" * 64}  # as if recorded by another descgen
    verdict.write_text(json.dumps(data, indent=2) + "\n")
    # report runs the control evidence again, finds it current and records today's inputs
    assert cli("report", SPEC, cwd=root).returncode == 0
    again = json.loads(verdict.read_text())
    assert again["reuse"]["input-sha256"] != "0" * 64
    assert {k: v for k, v in again.items() if k != "reuse"} == {k: v for k, v in data.items() if k != "reuse"}
    return root


@pytest.fixture
def project(recorded: Path, tmp_path: Path) -> Path:
    """The recorded copy, copied again to another path (the records hold no absolute path)."""
    shutil.copytree(recorded, tmp_path / "p")
    return tmp_path / "p"


def _refuse(what: str) -> Callable[..., Any]:
    def refused(*args: object, **kwargs: object) -> Any:
        raise AssertionError(f"{what} was computed although its recorded inputs are unchanged")

    return refused


def _counted(fn: Callable[..., Any], calls: list[str], name: str) -> Callable[..., Any]:
    def counted(*args: Any, **kwargs: Any) -> Any:
        calls.append(name)
        return fn(*args, **kwargs)

    return counted


def _errors(project: Path) -> list[tuple[str, str]]:
    return [(f.code, f.subject) for f in check(project / SPEC).findings if f.severity == "error"]


@pytest.fixture
def counting(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    calls: list[str] = []
    monkeypatch.setattr(evidence_page, "build", _counted(evidence_page.build, calls, "page"))
    monkeypatch.setattr(evidence_check, "_rerun", _counted(evidence_check._rerun, calls, "control"))
    return calls


def test_unchanged_inputs_reuse_the_committed_page_and_control_run(
    project: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # the files record their input hashes (written by descgen report / control)
    page = (project / "generated" / PKG / evidence_page.PAGE).read_text()
    verdict = json.loads((project / "generated" / PKG / "evidence" / "verdict.json").read_text())
    assert evidence_hash.STAMP.search(page.splitlines()[-1])
    assert set(verdict["reuse"]) == {"input-sha256", "content-sha256"}
    monkeypatch.setattr(evidence_page, "build", _refuse("the evidence page"))
    monkeypatch.setattr(evidence_check, "_rerun", _refuse("the control run"))
    assert _errors(project) == []


def test_a_changed_spec_is_computed_again_and_reported_stale(project: Path, counting: list[str]) -> None:
    spec = project / SPEC
    text = spec.read_text()
    assert "mass: {value: 28.0 kg, source: M06}" in text
    spec.write_text(text.replace("mass: {value: 28.0 kg, source: M06}", "mass: {value: 29.0 kg, source: M06}"))
    found = _errors(project)
    assert ("GEN005", "file:urdf/warehouse_arm.urdf") in found  # as without reuse
    assert ("GEN080", f"file:{evidence_page.PAGE}") in found  # the page shows the new check output
    assert sorted(counting) == ["control", "page"]  # both computed again


def test_a_changed_trajectory_runs_the_control_evidence_again(project: Path, counting: list[str]) -> None:
    trajectory = project / TRAJECTORY
    trajectory.write_text(trajectory.read_text() + "\n# a comment: the same points, other bytes\n")
    assert _errors(project) == []  # the same run: nothing stale
    assert counting == ["control"]  # but it was run (the page's inputs did not change)


def test_an_edit_to_descgens_source_alone_computes_nothing_again(
    project: Path, counting: list[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # committed evidence is keyed by format versions and the release (descgen/infra/keys.py
    # EVIDENCE), not by the bytes of descgen's source: a comment or a refactoring keeps it current
    monkeypatch.setattr(evidence_hash, "source_digest", lambda: "0" * 64)  # descgen's code edited
    assert _errors(project) == []
    assert counting == []


@pytest.mark.parametrize("bumped", ["page", "control"])
def test_another_descgen_computes_again(
    project: Path, counting: list[str], monkeypatch: pytest.MonkeyPatch, bumped: str
) -> None:
    """A bumped format version (what computes the evidence changed) computes it again; another
    release does too (tests/test_keys.py: the release is in every committed key)."""
    from descgen.commands.control import record

    bumping = evidence_page if bumped == "page" else record
    monkeypatch.setattr(bumping, "FORMAT", bumping.FORMAT + 1)
    assert _errors(project) == []  # the same results today
    assert counting == [bumped]


def test_recompute_refuses_every_record(project: Path, counting: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """DESCGEN_RECOMPUTE=1 (tests/test_evidence_recompute.py): computed again though current."""
    monkeypatch.setenv(evidence_hash.RECOMPUTE_ENV, "1")
    assert _errors(project) == []
    assert sorted(counting) == ["control", "page"]


def test_a_tampered_page_with_its_hash_kept_fails(project: Path, counting: list[str]) -> None:
    target = project / "generated" / PKG / evidence_page.PAGE
    page = target.read_text()
    row = "| known poses match forward kinematics | passed |"
    assert row in page
    target.write_text(page.replace(row, "| known poses match forward kinematics | passed (checked twice) |"))
    assert ("GEN080", f"file:{evidence_page.PAGE}") in _errors(project)
    assert "page" in counting


def test_a_tampered_verdict_with_its_hash_kept_fails(project: Path, counting: list[str]) -> None:
    target = project / "generated" / PKG / "evidence" / "verdict.json"
    verdict = json.loads(target.read_text())
    verdict["tracking"]["elbow_joint"] = 0.001  # a better-looking result, reuse record untouched
    target.write_text(json.dumps(verdict, indent=2) + "\n")
    assert ("GEN005", "file:evidence/verdict.json") in _errors(project)
    assert "control" in counting


def test_a_tampered_recording_with_its_hash_kept_is_computed_again(project: Path, counting: list[str]) -> None:
    bag = project / "generated" / PKG / "evidence" / "control_run"
    mcap = next(bag.glob("*.mcap"))
    mcap.write_bytes(mcap.read_bytes()[:-64])  # a truncated recording
    assert ("GEN005", "file:evidence/control_run/") in _errors(project)
    assert "control" in counting


def test_a_deleted_plot_is_reported_missing(project: Path, counting: list[str]) -> None:
    (project / "generated" / PKG / "evidence" / "elbow_joint.png").unlink()
    assert ("GEN006", "file:evidence/elbow_joint.png") in _errors(project)


def test_the_record_is_over_its_own_content() -> None:
    key = evidence_hash.digest({"a": [1, 2.5]})
    assert key == evidence_hash.digest({"a": [1, 2.5]}) != evidence_hash.digest({"a": [1, 2.25]})
    record = evidence_hash.recorded(f"<!-- {evidence_hash.stamp(key, 'result')} -->")
    assert evidence_hash.reusable(record, key, "result")
    assert not evidence_hash.reusable(record, key, "result edited")
    assert not evidence_hash.reusable(record, evidence_hash.digest({}), "result")
    assert not evidence_hash.reusable(None, key, "result")


def test_committed_evidence_outlives_a_python_patch_release(monkeypatch: pytest.MonkeyPatch) -> None:
    # a checkout on Debian 12's Python 3.11.2 reuses evidence committed from 3.11.7 (a fresh CI
    # runner recomputed every piece of it, importing numpy, when the identity held the patch)
    from types import SimpleNamespace

    from descgen.infra import keys, result_cache

    monkeypatch.setattr(keys, "sys", SimpleNamespace(version_info=(3, 11, 7, "final", 0)))
    committed, cache_key = keys.key("x", 1, {}, (), keys.EVIDENCE), result_cache.key("x", {})
    monkeypatch.setattr(keys, "sys", SimpleNamespace(version_info=(3, 11, 2, "final", 0)))
    assert keys.key("x", 1, {}, (), keys.EVIDENCE) == committed
    # the local result cache stays strict: another patch release is another key
    assert result_cache.key("x", {}) != cache_key
    monkeypatch.setattr(keys, "sys", SimpleNamespace(version_info=(3, 12, 0, "final", 0)))
    assert keys.key("x", 1, {}, (), keys.EVIDENCE) != committed
