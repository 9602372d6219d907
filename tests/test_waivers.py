"""Waivers (issue 29): a spec accepts a finding by its code and subject, with a reason. The
finding is still reported, as waived, in every output; it fails nothing; a waiver that matches
nothing is SPEC130. The defects are planted in the example spec; what each command prints and
exits with is the oracle (the exit code contract: README, Commands)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
import yaml

from .conftest import ROOT
from .helpers import EXAMPLE_TEXT, cli, plant

SPEC = "specs/warehouse_arm.yaml"
# the elbow's effort limit planted at 0: JOINT005, an input-stage rule (validate)
ZERO_EFFORT = ("velocity: 120 deg/s, effort: 20 N*m, source: M21,", "velocity: 120 deg/s, effort: 0 N*m, source: M21,")
JOINT005 = {"code": "JOINT005", "subject": "joint:elbow_joint", "reason": "the elbow is re-measured (ticket 42)"}


def _project(tmp_path: Path, text: str, waivers: list[dict[str, str]]) -> Path:
    (tmp_path / "specs" / "trajectories").mkdir(parents=True)
    data = yaml.safe_load(text)
    if waivers:
        data["waivers"] = waivers
    (tmp_path / SPEC).write_text(yaml.safe_dump(data, sort_keys=False))
    shutil.copy(ROOT / "specs" / "trajectories" / "ready.yaml", tmp_path / "specs" / "trajectories" / "ready.yaml")
    return tmp_path / SPEC


def test_a_waived_error_is_reported_everywhere_and_fails_nothing(tmp_path: Path) -> None:
    text = plant(*ZERO_EFFORT)
    unwaived = _project(tmp_path / "a", text, [])
    assert cli("validate", unwaived).returncode == 2  # the planted defect fails without a waiver

    spec = _project(tmp_path / "b", text, [JOINT005])
    ran = cli("validate", spec)
    assert ran.returncode == 0, ran.stderr
    assert "error[JOINT005]" in ran.stderr and f"  waived: {JOINT005['reason']}" in ran.stderr
    doc = json.loads(cli("validate", spec, "--format", "json").stdout)
    (f,) = [f for f in doc["findings"] if f["code"] == "JOINT005"]
    assert f["waived"] == JOINT005["reason"] and f["severity"] == "error"
    assert doc["summary"]["waived"] == 1 and doc["summary"]["error"] == 0
    sarif = json.loads(cli("audit", spec, "--format", "sarif").stdout)
    (result,) = [r for r in sarif["runs"][0]["results"] if r["ruleId"] == "JOINT005"]
    assert result["suppressions"] == [{"kind": "inSource", "justification": JOINT005["reason"]}]
    junit = cli("validate", spec, "--format", "junit").stdout
    assert 'failures="0"' in junit and "JOINT005" in junit
    assert cli("audit", spec).returncode == 0
    assert cli("generate", spec).returncode == 0
    checked = cli("check", spec)
    assert checked.returncode == 0 and "waived:" in checked.stderr
    # the evidence page lists what is accepted for now in a section of its own
    assert cli("control", spec, "--trajectory", spec.parent / "trajectories" / "ready.yaml").returncode == 0
    assert cli("report", spec).returncode == 0
    page = (spec.parent.parent / "generated" / "warehouse_arm_description" / "evidence" / "README.md").read_text()
    section = page.split("## 10. Waivers", 1)[1]
    assert "| `JOINT005` | `joint:elbow_joint` | the elbow is re-measured (ticket 42) |" in section
    assert "**Verdict: WAIVED**: 1 waiver(s)" in section


@pytest.mark.parametrize(
    ("waiver", "says"),
    [
        ({"code": "JOINT005", "subject": "joint:shoulder_pan_joint", "reason": "a typo in the subject"}, "matches no"),
        ({"code": "GEN001", "subject": "file:urdf/warehouse_arm.urdf", "reason": "a proof"}, "no audit rule's code"),
    ],
)
def test_a_waiver_that_matches_nothing_is_spec130(tmp_path: Path, waiver: dict[str, str], says: str) -> None:
    spec = _project(tmp_path, plant(*ZERO_EFFORT), [JOINT005, waiver])
    ran = cli("validate", spec, "--format", "json")
    assert ran.returncode == 0
    found = [f for f in json.loads(ran.stdout)["findings"] if f["code"] == "SPEC130"]
    assert [(f["severity"], f["line"]) for f in found] == [("warning", _line_of_waiver(spec, 1))]
    assert says in found[0]["message"]


def _line_of_waiver(spec: Path, index: int) -> int:
    lines = spec.read_text().splitlines()
    start = lines.index("waivers:")
    items = [i for i, line in enumerate(lines[start:], start) if line.startswith("- ")]
    return items[index] + 1


def test_a_check_stage_code_is_judged_by_validate_and_generate(tmp_path: Path) -> None:
    """POSE010 (a known pose off its forward kinematics) is a check-stage rule; validate runs it
    too (issue 29: "valid" means generate's rules pass), and both honour its waiver."""
    # the camera measured 5 mm off in the 'ready' pose
    text = EXAMPLE_TEXT.replace("xyz: [211 mm, 0 mm, 884 mm]", "xyz: [216 mm, 0 mm, 884 mm]", 1)
    assert text != EXAMPLE_TEXT
    pose = {"code": "POSE010", "subject": "pose:ready", "reason": "the camera mount is being reworked"}
    spec = _project(tmp_path / "a", text, [pose])
    validated = cli("validate", spec)
    assert validated.returncode == 0 and "SPEC130" not in validated.stderr
    assert "error[POSE010]" in validated.stderr and "waived: the camera mount" in validated.stderr
    generated = cli("generate", spec)
    assert generated.returncode == 0, generated.stderr
    assert "error[POSE010]" in generated.stderr and "waived: the camera mount" in generated.stderr
    assert cli("check", spec).returncode == 0
    # the same waiver on a spec without the defect: unused, said by both
    clean = _project(tmp_path / "b", EXAMPLE_TEXT, [pose])
    assert cli("validate", clean).stderr.count("warning[SPEC130]") == 1
    assert "warning[SPEC130]" in cli("generate", clean).stderr
    # and without the waiver the planted pose fails validate (2, invalid) and generate (1, a check)
    bad = _project(tmp_path / "c", text, [])
    refused = cli("validate", bad)
    assert refused.returncode == 2 and refused.stderr.count("error[POSE010]") == 1
    assert "valid:" not in refused.stdout
    assert cli("generate", bad).returncode == 1
