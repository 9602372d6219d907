"""``--format junit`` for validate, check and audit, read back by junitparser (the JUnit reader
CI tooling uses: its suites, cases and results) and its ``verify`` command (non-zero exactly
when a case failed). Expected failures come from the specs and files by hand: a planted error is
one failing case, warnings fail only with ``--strict``, and a stale package fails per stale file
with the diff shown on the command's own case."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from junitparser import Failure, JUnitXml
from lxml import etree

from descgen.core.findings import Finding, Where
from descgen.output.report import junit
from tests.helpers import EXAMPLE_TEXT, ROOT, cli, plant, user_project


def _read(xml: str) -> JUnitXml:
    doc = JUnitXml.fromstring(xml.encode("utf-8"))
    assert isinstance(doc, JUnitXml)
    return doc


def _failures(doc: JUnitXml) -> list[tuple[str, str, str]]:
    """(suite, case, failure type) of every failing case."""
    out = []
    for suite in doc:
        for case in suite:
            out += [(suite.name, case.name, r.type) for r in case.result if isinstance(r, Failure)]
    return out


def _verify(xml: str, tmp_path: Path) -> int:
    report = tmp_path / "report.xml"
    report.write_text(xml)
    return subprocess.run([sys.executable, "-m", "junitparser", "verify", str(report)], capture_output=True).returncode


def test_validate_one_good_one_bad_spec(tmp_path: Path) -> None:
    good = tmp_path / "good.yaml"
    good.write_text(EXAMPLE_TEXT)
    bad = tmp_path / "bad.yaml"
    bad.write_text(plant("mass: {value: 28.0 kg", "mass: {value: 28.0 furlongs"))
    done = cli("validate", "--format", "junit", good, bad)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    doc = _read(done.stdout)
    assert [s.name for s in doc] == [str(good), str(bad)]
    assert [(suite, case.split()[0], kind) for suite, case, kind in _failures(doc)] == [(str(bad), "UNIT003", "error")]
    assert doc.tests == sum(s.tests for s in doc) and doc.failures == 1
    assert _verify(done.stdout, tmp_path) != 0


def test_validate_clean_spec_passes_verify(tmp_path: Path) -> None:
    done = cli("validate", "--format", "junit", ROOT / "specs" / "warehouse_arm.yaml")
    assert done.returncode == 0
    doc = _read(done.stdout)
    assert _failures(doc) == [] and doc.tests >= 1
    assert _verify(done.stdout, tmp_path) == 0


def test_check_stale_package_fails_per_stale_file_with_the_diff(tmp_path: Path) -> None:
    project = user_project(tmp_path)
    urdf = project / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"
    urdf.write_text(urdf.read_text().replace('<link name="tool_link"', '<link name="tool_link_edited"', 1))
    done = cli("check", "--format", "junit", project / "specs" / "warehouse_arm.yaml", cwd=project)
    assert done.returncode == 1 and "Traceback" not in done.stderr
    doc = _read(done.stdout)
    failing = _failures(doc)
    assert ("GEN004 file:urdf/warehouse_arm.urdf", "error") in [(case, kind) for _, case, kind in failing]
    assert all(case.startswith("GEN0") for _, case, _ in failing)  # the stale file and what it invalidates
    (suite,) = list(doc)
    (own,) = [c for c in suite if c.name == "check"]
    assert "tool_link_edited" in (own.system_out or "") and own.is_passed
    assert _verify(done.stdout, tmp_path) != 0


def test_audit_warnings_fail_only_with_strict(tmp_path: Path) -> None:
    urdf = tmp_path / "r.urdf"
    # a tree without any <inertial>: GEOM040, a warning (Gazebo drops the links), and no error
    urdf.write_text(
        '<robot name="r"><link name="a"/><link name="b"/>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>'
    )
    plain = cli("audit", "--format", "junit", urdf)
    strict = cli("audit", "--format", "junit", "--strict", urdf)
    assert plain.returncode == 0 and strict.returncode == 1
    assert _failures(_read(plain.stdout)) == []
    failing = _failures(_read(strict.stdout))
    assert [(case.split()[0], kind) for _, case, kind in failing] == [("GEOM040", "warning")]
    assert _verify(plain.stdout, tmp_path) == 0 and _verify(strict.stdout, tmp_path) != 0


def test_values_that_xml_cannot_hold_are_escaped() -> None:
    hostile = "a\x00b\x1b[31m]]></failure><x>&amp;\ud800"
    found = [Finding("GEN001", "error", hostile, hostile, f"link:{hostile}", Where(f"f{hostile}.urdf", 3, 1))]
    xml = junit("audit", [(f"f{hostile}.urdf", found, hostile)])
    root = etree.fromstring(xml.encode("utf-8"))  # lxml refuses any character XML 1.0 cannot hold
    (failure,) = root.iter("failure")
    assert failure.get("message") == "a\\x00b\\x1b[31m]]></failure><x>&amp;\\xd800"
    assert len(list(root.iter("x"))) == 0
    assert _failures(_read(xml)) == [
        (
            f"fa{chr(92)}x00b{chr(92)}x1b[31m]]></failure><x>&amp;{chr(92)}xd800.urdf",
            failure.getparent().get("name"),
            "error",
        )
    ]


@pytest.mark.parametrize("command", ["validate", "check", "audit"])
def test_junit_is_offered(command: str) -> None:
    assert "junit" in cli(command, "--help").stdout
