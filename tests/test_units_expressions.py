"""Arithmetic in quantity text ("75 mm - 30 mm", "19.1 in / 2") is evaluated without pint
(units._simple_si -> _expression_si) and must give exactly what pint gives: the same float, or
no answer so that pint decides. The oracle is pint itself, through the slow path."""

from __future__ import annotations

import random
import subprocess
import sys

import pytest

from descgen.core import units
from tests.conftest import EXAMPLE, ROOT
from tests.helpers import pint_si

# (text, kind, whether the pint-free path must answer it)
CASES = [
    # the example's texts
    ("75 mm - 30 mm", "length", True),
    ("100 mm / 2", "length", True),
    ("19.1 in / 2", "length", True),
    ("-19.1 in / 2", "length", True),
    ("25 mm + 2 * 5 mm", "length", True),
    ("30 rpm", "angular_velocity", True),
    ("112 rpm", "angular_velocity", True),
    # order of operations and float rounding: pint groups left to right, unary binds tightest
    ("0.1 * 3 mm / 7", "length", True),
    ("7 mm / 3 * 3", "length", True),
    ("1 / 3 mm", "length", True),
    ("2 * -5 mm", "length", True),
    ("- - 5 mm + 3 mm", "length", True),
    ("0.1 mm + 0.2 mm - 0.3 mm", "length", True),
    ("0.1 mm + 0.2 mm + 0.3 mm", "length", True),
    ("1e-3 m * 3 + 2 m / 7", "length", True),
    ("-90 deg + 0.5 deg", "angle", True),
    ("mm", "length", True),
    ("-mm", "length", True),
    ("5 mm - 5 mm", "length", True),
    ("-0.0 mm", "length", True),
    # left to pint: it converts, refuses or reads them otherwise
    ("0123 mm", "length", False),  # Python's tokenizer: 0 and 123, so pint says 0 mm
    ("0 + 5 mm", "length", False),  # pint adds a bare zero to a quantity
    ("1 in + 1 mm", "length", False),  # two units: pint converts
    ("5 mm / 0", "length", False),  # ZeroDivisionError in pint: UNIT002
    ("5 mm * 3 mm", "length", False),  # an area
    ("6 mm / 2 mm", "length", False),  # dimensionless
    ("(300 mm) / 2", "length", False),  # parentheses
    ("300 mm ** 1", "length", False),  # a power
    ("5mm + 3 mm", "length", False),  # a number glued to its unit inside arithmetic
    ("2 3 mm", "length", False),  # two numbers in a row
    ("mm 2", "length", False),
    ("5 mm +", "length", False),
    ("5 mm // 2", "length", False),
    ("5 deg + 3 mm", "length", False),
    ("1e99 * 1e99 * 1e99 * 1e99 mm", "length", False),  # overflows to inf: pint refuses
    ("100 mm /\u00a02", "length", False),  # a no-break space: pint's tokenizer refuses it
    ("3 mm + 2", "length", False),
    ("30 rpm / 2 s", "angular_velocity", False),
    ("30 rpm", "angle", False),  # another kind: pint's UNIT003
]


@pytest.mark.parametrize(("text", "kind", "fast"), CASES)
def test_arithmetic_is_pints(text: str, kind: str, fast: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    got = units._simple_si(text, kind)
    assert (got is not None) == fast, text
    slow = pint_si(text, kind, monkeypatch)
    if got is not None:
        assert repr(got) == repr(slow), text  # repr: 0.175 vs 0.17500000000000002, 0.0 vs -0.0
    try:
        whole: float | str = units._to_si(text, kind)
    except units.QuantityError as exc:
        whole = exc.code
    assert repr(whole) == repr(slow), text


def _random_text(rng: random.Random) -> tuple[str, str]:
    kind, names = rng.choice(
        [("length", ["mm", "cm", "m", "in", "ft"]), ("angle", ["deg", "rad"]), ("mass", ["g", "kg"])]
    )
    numbers = ["0", "1", "2", "3", "7", "10", "0.1", "0.2", "0.3", "19.1", "2.5e-3", "1E+2", "123456.789"]
    parts: list[str] = []
    for i in range(rng.randint(1, 4)):
        if i:
            parts.append(rng.choice([" + ", " - ", " * ", " / ", "+", "-", "*", "/"]))
        sign = rng.choice(["", "", "-", "+", "- "])
        shape = rng.randint(0, 4)
        number = rng.choice(numbers)
        unit = rng.choice(names if rng.random() < 0.9 else ["mm", "deg", "kg", "s"])
        shapes = [f"{number} {unit}", number, unit, f"{number} * {unit}", f"{number} {unit} / {rng.choice(numbers)}"]
        parts.append(sign + shapes[shape])
    return "".join(parts), kind


def test_random_arithmetic_is_pints(monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(17)
    answered = 0
    for _ in range(600):
        text, kind = _random_text(rng)
        got = units._simple_si(text, kind)
        if got is None:
            continue
        answered += 1
        assert repr(got) == repr(pint_si(text, kind, monkeypatch)), text
    assert answered > 100  # the pint-free path really ran on a good share of them


def test_validating_the_example_never_imports_pint() -> None:
    probe = (
        "import sys\nfrom descgen.audit.spec import load_spec\nload_spec(sys.argv[1])\n"
        "print('PINT' if 'pint' in sys.modules else 'NO-PINT')"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe, str(EXAMPLE)], capture_output=True, text=True, cwd=ROOT, timeout=60
    )
    assert done.stdout.strip().splitlines()[-1] == "NO-PINT", done.stderr[-2000:]
