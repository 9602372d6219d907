"""The one catalogue of finding codes (descgen/codes/, one module per stage, plus the audit rules).

The session-wide check that every code a test saw descgen make is registered lives in
conftest.py (tests/codes_seen.py); this file holds the static checks and the commands
that read the catalogue.
"""

from __future__ import annotations

import ast
import importlib
import json
import re
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

from descgen import codes
from descgen.audit import RULES, catalogue
from descgen.cli import main
from descgen.codes.generate import GEN005, GEN020
from descgen.codes.spec import YAML003, YAML004
from descgen.core.findings import SEVERITIES, Finding, Where
from descgen.output.report import sarif

from . import codes_seen

ROOT = Path(__file__).resolve().parents[1]
CODE = re.compile(r"[A-Z]{3,6}\d{3}")
ENTRIES = list(catalogue.entries())
KNOWN = {e.code for e in ENTRIES}


def _literal_sites() -> dict[str, set[str]]:
    """Every string constant in descgen/ that is exactly a code, with the files that hold it
    (found with ``ast``, so comments and names such as ``REP103 = ...`` do not count)."""
    found: dict[str, set[str]] = {}
    for path in sorted((ROOT / "descgen").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and CODE.fullmatch(node.value):
                found.setdefault(node.value, set()).add(str(path.relative_to(ROOT)))
    return found


def _literal_codes() -> dict[str, str]:
    """Every code written as a string in descgen/, with one file that holds it."""
    return {code: min(files) for code, files in _literal_sites().items()}


def test_the_static_scan_finds_codes_from_every_stage() -> None:
    # a scan that found nothing would pass the next test vacuously
    found = _literal_codes()
    assert {"UNIT004", "SPEC010", "CTRL014", "GEN005", "READ004", "BAG014", "YAML010", "JOINT004"} <= set(found)


def test_every_code_literal_in_descgen_is_registered() -> None:
    missing = {code: where for code, where in _literal_codes().items() if code not in KNOWN}
    assert not missing, f"declare these in descgen/codes/<stage>.py (or as an audit @rule): {missing}"


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


def test_rules_lists_every_code_once_sorted_by_code(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules"]) == 0
    lines = capsys.readouterr().out.splitlines()
    listed = [ln.split()[0] for ln in lines]
    assert sorted(listed) == sorted(KNOWN) and len(listed) == len(set(listed))
    # sorted by code (issue 30; it was grouped as GROUPS orders them): a code is found where it
    # sorts, whichever stage declares it; the group is still the third column
    assert listed == sorted(listed)
    assert {ln.split()[2] for ln in lines} <= set(codes.GROUPS)
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
    _fail("f.yaml", "m", "h", code=YAML004)  # descgen's code makes the finding, through YAML004.finding
    assert codes_seen.SEEN.get("YAML004") == "descgen.infra.yamlsource"  # the raiser, not the registry
    Finding("ZZZ999", "error", "a test's own finding")  # a test's hand-made finding is not descgen's
    assert "ZZZ999" not in codes_seen.SEEN
    codes_seen.SEEN.pop("YAML003", None)
    YAML003.finding("a test raising a code itself")  # nor is one a test raises through the entry
    assert "YAML003" not in codes_seen.SEEN


def test_the_session_check_names_an_unregistered_code() -> None:
    # the check the session runs at its end, on a planted unknown code
    assert codes_seen.unregistered({"UNIT004": "descgen.core.units", "QQQ123": "descgen.x"}) == {"QQQ123": "descgen.x"}


def test_the_session_check_names_a_retired_code(scratch: None) -> None:
    codes.Stage("generate").retired("GEN998", "test-retired-998", "error", "s", _WHY, issue=30, why="a test")
    assert codes_seen.unregistered({"GEN998": "descgen.x", "GEN005": "descgen.y"}) == {"GEN998": "descgen.x"}


# --------------------------------------------------------------------------- stages, raising, status (issue 30)

_WHY = "a rationale long enough to explain the code"
# Files that still build a catalogue code's Finding by hand, with its severity repeated: core is
# below codes (layers) and cannot import them; the others were being changed by another engineer
# when the codes were converted (issue 30). Convert them to CODE.finding(...) and drop them here.
BUILT_BY_HAND = {
    "descgen/core/launch_subst.py",
    "descgen/infra/result_cache.py",
    "descgen/infra/evidence_hash.py",
    "descgen/meshes/cache.py",
    "descgen/audit/findings_cache.py",
    "descgen/physics/collision.py",
    "descgen/physics/sweep/__init__.py",
    "descgen/prove/package.py",
    "descgen/prove/sweep.py",
    "descgen/commands/control/record.py",
    "descgen/commands/control/evidence_check.py",
    "descgen/commands/evidence_page.py",
    "descgen/commands/generate.py",
    "descgen/write/pose_images.py",
}


@pytest.fixture
def scratch() -> Iterator[None]:
    """Whatever a test registers in the catalogue is gone afterwards."""
    saved, names = dict(codes.CODES), set(codes.NAMES)
    try:
        yield
    finally:
        codes.CODES.clear()
        codes.CODES.update(saved)
        codes.NAMES.clear()
        codes.NAMES.update(names)


def _module(group: str) -> ModuleType:
    return importlib.import_module(f"descgen.codes.{'importer' if group == 'import' else group}")


@pytest.mark.parametrize("group", [g for g in codes.GROUPS if g != "rule"])
def test_each_stage_module_declares_its_codes_by_code(group: str) -> None:
    module = _module(group)
    declared = {n: v for n, v in vars(module).items() if isinstance(v, codes.Code | codes.VaryingCode)}
    # one constant per stable code of the group, named as the code, in code order
    assert all(name == c.code and c.group == group for name, c in declared.items())
    assert set(declared) == {c for c, e in codes.CODES.items() if e.group == group and e.status is None}
    assert list(declared) == sorted(declared)  # the order they are written in


def test_a_code_is_raised_through_its_entry_with_its_severity() -> None:
    f = GEN005.finding("m", "h", "file:x", Where("x", 3))
    assert f == Finding("GEN005", "error", "m", "h", "file:x", Where("x", 3))
    assert YAML003.finding("m").where == Finding("YAML003", "error", "m").where  # the same default place
    # a code whose severity varies takes it at the raise (mypy requires severity= there)
    assert GEN020.finding("m", "h", severity="info").severity == "info"
    assert GEN020.severity == "varies" and isinstance(GEN020, codes.VaryingCode)


def test_a_code_arriving_as_text_is_looked_up() -> None:
    assert codes.raisable("YAML003") is YAML003
    with pytest.raises(KeyError):
        codes.raisable("QQQ123")
    with pytest.raises(TypeError, match="no one severity"):
        codes.raisable("GEN020")


def test_no_catalogue_code_is_built_by_hand() -> None:
    """A Finding("CODE", "error", ...) of a catalogue code repeats its severity: raise CODE.finding(...)."""
    by_hand: dict[str, list[str]] = {}
    for path in sorted((ROOT / "descgen").rglob("*.py")):
        rel = str(path.relative_to(ROOT))
        if rel.startswith("descgen/codes/") or rel in BUILT_BY_HAND:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Name)
                and node.func.id == "Finding"
                and node.args
                and isinstance(node.args[0], ast.Constant)
                and node.args[0].value in codes.CODES
            ):
                by_hand.setdefault(rel, []).append(f"{node.args[0].value}:{node.lineno}")
    assert not by_hand, f"raise these through their entry, CODE.finding(...): {by_hand}"


def test_a_retired_code_stays_explained_and_listed(scratch: None, capsys: pytest.CaptureFixture[str]) -> None:
    # declared without a constant (retired() returns nothing): nothing can import it to raise it
    codes.Stage("generate").retired(
        "GEN998", "test-retired-998", "error", "What it reported.", _WHY, issue=41, why="folded into GEN006"
    )
    entry = catalogue.explain("GEN998")
    assert entry is not None and entry.status == "retired"
    assert entry.note == "retired by issue 41: folded into GEN006"
    assert main(["rules", "GEN998"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0] == (
        "GEN998 test-retired-998 (error; generate and check (the proofs of the written package); "
        "retired by issue 41: folded into GEN006)"
    )
    assert "## Status\nRetired by issue 41: folded into GEN006." in out and "What it reported." in out
    assert main(["rules", "--group", "generate"]) == 0
    listed = {ln.split()[0]: ln for ln in capsys.readouterr().out.splitlines()}
    assert "[retired] What it reported." in listed["GEN998"]
    assert ": [" not in listed["GEN005"]  # a stable code says nothing more


def test_a_retired_code_number_is_never_registered_again(scratch: None) -> None:
    codes.Stage("generate").retired("GEN998", "test-retired-998", "error", "s", _WHY, issue=41, why="gone")
    before = dict(codes.CODES)
    # with another meaning, or the same: refused, and the catalogue is unchanged
    for again in (
        codes.Code("GEN998", "a-new-meaning-998", "warning", "generate", "s", _WHY),
        codes.Code("GEN998", "test-retired-998", "error", "generate", "s", _WHY),
    ):
        with pytest.raises(ValueError, match=r"GEN998 is retired by issue 41: gone; a retired code is never reused"):
            codes.register(again)
    with pytest.raises(ValueError, match="retired"):
        codes.Stage("sweep").retired("GEN998", "other-998", "error", "s", _WHY, issue=42, why="again")
    assert before == codes.CODES


def test_a_retired_code_cannot_be_raised(scratch: None) -> None:
    codes.Stage("generate").retired("GEN998", "test-retired-998", "error", "s", _WHY, issue=41, why="gone")
    with pytest.raises(ValueError, match="GEN998 is retired by issue 41: gone: it cannot be raised"):
        codes.CODES["GEN998"].finding("m", "h")
    with pytest.raises(ValueError, match="cannot be raised"):
        codes.raisable("GEN998").finding("m")  # nor when the code arrives as text


def test_a_redirected_code_names_its_successor(scratch: None, capsys: pytest.CaptureFixture[str]) -> None:
    codes.Stage("generate").redirected("GEN997", "test-moved-997", "error", "s", _WHY, to="GEN006", issue=41)
    entry = catalogue.explain("GEN997")
    assert entry is not None and (entry.status, entry.note) == ("redirected", "redirected to GEN006 by issue 41")
    assert main(["rules", "GEN997"]) == 0
    assert "redirected to GEN006 by issue 41" in capsys.readouterr().out.splitlines()[0]
    with pytest.raises(ValueError, match="redirected to GEN006 by issue 41: it cannot be raised"):
        codes.CODES["GEN997"].finding("m")
    with pytest.raises(ValueError, match="not another code"):
        codes.Stage("generate").redirected("GEN996", "test-moved-996", "error", "s", _WHY, to="GEN996", issue=41)


def test_every_redirect_names_a_stable_code() -> None:
    stable = {e.code for e in ENTRIES if e.status == "stable"}
    for c in codes.CODES.values():
        if isinstance(c.status, codes.Redirected):
            assert c.status.to in stable, c.code


def test_no_retired_code_is_written_outside_the_catalogue() -> None:
    # the static half of "a retired code cannot be raised": no string in descgen/ names one
    gone = {c for c, e in codes.CODES.items() if e.status is not None}
    outside = {
        c: sorted(f for f in files if not f.startswith("descgen/codes/"))
        for c, files in _literal_sites().items()
        if c in gone
    }
    assert not {c: files for c, files in outside.items() if files}
