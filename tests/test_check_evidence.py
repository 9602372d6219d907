"""`descgen check` covers the committed control evidence: it runs the recorded trajectory again
and reports evidence that no longer matches like a stale generated file (GEN005/006/007)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from descgen.commands.generate import check

from .conftest import ROOT
from .helpers import cli

PKG = "warehouse_arm_description"
SPEC = "specs/warehouse_arm.yaml"
TRAJECTORY = "specs/trajectories/ready.yaml"
RERUN = f"re-run descgen control {SPEC} --trajectory {TRAJECTORY} and commit the result"


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A copy of the repository's example: spec, trajectory and the committed package."""
    (tmp_path / "specs" / "trajectories").mkdir(parents=True)
    shutil.copy(ROOT / SPEC, tmp_path / SPEC)
    shutil.copy(ROOT / TRAJECTORY, tmp_path / TRAJECTORY)
    # without the evidence page (tests/test_evidence_page.py): these tests are about the control run
    shutil.copytree(ROOT / "generated" / PKG, tmp_path / "generated" / PKG, ignore=shutil.ignore_patterns("README.md"))
    moveit = "warehouse_arm_moveit_config"  # the spec's moveit: package, which check compares too
    shutil.copytree(ROOT / "generated" / moveit, tmp_path / "generated" / moveit)
    return tmp_path


def evidence_findings(project: Path) -> list[tuple[str, str]]:
    """(code, subject) of every finding check makes about evidence the control run wrote."""
    out = check(project / SPEC)
    return [(f.code, f.subject) for f in out.findings if f.subject.startswith("file:")]


def test_the_committed_evidence_is_what_its_recorded_run_gives(project: Path) -> None:
    verdict = json.loads((project / "generated" / PKG / "evidence" / "verdict.json").read_text())
    # the evidence says what produced it, relative to the project (the README's command)
    assert verdict["run"]["trajectory"] == TRAJECTORY
    assert verdict["run"]["duration_s"] is None and verdict["run"]["plant"]["kind"] == "mock"
    assert evidence_findings(project) == []


def test_a_changed_csv_value_is_stale_with_the_command_to_rerun(project: Path) -> None:
    csv = project / "generated" / PKG / "evidence" / "desired_vs_measured.csv"
    lines = csv.read_text().splitlines(keepends=True)
    # the first row after the header (0.010 s, lift_joint): desired 0.75 mm made 1.75 mm
    assert lines[1].startswith("0.010,lift_joint,")
    lines[1] = lines[1].replace(",0.00075,0.00075,", ",0.00175,0.00075,", 1)
    csv.write_text("".join(lines))
    found = check(project / SPEC).findings
    [f] = [f for f in found if f.code.startswith("GEN")]
    assert (f.code, f.subject) == ("GEN005", "file:evidence/desired_vs_measured.csv")
    assert f.where.file == str(csv) and f.hint == RERUN


def test_a_last_digit_difference_is_not_stale(project: Path) -> None:
    # another libm may print the last digits differently: a change of 1e-13 in 7.5e-4 is a
    # relative 1.3e-10, inside the 1e-9 tolerance
    csv = project / "generated" / PKG / "evidence" / "desired_vs_measured.csv"
    text = csv.read_text()
    csv.write_text(text.replace("0.010,lift_joint,0.00075,", "0.010,lift_joint,0.0007500000001,", 1))
    assert csv.read_text() != text
    assert evidence_findings(project) == []


def test_a_changed_trajectory_makes_the_data_stale(project: Path) -> None:
    traj = project / TRAJECTORY
    traj.write_text(traj.read_text().replace('"-90 deg"]', '"-80 deg"]'))
    found = set(evidence_findings(project))
    # the elbow's desired and measured positions change: the table, the verdict's tracking
    # error and the recording; the lifecycle (no position in it) and interfaces do not
    assert found == {
        ("GEN005", "file:evidence/desired_vs_measured.csv"),
        ("GEN005", "file:evidence/verdict.json"),
        ("GEN005", "file:evidence/control_run/"),
    }


def test_a_recording_of_another_run_is_stale(project: Path, tmp_path: Path) -> None:
    other = tmp_path / "other"
    short = tmp_path / "short.yaml"
    short.write_text(
        "controller: arm_controller\njoints: [elbow_joint]\n"
        'points:\n  - {time_from_start: "1 s", positions: ["-10 deg"]}\n'
    )
    r = cli("control", project / SPEC, "--trajectory", short, "--out", other, cwd=project)
    assert r.returncode == 0, r.stderr
    bag = project / "generated" / PKG / "evidence" / "control_run"
    shutil.rmtree(bag)
    shutil.copytree(other / "control_run", bag)
    assert evidence_findings(project) == [("GEN005", "file:evidence/control_run/")]


def test_evidence_without_its_run_record_is_stale(project: Path) -> None:
    path = project / "generated" / PKG / "evidence" / "verdict.json"
    verdict = json.loads(path.read_text())
    del verdict["run"]
    path.write_text(json.dumps(verdict, indent=2) + "\n")
    found = check(project / SPEC).findings
    [f] = [f for f in found if f.code.startswith("GEN")]
    assert (f.code, f.subject) == ("GEN005", "file:evidence/verdict.json")
    assert "does not record the run" in f.message and "descgen control" in f.hint


def test_a_missing_trajectory_is_reported_not_a_traceback(project: Path) -> None:
    (project / TRAJECTORY).unlink()
    r = cli("check", project / SPEC, cwd=project)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "error[GEN005]: evidence/verdict.json cannot be reproduced" in r.stderr


def test_plots_missing_or_left_over_but_not_their_bytes(project: Path) -> None:
    evidence = project / "generated" / PKG / "evidence"
    # PNG bytes depend on matplotlib's version and fonts: not compared (their data is the CSV's)
    (evidence / "lift_joint.png").write_bytes(b"\x89PNG\r\n\x1a\n other bytes")
    assert evidence_findings(project) == []
    (evidence / "elbow_joint.png").unlink()
    (evidence / "wrist_joint.png").write_bytes(b"\x89PNG\r\n\x1a\n")
    assert sorted(evidence_findings(project)) == [
        ("GEN006", "file:evidence/elbow_joint.png"),
        ("GEN007", "file:evidence/wrist_joint.png"),
    ]


def test_a_package_without_control_evidence_has_nothing_to_check(project: Path) -> None:
    evidence = project / "generated" / PKG / "evidence"
    for name in ("verdict.json", "desired_vs_measured.csv", "lifecycle.jsonl", "lifecycle.md", "interfaces.md"):
        (evidence / name).unlink()
    shutil.rmtree(evidence / "control_run")
    for png in evidence.glob("*.png"):
        png.unlink()
    assert evidence_findings(project) == []
