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
