"""Unit conversion against hand-computed SI values."""

from __future__ import annotations

import math

import pytest

from descgen.core import units


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("19.1 in", "length", 0.48514),  # 19.1 * 25.4 mm
        ("300 mm", "length", 0.3),
        ("175 mm", "length", 0.175),  # exact, not 0.17500000000000002
        ("0.18 m", "length", 0.18),
        ("19.1 in / 2", "length", 0.24257),
        ("25 mm + 2 * 5 mm", "length", 0.035),
        ("30 rpm", "angular_velocity", math.pi),  # 30 rev/min = 0.5 rev/s = pi rad/s
        ("112 rpm", "angular_velocity", 112 * 2 * math.pi / 60),
        ("90 deg/s", "angular_velocity", math.pi / 2),
        ("-90 deg", "angle", -math.pi / 2),
        ("-170 deg", "angle", -170 * math.pi / 180),
        ("1200 g", "mass", 1.2),
        ("28.0 kg", "mass", 28.0),
        ("40 N*m", "torque", 40.0),
        ("12 N·m", "torque", 12.0),
        ("500 N", "force", 500.0),
        ("0.1 m/s", "linear_velocity", 0.1),
        ("100 Hz", "frequency", 100.0),
        ("500 ms", "time", 0.5),
        ("0.01 kg*m^2", "inertia", 0.01),
        (0, "length", 0.0),
    ],
)
def test_to_si_hand_computed(text: object, kind: str, expected: float) -> None:
    assert units.to_si(text, kind) == pytest.approx(expected, rel=1e-15, abs=1e-15)


@pytest.mark.parametrize(
    ("text", "kind", "code"),
    [
        ("2 kg", "length", "UNIT003"),
        (300, "length", "UNIT001"),
        ("300", "length", "UNIT001"),
        ("3", "angle", "UNIT001"),
        ("1,5 m", "length", "UNIT002"),
        ("nan m", "length", "UNIT002"),
        ("inf mm", "length", "UNIT002"),
        ("1 Hz", "angular_velocity", "UNIT003"),  # no angle unit: not 1 rad/s
        ("90 deg/s", "frequency", "UNIT003"),  # an angle unit: not a frequency
        ("40 J", "torque", "UNIT003"),  # energy has a torque's dimensions
        ("", "length", "UNIT002"),
        ("mm mm mm (", "length", "UNIT002"),
        ("1/0 m", "length", "UNIT002"),
        (True, "length", "UNIT001"),
        (None, "mass", "UNIT001"),
        ([1, 2], "mass", "UNIT001"),
    ],
)
def test_to_si_refuses(text: object, kind: str, code: str) -> None:
    with pytest.raises(units.QuantityError) as exc:
        units.to_si(text, kind)
    assert exc.value.code == code
    assert exc.value.hint  # every refusal says how to fix it


def test_bare_number_hint_suggests_a_unit() -> None:
    with pytest.raises(units.QuantityError) as exc:
        units.to_si(85, "length")
    assert '"85 mm"' in exc.value.hint


def test_negative_zero_is_plain_zero() -> None:
    value = units.to_si("-0 mm", "length")
    assert value == 0 and math.copysign(1, value) == 1
