"""`validate` reports every problem in one run, without cascades, with unit hints that fit.

Expected lines come from ``line_of`` on the planted text (the oracle for positions);
expected hints are written by hand.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from pathlib import Path

import pytest

from descgen.audit import RULES, iter_rules, registry
from descgen.cli import main
from descgen.core import units
from descgen.core.findings import Finding
from descgen.core.model import Robot

from .helpers import EXAMPLE_TEXT, line_of, plant

LINE = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<col>\d+): error\[(?P<code>[A-Z]+\d{3})\]: ")

CASTER_MASS = ("inertial: {mass: 300 g, from: collision}", "inertial: {mass: 3 m, from: collision}")
LIFT_SIZE = ("geometry: {box: {size: [100 mm, 100 mm, 60 mm]}}", "geometry: {box: {size: [100 mm, 3 kg, 60 mm]}}")
ELBOW_ORIGIN = ("origin: {xyz: [300 mm, 0, 0], source: M20}", "origin: {xyz: [300, 0, 0], source: M20}")
ELBOW_LOWER = ("limit: {lower: -150 deg", "limit: {lower: -150 kg")
BAD_GROUP = ("- {name: zero, group: arm, pose: zero}", "- {name: zero, group: arms, pose: zero}")


def _validate(text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> tuple[int, list[tuple[int, str]]]:
    spec = tmp_path / "robot.yaml"
    spec.write_text(text)
    code = main(["validate", str(spec)])
    err = capsys.readouterr().err
    found = []
    for line in err.splitlines():
        m = LINE.match(line)
        if m:
            assert m["file"] == str(spec)
            found.append((int(m["line"]), m["code"]))
    return code, found


def _planted(*changes: tuple[str, str]) -> str:
    text = EXAMPLE_TEXT
    for old, new in changes:
        text = plant(old, new, text)
    return text


def test_three_unit_mistakes_in_three_places_are_three_errors_in_one_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = _planted(CASTER_MASS, LIFT_SIZE, ELBOW_ORIGIN)
    code, found = _validate(text, tmp_path, capsys)
    assert code == 2
    assert found == [
        (line_of(text, "mass: 3 m"), "UNIT003"),
        (line_of(text, "3 kg, 60 mm"), "UNIT003"),
        (line_of(text, "xyz: [300, 0, 0]"), "UNIT001"),
    ]


def test_a_value_the_builder_converts_is_reported_with_the_schema_errors(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # joint limits are converted after the schema (their kind depends on the joint type):
    # today's loader stopped at the schema errors and never reported this fourth mistake
    text = _planted(CASTER_MASS, LIFT_SIZE, ELBOW_ORIGIN, ELBOW_LOWER)
    _, found = _validate(text, tmp_path, capsys)
    assert (line_of(text, "lower: -150 kg"), "UNIT003") in found
    assert len(found) == 4


def test_a_wrong_kind_limit_does_not_cascade_into_a_missing_limit(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = _planted(ELBOW_LOWER)
    code, found = _validate(text, tmp_path, capsys)
    # one mistake, one error: not also JOINT003 "limit lacks lower or upper"
    assert (code, found) == (2, [(line_of(text, "lower: -150 kg"), "UNIT003")])


def test_whole_model_rules_run_despite_a_unit_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = _planted(CASTER_MASS, BAD_GROUP)
    code, found = _validate(text, tmp_path, capsys)
    assert code == 2
    assert found == [
        (line_of(text, "mass: 3 m"), "UNIT003"),
        (line_of(text, "group: arms"), "SRDF002"),
    ]


def test_a_wrong_kind_size_does_not_cascade_into_a_zero_size(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # every size of the caster sphere wrong: the stand-in must not show up as GEOM/INER errors
    text = _planted(("inertial: {mass: 300 g, from: collision}", "inertial: {mass: 300 g, from: collision}"))
    text = text.replace("geometry: {sphere: {diameter: 60 mm}}", "geometry: {sphere: {diameter: 60 kg}}")
    code, found = _validate(text, tmp_path, capsys)
    assert code == 2
    assert {c for _, c in found} == {"UNIT003"} and len(found) == 2


def test_a_missing_key_still_reports_the_unit_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # no model can be built without a joint's child, so only the schema errors are reported
    text = _planted(CASTER_MASS, ("    child: forearm_link\n", ""))
    code, found = _validate(text, tmp_path, capsys)
    assert code == 2
    assert {c for _, c in found} == {"UNIT003", "SPEC002"}


# --------------------------------------------------------------------------- stand-ins


@pytest.fixture
def clean_rules() -> Iterator[None]:
    list(iter_rules())
    saved = dict(RULES)
    try:
        yield
    finally:
        RULES.clear()
        RULES.update(saved)


def _free(prefix: str = "TIME") -> str:
    return next(f"{prefix}{n:03d}" for n in range(999, 0, -1) if f"{prefix}{n:03d}" not in RULES)


@pytest.mark.usefixtures("clean_rules")
def test_a_finding_that_depends_on_a_stand_in_is_dropped(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A rule that reads the caster's mass but reports at the arm's elbow joint (another
    element): with the mass unreadable, its verdict depends on the stand-in and must go;
    a rule that does not read it must still report."""

    def reads_caster_mass(robot: Robot) -> Iterable[Finding]:
        """## What it does
        Test only.
        ## Why is this bad?
        Test only.
        """
        caster = next(link for link in robot.links if link.name == "caster_link")
        elbow = next(j for j in robot.joints if j.name == "elbow_joint")
        if caster.inertial is not None and caster.inertial.mass < 0.1:
            yield registry.at(dep, elbow, "caster lighter than 100 g", "test")

    def independent(robot: Robot) -> Iterable[Finding]:
        """## What it does
        Test only.
        ## Why is this bad?
        Test only.
        """
        yield registry.at(ind, next(j for j in robot.joints if j.name == "elbow_joint"), "always", "test")

    dep = _free()
    registry.rule(dep, "test-reads-caster-mass", "error")(reads_caster_mass)
    ind = _free()
    registry.rule(ind, "test-independent", "error")(independent)
    text = _planted(CASTER_MASS)
    _, found = _validate(text, tmp_path, capsys)
    codes = [c for _, c in found]
    assert ind in codes and dep not in codes
    assert "UNIT003" in codes


# --------------------------------------------------------------------------- bare-number hints


@pytest.mark.parametrize(
    ("kind", "value", "expected"),
    [
        ("length", 300, "300 mm"),
        ("length", 0.3, "0.3 m"),
        ("length", 12, "12 mm"),
        ("length", 2.5, "2.5 m"),
        ("mass", 1200, "1200 g"),
        ("mass", 2.5, "2.5 kg"),
        ("mass", 28, "28 kg"),
        ("angle", 90, "90 deg"),
        ("angle", -150, "-150 deg"),
        ("angle", 1.57, "1.57 rad"),
        ("time", 3, "3 s"),
    ],
)
def test_bare_number_hint_suggests_a_plausible_unit(kind: str, value: float, expected: str) -> None:
    with pytest.raises(units.QuantityError) as exc:
        units.to_si(value, kind)
    assert exc.value.code == "UNIT001"
    assert f'"{expected}"' in exc.value.hint
    # also when the bare number is written as text
    with pytest.raises(units.QuantityError) as text_exc:
        units.to_si(str(value), kind)
    assert f'"{expected}"' in text_exc.value.hint


@pytest.mark.parametrize(
    ("change", "expected"),
    [
        (("inertial: {mass: 300 g, from: collision}", "inertial: {mass: 300, from: collision}"), "300 g"),
        (("inertial: {mass: 2.5 kg, from: collision}", "inertial: {mass: 2.5, from: collision}"), "2.5 kg"),
        (("origin: {xyz: [0, 0, 85 mm], source: M09}", "origin: {xyz: [0, 0, 0.085], source: M09}"), "0.085 m"),
        (("origin: {xyz: [0, 0, 85 mm], source: M09}", "origin: {xyz: [0, 0, 85], source: M09}"), "85 mm"),
        (("lower: -170 deg", "lower: -170"), "-170 deg"),
        (("rpy: [90 deg, 0, 0], source: M01}", "rpy: [1.5708, 0, 0], source: M01}"), "1.5708 rad"),
    ],
)
def test_bare_number_hint_in_validate(
    change: tuple[str, str], expected: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(plant(*change))
    assert main(["validate", str(spec)]) == 2
    err = capsys.readouterr().err
    assert "error[UNIT001]" in err and f'e.g. "{expected}"' in err, err


SEVERITY = re.compile(r"^.+?:\d+:\d+: (?P<severity>error|warning|info)\[(?P<code>[A-Z]+\d{3})\]: ", re.MULTILINE)
UNUSED = "waivers:\n  - {code: INER004, subject: 'link:nowhere', reason: left over}\n"


@pytest.mark.parametrize("error", [BAD_GROUP, CASTER_MASS], ids=["rule error", "unit error"])
def test_a_refused_spec_still_shows_its_warnings_and_infos(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], error: tuple[str, str]
) -> None:
    """One error used to hide every warning (the refusal carried errors only), and the
    check-stage rules did not run at all: a user fixed the error to meet the next surprise."""
    spec = tmp_path / "robot.yaml"
    spec.write_text(_planted(error) + UNUSED)
    code = main(["validate", str(spec)])
    shown = {(m["severity"], m["code"]) for m in SEVERITY.finditer(capsys.readouterr().err)}
    assert code == 2
    assert ("error", "SRDF002" if error is BAD_GROUP else "UNIT003") in shown
    assert ("warning", "SPEC130") in shown  # the waiver that matches nothing
    assert ("info", "GEOM041") in shown  # a check-stage rule's info: the model was built, so it ran
