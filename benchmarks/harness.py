"""The one way a benchmark times descgen beside its anchor.

:func:`compare` runs descgen (A) and its anchor (B) interleaved in one run, A B A B …, after
``warmup`` uncounted pairs (the OS file cache, bytecode, descgen's own caches where the row
keeps them), :data:`PAIRS` counted pairs (7 unless ``--pairs N``; 3 with ``--quick``). Each
side of each pair is a :class:`Timing`: CPU time of the process tree (user + system) and wall
time, taken by

- :func:`process`: a fresh process, ``resource.getrusage(RUSAGE_CHILDREN)`` deltas around it
  (the process and every child it waited for: check_urdf, dot, xacro, …);
- :func:`in_process`: a callable in this process, ``time.process_time`` plus the children it
  waited for (only where both sides run in-process);
- a callable of the benchmark's own that returns a Timing (e.g. one the anchor's process
  measured around its own loop and printed), said in the benchmark's docstring.

The row (benchmarks/rows.py) shows the median and min CPU time of each side, the ratio of the
medians (descgen / anchor; for rates anchor / descgen, so above 1 always means descgen is
slower), the ratio of the wall-time medians and the number of pairs. ``before_descgen`` /
``before_anchor`` run before each side, outside its timing (emptying a cache, writing a file).

Every script takes ``--quick`` (3 pairs and the smaller workloads the script names: for CI,
which fails on nothing and still prints the table) and ``--pairs N`` (:func:`parse`).

Run: .venv/bin/python benchmarks/harness.py   (prints the machine line `make bench` starts with)
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rows import Kind, header, row

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
PAIRS = 7
QUICK_PAIRS = 3
QUICK = False  # set by parse(): the script's smaller workloads


@dataclass(frozen=True)
class Timing:
    cpu: float  # user + system seconds of the process tree (or of this process, in-process)
    wall: float


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def machine() -> str:
    """The machine line: CPU model, cores, Python."""
    return f"{cpu_model()}, {os.cpu_count()} cores (nproc), Python {platform.python_version()}, {platform.system()}"


def parse(doc: str | None = None, add: Callable[[argparse.ArgumentParser], None] | None = None) -> argparse.Namespace:
    """The script's arguments: ``--quick``, ``--pairs N`` and whatever ``add`` adds. Sets
    :data:`PAIRS` and :data:`QUICK`, prints the pairs and the load, and the table's header."""
    global PAIRS, QUICK
    ap = argparse.ArgumentParser(description=(doc or "").split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help=f"{QUICK_PAIRS} pairs and smaller workloads (CI)")
    ap.add_argument("--pairs", type=int, default=None, help=f"counted A B pairs per row (default {PAIRS})")
    if add is not None:
        add(ap)
    args = ap.parse_args()
    QUICK = args.quick
    PAIRS = args.pairs if args.pairs else (QUICK_PAIRS if args.quick else PAIRS)
    mode = "quick" if QUICK else "full"
    print(f"{mode}: {PAIRS} pairs per row (A B A B …), CPU time of the process tree; load {load():.2f}")
    header()
    return args


def load() -> float:
    return os.getloadavg()[0]


FAILED: list[str] = []  # rows whose runs failed


def done() -> None:
    """The script's end: the load, and exit 1 when a row failed (after every other row ran)."""
    print(f"load at the end {load():.2f}", flush=True)
    if FAILED:
        print(f"!! {len(FAILED)} row(s) not measured: {'; '.join(FAILED)}", flush=True)
        sys.exit(1)


# --- the clocks -----------------------------------------------------------------------------


def _children_cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def run(
    argv: Sequence[str],
    *,
    env: dict[str, str] | None = None,
    cwd: Path = ROOT,
    input: str | None = None,
    ok: tuple[int, ...] = (0,),
) -> tuple[Timing, str]:
    """One fresh process: its Timing (CPU of it and its children) and its stdout. An exit code
    outside ``ok``, or a traceback on stderr, stops the benchmark (a crash timed is no figure)."""
    c0, t0 = _children_cpu(), time.perf_counter()
    done_ = subprocess.run(list(argv), cwd=cwd, env=env, input=input, capture_output=True, text=True, check=False)
    wall, cpu = time.perf_counter() - t0, _children_cpu() - c0
    if done_.returncode not in ok or "Traceback (most recent call last)" in done_.stderr:
        raise SystemExit(f"{' '.join(map(str, argv))[:300]} exited {done_.returncode}:\n{done_.stderr[-2000:]}")
    return Timing(cpu, wall), done_.stdout


def process(argv: Sequence[str], **kw: object) -> Timing:
    """:func:`run`'s Timing alone."""
    return run(argv, **kw)[0]  # type: ignore[arg-type]


def in_process(fn: Callable[[], object]) -> Timing:
    """A callable in this process: ``time.process_time`` (this process's user + system CPU,
    every thread) plus the CPU of any child process it waited for (check_urdf, dot)."""
    c0, k0, t0 = time.process_time(), _children_cpu(), time.perf_counter()
    fn()
    return Timing(time.process_time() - c0 + _children_cpu() - k0, time.perf_counter() - t0)


def python(code: str, *args: str, **kw: object) -> tuple[Timing, str]:
    """A fresh ``python -c code args…`` (this venv's Python)."""
    return run([sys.executable, "-c", code, *args], **kw)  # type: ignore[arg-type]


# --- environments for fresh processes -------------------------------------------------------

# one folder for every benchmark's processes (bytecode is keyed by source path and mtime)
_PYCACHE = str(Path(tempfile.gettempdir()) / f"descgen-bench-pycache-{os.getuid()}")


def env(cache: str | Path | None, **extra: str) -> dict[str, str]:
    """This environment for a fresh process, with descgen's cache folder ``cache``
    (DESCGEN_CACHE_DIR; None: caching off) and Python's bytecode cache as an installed descgen
    has it (in a temporary folder, even when the shell sets PYTHONDONTWRITEBYTECODE)."""
    out = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    out["PYTHONPYCACHEPREFIX"] = _PYCACHE
    out["DESCGEN_CACHE_DIR"] = "" if cache is None else str(cache)
    return out | extra


class FreshCache:
    """A temporary DESCGEN_CACHE_DIR, emptied by :meth:`empty` (a ``before_descgen`` hook: every
    cache off for the run that follows) and removed by :meth:`close`."""

    def __init__(self) -> None:
        self.path = Path(tempfile.mkdtemp(prefix="descgen-bench-cache-"))

    def empty(self, *parts: str) -> None:
        """Remove ``parts`` of the cache (e.g. "results", "audit"), or all of it."""
        target = self.path.joinpath(*parts)
        shutil.rmtree(target, ignore_errors=True)
        self.path.mkdir(parents=True, exist_ok=True)

    def close(self) -> None:
        shutil.rmtree(self.path, ignore_errors=True)


# --- the comparison -------------------------------------------------------------------------


@dataclass
class Result:
    descgen: list[Timing] = field(default_factory=list)
    anchor: list[Timing] = field(default_factory=list)

    @staticmethod
    def _median(ts: list[Timing], clock: str) -> float:
        return statistics.median(getattr(t, clock) for t in ts)

    def median(self, side: str, clock: str = "cpu") -> float:
        return self._median(getattr(self, side), clock)

    def best(self, side: str, clock: str = "cpu") -> float:
        return min(getattr(t, clock) for t in getattr(self, side))

    def ratio(self, clock: str = "cpu") -> float | None:
        if not self.anchor:
            return None
        a = self.median("anchor", clock)
        return self.median("descgen", clock) / a if a else None


def _nothing() -> None:
    return None


def compare(
    measure: str,
    descgen: Callable[[], Timing],
    anchor: Callable[[], Timing] | None,
    *,
    kind: Kind,
    anchor_name: str = "",
    before_descgen: Callable[[], object] = _nothing,
    before_anchor: Callable[[], object] = _nothing,
    warmup: int = 1,
    pairs: int | None = None,
    work: float | None = None,
    unit: str = "s",
    clock: str = "cpu",
    reference: float | None = None,
) -> Result:
    """Time ``descgen`` and ``anchor`` interleaved (A B A B …): ``warmup`` uncounted pairs, then
    ``pairs`` (default :data:`PAIRS`) counted ones; print the row and return the timings.

    ``work``: the row is a rate, ``work`` units (``unit``, e.g. "lookups/s") per second of
    each run. ``clock``: "cpu" (default) or "wall", the figure shown. ``anchor=None`` with a
    ``reference``: a fixed anchor (e.g. real time); with neither, descgen alone (no ratio)."""
    n = PAIRS if pairs is None else pairs
    result = Result()
    try:
        for i in range(warmup + n):
            before_descgen()
            d = descgen()
            a = None
            if anchor is not None:
                before_anchor()
                a = anchor()
            if i >= warmup:
                result.descgen.append(d)
                if a is not None:
                    result.anchor.append(a)
    except SystemExit as exc:  # a side crashed (run() refuses to time a crash): the next rows still run
        FAILED.append(measure)
        print(f"!! {measure}: not measured, a run failed:\n{exc}", flush=True)
        return result
    report(measure, result, kind=kind, anchor_name=anchor_name, work=work, unit=unit, clock=clock, reference=reference)
    return result


def report(
    measure: str,
    result: Result,
    *,
    kind: Kind,
    anchor_name: str = "",
    work: float | None = None,
    unit: str = "s",
    clock: str = "cpu",
    reference: float | None = None,
    pairs: int | None = None,
) -> None:
    """The row of ``result`` (see :func:`compare`); ``pairs``: the pairs it is of, when not
    one per timing (a pass robot by robot)."""

    def figure(seconds: float) -> float:
        return work / seconds if work is not None and seconds else seconds

    one = len(result.descgen) == 1  # a single run has no min of its own
    d_med = figure(result.median("descgen", clock))
    d_min = None if one else figure(result.best("descgen", clock))
    a_med = a_min = wall_ratio = None
    if result.anchor:
        a_med = figure(result.median("anchor", clock))
        a_min = None if one else figure(result.best("anchor", clock))
        wall_ratio = result.ratio("wall")
    elif reference is not None:
        a_med = reference
    row(
        measure,
        d_med,
        a_med,
        kind,
        unit if work is not None else "s",
        anchor_name,
        descgen_min=d_min,
        anchor_min=a_min,
        pairs=len(result.descgen) if pairs is None else pairs,
        wall_ratio=wall_ratio,
    )


def alone(measure: str, descgen: Callable[[], Timing], *, kind: Kind, **kw: object) -> Result:
    """descgen's own figure with no anchor (median and min of :data:`PAIRS` runs)."""
    return compare(measure, descgen, None, kind=kind, **kw)  # type: ignore[arg-type]


if __name__ == "__main__":
    print(f"Machine: {machine()}; load {load():.2f}")
