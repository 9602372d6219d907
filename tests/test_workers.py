"""descgen/infra/workers.py: --jobs work in processes. What the workers start with is checked
directly; the end-to-end cases (a worker killed, SIGTERM, Ctrl-C) are in tests/test_audit_many.py."""

from __future__ import annotations

import signal

import pytest

from descgen.infra import workers


def _state(n: int) -> tuple[int, str, str, bool, bool]:
    """In a worker: its item, its SIGTERM and SIGINT dispositions, and whether SIGINT / SIGTERM
    are blocked."""
    blocked = signal.pthread_sigmask(signal.SIG_BLOCK, [])
    term, interrupt = signal.getsignal(signal.SIGTERM), signal.getsignal(signal.SIGINT)
    return (
        n,
        "default" if term == signal.SIG_DFL else repr(term),
        "ignored" if interrupt == signal.SIG_IGN else repr(interrupt),
        signal.SIGINT in blocked,
        signal.SIGTERM in blocked,
    )


def test_workers_die_on_sigterm_and_let_signals_through() -> None:
    # forked while the parent turns SIGTERM into SystemExit and holds both signals: a worker
    # keeping either would outlive the parent's terminate(); Ctrl-C is the parent's (a SIGINT
    # reaching a worker still in the pool's initializer raised KeyboardInterrupt there)
    if workers._cpus() < 2:
        pytest.skip("one CPU: the work runs in this process, there is no worker to look at")
    before = signal.getsignal(signal.SIGTERM)
    got = workers.map_in_processes(_state, [1, 2, 3, 4], jobs=2)
    assert [g[0] for g in got] == [1, 2, 3, 4]  # in the items' order
    assert all(g[1:] == ("default", "ignored", False, False) for g in got), got
    # and the parent is as it was: its own handler back, nothing left blocked
    assert signal.getsignal(signal.SIGTERM) is before
    assert signal.SIGTERM not in signal.pthread_sigmask(signal.SIG_BLOCK, [])


def test_duplicates_and_order() -> None:
    assert workers.map_in_processes(abs, [3, -3, 1, 3], jobs=2) == [3, 3, 1, 3]
    assert workers.map_in_processes(abs, [-2], jobs=4) == [2]  # one item: done here


def _pid_or_die(n: int) -> int:
    """In a worker: its pid, except that item 1 kills its worker (as a segfault would)."""
    import os

    if n == 1:
        os.kill(os.getpid(), signal.SIGKILL)
    return os.getpid()


def test_one_crashing_item_is_reported_and_the_rest_keep_their_width() -> None:
    """30 items on 2 workers, item 1 crashing its worker every time: it alone is reported, and
    the others are not run one worker each (which made a fleet run serially after one crash)."""
    got = workers.map_in_processes(_pid_or_die, list(range(30)), jobs=2, crashed=lambda n: -n)
    assert got[1] == -1 and all(p > 0 for i, p in enumerate(got) if i != 1)
    # a pool of 2, a pool of 2 for what it left, the few first in line alone: well under 29
    assert len({p for i, p in enumerate(got) if i != 1}) < 12


def _raise_os_error(n: int) -> int:
    raise FileNotFoundError(f"item {n}")


def test_an_error_of_the_work_is_raised_not_taken_for_a_dead_worker() -> None:
    # an OSError of fn (or of the sink that writes results) was swallowed as a pool that broke
    with pytest.raises(FileNotFoundError):
        workers.map_in_processes(_raise_os_error, [1, 2, 3], jobs=2, crashed=lambda n: -n)
    written: list[int] = []

    def sink(i: int, r: int) -> None:
        if written:
            raise OSError(28, "No space left on device")
        written.append(r)

    with pytest.raises(OSError, match="No space"):
        workers.each_in_processes(abs, [1, 2, 3, 4], 2, sink, crashed=lambda n: -n)
    assert len(written) == 1


def _slow_crash(n: int) -> int:
    """Item 0 dies after a while (others are quick): it must not be run again in every new pool."""
    import os
    import time

    if n == 0:
        time.sleep(0.3)
        os.kill(os.getpid(), signal.SIGKILL)
    return os.getpid()


def test_an_item_that_crashes_late_is_isolated_after_two_strikes() -> None:
    runs: list[int] = []
    got = workers.map_in_processes(_slow_crash, list(range(40)), jobs=2, crashed=lambda n: runs.append(n) or -1)
    assert got[0] == -1 and runs == [0] and all(p > 0 for p in got[1:])
