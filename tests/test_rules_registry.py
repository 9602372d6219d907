"""The rule catalogue: stable well-formed codes, unique names, documented rules, and the `rules` command."""

from __future__ import annotations

import contextlib
import inspect
import re
from collections.abc import Iterable, Iterator

import pytest

from descgen.audit import RULES, iter_rules, registry
from descgen.core.findings import SEVERITIES, Finding
from descgen.core.model import Robot

from .helpers import cli

ALL = list(iter_rules())


def test_there_are_rules() -> None:
    assert len(ALL) >= 20
    assert [r.code for r in ALL] == sorted(RULES)


# What @rule does not check when it registers (the code pattern, unique codes and names and
# both doc headings it refuses at import; see the refusal tests below).
@pytest.mark.parametrize("info", ALL, ids=[r.code for r in ALL])
def test_rule_is_well_formed(info: registry.RuleInfo) -> None:
    assert re.fullmatch(r"[a-z][a-z0-9]*(-[a-z0-9]+)*", info.name), info.name
    assert info.severity in SEVERITIES
    assert info.doc.index("## What it does") < info.doc.index("## Why is this bad?")
    what = info.doc.split("## What it does", 1)[1].split("## Why is this bad?", 1)[0]
    why = info.doc.split("## Why is this bad?", 1)[1]
    assert what.strip() and why.strip(), info.doc
    assert info.summary and "##" not in info.summary


# --------------------------------------------------------------------------- registering


@contextlib.contextmanager
def restoring_rules() -> Iterator[None]:
    """Whatever is registered inside is gone afterwards."""
    list(iter_rules())  # make sure every rule module is imported before the snapshot
    saved = dict(RULES)
    try:
        yield
    finally:
        RULES.clear()
        RULES.update(saved)


@pytest.fixture
def clean_rules() -> Iterator[None]:
    with restoring_rules():
        yield


def _dummy(robot: Robot) -> Iterable[Finding]:
    """## What it does
    Nothing.
    ## Why is this bad?
    It is a test.
    """
    return []


def _undocumented(robot: Robot) -> Iterable[Finding]:
    """Does something."""
    return []


def _free_code(prefix: str = "TIME") -> str:
    return next(f"{prefix}{n:03d}" for n in range(999, 0, -1) if f"{prefix}{n:03d}" not in RULES)


def test_registering_a_new_rule_works_and_is_cleaned_up() -> None:
    code = _free_code()
    before = [r.code for r in iter_rules()]
    with restoring_rules():
        registry.rule(code, "test-only-rule", "info")(_dummy)
        assert RULES[code].name == "test-only-rule"
        assert [r.code for r in iter_rules()] == sorted([*before, code])
    assert [r.code for r in iter_rules()] == before


@pytest.mark.usefixtures("clean_rules")
def test_duplicate_code_is_refused() -> None:
    before = dict(RULES)
    with pytest.raises(ValueError, match="duplicate"):
        registry.rule("JOINT004", "a-brand-new-name", "error")(_dummy)
    assert before == RULES
    assert RULES["JOINT004"].name == "limits-out-of-order"


@pytest.mark.usefixtures("clean_rules")
def test_duplicate_name_is_refused() -> None:
    before = dict(RULES)
    with pytest.raises(ValueError, match="duplicate"):
        registry.rule(_free_code(), "limits-out-of-order", "error")(_dummy)
    assert before == RULES


@pytest.mark.usefixtures("clean_rules")
@pytest.mark.parametrize("code", ["FOO001", "JOINT04", "JOINT0004", "joint004", "JOINT", "004", "XJOINT004", ""])
def test_bad_code_is_refused(code: str) -> None:
    before = dict(RULES)
    with pytest.raises(ValueError, match="category prefix"):
        registry.rule(code, f"bad-code-{len(code)}", "error")(_dummy)
    assert before == RULES


@pytest.mark.usefixtures("clean_rules")
def test_a_retired_rule_code_is_never_reused() -> None:
    """A rule that is gone keeps its entry in the catalogue (group "rule", retired): @rule refuses
    its number, with any name, and ``descgen rules`` still explains it."""
    from descgen import codes
    from descgen.audit.catalogue import explain

    code = _free_code("JOINT")
    saved, names = dict(codes.CODES), set(codes.NAMES)
    why = "the rule is gone; its findings are reported by another rule now"
    try:
        with pytest.raises(ValueError, match="unknown group"):  # only a retired code may sit in group "rule"
            codes.register(codes.Code(code, "test-retired-rule", "error", "rule", "What it did.", why))
        retired = codes.Retired(30, "merged into JOINT004")
        codes.register(codes.Code(code, "test-retired-rule", "error", "rule", "What it did.", why, retired))
        entry = explain(code)
        assert entry is not None and (entry.group, entry.status) == ("rule", "retired")
        with pytest.raises(ValueError, match=rf"duplicates a catalogue code \({code} is retired by issue 30"):
            registry.rule(code, "a-fresh-rule-name", "error")(_dummy)
        assert code not in RULES
    finally:
        codes.CODES.clear()
        codes.CODES.update(saved)
        codes.NAMES.clear()
        codes.NAMES.update(names)


@pytest.mark.usefixtures("clean_rules")
def test_undocumented_rule_is_refused() -> None:
    before = dict(RULES)
    with pytest.raises(ValueError, match="doc"):
        registry.rule(_free_code(), "undocumented-rule", "error")(_undocumented)
    assert before == RULES


# --------------------------------------------------------------------------- the `rules` command


def test_cli_rules_lists_every_code() -> None:
    r = cli("rules")
    assert r.returncode == 0, r.stderr
    listed = [line.split()[0] for line in r.stdout.splitlines() if line.strip()]
    from descgen.audit.catalogue import entries

    assert listed == [e.code for e in entries()]  # the whole catalogue, rules among it
    assert {info.code for info in ALL} <= set(listed)
    for info in ALL:
        assert info.name in r.stdout


def test_cli_rules_code_prints_its_doc() -> None:
    r = cli("rules", "JOINT004")
    assert r.returncode == 0, r.stderr
    info = RULES["JOINT004"]
    first = r.stdout.splitlines()[0]
    assert first.startswith("JOINT004") and info.name in first and info.severity in first
    out_lines = [line.strip() for line in r.stdout.splitlines()]
    for line in inspect.cleandoc(info.doc).splitlines():
        if line.strip():
            assert line.strip() in out_lines, line
    assert "JOINT001" not in r.stdout


def test_cli_rules_doc_is_markdown_with_headings_at_line_start() -> None:
    """The doc is also rule help (SARIF, markdown): an indented '## ...' is a code block, not a heading."""
    r = cli("rules", "JOINT004")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert "## What it does" in lines, r.stdout
    assert "## Why is this bad?" in lines, r.stdout
