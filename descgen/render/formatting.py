"""How values are written into output files (shortest round-trip floats, escaping)."""

from __future__ import annotations

import math
import re
from collections.abc import Iterable

from markupsafe import Markup


def num(x: float | int) -> str:
    """Shortest text that reads back as the same float; ``-0.0`` prints as ``0``;
    whole numbers print without a fraction."""
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"cannot write non-finite value {v!r}")
    if v == 0:
        return "0"
    if v.is_integer() and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def vec(values: Iterable[float]) -> str:
    return " ".join(num(v) for v in values)


_DASHES = re.compile(r"-{2,}")


def comment(text: object) -> str:
    """Text safe inside an XML comment (no ``--``, no trailing ``-``) or after ``#``:
    one line, so that nothing can end the comment early."""
    s = " ".join(str(text).split())
    s = _DASHES.sub(lambda m: "- " * (len(m.group()) - 1) + "-", s)
    return s + " " if s.endswith("-") else s


def xacro_text(text: object) -> str:
    """Spec text placed where xacro evaluates ``${}``/``$()``: every ``$`` becomes the
    expression ``${'$'}``, which evaluates to a literal dollar, so no spec text can become
    a xacro expression or substitution (xacro 2.x lexer: reference/xacro.md)."""
    return str(text).replace("$", "${'$'}")


def yaml_scalar_safe(text: str) -> Markup:
    """Mark already-serialised YAML as safe for a template (no HTML escaping)."""
    return Markup(text)


def mdcell(text: object) -> str:
    """Text safe in a Markdown table cell: one line, pipes and markup escaped."""
    s = " ".join(str(text).split())
    for ch in "\\|`*_[]<>":
        s = s.replace(ch, "\\" + ch)
    return s
