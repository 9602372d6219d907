"""SI values from a description -> quantity texts in a reviewer's unit, exactly.

A URDF number is a float. Its text in another unit is computed in decimal from the
float's shortest repr (``0.48514`` m -> ``485.14 mm``, never ``485.14000000000004 mm``),
then read back with the spec's own parser (:func:`descgen.core.units.to_si`): only a text
that gives the very same float is used, else the value is written in its SI unit, which
is always exact. So an imported spec means bit for bit the numbers of the description.
"""

from __future__ import annotations

import math
import re
from decimal import Decimal

from descgen.core import units
from descgen.core.record import record

# What --units may name, per kind: the unit written and how many SI units one of it is.
_SCALED = {"mm": Decimal("1000"), "g": Decimal("1000"), "cm": Decimal("100")}


@record
class Units:
    """The units written for lengths, angles and masses (everything else stays SI)."""

    length: str = "mm"
    angle: str = "deg"
    mass: str = "kg"

    @classmethod
    def parse(cls, text: str) -> Units:
        """``mm,deg,kg`` (any order, any subset) or ``si``; ValueError names the problem."""
        if text.strip() == "si":
            return cls("m", "rad", "kg")
        chosen = {"length": "m", "angle": "rad", "mass": "kg"}
        allowed = {
            "mm": "length",
            "cm": "length",
            "m": "length",
            "deg": "angle",
            "rad": "angle",
            "kg": "mass",
            "g": "mass",
        }
        for part in (p.strip() for p in text.split(",")):
            if part not in allowed:
                raise ValueError(f"'{part}' is not one of {', '.join(allowed)} (or write si)")
            chosen[allowed[part]] = part
        return cls(chosen["length"], chosen["angle"], chosen["mass"])


def _plain(d: Decimal) -> str:
    """A decimal without exponent or trailing zeros: ``485.14``, ``-0.001``, ``12``."""
    text = format(d.normalize(), "f")
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def si_text(value: float) -> str:
    """The float's shortest decimal text, without exponent (``1e-05`` -> ``0.00001``)."""
    return _plain(Decimal(repr(value)))


def _exact(text: str, kind: str, value: float) -> bool:
    try:
        return units.to_si(text, kind) == value
    except units.QuantityError:
        return False


def quantity(value: float, kind: str, unit: str) -> str | int:
    """``value`` (SI) as a quantity text in ``unit`` when that reads back exactly, else in SI.

    Zero is written ``0`` (zero in every unit)."""
    if value == 0:
        return 0
    si_unit = units.KINDS[kind].si_unit
    si_unit = si_unit.replace("**", "^")
    si_written = f"{si_text(value)} {si_unit}"
    if not _exact(si_written, kind, value):  # too many digits for the parser: keep the exponent
        si_written = f"{value!r} {si_unit}"
    if unit in _SCALED:
        text = f"{_plain(Decimal(repr(value)) * _SCALED[unit])} {unit}"
    elif unit in ("deg", "deg/s"):
        text = _shortest_degrees(value, kind, unit)
        # an angle is written in degrees when that is no longer than radians (90 deg, not
        # 1.5707963267948966 rad), and 0.1 rad stays 0.1 rad (not 5.729577951308233 deg)
        if _digits(text) > _digits(si_written):
            return si_written
    else:
        return si_written
    return text if _exact(text, kind, value) else si_written


def _digits(text: str) -> int:
    return len(re.sub(r"[^0-9]", "", text.split(" ")[0]).lstrip("0"))


def _shortest_degrees(value: float, kind: str, unit: str) -> str:
    """The shortest degree text that reads back as ``value`` (-120 deg, not
    -119.99999999999999 deg, when both give the same radians)."""
    deg = math.degrees(value)
    for digits in range(1, 18):
        text = f"{si_text(float(f'{deg:.{digits}g}'))} {unit}"
        if _exact(text, kind, value):
            return text
    return f"{si_text(deg)} {unit}"
