"""Work spread over processes (``audit --jobs``, ``tf-audit --jobs``), as dependable as the same
work in one process.

Each item is done by ``fn`` in a worker (forked: it starts with what the parent imported); the
results come back in the items' order. What can go wrong with processes is handled here, so a
command never shows it as a traceback or a hang:

- a worker that dies (killed by the system when memory runs out): the items it had not
  finished are done again in this process, one by one, as ``--jobs 1`` would;
- workers that cannot be started (too many open files): the same;
- Ctrl-C, or SIGTERM to this process alone (``Popen.terminate()``, a CI runner's timeout):
  items not started are dropped, running workers are terminated, and the interruption goes
  on (exit 130, or 143 for SIGTERM), leaving no worker behind. The signals wait while workers
  are forked (one handled inside a fork would be lost, or leave a worker unrecorded), and a
  worker dies on SIGTERM, not through the handler it was forked with;
- SIGKILL of this process (the OOM killer, ``kill -9``, a CI runner's hard timeout), which runs
  no clean-up: each worker gets the kernel's parent-death signal (Linux ``PR_SET_PDEATHSIG``,
  else a thread watching the parent's pid), so none is left running, blocked on its pipe.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from typing import TypeVar

from descgen.infra import interruptions
from descgen.infra.progress import Step

T = TypeVar("T")
R = TypeVar("R")

SIGTERM_EXIT = 128 + signal.SIGTERM


def map_in_processes(
    fn: Callable[[T], R],
    items: Sequence[T],
    jobs: int,
    step: Step | None = None,
    crashed: Callable[[T], R] | None = None,
    weight: Callable[[T], int] | None = None,
) -> list[R]:
    """``[fn(x) for x in items]``, up to ``jobs`` at once in worker processes (never more than
    the items or the CPUs: CPU-bound work gains nothing beyond them); ``step(1)`` as each is done.
    ``crashed`` and ``weight`` as for :func:`each_in_processes`."""
    results: dict[int, R] = {}
    each_in_processes(fn, items, jobs, results.__setitem__, step, crashed, weight)
    return [results[i] for i in range(len(items))]


def each_in_processes(
    fn: Callable[[T], R],
    items: Sequence[T],
    jobs: int,
    sink: Callable[[int, R], None],
    step: Step | None = None,
    crashed: Callable[[T], R] | None = None,
    weight: Callable[[T], int] | None = None,
) -> None:
    """``sink(i, fn(items[i]))`` for every item, as each is done (in any order, nothing kept
    here: a caller that writes each result out holds one at a time). An error of ``fn`` or of
    ``sink`` ends the work and goes on (a worker's is raised here again).

    ``crashed``: what an item whose worker died gives. Without it, what a dead worker left is
    done again in this process (a worker killed for memory while others ran). With it, what is
    left goes to a new pool of the same width. A pool hands out items in order, so those first in
    line when it broke were in its workers: each gets a strike, and one with two strikes runs
    alone in a new worker; one that kills that worker too gives ``crashed(item)``. One item that
    crashes its process cannot end the others' work, nor make them run one at a time. With
    ``crashed`` and two or more jobs, work runs in workers even on one CPU or for one item.
    Workers that cannot start at all (too many open files): the rest is done in this process.
    ``weight``: what ``step`` is given for an item (its bytes, say), 1 without it."""
    tick = step or (lambda n: None)
    finished: set[int] = set()

    def done(i: int, result: R) -> None:
        finished.add(i)
        sink(i, result)
        tick(weight(items[i]) if weight else 1)

    def here(left: Iterable[int]) -> None:
        for i in left:
            done(i, fn(items[i]))

    workers = min(jobs, len(items), _cpus())
    if crashed is not None and jobs > 1:
        workers = max(workers, 1)  # isolation is the point, even on one CPU
    elif workers <= 1:
        here(range(len(items)))
        return
    left = list(range(len(items)))
    strikes: dict[int, int] = {}
    while left:
        ended = _in_workers(fn, items, left, workers, done)
        left = [i for i in left if i not in finished]
        if not left:
            return
        if crashed is None or ended == UNSTARTED:  # killed for memory, or no worker at all: here
            here(left)
            return
        for i in left[: workers + 1]:  # in the broken pool's workers (or next to go to one)
            strikes[i] = strikes.get(i, 0) + 1
        for i in [i for i in left if strikes.get(i, 0) >= 2]:
            if _in_workers(fn, items, [i], 1, done) == UNSTARTED:
                here([i])
            elif i not in finished:
                done(i, crashed(items[i]))
        left = [i for i in left if i not in finished]


DONE, BROKEN, UNSTARTED = "done", "broken", "unstarted"  # how a pool ended


def _in_workers(
    fn: Callable[[T], R], items: Sequence[T], chosen: Iterable[int], workers: int, done: Callable[[int, R], None]
) -> str:
    """The chosen items on a new pool of ``workers``, in their order, until all are done
    (DONE), a worker dies (BROKEN) or none can start (UNSTARTED); the caller sees what is left."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    futures = {}
    pool = None
    try:
        with sigterm_raises():
            try:
                pool = ProcessPoolExecutor(max_workers=workers, initializer=_worker_start, initargs=(os.getpid(),))
                # the workers are forked, and the pool's threads started, by the submits: a
                # signal handled in the middle of that would be lost in a fork hook or leave a
                # worker nobody knows of, so SIGINT and SIGTERM wait until they are started
                # (the pool's threads keep them blocked; the workers unblock them)
                with interruptions.held():
                    for i in chosen:
                        futures[pool.submit(fn, items[i])] = i
            except (BrokenProcessPool, OSError):
                return UNSTARTED  # a worker could not start (too many open files)
            for future in as_completed(futures):
                try:
                    result = future.result()  # fn's own error, an OSError included, goes on from here
                except BrokenProcessPool:
                    return BROKEN
                done(futures[future], result)
            return DONE
    except BaseException:  # Ctrl-C, SIGTERM, or fn's own error: drop what has not started
        for future in futures:
            future.cancel()
        for child in multiprocessing.active_children():
            child.terminate()
        raise
    finally:
        if pool is not None:
            pool.shutdown(wait=True, cancel_futures=True)


def _cpus() -> int:
    """The CPUs this process may run on (its affinity, where the system tells it)."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def _worker_start(parent: int) -> None:
    """In each worker: SIGTERM ends it at once (the parent's terminate()), not through the
    parent's handler it was forked with, and the signals held while it was forked are let through.
    And it dies with its parent: a parent killed with SIGKILL (the OOM killer, ``kill -9``, a CI
    runner's hard timeout) runs no clean-up, and its workers would wait on their pipe forever.
    Ctrl-C is the parent's to handle (it terminates the workers): a worker ignores SIGINT, so
    one that reaches a worker still starting (a terminal sends it to the whole group) is dropped
    instead of raising KeyboardInterrupt inside the pool's initializer, which printed a traceback."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    _die_with(parent)
    interruptions.let_through()


PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def _die_with(parent: int) -> None:
    """SIGKILL this process when ``parent`` dies: the kernel's parent-death signal on Linux
    (prctl through ctypes), else a thread that watches the parent's pid. A parent already gone
    before that was set up (re-parented: getppid changed) ends the worker here."""
    armed = False
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            armed = libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
        except (OSError, AttributeError):
            armed = False
    if os.getppid() != parent:
        os._exit(1)
    if not armed:

        def watch() -> None:
            while os.getppid() == parent:
                time.sleep(0.5)
            os._exit(1)

        threading.Thread(target=watch, name="descgen-parent-watch", daemon=True).start()


@contextmanager
def sigterm_raises() -> Iterator[None]:
    """SIGTERM to this process becomes SystemExit(143) while workers run, so they are
    terminated with it instead of being left waiting on a pipe (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum: int, frame: object) -> None:
        raise SystemExit(SIGTERM_EXIT)

    before = signal.signal(signal.SIGTERM, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, before)
