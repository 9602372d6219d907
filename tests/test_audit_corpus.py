"""The audit on real descriptions nobody here wrote (example-robot-data), and planted faults."""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

import pytest

from descgen.commands.faults import plant_all
from descgen.core.findings import Finding
from descgen.read.description import Options, audit, load_description

from .conftest import ROOT
from .corpus import FAULT_ROBOTS, counts, descriptions, share
from .helpers import cli

CORPUS = descriptions()
IDS = [ident for ident, _, _ in CORPUS]
DOC = ROOT / "docs" / "audit-corpus.md"


def test_corpus_is_installed() -> None:
    # example-robot-data is a test dependency: without it these tests would prove nothing
    assert share() is not None and len(CORPUS) >= 60


@cache
def findings_of(ident: str) -> list[Finding]:
    _, urdf, srdf = next(c for c in CORPUS if c[0] == ident)
    root = share()
    return audit(urdf, Options(srdf=srdf, package_paths=(root,) if root else ()))


def documented() -> dict[str, tuple[str, str]]:
    rows = {}
    for line in DOC.read_text().splitlines():
        m = re.match(r"^\| `([^`]+)` \| ([^|]*) \| ([^|]*) \|", line)
        if m:
            rows[m.group(1)] = (m.group(2).strip(), m.group(3).strip())
    return rows


@pytest.mark.parametrize("ident", IDS)
def test_corpus_description_audits_and_matches_the_table(ident: str) -> None:
    found = findings_of(ident)  # no InputError: every corpus file is usable input
    assert all(f.message and f.code for f in found)
    rows = documented()
    assert ident in rows, f"{ident} is not in docs/audit-corpus.md"
    errors, warnings = rows[ident]
    assert counts(found, "error") == errors, f"{ident}: errors differ from the reviewed table"
    assert counts(found, "warning") == warnings, f"{ident}: warnings differ from the reviewed table"


def test_every_table_row_has_a_reason() -> None:
    for line in DOC.read_text().splitlines():
        if line.startswith("| `"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            assert len(cells) == 4 and cells[3], line
            if cells[1] != "—" or cells[2] != "—":
                for code in re.findall(r"([A-Z]+\d{3})×", cells[1] + " " + cells[2]):
                    assert code in cells[3], f"{cells[0]}: {code} is not explained"


@pytest.mark.parametrize("ident", FAULT_ROBOTS)
def test_every_planted_fault_is_caught_on_corpus_robots(ident: str) -> None:
    _, urdf, srdf = next(c for c in CORPUS if c[0] == ident)
    robot, _ = load_description(urdf, Options(srdf=srdf, package_paths=(share(),)))  # type: ignore[arg-type]
    results = plant_all(robot)
    missed = [(r.fault.name, r.planted) for r in results if r.applicable and not r.caught]
    assert missed == []
    # only the prismatic fault may lack a place: pr2 and tiago have a torso lift, the others none
    has_prismatic = any(j.type == "prismatic" for j in robot.joints)
    assert [r.fault.name for r in results if not r.applicable] == ([] if has_prismatic else ["prismatic-travel-mm"])
    for r in results:
        assert not r.applicable or (r.by is not None and r.by.code in r.fault.expects), (r.fault.name, r.by)


def test_faults_cli_on_the_example() -> None:
    r = cli("faults", "specs/warehouse_arm.yaml", "--format", "json")
    assert r.returncode == 0, r.stderr
    import json

    doc = json.loads(r.stdout)
    assert doc["missed"] == 0 and doc["caught"] == len(doc["faults"]) == 24


def test_a_fault_the_catalogue_cannot_see_is_reported_missed(tmp_path: Path) -> None:
    """UR5 has no mirror-image joints and no measured poses: a wrong axis goes unseen, and
    the command says so with exit 1."""
    ident = "ur_description/urdf/ur5_robot.urdf"
    _, urdf, _ = next(c for c in CORPUS if c[0] == ident)
    r = cli("faults", str(urdf))
    assert r.returncode == 1
    assert re.search(r"^MISSED\s+wrong-axis", r.stdout, re.M)
