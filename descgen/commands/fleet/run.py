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
    process or network boundary), and any other error as that recording's failure (BAG017),
    the same on every engine."""
    try:
        return audit(task.path, window=task.window, **kwargs), ()
    except InputError as exc:
        return None, exc.findings
    except Exception as exc:  # a bug, or a library's error nothing above maps: this recording's, not the run's
        return _crashed(task, f"the audit raised {type(exc).__name__}: {' '.join(str(exc).split())[:300]}")


DIED = "its worker process died (killed, or a crash in a library)"


def _crashed(task: Task, why: str = DIED) -> TaskResult:
    w = task.window
    where = "" if w is None or w.start is None else f" (the window from {w.start / 1e9:.3f} s)"
    hint = (
        "audit it alone with --jobs 1 to see how it ends; any other recording is reported"
        if not why.startswith("the audit raised")
        else "a defect of descgen or of a library it reads with: report it with this message; "
        "any other recording is reported"
    )
    return None, (
        BAG017.finding(f"the audit of this recording{where} crashed: {why}", hint, "file", Where(str(task.path))),
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
    # on a cluster a task runs in another working directory: it gets the absolute path, and its
    # findings name the recording as given
    where = [Path(p).absolute() if engine == "ray" else Path(p) for p in paths]
    tasks: list[Task] = []
    for i, p in enumerate(paths):
        try:
            cut = _plan(Path(p), window_ns, kwargs, outcomes[i].bytes)
        except InputError as exc:
            outcomes[i].findings = exc.findings
            if each:
                each(i, outcomes[i])
            continue
        outcomes[i].windows = len(cut)
        tasks.extend(Task(i, where[i], w) for w in cut)
    again: list[int] = []  # recordings whose windows disagreed: audited again, whole

    def finished(i: int, got: list[tuple[Task, TaskResult]]) -> None:
        if _finish(outcomes[i], paths[i], sorted(got, key=_window_start), kwargs):
            if each:
                each(i, outcomes[i])
        else:
            again.append(i)

    run = partial(run_task, kwargs=kwargs)
    _dispatch(tasks, finished, run, engine, jobs, address, show_progress, outcomes, kwargs)
    if again:
        for i in again:
            outcomes[i].note = (
                f"audited in one pass: its {outcomes[i].windows} windows did not see what one pass sees "
                "(a transform older than the horizon was still in the buffer at a boundary)"
            )
            outcomes[i].windows = 1
        whole = [Task(i, where[i], None) for i in again]
        _dispatch(whole, finished, run, engine, jobs, address, show_progress, outcomes, kwargs)
    return outcomes


def _dispatch(
    tasks: list[Task],
    finished: Callable[[int, list[tuple[Task, TaskResult]]], None],
    run: Callable[[Task], TaskResult],
    engine: str,
    jobs: int,
    address: str | None,
    show_progress: bool,
    outcomes: list[Outcome],
    kwargs: dict[str, Any],
) -> None:
    """Run the tasks on the engine; ``finished(i, parts)`` when every task of recording i is done."""
    planned: dict[int, int] = {}
    for t in tasks:
        planned[t.recording] = planned.get(t.recording, 0) + 1
    parts: dict[int, list[tuple[Task, TaskResult]]] = {i: [] for i in planned}

    def sink(k: int, result: TaskResult) -> None:
        task = tasks[k]
        got = parts[task.recording]
        got.append((task, result))
        if len(got) == planned[task.recording]:
            del parts[task.recording]
            finished(task.recording, got)

    if not tasks:
        return
    if engine == "local" and jobs <= 1:
        for k, task in enumerate(tasks):  # in this process: each recording's messages on the terminal
            sink(k, run_task(task, kwargs | {"show_progress": show_progress}))
        return
    sizes = {i: outcomes[i].bytes // max(1, planned[i]) for i in planned}

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


def _window_start(part: tuple[Task, TaskResult]) -> int:
    w = part[0].window
    return -(2**63) if w is None or w.start is None else w.start


def _plan(path: Path, window_ns: int | None, kwargs: dict[str, Any], size: int) -> list[Window | None]:
    if window_ns is None:
        return [None]
    start, end = time_range(path)
    horizon = int(kwargs.get("cache_ns", 10_000_000_000)) + int(kwargs.get("wait_ns", 0))
    return windows.plan(start, end, max(window_ns, windows.MIN_WINDOW_NS), horizon, size or None)


def _finish(outcome: Outcome, given: str, got: list[tuple[Task, TaskResult]], kwargs: dict[str, Any]) -> bool:
    """Join a recording's windows and run the checks of a whole recording; False when the
    windows disagree at a boundary (the recording is then audited again, whole)."""
    errors = [_as_given(f, got[0][0].path, given) for _, (_, found) in got for f in found]
    if errors:
        outcome.findings = (errors[0],)  # the windows of an unreadable recording say the same
        return True
    reports = [rep for _, (rep, _) in got if rep is not None]
    report = reports[0] if len(reports) == 1 else windows.join(reports, int(kwargs.get("examples", 5)))
    if report is None:  # a transform older than the horizon was still held at a boundary
        return False
    try:
        check_lookups(
            Path(given), str(kwargs["target"]), tuple(kwargs.get("topics", ())), report.lookups, report.frames
        )
    except InputError as exc:
        outcome.findings = exc.findings
        return True
    outcome.report = report
    return True


def _as_given(f: Finding, sent: Path, given: str) -> Finding:
    """A task's finding about the absolute path it was sent, about the path as given."""
    if f.where.file != str(sent) or str(sent) == given:
        return f
    from dataclasses import replace

    return replace(f, where=replace(f.where, file=given))
