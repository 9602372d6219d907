"""tf-audit over many recordings, on an engine: this machine's processes (``--jobs``) or a Ray
cluster (``--engine ray``). Both run the same task, one recording or one time window of it,
with descgen's own reader, and give the same reports; what differs is only where it runs.

A recording whose task fails (unreadable: its input errors; crashed: BAG017) is reported by
name beside the others, which complete. Each recording is handed to ``each`` as soon as all
of it is done, so a caller writing its rows out (``--out``) holds one recording's at a time.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any, NamedTuple

from descgen.codes.recording import BAG017
from descgen.commands.fleet import windows
from descgen.commands.tf.bagaudit import Report, Window, audit, check_lookups, time_range
from descgen.core.findings import Finding, InputError, Where
from descgen.infra.progress import reading

ENGINES = ("local", "ray")


@dataclass
class Outcome:
    path: str  # as given
    report: Report | None
    findings: tuple[Finding, ...] = ()
    windows: int = 1  # how many time windows it was audited in
    note: str = ""  # how it was audited, where that is not plain
    bytes: int = 0  # of its files on disk


class Task(NamedTuple):
    recording: int
    path: Path
    window: Window | None


TaskResult = tuple[Report | None, tuple[Finding, ...]]


def run_task(task: Task, kwargs: dict[str, Any]) -> TaskResult:
    """One recording, or one window of it; input errors returned as data (they cross a
    process or network boundary)."""
    try:
        return audit(task.path, window=task.window, **kwargs), ()
    except InputError as exc:
        return None, exc.findings


def _crashed(task: Task, why: str = "its worker process died (killed, or a crash in a library)") -> TaskResult:
    where = "" if task.window is None else f" (the window from {task.window.start / 1e9:.3f} s)"
    return None, (
        BAG017.finding(
            f"the audit of this recording{where} crashed: {why}",
            "audit it alone (descgen tf-audit PATH) to see why; the other recordings are reported",
            "file",
            Where(str(task.path)),
        ),
    )


def _size(path: Path) -> int:
    try:
        folder = path if path.is_dir() else path.parent
        return sum(f.stat().st_size for f in folder.iterdir() if f.is_file())
    except OSError:
        return 0


def audit_fleet(
    paths: list[str],
    target: str,
    *,
    engine: str = "local",
    jobs: int = 1,
    address: str | None = None,
    window_ns: int | None = None,
    show_progress: bool = False,
    each: Callable[[int, Outcome], None] | None = None,
    **kwargs: Any,
) -> list[Outcome]:
    """Every recording's outcome, in the order given; ``each(i, outcome)`` as each is complete
    (it may take ``outcome.report.failures`` and empty it). ``kwargs`` go to ``bagaudit.audit``."""
    kwargs["target"] = target
    outcomes = [Outcome(p, None, bytes=_size(Path(p))) for p in paths]
    tasks: list[Task] = []
    planned: dict[int, int] = {}
    for i, p in enumerate(paths):
        try:
            cut = _plan(Path(p), window_ns, kwargs)
        except InputError as exc:
            outcomes[i].findings = exc.findings
            continue
        planned[i] = len(cut)
        outcomes[i].windows = len(cut)
        tasks.extend(Task(i, Path(p), w) for w in cut)
    parts: dict[int, list[tuple[Task, TaskResult]]] = {i: [] for i in planned}
    done: list[int] = [i for i in range(len(paths)) if i not in planned]
    for i in done:
        if each:
            each(i, outcomes[i])

    def sink(k: int, result: TaskResult) -> None:
        task = tasks[k]
        got = parts[task.recording]
        got.append((task, result))
        if len(got) == planned[task.recording]:
            _finish(outcomes[task.recording], sorted(got, key=_window_start), kwargs)
            del parts[task.recording]
            if each:
                each(task.recording, outcomes[task.recording])

    run = partial(run_task, kwargs=kwargs)
    if engine == "local" and (jobs <= 1 or len(tasks) <= 1):
        for k, task in enumerate(tasks):  # in this process: each recording's messages on the terminal
            sink(k, run_task(task, kwargs | {"show_progress": show_progress}))
        return outcomes
    sizes = {i: o.bytes // max(1, o.windows) for i, o in enumerate(outcomes)}

    def weight(task: Task) -> int:
        return sizes[task.recording]

    total = sum(weight(t) for t in tasks)
    with reading(total or None, len(tasks), f"tf-audit {len(planned)} recordings", show_progress) as step:
        if engine == "ray":
            from descgen.infra.ray_engine import each_on_ray

            each_on_ray(run, tasks, sink, _crashed, address, jobs if jobs > 1 else None, step, weight)
        else:
            from descgen.infra.workers import each_in_processes

            each_in_processes(run, tasks, jobs, sink, step, _crashed, weight)
    return outcomes


def _window_start(part: tuple[Task, TaskResult]) -> int:
    w = part[0].window
    return -1 if w is None else w.start


def _plan(path: Path, window_ns: int | None, kwargs: dict[str, Any]) -> list[Window | None]:
    if window_ns is None:
        return [None]
    start, end = time_range(path)
    horizon = int(kwargs.get("cache_ns", 10_000_000_000)) + int(kwargs.get("wait_ns", 0))
    return windows.plan(start, end, max(window_ns, windows.MIN_WINDOW_NS), horizon)


def _finish(outcome: Outcome, got: list[tuple[Task, TaskResult]], kwargs: dict[str, Any]) -> None:
    """Join a recording's windows, and run the checks of a whole recording."""
    errors = [f for _, (_, found) in got for f in found]
    if errors:
        outcome.findings = (errors[0],)  # the windows of an unreadable recording say the same
        return
    reports = [rep for _, (rep, _) in got if rep is not None]
    task = got[0][0]
    if len(reports) == 1:
        report: Report | None = reports[0]
    else:
        report = windows.join(reports, int(kwargs.get("examples", 5)))
        if report is None:  # a transform older than the horizon was still held at a boundary
            outcome.note = (
                f"audited in one pass: its {len(reports)} windows did not see what one pass sees "
                "(a transform older than the horizon was still in the buffer at a boundary)"
            )
            report, found = run_task(Task(task.recording, task.path, None), kwargs)
            outcome.report, outcome.findings = report, found
            return
    assert report is not None
    try:
        check_lookups(task.path, str(kwargs["target"]), tuple(kwargs.get("topics", ())), report.lookups, report.frames)
    except InputError as exc:
        outcome.findings = exc.findings
        return
    outcome.report = report
