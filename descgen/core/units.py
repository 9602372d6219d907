"""Quantities: the only pint registry, and the only place a unit is converted to SI.

Every dimensional value in a spec is text with an explicit unit (``"300 mm"``,
``"-90 deg"``, ``"30 rpm"``). :func:`to_si` reads it with pint, checks that it is the
kind of quantity the field wants, and returns metres, radians, kilograms, seconds,
newtons or newton-metres. Nothing downstream sees a unit again.

pint pitfalls handled here (see STYLE.md):
- bad text raises more than ``PintError`` (AssertionError, TokenError, ZeroDivisionError);
- ``"1,5 m"`` reads as 15 m, so commas are rejected first;
- ``"nan m"`` parses, hence the finiteness check;
- the radian is dimensionless, so ``"1 Hz"`` would pass as 1 rad/s and a bare ``"3"``
  as an angle: angle-bearing kinds must name an angle unit, and frequencies must not;
- ``"40 J"`` has the dimensions of a torque, so energy units are refused for torques.
"""

from __future__ import annotations

import functools
import math
import re
import sys
from decimal import Decimal
from pathlib import Path
from typing import TYPE_CHECKING, Any

from descgen.core.cache_dir import cache_folder
from descgen.core.record import record

if TYPE_CHECKING:
    import pint

# Environment variable naming the folder for pint's parsed-definition cache ("" = no cache).


def _import_pint() -> Any:
    """pint, imported without its optional scipy support.

    pint probes ``import scipy`` at import, only for numpy-array functions descgen never
    calls; that probe would put scipy into every cold start. Hidden only while pint is
    first imported (a later ``import scipy`` anywhere works as usual)."""
    if "pint" not in sys.modules and "scipy" not in sys.modules:
        sys.modules["scipy"] = None  # type: ignore[assignment]  # makes "import scipy" raise ImportError
        try:
            import pint
        finally:
            del sys.modules["scipy"]
    import pint

    return pint


@functools.cache
def registry() -> pint.UnitRegistry[Any]:
    """The project's one registry, built on first use. Never create another (quantities
    from two registries cannot be combined).

    Built lazily because ``--help``, ``rules`` and ``schema`` need no units, and from pint's
    definition cache because parsing pint's definition file is ~0.15 s of every cold start."""
    lib = _import_pint()
    reg: pint.UnitRegistry[Any]
    folder = _cache_folder()
    if folder is not None:
        try:
            reg = lib.UnitRegistry(cache_folder=folder)
            return reg
        except Exception:  # a cache another process is writing, or unwritable: build it afresh
            pass
    reg = lib.UnitRegistry()
    return reg


def _cache_folder() -> Path | None:
    """Where pint may cache its parsed definitions, per pint version; None when caching is off
    or the folder cannot be made."""
    return cache_folder(f"pint-{_import_pint().__version__}")


def __getattr__(name: str) -> Any:
    # ``units.ureg`` still works, built on first access like ``registry()``
    if name == "ureg":
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@record
class Kind:
    """A kind of physical quantity a field accepts."""

    name: str
    dimensionality: str  # pint dimensionality, ignoring angles
    si_unit: str  # what the value is converted to
    radians: tuple[int, ...]  # allowed powers of an angle unit (rad is dimensionless in pint)
    example: str


KINDS: dict[str, Kind] = {
    k.name: k
    for k in (
        Kind("length", "[length]", "m", (0,), "300 mm"),
        Kind("angle", "[]", "rad", (1,), "-90 deg"),
        Kind("mass", "[mass]", "kg", (0,), "1200 g"),
        Kind("time", "[time]", "s", (0,), "2 s"),
        Kind("frequency", "1/[time]", "Hz", (0,), "100 Hz"),
        Kind("linear_velocity", "[length]/[time]", "m/s", (0,), "0.1 m/s"),
        Kind("angular_velocity", "1/[time]", "rad/s", (1,), "90 deg/s"),
        # joint acceleration limits (MoveIt's joint_limits.yaml; a URDF has none)
        Kind("linear_acceleration", "[length]/[time]**2", "m/s**2", (0,), "0.2 m/s^2"),
        Kind("angular_acceleration", "1/[time]**2", "rad/s**2", (1,), "180 deg/s^2"),
        Kind("force", "[force]", "N", (0,), "500 N"),
        Kind("torque", "[force]*[length]", "N*m", (0,), "40 N*m"),
        Kind("inertia", "[mass]*[length]**2", "kg*m**2", (0,), "0.01 kg*m^2"),
        Kind("density", "[mass]/[length]**3", "kg/m**3", (0,), "2700 kg/m^3"),
        # joint dynamics and safety-controller gains, in URDF's units per joint type
        Kind("linear_damping", "[force]*[time]/[length]", "N*s/m", (0,), "5 N*s/m"),
        Kind("angular_damping", "[force]*[length]*[time]", "N*m*s/rad", (-1, 0), "0.5 N*m*s/rad"),
        Kind("linear_stiffness_gain", "1/[time]", "1/s", (0,), "100 1/s"),
        Kind("angular_stiffness_gain", "1/[time]", "1/s", (0,), "100 1/s"),
    )
}


@functools.cache
def _energy() -> Any:
    return registry().get_dimensionality("[energy]")


class QuantityError(ValueError):
    """A quantity text that cannot be used; ``code`` is the finding code."""

    def __init__(self, code: str, message: str, hint: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
        self.hint = hint


# A bare number's likely unit, for the hint only (the value is still refused): the unit in
# which that number is a plausible size for a robot. Millimetres and grams are how parts are
# measured, so numbers from 10 mm and 100 g up read as those; an angle beyond one turn in
# radians is surely in degrees. (unit below, unit from this magnitude up)
_LIKELY_UNIT: dict[str, tuple[str, float, str]] = {
    "length": ("m", 10.0, "mm"),
    "mass": ("kg", 100.0, "g"),
    "angle": ("rad", 2 * math.pi + 1e-9, "deg"),
    "angular_velocity": ("rad/s", 2 * math.pi + 1e-9, "deg/s"),
}


def likely_unit(kind_name: str, magnitude: float) -> str:
    """The unit a bare ``magnitude`` of this kind was most likely measured in: 300 → mm and
    0.3 → m for a length, 1200 → g and 2.5 → kg for a mass, 90 → deg and 1.57 → rad for
    an angle; other kinds get their usual unit."""
    small, threshold, large = _LIKELY_UNIT.get(kind_name, ("", 0.0, ""))
    if not small:
        return KINDS[kind_name].example.split(" ", 1)[1]
    return large if abs(magnitude) >= threshold else small


def _a(kind_name: str) -> str:
    words = kind_name.replace("_", " ")
    return ("an " if words[0] in "aeiou" else "a ") + words


def _radian_power(q: pint.Quantity[Any]) -> int:
    _, root = registry().get_root_units(q.units)
    return int(dict(root._units).get("radian", 0))  # type: ignore[arg-type]


# pint evaluates its text as arithmetic with Python numbers, so "9**9**9 kg" would compute a
# number with hundreds of millions of digits before anything else is checked. Quantity text
# is therefore bounded first; these limits are far beyond any measured value.
MAX_TEXT = 200  # characters of quantity text
MAX_DIGITS = 40  # digits in one number
MAX_EXPONENT = 100  # |n| in "x**n" / "x^n"
_NUMBER = r"(?:\d[\d_]*\.?[\d_]*|\.\d[\d_]*)(?:[eE][+-]?\d+)?"
# an exponent pint may evaluate: a plain number, optionally signed, optionally in parentheses
# (pint turns "m²" into "m**(2)"); nothing may follow it that continues a name or a number
_EXPONENT = re.compile(rf"\s*(?:[+-]\s*)?(?:({_NUMBER})|\(\s*(?:[+-]\s*)?({_NUMBER})\s*\))(?![\w.])")
_POWER = re.compile(r"\*\*")


def _too_complex(text: str) -> str | None:
    """Why pint must not evaluate ``text`` (None if it may). Checked on pint's own
    preprocessed form, where "^" and superscripts have already become "**"."""
    if len(text) > MAX_TEXT:
        return f"is {len(text)} characters long; quantity text is at most {MAX_TEXT}"
    expr = _import_pint().util.string_preprocessor(text)
    for digits in re.findall(r"\d[\d_]*", expr):
        if len(digits) > MAX_DIGITS:
            return f"has a number with {len(digits)} digits; at most {MAX_DIGITS} are read"
    for power in _POWER.finditer(expr):
        m = _EXPONENT.match(expr, power.end())
        if m is None:
            return "raises to a power that is not a plain number"
        exponent = float((m.group(1) or m.group(2)).replace("_", ""))
        if abs(exponent) > MAX_EXPONENT:
            return f"raises to the power {exponent:g}; at most {MAX_EXPONENT} is read"
        if expr[m.end() :].lstrip().startswith("**"):
            return "chains powers (a**b**c)"
        if expr[: power.start()].rstrip().endswith(")") and "**" in _group_before(expr, power.start()):
            return "raises a power to a power ((a**b)**c)"
    return None


def _group_before(expr: str, end: int) -> str:
    """The parenthesised group that closes just before ``end``."""
    i = expr.rindex(")", 0, end)
    depth = 0
    for k in range(i, -1, -1):
        depth += {")": 1, "(": -1}.get(expr[k], 0)
        if depth == 0:
            return expr[k : i + 1]
    return expr[: i + 1]  # unbalanced: pint refuses it anyway, the whole prefix is the group


def parse(text: str) -> pint.Quantity[Any]:
    """Read quantity text with pint; refuse text that pint would misread or could not
    evaluate in bounded time."""
    stripped = text.strip()
    if not stripped:
        raise QuantityError("UNIT002", "empty quantity", 'write a value and a unit, e.g. "300 mm"')
    why = _too_complex(stripped)
    if why is not None:
        shown = stripped if len(stripped) <= 40 else stripped[:37] + "..."
        raise QuantityError(
            "UNIT020",
            f'quantity text "{shown}" {why}',
            'write a number and a unit, e.g. "300 mm" or "0.01 kg*m^2"',
        )
    if "," in stripped:
        raise QuantityError(
            "UNIT002",
            f'"{text}" contains a comma (pint would read "1,5 m" as 15 m)',
            "use a decimal point, and write vectors as a YAML list",
        )
    try:
        q: Any = registry().Quantity(stripped.replace("·", "*").replace("×", "*"))
    except Exception:  # pint raises AssertionError, TokenError, ... on bad text
        raise QuantityError(
            "UNIT002", f'cannot read "{text}" as a quantity', 'write a number and a unit, e.g. "300 mm"'
        ) from None
    if not isinstance(q, registry().Quantity):
        raise QuantityError("UNIT002", f'"{text}" is not a quantity', 'write a number and a unit, e.g. "300 mm"')
    mag = q.magnitude
    try:
        finite = isinstance(mag, int | float) and not isinstance(mag, bool) and math.isfinite(float(mag))
    except OverflowError:  # an integer too large for a float
        finite = False
    if not finite:
        raise QuantityError("UNIT002", f'"{text}" is not a finite number', "write a finite value")
    return q


def to_si(value: object, kind_name: str) -> float:
    """Convert one written value to the SI unit of ``kind_name`` (see :func:`_to_si`)."""
    if isinstance(value, str | int | float) and not isinstance(value, bool):
        si = _to_si_cached(value, kind_name)
        if isinstance(si, tuple):  # a refusal, remembered as its words: raised anew each time
            raise QuantityError(*si)
        return si
    return _to_si(value, kind_name)


@functools.lru_cache(maxsize=4096, typed=True)
def _to_si_cached(value: str | int | float, kind_name: str) -> float | tuple[str, str, str]:
    # pint parses slowly (~0.5 ms); specs repeat the same texts ("0", "100 mm") a lot, and a
    # bad text repeated (a YAML alias, a copied line) is refused as often: the refusal is
    # remembered too (code, message, hint), so 10,000 repeats cost one parse. Typed: 28 and
    # 28.0 are one key otherwise, and the refusal of one would quote the other ("28.0 kg")
    try:
        return _to_si(value, kind_name)
    except QuantityError as exc:
        return (exc.code, exc.message, exc.hint)


def _to_si(value: object, kind_name: str) -> float:
    """Convert one written value to the SI unit of ``kind_name``.

    A bare number is refused (except exactly zero, which is zero in every unit), so a
    value can never be silently read in the wrong unit.
    """
    kind = KINDS[kind_name]
    if isinstance(value, bool) or value is None:
        raise QuantityError(
            "UNIT001",
            f"expected {_a(kind.name)} with a unit, got {value!r}",
            f'write it with a unit, e.g. "{kind.example}"',
        )
    if isinstance(value, int | float):
        if value == 0:
            return 0.0
        raise QuantityError(
            "UNIT001",
            f"bare number {value!r} where {_a(kind.name)} is expected",
            f'write the unit it was measured in, e.g. "{value} {likely_unit(kind.name, value)}"',
        )
    if not isinstance(value, str):
        raise QuantityError(
            "UNIT001",
            f"expected {_a(kind.name)} as text with a unit",
            f'write e.g. "{kind.example}"',
        )
    fast = _simple_si(value, kind.name)
    if fast is not None:
        return fast
    q = parse(value)
    if q.unitless:
        if q.magnitude == 0:
            return 0.0
        raise QuantityError(
            "UNIT001",
            f'"{value}" has no unit where {_a(kind.name)} is expected',
            f'write the unit it was measured in, e.g. "{q.magnitude} {likely_unit(kind.name, q.magnitude)}"',
        )
    wrong = QuantityError(
        "UNIT003",
        f'"{value}" is not {_a(kind.name)} ({q.units:~} has the wrong dimensions)',
        f'write {_a(kind.name)}, e.g. "{kind.example}"',
    )
    if not q.check(kind.dimensionality):
        raise wrong
    if _radian_power(q) not in kind.radians:
        if kind.radians == (1,):
            raise QuantityError(
                "UNIT003",
                f'"{value}" names no angle unit, so it is not {_a(kind.name)}',
                f'write an angle unit (rad, deg, rev), e.g. "{kind.example}"',
            )
        raise QuantityError(
            "UNIT003",
            f'"{value}" names an angle unit, so it is not {_a(kind.name)}',
            f'write {_a(kind.name)}, e.g. "{kind.example}"',
        )
    if kind.name == "torque" and any(registry().get_dimensionality(u) == _energy() for u in dict(q._units)):
        raise QuantityError(
            "UNIT003",
            f'"{value}" is an energy, not a torque',
            'write a torque as force times length, e.g. "40 N*m"',
        )
    target = kind.si_unit if kind.radians == (0,) else q.to_base_units().units
    si = _convert(q, target)
    return 0.0 if si == 0 else si  # -0.0 would print as "-0"


# The texts nearly every spec is written in ("300 mm", "-90 deg", "1.2 kg", "75 mm - 30 mm")
# are converted without pint: a number and one of these units, each with the kind it is and its
# factor to SI exactly as pint states it (tests/test_units_fast.py compares every entry with
# pint), or + - * / arithmetic over such terms (see _expression_si). pint costs ~0.5 ms per
# text, and importing it and building its registry ~0.1 s per process; anything else, and any
# unit of another kind than the field's, still goes through pint and its checks.
_SIMPLE_UNITS: dict[str, tuple[str, str]] = {
    "mm": ("length", "0.001"),
    "cm": ("length", "0.01"),
    "m": ("length", "1.0"),
    "in": ("length", "0.0254"),
    "ft": ("length", "0.30479999999999996"),
    "deg": ("angle", "0.017453292519943295"),
    "rad": ("angle", "1.0"),
    "g": ("mass", "0.001"),
    "kg": ("mass", "1.0"),
    "s": ("time", "1.0"),
    "ms": ("time", "0.001"),
    "N": ("force", "1.0"),
    "N*m": ("torque", "1.0"),
    "Hz": ("frequency", "1.0"),
    "m/s": ("linear_velocity", "1.0"),
    "mm/s": ("linear_velocity", "0.001"),
    "rad/s": ("angular_velocity", "1.0"),
    "deg/s": ("angular_velocity", "0.017453292519943295"),
    "rpm": ("angular_velocity", "0.10471975511965977"),
    "m/s^2": ("linear_acceleration", "1.0"),
    "rad/s^2": ("angular_acceleration", "1.0"),
    "deg/s^2": ("angular_acceleration", "0.017453292519943295"),
    "kg*m^2": ("inertia", "1.0"),
}
# At most 15 significant digits and a small exponent: always a finite float, read as pint reads
# it. No leading zero before a digit: Python's tokenizer, which pint uses, reads "0123" as the
# two numbers 0 and 123 (pint: 0 mm), so such text is left to pint.
_NUMBER_TEXT = r"(?:0|[1-9][0-9]{0,14})(?:\.[0-9]{1,15})?(?:[eE][+-]?[0-9]{1,2})?"
_SIMPLE = re.compile(rf"([+-]?{_NUMBER_TEXT}) {{0,4}}([A-Za-z*/^2]+)")


def _simple_si(text: str, kind_name: str) -> float | None:
    """The SI value of a plain "<number> <unit>" text of this kind, or of + - * / arithmetic
    over such terms, computed as pint computes it; None for anything else (pint decides)."""
    if len(text) > MAX_TEXT:
        return None
    m = _SIMPLE.fullmatch(text.strip())
    if m is None:
        return _expression_si(text, kind_name)
    unit = _SIMPLE_UNITS.get(m.group(2))
    if unit is None or unit[0] != kind_name:
        return None
    si = float(Decimal(repr(float(m.group(1)))) * Decimal(unit[1]))
    return 0.0 if si == 0 else si


# Arithmetic in quantity text ("75 mm - 30 mm", "19.1 in / 2", "25 mm + 2 * 5 mm"), evaluated the
# way pint evaluates it (pint_eval.py): numbers are Python ints or floats as Python's tokenizer
# reads them, a unit name is a quantity of magnitude 1, "*", "/" and the implicit product of a
# number and a unit bind tighter than "+" and "-", operators of equal priority group left to right,
# and a unary sign binds tightest; a sum of two quantities in the same unit adds their magnitudes.
# Accepted only when the result is one unit of the field's kind to the first power: each term has
# exactly one unit, never in a divisor, and every term of a sum has the same unit. Anything else
# (another unit, parentheses, powers, a zero divisor, a non-finite result) is left to pint.
_TOKEN = re.compile(rf"( *)(?:({_NUMBER_TEXT})|([A-Za-z]+)|([-+*/]))")
_ATOMIC_UNITS = {name: unit for name, unit in _SIMPLE_UNITS.items() if name.isalpha()}
_Term = tuple[int | float, str | None]  # magnitude, unit name (None: a plain number)


class _NotSimpleError(Exception):
    pass


def _tokens(text: str) -> list[str]:
    """Operators, numbers and unit names, with "" for the implicit product of a number and the
    unit written after it ("5 mm"); _NotSimpleError for anything pint might read otherwise."""
    out: list[str] = []
    kinds: list[str] = []
    pos, end = 0, len(text)
    while pos < end:
        m = _TOKEN.match(text, pos)
        if m is None:
            raise _NotSimpleError
        kind = "number" if m.group(2) else "name" if m.group(3) else "op"
        if kinds and kinds[-1] != "op" and kind != "op":
            # two operands in a row: only "<number> <unit>", with a space between them
            if not (kinds[-1] == "number" and kind == "name" and m.group(1)):
                raise _NotSimpleError
            out.append("")
            kinds.append("op")
        out.append(m.group(2) or m.group(3) or m.group(4))
        kinds.append(kind)
        pos = m.end()
    return out


def _expression_si(text: str, kind_name: str) -> float | None:
    try:
        tokens = _tokens(text.strip())
        (mag, unit), pos = _sum(tokens, 0)
        if pos != len(tokens) or unit is None:
            return None
        factor_of = _ATOMIC_UNITS[unit]
        if factor_of[0] != kind_name:
            return None
        value = float(mag)
    except (_NotSimpleError, OverflowError, ZeroDivisionError, IndexError):
        return None
    if not math.isfinite(value):
        return None
    si = float(Decimal(repr(value)) * Decimal(factor_of[1]))
    return 0.0 if si == 0 else si


def _sum(tokens: list[str], pos: int) -> tuple[_Term, int]:
    (a, ua), pos = _product(tokens, pos)
    while pos < len(tokens) and tokens[pos] in ("+", "-"):
        op = tokens[pos]
        (b, ub), pos = _product(tokens, pos + 1)
        if ua != ub:
            raise _NotSimpleError  # pint converts or refuses: its answer
        a = a + b if op == "+" else a - b
    return (a, ua), pos


def _product(tokens: list[str], pos: int) -> tuple[_Term, int]:
    (a, ua), pos = _signed(tokens, pos)
    while pos < len(tokens) and tokens[pos] in ("*", "/", ""):
        op = tokens[pos]
        (b, ub), pos = _signed(tokens, pos + 1)
        if ub is not None and (ua is not None or op == "/"):
            raise _NotSimpleError  # a unit squared, or a unit in a divisor
        a, ua = (a / b if op == "/" else a * b), ua or ub
    return (a, ua), pos


def _signed(tokens: list[str], pos: int) -> tuple[_Term, int]:
    token = tokens[pos]
    if token in ("+", "-"):
        (a, ua), pos = _signed(tokens, pos + 1)
        return (a * -1 if token == "-" else a, ua), pos  # pint: x * -1
    if token in ("*", "/", ""):
        raise _NotSimpleError
    if token[0].isdigit():
        number: int | float = int(token) if token.isdigit() else float(token)
        return (number, None), pos + 1
    if token not in _ATOMIC_UNITS:
        raise _NotSimpleError
    return (1, token), pos + 1


def _convert(q: pint.Quantity[Any], target: Any) -> float:
    """Multiply by the conversion factor in decimal, so that "175 mm" is 0.175 m and not
    0.17500000000000002 (which would then be printed, diffed and compared as such)."""
    factor = registry().Quantity(1, q.units).to(target).magnitude
    return float(Decimal(repr(float(q.magnitude))) * Decimal(repr(float(factor))))


_BARE_NUMBER = re.compile(rf"[+-]?{_NUMBER}")


def duration(value: object, low: float, high: float, bare_seconds: bool = False) -> float:
    """A time in seconds within ``[low, high]``: option values and trajectory times.

    ``bare_seconds`` reads a plain number as seconds, for options documented as "seconds"
    before they took units. Raises :class:`QuantityError` (UNIT021 when out of range).
    """
    written = value
    if bare_seconds and isinstance(value, str) and _BARE_NUMBER.fullmatch(value.strip()):
        written = f"{value.strip()} s"
    seconds = to_si(written, "time")
    if not low <= seconds <= high:
        raise QuantityError(
            "UNIT021",
            f'"{value}" (= {describe_si(seconds, "time")}) is outside the allowed range '
            f"{describe_si(low, 'time')} to {describe_si(high, 'time')}",
            f"give a time from {low:g} s to {high:g} s",
        )
    return seconds


def describe_si(value: float, kind_name: str) -> str:
    """How an SI value is shown in messages, e.g. ``25 m``."""
    unit = {"angle": "rad", "angular_velocity": "rad/s", "angular_acceleration": "rad/s^2"}.get(
        kind_name, KINDS[kind_name].si_unit
    )
    return f"{value:.6g} {unit.replace('**', '^')}"


@record
class Range:
    """Plausible SI magnitudes for one role of a quantity (inclusive)."""

    kind: str
    low: float  # smallest plausible |value| for a non-zero value (0 = no lower bound)
    high: float  # largest plausible |value|


# Defaults for robots from a hand-sized gripper to a forklift. A spec overrides any of
# them under `plausibility:`. The gaps are wide on purpose: they exist to catch values
# a thousand times off (millimetres typed as metres, grams as kilograms), not to judge design.
DEFAULT_RANGES: dict[str, Range] = {
    "offset": Range("length", 0.0, 10.0),
    "size": Range("length", 0.0005, 10.0),
    "angle": Range("angle", 0.0, 2 * math.pi),
    "joint_travel": Range("length", 0.0, 20.0),
    "joint_angle": Range("angle", 0.0, 4 * math.pi),
    "mass": Range("mass", 0.0005, 5000.0),
    "linear_velocity": Range("linear_velocity", 0.0, 10.0),
    "angular_velocity": Range("angular_velocity", 0.0, 100.0),
    "linear_acceleration": Range("linear_acceleration", 0.0, 100.0),
    "angular_acceleration": Range("angular_acceleration", 0.0, 1000.0),
    "force": Range("force", 0.0, 1e5),
    "torque": Range("torque", 0.0, 1e4),
    "frequency": Range("frequency", 0.1, 10000.0),
    "tolerance": Range("length", 1e-6, 0.5),
    "density": Range("density", 5.0, 25000.0),
}
