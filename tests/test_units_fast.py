"""The pint-free path for plain "<number> <unit>" texts (units._simple_si) must give exactly
what pint gives: same float, same refusals. The oracle is pint itself, through the slow path."""

from __future__ import annotations

import pytest

from descgen.core import cache_dir, units
from tests.helpers import pint_si

NUMBERS = ["0", "-0", "1", "300", "-90", "0.175", "19.1", "1e-3", "2.5E+2", "+7", "123456789012345", "0.1"]


@pytest.mark.parametrize("unit", sorted(units._SIMPLE_UNITS))
def test_every_simple_unit_converts_exactly_as_pint(unit: str, monkeypatch: pytest.MonkeyPatch) -> None:
    kind, _factor = units._SIMPLE_UNITS[unit]
    for number in NUMBERS:
        for text in (f"{number} {unit}", f"{number}{unit}", f"  {number}  {unit} "):
            fast = units._simple_si(text, kind)
            assert fast is not None, text
            slow = pint_si(text, kind, monkeypatch)
            assert repr(fast) == repr(slow), text  # repr: 0.175 vs 0.17500000000000002, 0.0 vs -0.0


@pytest.mark.parametrize("unit", sorted(units._SIMPLE_UNITS))
def test_the_factor_table_is_pints(unit: str) -> None:
    kind, factor = units._SIMPLE_UNITS[unit]
    reg = units.registry()
    target = reg.Quantity(1, unit).to_base_units().units if kind in ("angle", "angular_velocity") else None
    expected = reg.Quantity(1, unit).to(target or units.KINDS[kind].si_unit).magnitude
    assert repr(float(expected)) == factor
    assert reg.Quantity(1, unit).check(units.KINDS[kind].dimensionality)


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        ("300 mm", "angle"),  # a unit of another kind: pint's UNIT003, not a silent number
        ("90 deg", "length"),
        ("1 Hz", "angular_velocity"),
        ("3", "length"),  # bare number text
        ("1,5 m", "length"),  # comma
        ("(300 mm) / 2", "length"),  # parentheses (plain arithmetic: tests/test_units_expressions.py)
        ("0123 mm", "length"),  # Python's tokenizer reads 0 and 123: pint says 0 mm
        ("1" * 41 + " mm", "length"),  # too many digits
        ("1e999 m", "length"),  # not finite
        ("300" + " " * 300 + "mm", "length"),  # too long
        ("٣ mm", "length"),  # a non-ASCII digit
        ("300 mm\n", "length"),
    ],
)
def test_anything_else_is_left_to_pint(text: str, kind: str, monkeypatch: pytest.MonkeyPatch) -> None:
    if units._SIMPLE.fullmatch(text.strip()) and units._SIMPLE_UNITS.get(text.split()[-1], ("",))[0] == kind:
        assert units._simple_si(text, kind) == pint_si(text, kind, monkeypatch)
        return
    assert units._simple_si(text, kind) is None
    try:
        got: float | str = units._to_si(text, kind)
    except units.QuantityError as exc:
        got = exc.code
    assert got == pint_si(text, kind, monkeypatch)


def test_the_registry_from_the_cache_converts_as_a_fresh_one(tmp_path, monkeypatch: pytest.MonkeyPatch) -> None:
    import pint

    monkeypatch.setenv(cache_dir.CACHE_ENV, str(tmp_path))
    folder = units._cache_folder()
    assert folder is not None and folder.parent == tmp_path
    first = pint.UnitRegistry(cache_folder=folder)  # writes the cache
    assert any(folder.iterdir())
    cached = pint.UnitRegistry(cache_folder=folder)  # reads it
    fresh = pint.UnitRegistry()
    for text, unit in [("19.1 in", "m"), ("30 rpm", "rad/s"), ("1200 g", "kg"), ("40 N*m", "N*m")]:
        want = fresh.Quantity(text).to(unit).magnitude
        assert cached.Quantity(text).to(unit).magnitude == want == first.Quantity(text).to(unit).magnitude


def test_caching_can_be_switched_off(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(cache_dir.CACHE_ENV, "")
    assert units._cache_folder() is None
