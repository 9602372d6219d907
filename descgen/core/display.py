"""How numbers are shown to people, written once: millimetre vectors in reports and
evidence, and the test behind every "a thousand times off" hint.
"""

from __future__ import annotations

import math
from collections.abc import Sequence


def mm(v: Sequence[float], digits: int = 1) -> str:
    """A vector in metres shown in millimetres to ``digits`` decimals (0.1 mm by default):
    ``0.1, 0, 0.25`` -> ``100.0, 0.0, 250.0``. A value that rounds to zero is ``0.0``, never
    ``-0.0`` (a reader would hunt for a sign)."""
    return ", ".join(f"{round(c * 1000, digits) + 0.0:.{digits}f}" for c in v)


def mm_digits(tolerance_m: float) -> int:
    """Decimals of millimetres that show a value a tolerance of ``tolerance_m`` can judge: one
    more than the tolerance's own (0.001 mm -> 4), at least 1, at most 6."""
    tol_mm = tolerance_m * 1000
    if tol_mm <= 0 or not math.isfinite(tol_mm):
        return 6
    return max(1, min(6, math.ceil(-math.log10(tol_mm)) + 1))


def thousand_off(magnitude: float, low: float, high: float) -> float | None:
    """1000 when ``magnitude`` is above [low, high] and a thousandth of it is inside (grams
    typed as kilograms, millimetres as metres); 0.001 when it is below and a thousand times
    it is inside; None otherwise. Every "1000x off" hint asks this."""
    if magnitude > high and low <= magnitude / 1000 <= high:
        return 1000.0
    if magnitude < low and low <= magnitude * 1000 <= high:
        return 0.001
    return None
