"""Pydantic field types for written quantities.

A quantity field accepts ``"300 mm"`` or ``{value: "300 mm", source: M17}``. Fields whose
kind is fixed (a box side is a length) are converted and range-checked here, during
validation. Fields whose kind depends on something else (a joint limit is an angle or a
length depending on the joint type) are kept as :class:`Written` and converted by the
builder with the same :func:`descgen.core.units.to_si`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Annotated, Any

from pydantic import BeforeValidator, ValidationInfo, WithJsonSchema
from pydantic_core import PydanticCustomError

from descgen.core import display, units
from descgen.core.record import record

_SOURCE_DESCRIPTION = "where the value comes from, e.g. the measurement-sheet row M01 (see require_sources, SPEC010)"
QUANTITY_SCHEMA: dict[str, Any] = {
    "anyOf": [
        {"type": "string", "description": 'a number and a unit, e.g. "300 mm"'},
        {"type": "number", "const": 0},
        {
            "type": "object",
            # {value: 0, source: ...} as import writes a zero (a bare 0 needs no unit)
            "properties": {
                "value": {
                    "anyOf": [{"type": "string"}, {"type": "number", "const": 0}],
                    "description": 'the value with its unit, e.g. "170 mm" (a bare 0 needs none)',
                },
                "source": {"type": "string", "description": _SOURCE_DESCRIPTION},
            },
            "required": ["value"],
            "additionalProperties": False,
        },
    ]
}


@record
class Written:
    """A value as written in the spec, with its source; not yet converted."""

    value: object
    source: str | None = None

    @property
    def text(self) -> str:
        if isinstance(self.value, tuple):  # a planar/floating joint's list, as written
            return "[" + ", ".join(map(str, self.value)) + "]"
        return str(self.value)


@record
class Measured:
    """A converted value: SI magnitude, what was written, its source."""

    si: float
    text: str
    kind: str
    source: str | None = None


def error(code: str, message: str, hint: str) -> PydanticCustomError:
    # Messages carry user text, which may contain braces: pass everything through ctx.
    return PydanticCustomError(code, "{message}", {"message": message, "hint": hint})


def unwrap(value: object) -> Written:
    """Split the ``{value, source}`` form; pass plain values through."""
    if isinstance(value, Written):
        return value
    if isinstance(value, dict):
        extra = sorted(set(value) - {"value", "source"})
        if extra:
            raise error("SPEC001", f"unknown key '{extra[0]}' in a quantity", "a quantity takes only value and source")
        if "value" not in value:
            raise error(
                "SPEC002", "a quantity written as a mapping needs 'value'", 'write {value: "300 mm", source: M01}'
            )
        source = value.get("source")
        if source is not None and not isinstance(source, str | int):
            raise error("SPEC003", "source must be text, e.g. M17", "write the measurement's row ID")
        return Written(value["value"], None if source is None else str(source))
    return Written(value)


def check_range(si: float, text: str, role: str, ranges: dict[str, units.Range]) -> None:
    r = ranges.get(role)
    if r is None or si == 0:
        return
    mag = abs(si)
    if r.low <= mag <= r.high:
        return
    shown = units.describe_si(si, r.kind)
    lo = units.describe_si(r.low, r.kind)
    hi = units.describe_si(r.high, r.kind)
    hint = f"if it is right, widen plausibility.{role} in the spec"
    off = display.thousand_off(mag, r.low, r.high)
    if off == 1000:
        guess = {"length": "mm", "mass": "g"}.get(r.kind)
        thousand = (
            f'was it measured in {guess}? e.g. "{_number(text)} {guess}"'
            if guess
            else "is it a thousand times too large?"
        )
        hint = f"{thousand}; {hint}"
    elif off == 0.001:
        guess = {"length": "m", "mass": "kg"}.get(r.kind)
        thousand = (
            f'was it measured in {guess}? e.g. "{_number(text)} {guess}"'
            if guess
            else "is it a thousand times too small?"
        )
        hint = f"{thousand}; {hint}"
    raise error(
        "UNIT004",
        f'"{text}" (= {shown}) is outside the plausible range for {role.replace("_", " ")}: {lo} to {hi}',
        hint,
    )


def _number(text: str) -> str:
    head = text.strip().split(" ", 1)[0]
    return head if head else text


def convert(w: Written, kind: str, role: str | None, ranges: dict[str, units.Range]) -> Measured:
    return _convert(w.value, w.text, w.source, kind, role, ranges)


def _convert(
    value: object, text: str, source: str | None, kind: str, role: str | None, ranges: dict[str, units.Range]
) -> Measured:
    try:
        si = units.to_si(value, kind)
    except units.QuantityError as exc:
        raise error(exc.code, exc.message, exc.hint) from None
    if role is not None:
        check_range(si, text, role, ranges)
    return Measured(si, text, kind, source)


def _ranges(info: ValidationInfo | None) -> dict[str, units.Range]:
    ctx = info.context if info is not None and isinstance(info.context, dict) else {}
    ranges = ctx.get("ranges")
    return ranges if isinstance(ranges, dict) else units.DEFAULT_RANGES


MEMO = "quantities"
"""The validation context's key for a per-spec memo of plain quantity texts already converted:
(text, kind, role) -> Measured. A spec repeats its texts ("0", "40 mm") thousands of times;
the result depends only on them and the context's ranges, and a Measured is immutable."""


def _memo(info: ValidationInfo | None) -> dict[tuple[str, str, str | None], Measured] | None:
    ctx = info.context if info is not None else None
    memo = ctx.get(MEMO) if isinstance(ctx, dict) else None
    return memo if isinstance(memo, dict) else None


def _measured(kind: str, role: str | None) -> Callable[[object, ValidationInfo], Measured]:
    def validate(value: object, info: ValidationInfo) -> Measured:
        if type(value) is str:  # nearly every value ("300 mm"): what unwrap and convert do, without a Written
            memo = _memo(info)
            if memo is None:
                return _convert(value, value, None, kind, role, _ranges(info))
            key = (value, kind, role)
            done = memo.get(key)
            if done is None:  # a value that fails is not kept: it fails again, with its message
                done = memo[key] = _convert(value, value, None, kind, role, _ranges(info))
            return done
        if isinstance(value, Measured):
            return value
        return convert(unwrap(value), kind, role, _ranges(info))

    return validate


def _written(value: object) -> Written:
    w = unwrap(value)
    if not isinstance(w.value, str | int | float) or isinstance(w.value, bool):
        raise error("UNIT001", "expected a quantity with a unit", 'write e.g. "300 mm" or "-90 deg"')
    if isinstance(w.value, float) and not math.isfinite(w.value):
        raise error("UNIT002", "not a finite number", "write a finite value")
    return w


def Q(kind: str, role: str | None = None) -> Any:  # noqa: N802 - reads as a type
    """``Annotated[Measured, …]`` for a field of one kind and plausibility role."""
    example = units.KINDS[kind].example
    schema = dict(QUANTITY_SCHEMA, examples=[example])
    return Annotated[Measured, BeforeValidator(_measured(kind, role)), WithJsonSchema(schema)]


Length = Q("length", "offset")
Size = Q("length", "size")
Angle = Q("angle", "angle")
Mass = Q("mass", "mass")
InertiaQ = Q("inertia")
Tolerance = Q("length", "tolerance")
Frequency = Q("frequency", "frequency")
LinearVelocity = Q("linear_velocity", "linear_velocity")
AngularVelocity = Q("angular_velocity", "angular_velocity")
LinearAcceleration = Q("linear_acceleration", "linear_acceleration")
Duration = Q("time")
Raw = Annotated[Written, BeforeValidator(_written), WithJsonSchema(QUANTITY_SCHEMA)]
"""A quantity whose kind the builder decides (joint limits, joint values)."""


def _joint_written(value: object) -> Written:
    """One quantity, or a list of them (the several values of a planar or floating joint)."""
    w = unwrap(value)
    if not isinstance(w.value, list | tuple):
        return _written(value)
    if not w.value:
        raise error("UNIT001", "expected a list of quantities, got an empty list", "write e.g. [0 mm, 0 mm, 0 deg]")
    return Written(tuple(_written(v).value for v in w.value), w.source)


_JOINT_VALUE_SCHEMA: dict[str, Any] = {
    "anyOf": [
        *QUANTITY_SCHEMA["anyOf"],
        {"type": "array", "items": {"anyOf": [{"type": "string"}, {"type": "number"}]}, "minItems": 1},
        {
            "type": "object",
            "properties": {
                "value": {
                    "type": "array",
                    "items": {"anyOf": [{"type": "string"}, {"type": "number"}]},
                    "minItems": 1,
                    "description": "the joint's values in MoveIt's variable order, e.g. [0 mm, 0 mm, 90 deg] for x, y, "
                    "theta of a planar joint",
                },
                "source": {"type": "string", "description": _SOURCE_DESCRIPTION},
            },
            "required": ["value"],
            "additionalProperties": False,
        },
    ]
}
JointRaw = Annotated[Written, BeforeValidator(_joint_written), WithJsonSchema(_JOINT_VALUE_SCHEMA)]
"""A joint value in a group state or known pose: one quantity, or for a planar or floating
(virtual) joint a list, in MoveIt's variable order (x, y, theta; trans_x..z, rot_x..w)."""

ZERO = Measured(0.0, "0", "length")
ZERO_ANGLE = Measured(0.0, "0", "angle")
