"""Progress of long work, shown on a terminal and nowhere else.

An audit of many files, a long recording's tf-audit and a sweep take seconds to minutes; on a
terminal tqdm draws a bar on stderr. In a pipe, a log, CI (``CI`` set, as every CI service sets
it) or a machine-readable format nothing is written: stdout and stderr stay exactly what the
command reports. tqdm is imported only when a bar is drawn (cold start).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

Step = Callable[[int], None]


def wanted(text_output: bool = True) -> bool:
    """Whether to draw progress: text output, stderr a terminal, not in CI (``CI`` set to
    anything but empty, ``0`` or ``false``, as CI services set it to ``true`` or ``1``)."""
    in_ci = os.environ.get("CI", "").strip().lower() not in ("", "0", "false")
    return text_output and sys.stderr.isatty() and not in_ci


def _nothing(n: int = 1) -> None:
    return None


@contextmanager
def counting(total: int | None, what: str, unit: str, show: bool) -> Iterator[Step]:
    """A function to call with each step's count (``step(1)``); a bar of ``total`` steps on
    stderr while the block runs when ``show``, else a function that does nothing. The bar is
    cleared when the block ends, so the command's own report follows on a clean line."""
    if not show:
        yield _nothing
        return
    with _bar(total, what, unit, scale=False) as bar:
        yield bar.update


@contextmanager
def reading(total_bytes: int | None, items: int, what: str, show: bool) -> Iterator[Step]:
    """A bar of bytes read (MB and MB/s) that also counts the items done: ``step(nbytes)`` as
    each item is done. Nothing when not ``show``, as :func:`counting`."""
    if not show:
        yield _nothing
        return
    with _bar(total_bytes, what, "B", scale=True) as bar:
        done = [0]

        def item(n: int = 0) -> None:
            done[0] += 1
            bar.set_postfix_str(f"{done[0]}/{items} done", refresh=False)
            bar.update(n)

        yield item


@contextmanager
def _bar(total: int | None, what: str, unit: str, scale: bool) -> Iterator[Any]:
    """tqdm's bar on stderr, closed (and cleared) when the block ends. ``scale``: the count in
    k, M, G (bytes as MB and MB/s)."""
    from tqdm import tqdm

    # no monitor thread: a bar is drawn from the working thread, and a thread alive while
    # `audit --jobs` forks its workers is what fork-safety warnings are about
    tqdm.monitor_interval = 0
    bar = tqdm(
        total=total,
        desc=what,
        unit=unit,
        file=sys.stderr,
        leave=False,
        dynamic_ncols=True,
        unit_scale=scale,
        unit_divisor=1000,
    )
    try:
        yield bar
    finally:
        bar.close()
