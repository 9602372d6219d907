"""One printed row per measurement:
`measure | descgen median (min) | anchor median (min) | ratio | wall ratio | pairs | cold/warm`.

Every benchmark prints its figures through :func:`row` (benchmarks/harness.py calls it for
every comparison it times), so `make bench` reads as one table. ``cold`` means both sides are
fresh processes (what a user or a pre-commit hook pays); ``warm`` means in-process after
imports (the work alone), both sides alike unless the measure says otherwise. ``ratio`` is of
the medians, descgen / anchor for times and anchor / descgen for rates, so above 1 always
means descgen is slower; ``wall ratio`` is the same ratio of wall-time medians. When
``BENCH_ROWS`` names a file, each row is also appended to it as one JSON line, for
``benchmarks/summary.py``.
"""

from __future__ import annotations

import json
import os
from typing import Literal

Kind = Literal["cold", "warm"]

COLUMNS = ("measure", "descgen median (min)", "anchor median (min)", "ratio", "wall ratio", "pairs", "cold/warm")


def seconds(value: float) -> str:
    if value < 0.1:
        return f"{value * 1000:.2f} ms"
    return f"{value:.3f} s" if value < 10 else f"{value:.1f} s"


def _shown(value: float, unit: str, best: float | None) -> str:
    if unit == "s":
        text = seconds(value)
        return text if best is None else f"{text} (min {seconds(best)})"
    text = f"{value:,.0f} {unit}"
    return text if best is None else f"{text} (best {best:,.0f})"


def _ratio(descgen: float, anchor: float | None, unit: str) -> float | None:
    if not anchor or not descgen:
        return None
    return descgen / anchor if unit == "s" else anchor / descgen


def _times(ratio: float | None) -> str:
    if ratio is None:
        return "—"
    return f"{ratio:.2f}x" if ratio >= 0.1 else f"{ratio:.2g}x"


def row(
    measure: str,
    descgen: float,
    anchor: float | None,
    kind: Kind,
    unit: str = "s",
    anchor_name: str = "",
    *,
    descgen_min: float | None = None,
    anchor_min: float | None = None,
    pairs: int | None = None,
    wall_ratio: float | None = None,
) -> None:
    """``descgen`` and ``anchor`` (medians) in ``unit`` (seconds unless told, e.g. "lookups/s",
    where more is better); ``*_min`` the best run of each side (for a rate: the highest);
    ``pairs`` how many A B pairs the medians are of; ``wall_ratio`` the ratio of the wall-time
    medians (the ratio shown first is of the figures given, CPU time unless the measure says)."""
    shown = _shown(descgen, unit, descgen_min)
    anchor_shown = _shown(anchor, unit, anchor_min) if anchor is not None else "—"
    if anchor_name and anchor is not None:
        anchor_shown = f"{anchor_name} {anchor_shown}"
    ratio = _ratio(descgen, anchor, unit)
    ratio_shown = _times(ratio)
    wall_shown = _times(wall_ratio)
    pairs_shown = str(pairs) if pairs is not None else "—"
    cells = (measure, shown, anchor_shown, ratio_shown, wall_shown, pairs_shown, kind)
    print("| " + " | ".join(cells) + " |", flush=True)
    target = os.environ.get("BENCH_ROWS")
    if target:
        with open(target, "a", encoding="utf-8") as f:
            f.write(
                json.dumps(
                    {
                        "measure": measure,
                        "descgen": shown,
                        "anchor": anchor_shown,
                        "ratio": ratio_shown,
                        "wall_ratio": wall_shown,
                        "pairs": pairs_shown,
                        "kind": kind,
                    }
                )
                + "\n"
            )


def header() -> None:
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
