"""One printed row per measurement: `measure | descgen | anchor | ratio | cold/warm`.

Every benchmark prints its figures through :func:`row`, so `make bench` reads as one table.
``cold`` means both sides are fresh processes (what a user or a pre-commit hook pays);
``warm`` means in-process after imports (the work alone), and the anchor is then said to be
warm or cold in the measure's own words. When ``BENCH_ROWS`` names a file, each row is also
appended to it as one JSON line, for ``benchmarks/summary.py``.
"""

from __future__ import annotations

import json
import os
from typing import Literal

Kind = Literal["cold", "warm"]


def seconds(value: float) -> str:
    return f"{value:.3f} s" if value < 10 else f"{value:.1f} s"


def row(measure: str, descgen: float, anchor: float | None, kind: Kind, unit: str = "s", anchor_name: str = "") -> None:
    """``descgen`` and ``anchor`` in ``unit`` (seconds unless told, e.g. "lookups/s", where
    more is better); the ratio is descgen / anchor for times and anchor / descgen for rates,
    so above 1 always means descgen is slower."""
    if unit == "s":
        shown, anchor_shown = seconds(descgen), seconds(anchor) if anchor is not None else "—"
        ratio = descgen / anchor if anchor else None
    else:
        shown, anchor_shown = f"{descgen:,.0f} {unit}", f"{anchor:,.0f} {unit}" if anchor is not None else "—"
        ratio = anchor / descgen if anchor and descgen else None
    if anchor_name and anchor is not None:
        anchor_shown = f"{anchor_name} {anchor_shown}"
    ratio_shown = f"{ratio:.2f}x" if ratio is not None else "—"
    print(f"| {measure} | {shown} | {anchor_shown} | {ratio_shown} | {kind} |", flush=True)
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
                        "kind": kind,
                    }
                )
                + "\n"
            )


def header() -> None:
    print("| measure | descgen | anchor | ratio | cold/warm |")
    print("|---|---|---|---|---|")
