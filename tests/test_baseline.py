"""``audit --baseline`` / ``--write-baseline`` (issue 29): for descriptions descgen did not
write, CI fails only on new findings. The fixture is CTRL006's suspended base with its planted
unit slip (tests/rules/CTRL006/bad11): the exit codes are the oracle (README, Commands)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from .conftest import ROOT
from .helpers import cli

RULES = ROOT / "tests" / "rules" / "CTRL006"


def _robot(tmp_path: Path) -> tuple[Path, Path]:
    shutil.copy(RULES / "bad11.urdf", tmp_path / "r.urdf")
    shutil.copy(RULES / "bad11.controllers.yaml", tmp_path / "c.yaml")
    return tmp_path / "r.urdf", tmp_path / "c.yaml"


def test_only_new_findings_fail(tmp_path: Path) -> None:
    _, controllers = _robot(tmp_path)
    assert cli("audit", "r.urdf", "--controllers", "c.yaml", cwd=tmp_path).returncode == 1  # the defects fail
    wrote = cli("audit", "r.urdf", "--controllers", "c.yaml", "--write-baseline", "base.json", cwd=tmp_path)
    assert wrote.returncode == 1 and "wrote base.json" in wrote.stderr  # writing changes no verdict
    entries = json.loads((tmp_path / "base.json").read_text())["findings"]
    assert ("CTRL006", "controller:diff_drive_controller", "c.yaml") in {
        (e["code"], e["subject"], e["file"]) for e in entries
    }
    again = cli(
        "audit", "r.urdf", "--controllers", "c.yaml", "--baseline", "base.json", "--format", "json", cwd=tmp_path
    )
    assert again.returncode == 0
    doc = json.loads(again.stdout)
    assert doc["summary"]["error"] == 0 and doc["summary"]["waived"] == len(entries)
    # a new defect of the same controller (another parameter, another message) fails
    controllers.write_text(controllers.read_text().replace("wheel_radius: 0.036", "wheel_radius: 0.36"))
    new = cli("audit", "r.urdf", "--controllers", "c.yaml", "--baseline", "base.json", "--format", "json", cwd=tmp_path)
    assert new.returncode == 1
    failing = [f for f in json.loads(new.stdout)["findings"] if f["severity"] == "error" and "waived" not in f]
    assert [(f["code"], "wheel_radius" in f["message"]) for f in failing] == [("CTRL006", True)]
    # the old defect fixed: its entry is unused (BASE002, a warning), nothing fails
    controllers.write_text(
        controllers.read_text().replace("wheel_radius: 0.36", "wheel_radius: 0.036").replace("23.3", "0.233")
    )
    fixed = cli("audit", "r.urdf", "--controllers", "c.yaml", "--baseline", "base.json", cwd=tmp_path)
    assert fixed.returncode == 0 and fixed.stderr.count("warning[BASE002]") == 1


def test_a_baseline_that_is_not_one_is_exit_2(tmp_path: Path) -> None:
    _robot(tmp_path)
    (tmp_path / "bad.json").write_text('{"findings": []}')
    ran = cli("audit", "r.urdf", "--baseline", "bad.json", cwd=tmp_path)
    assert ran.returncode == 2 and "error[BASE001]" in ran.stderr and "Traceback" not in ran.stderr
    ran = cli("audit", "r.urdf", "--write-baseline", str(tmp_path / "no" / "such" / "x.json"), cwd=tmp_path)
    assert ran.returncode == 2 and "error[BASE003]" in ran.stderr
