"""Each audit rule on its own bad and good fixtures (tests/rules/<CODE>/, see its README).

A dropped branch, a loosened threshold or a misread attribute changes the findings of some
bad case (or makes a good case fire), so it fails here, not only in a corpus count.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from descgen.audit import RULES, iter_rules, run
from descgen.core.findings import Finding
from descgen.read.description import Options, load_description

FIXTURES = Path(__file__).with_name("rules")
MAIN_SUFFIXES = (".urdf", ".xacro", ".yaml")


def _cases() -> list[tuple[str, str, Path]]:
    out = []
    for folder in sorted(p for p in FIXTURES.iterdir() if p.is_dir()):
        for main in sorted(folder.iterdir()):
            if main.suffix in MAIN_SUFFIXES and not main.name.endswith(".controllers.yaml"):
                out.append((folder.name, main.stem, main))
    return out


CASES = _cases()


def _line(f: Finding) -> str:
    return "\t".join([f.code, f.severity, f.subject, str(f.where.line), f.message])


def _findings(code: str, main: Path) -> list[str]:
    stem = main.with_suffix("")
    srdf = stem.with_suffix(".srdf")
    controllers = Path(f"{stem}.controllers.yaml")
    moveit = Path(f"{stem}.moveit")  # a MoveIt config folder (MOVEIT rules)
    options = Options(
        srdf=srdf if srdf.is_file() else None,
        controllers=controllers if controllers.is_file() else None,
        package_paths=(main.parent,),
        moveit_config=moveit if moveit.is_dir() else None,
    )
    robot, _ = load_description(main, options)
    # a message that cites another place ("first at <file>:3:1") names the fixture by its
    # absolute path; the expected file names it relative to its folder, so it holds in any checkout
    return [_line(f).replace(f"{main.parent}/", "") for f in run(robot, codes=[code])]


@pytest.mark.parametrize(("code", "case", "main"), CASES, ids=[f"{c}/{k}" for c, k, _ in CASES])
def test_rule_on_its_fixture(code: str, case: str, main: Path) -> None:
    assert code in {r.code for r in iter_rules()}, f"tests/rules/{code} names no registered rule"
    got = _findings(code, main)
    if case.startswith("good"):
        assert got == [], f"{code} fired on its good fixture {main.name}"
        return
    expected_file = main.with_name(f"{case}.expected")
    assert expected_file.is_file(), f"{expected_file} is missing"
    expected = [line for line in expected_file.read_text(encoding="utf-8").splitlines() if line.strip()]
    assert expected, f"{expected_file} is empty: a bad case must expect at least one finding"
    assert got == expected


def test_every_rule_has_a_bad_and_a_good_fixture() -> None:
    have: dict[str, set[str]] = {}
    for code, case, _ in CASES:
        have.setdefault(code, set()).add("good" if case.startswith("good") else "bad")
    list(iter_rules())
    missing = sorted(code for code in RULES if have.get(code) != {"bad", "good"})
    assert not missing, f"rules without a bad and a good fixture in tests/rules/: {missing}"
