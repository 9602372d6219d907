"""How numbers are shown to people, written once: millimetre vectors in reports and
evidence, and the test behind every "a thousand times off" hint.
"""

from __future__ import annotations

from collections.abc import Sequence


def mm(v: Sequence[float]) -> str:
    """A vector in metres shown in millimetres to 0.1 mm: ``0.1, 0, 0.25`` -> ``100.0, 0.0, 250.0``.
    A value that rounds to zero is ``0.0``, never ``-0.0`` (a reader would hunt for a sign)."""
    return ", ".join(f"{round(c * 1000, 1) + 0.0:.1f}" for c in v)


def thousand_off(magnitude: float, low: float, high: float) -> float | None:
    """1000 when ``magnitude`` is above [low, high] and a thousandth of it is inside (grams
    typed as kilograms, millimetres as metres); 0.001 when it is below and a thousand times
    it is inside; None otherwise. Every "1000x off" hint asks this."""
    if magnitude > high and low <= magnitude / 1000 <= high:
        return 1000.0
    if magnitude < low and low <= magnitude * 1000 <= high:
        return 0.001
    return None
