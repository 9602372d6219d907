"""The waivers a generated package carries (descgen-waivers.yaml, descgen/read/package_waivers.py):
generate writes the spec's waivers beside the description, so ``descgen audit`` of the generated
files gives check's verdict (issue 29, one verdict). The planted defect's finding with no waiver
(``--no-waivers``) is the oracle that the waiver, not a quiet rule, makes the audit pass."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import yaml

from .conftest import ROOT
from .helpers import cli, plant

SPEC = "specs/warehouse_arm.yaml"
ZERO_EFFORT = ("velocity: 120 deg/s, effort: 20 N*m, source: M21,", "velocity: 120 deg/s, effort: 0 N*m, source: M21,")
# a reason a YAML writer must quote and escape: a colon, a comment mark, both quotes, not ASCII
REASON = 'ticket "42": the elbow # is re-measured, it\'s \u00e9lan: - [next] {week}'
WAIVER = {"code": "JOINT005", "subject": "joint:elbow_joint", "reason": REASON}


@pytest.fixture(scope="module")
def package(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The example robot with its elbow's effort limit planted at 0 and that finding waived,
    generated and checked once; tests copy the package before changing it."""
    root = tmp_path_factory.mktemp("waived")
    (root / "specs" / "trajectories").mkdir(parents=True)
    data = yaml.safe_load(plant(*ZERO_EFFORT))
    data["waivers"] = [WAIVER]
    (root / SPEC).write_text(yaml.safe_dump(data, sort_keys=False))
    shutil.copy(ROOT / "specs" / "trajectories" / "ready.yaml", root / "specs" / "trajectories" / "ready.yaml")
    assert cli("generate", root / SPEC).returncode == 0
    assert cli("check", root / SPEC).returncode == 0
    return root / "generated" / "warehouse_arm_description"


def _copy(package: Path, tmp_path: Path) -> Path:
    copy = tmp_path / package.name
    shutil.copytree(package, copy)
    return copy


def _stamped(body: str) -> str:
    """A waivers file as generate writes it: descgen's header over ``body``."""
    from descgen.render import header

    return header.add("descgen-waivers.yaml", body, "specs/warehouse_arm.yaml", "0" * 64)


def _audit(package: Path, *more: object) -> tuple[int, str]:
    ran = cli(
        "audit",
        package / "urdf" / "warehouse_arm.urdf",
        "--srdf",
        package / "srdf" / "warehouse_arm.srdf",
        "--controllers",
        package / "config" / "ros2_controllers.yaml",
        *more,
    )
    return ran.returncode, ran.stderr


def test_generate_writes_the_spec_waivers_exactly(package: Path) -> None:
    doc = yaml.safe_load((package / "descgen-waivers.yaml").read_text(encoding="utf-8"))
    assert doc == {"waivers": [WAIVER]}  # the reason's quotes, colon and '#' read back as written


def test_the_audit_of_the_generated_files_gives_checks_verdict(package: Path) -> None:
    code, err = _audit(package)
    assert code == 0, err
    assert "error[JOINT005]" in err and "waived: ticket" in err and "(descgen-waivers.yaml)" in err
    for description in ("warehouse_arm.urdf.xacro", "warehouse_arm.urdf"):
        assert cli("audit", package / "urdf" / description).returncode == 0
    code, err = _audit(package, "--no-waivers")
    assert code == 1 and "error[JOINT005]" in err and "waived:" not in err


def test_an_example_without_waivers_has_no_file() -> None:
    assert not (ROOT / "generated" / "warehouse_arm_description" / "descgen-waivers.yaml").exists()


def test_only_the_package_holding_the_description_is_read(package: Path, tmp_path: Path) -> None:
    copy = _copy(package, tmp_path)
    (copy / "package.xml").unlink()  # no package: the file beside is nobody's
    assert _audit(copy)[0] == 1


def test_only_a_rules_finding_can_be_waived(package: Path, tmp_path: Path) -> None:
    copy = _copy(package, tmp_path)
    doc = {"waivers": [{**WAIVER, "code": "READ001"}, {**WAIVER, "subject": "joint:shoulder_joint"}]}
    (copy / "descgen-waivers.yaml").write_text(_stamped(yaml.safe_dump(doc)))
    code, err = _audit(copy)
    assert code == 1 and "waived:" not in err


@pytest.mark.parametrize(
    ("text", "line"),
    [
        ("- code: JOINT005\n", 1),  # a list, not a mapping
        ("waivers:\n  - {code: JOINT005, subject: 'joint:elbow_joint'}\n", 2),  # no reason
        ("waivers:\n  - {code: JOINT005, subject: 'joint:elbow_joint', reason: 1}\n", 2),  # not a string
        ("waivers:\n  - {code: JOINT005, subject: x, reason: y, also: z}\n", 2),  # a key too many
        ("waivers: []\nmore: 1\n", 1),  # another top-level key
        ("waivers: [\n", 2),  # not YAML
    ],
)
def test_a_waivers_file_that_is_not_one_is_an_error_at_its_line(
    package: Path, tmp_path: Path, text: str, line: int
) -> None:
    copy = _copy(package, tmp_path)
    (copy / "descgen-waivers.yaml").write_text(_stamped(text))
    code, err = _audit(copy)
    assert code == 2 and "Traceback" not in err, err
    assert f"descgen-waivers.yaml:{line + 2}:" in err and ("error[READ049]" in err or "error[YAML001]" in err)
    assert _audit(copy, "--no-waivers")[0] == 1  # ignored on request: the raw verdict


def test_a_changed_waivers_file_is_read_again_with_the_findings_cache_on(
    package: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The findings cache keeps the rules' findings, never the waivers applied to them."""
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(tmp_path / "cache"))
    copy = _copy(package, tmp_path)
    urdf = copy / "urdf" / "warehouse_arm.urdf"
    assert cli("audit", urdf).returncode == 0
    (copy / "descgen-waivers.yaml").write_text(_stamped("waivers: []\n"))
    assert cli("audit", urdf).returncode == 1


@pytest.mark.parametrize("how", ["no header", "edited after generate"])
def test_a_waivers_file_generate_did_not_write_is_refused(package: Path, tmp_path: Path, how: str) -> None:
    """A file that only looks like waivers (a third party's, one in a folder above that is no
    package of this robot, or one edited by hand) waives nothing: READ049, exit 2."""
    copy = _copy(package, tmp_path)
    target = copy / "descgen-waivers.yaml"
    text = target.read_text()
    if how == "no header":
        text = text.split("\n", 2)[2]
    else:
        text = text.replace("joint:elbow_joint", "joint:shoulder_lift_joint")
    target.write_text(text)
    code, err = _audit(copy)
    assert code == 2 and "error[READ049]" in err and "not the one descgen generate wrote" in err
    assert _audit(copy, "--no-waivers")[0] == 1
