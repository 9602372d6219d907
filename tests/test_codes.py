"""The one catalogue of finding codes (descgen/codes/__init__.py plus the audit rules).

The session-wide check that every code a test saw descgen make is registered lives in
conftest.py (tests/codes_seen.py); this file holds the static checks and the commands
that read the catalogue.
"""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path

import pytest

from descgen import codes
from descgen.audit import RULES, catalogue
from descgen.cli import main
from descgen.core.findings import SEVERITIES, Finding, Where
from descgen.output.report import sarif

from . import codes_seen

ROOT = Path(__file__).resolve().parents[1]
CODE = re.compile(r"[A-Z]{3,6}\d{3}")
ENTRIES = list(catalogue.entries())
KNOWN = {e.code for e in ENTRIES}


def _literal_codes() -> dict[str, str]:
    """Every string constant in descgen/ that is exactly a code, with a file that holds it
    (found with ``ast``, so comments and names such as ``REP103 = ...`` do not count)."""
    found: dict[str, str] = {}
    for path in sorted((ROOT / "descgen").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and CODE.fullmatch(node.value):
                found.setdefault(node.value, str(path.relative_to(ROOT)))
    return found


def test_the_static_scan_finds_codes_from_every_stage() -> None:
    # a scan that found nothing would pass the next test vacuously
    found = _literal_codes()
    assert {"UNIT004", "SPEC010", "CTRL014", "GEN005", "READ004", "BAG014", "YAML010", "JOINT004"} <= set(found)


def test_every_code_literal_in_descgen_is_registered() -> None:
    missing = {code: where for code, where in _literal_codes().items() if code not in KNOWN}
    assert not missing, f"register these in descgen/codes/__init__.py (or as an audit @rule): {missing}"


@pytest.mark.parametrize("entry", ENTRIES, ids=[e.code for e in ENTRIES])
def test_every_code_is_explained(entry: codes.Entry) -> None:
    assert CODE.fullmatch(entry.code)
    assert re.fullmatch(r"[a-z][a-z0-9]*(-[a-z0-9]+)*", entry.name), entry.name
    assert entry.severity in (*SEVERITIES, "varies")
    assert entry.group in codes.GROUPS
    assert entry.summary.strip()
    if entry.is_rule:
        why = RULES[entry.code].doc.split("## Why is this bad?", 1)[1]
    else:
        why = codes.CODES[entry.code].rationale
    assert len(why.split()) >= 5, f"{entry.code}: the rationale says too little: {why!r}"


def test_a_duplicate_code_is_refused_at_registration() -> None:
    before = dict(codes.CODES)
    dup = codes.Code("UNIT004", "another-name", "error", "spec", "s", "r")
    with pytest.raises(ValueError, match="duplicate finding code UNIT004"):
        codes.register(dup)
    with pytest.raises(ValueError, match="duplicate code name"):
        codes.register(codes.Code("UNIT099", "implausible-value", "error", "spec", "s", "r"))
    with pytest.raises(ValueError, match="rationale"):
        codes.register(codes.Code("UNIT098", "fresh-name-98", "error", "spec", "s", "  "))
    assert before == codes.CODES


# --------------------------------------------------------------------------- `descgen rules`


def test_rules_explains_a_code_that_is_not_an_audit_rule(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules", "UNIT004"]) == 0
    out = capsys.readouterr().out
    first = out.splitlines()[0]
    assert first.startswith("UNIT004 implausible-value (error")
    # the rationale is printed, as written in the catalogue (whitespace aside)
    assert " ".join(codes.CODES["UNIT004"].rationale.split()) in " ".join(out.split())
    assert "## Why it matters" in out.splitlines()


def test_rules_lists_every_code_once_grouped(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules"]) == 0
    lines = capsys.readouterr().out.splitlines()
    listed = [ln.split()[0] for ln in lines]
    assert sorted(listed) == sorted(KNOWN) and len(listed) == len(set(listed))
    groups = [ln.split()[2] for ln in lines]
    # grouped: each group's codes are contiguous, in the order of GROUPS
    firsts = [g for i, g in enumerate(groups) if i == 0 or groups[i - 1] != g]
    assert firsts == [g for g in codes.GROUPS if g in groups]
    assert {"UNIT004", "GEN005", "BAG014", "READ030", "CTRL014", "JOINT004"} <= set(listed)


def test_rules_group_filter(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules", "--group", "recording"]) == 0
    listed = {ln.split()[0] for ln in capsys.readouterr().out.splitlines()}
    assert listed == {c for c, e in codes.CODES.items() if e.group == "recording"}
    assert "BAG014" in listed and "JOINT004" not in listed


def test_rules_unknown_code_is_exit_2_with_a_hint(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules", "XYZ999"]) == 2
    err = capsys.readouterr().err
    assert "error[RULE001]" in err and "XYZ999" in err and "hint: run descgen rules" in err


def test_rules_accepts_a_lower_case_code(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules", "gen005"]) == 0
    assert capsys.readouterr().out.startswith("GEN005 generated-file-stale")


# --------------------------------------------------------------------------- SARIF


def test_sarif_carries_help_for_codes_that_are_not_rules() -> None:
    findings = [
        Finding("UNIT004", "error", "too big", "widen it", "x", Where("a.yaml", 3, 5)),
        Finding("GEN020", "info", "no check_urdf", "install it", "file", Where("a.urdf")),
        Finding("JOINT004", "error", "order", "swap", "joint:j", Where("a.urdf", 9)),
    ]
    run = json.loads(sarif(findings))["runs"][0]
    rules = {r["id"]: r for r in run["tool"]["driver"]["rules"]}
    assert set(rules) == {"UNIT004", "GEN020", "JOINT004"}
    unit = rules["UNIT004"]
    assert unit["name"] == "implausible-value"
    assert "millimetres typed as metres" in unit["help"]["text"]
    assert unit["defaultConfiguration"] == {"level": "error"}
    # a code whose severity varies has no default level (SARIF would otherwise claim one)
    assert "defaultConfiguration" not in rules["GEN020"]
    assert "liburdfdom-tools" in rules["GEN020"]["help"]["markdown"]
    assert "## Why is this bad?" in rules["JOINT004"]["help"]["text"]


# --------------------------------------------------------------------------- the session hook


def test_the_session_hook_records_codes_made_by_descgen() -> None:
    from descgen.infra.yamlsource import _fail
    from descgen.spec.quantity import error  # noqa: F401  (a descgen module that makes findings)

    codes_seen.SEEN.pop("YAML004", None)
    _fail("f.yaml", "m", "h", code="YAML004")  # descgen's code makes the finding
    assert codes_seen.SEEN.get("YAML004", "").startswith("descgen")
    Finding("ZZZ999", "error", "a test's own finding")  # a test's hand-made finding is not descgen's
    assert "ZZZ999" not in codes_seen.SEEN


def test_the_session_check_names_an_unregistered_code() -> None:
    # the check the session runs at its end, on a planted unknown code
    assert codes_seen.unregistered({"UNIT004": "descgen.core.units", "QQQ123": "descgen.x"}) == {"QQQ123": "descgen.x"}
