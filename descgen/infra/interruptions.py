"""Holding Ctrl-C and SIGTERM back for a few steps that must not be cut in two.

``generate`` switches two packages into place, and ``--jobs`` forks its workers: a signal
handled in the middle of either could leave one package new and the other old, or a worker
forked but not yet recorded. While :func:`held` runs, SIGINT and SIGTERM wait; they are
delivered when it ends.

Only in the main thread (the only one Python runs signal handlers in) and where the system has
``pthread_sigmask``. A program that embeds descgen with other threads running may still see the
interruption inside (a thread that does not block the signal takes it, and Python raises it in
the main thread); the CLI starts none before these steps.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager

SIGNALS = frozenset({signal.SIGINT, signal.SIGTERM})


@contextmanager
def held() -> Iterator[None]:
    """Block SIGINT and SIGTERM in this thread (and the threads it starts) for the block."""
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        yield
        return
    before = signal.pthread_sigmask(signal.SIG_BLOCK, SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, before)


def let_through() -> None:
    """Unblock them again (a forked worker starts with the mask it was forked under)."""
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, SIGNALS)
