"""Work spread over a Ray cluster (``tf-audit --engine ray``): the same function, each item a
Ray task, the results handed back as each is done.

Ray places the tasks and retries those whose worker died (``max_retries``); what still fails
is handed to ``crashed`` with Ray's reason, so one item cannot end the others' work. Without
``address`` a local cluster of ``cpus`` CPUs is started and stopped around the work; with one,
the work joins that cluster, whose nodes must have the same descgen installed (checked first,
on one node). Ray is imported only here, when asked for: it is the optional ``fleet`` extra.

Ray writes its own chatter (worker deaths, token notices) to the driver's stdout and logger;
both are silenced while it runs, so stdout stays what the command reports (``--format json``).
Everything else Ray does is Ray's: its session folder under /tmp/ray, and on a first local
start its authentication token in ~/.ray.
"""

from __future__ import annotations

import contextlib
import io
import logging
from collections.abc import Callable, Iterator, Sequence
from typing import Any, TypeVar

from descgen.codes.recording import BAG016
from descgen.core.findings import InputError, Where
from descgen.infra.progress import Step

T = TypeVar("T")
R = TypeVar("R")

RETRIES = 2  # Ray retries a task whose worker died this many times before it is reported


def _unavailable(message: str, hint: str) -> InputError:
    return InputError([BAG016.finding(message, hint, "option", Where("--engine"))])


def _ray() -> Any:
    try:
        import ray
    except ImportError:
        raise _unavailable(
            "--engine ray needs Ray, which is not installed",
            "pip install 'descgen[fleet]' (or run without --engine ray)",
        ) from None
    return ray


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Ray's messages dropped: its worker-death notices printed to stdout by its listener
    thread, and its logger's, which ``ray.init`` re-attaches to the root logger (whose last
    resort prints warnings to stderr)."""
    logger = logging.getLogger("ray")
    saved = (logger.handlers[:], logger.propagate, logging.lastResort)
    logger.handlers, logger.propagate = [logging.NullHandler()], False
    logging.lastResort = logging.NullHandler()
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            yield
    finally:
        logger.handlers, logger.propagate, logging.lastResort = saved


def _call(fn: Callable[[Any], Any], item: Any) -> Any:
    return fn(item)


def _version() -> str:
    from descgen import __version__

    return __version__


def each_on_ray(
    fn: Callable[[T], R],
    items: Sequence[T],
    sink: Callable[[int, R], None],
    crashed: Callable[[T, str], R],
    address: str | None = None,
    cpus: int | None = None,
    step: Step | None = None,
    weight: Callable[[T], int] | None = None,
) -> None:
    """``sink(i, fn(items[i]))`` for every item as its task is done; an item whose task failed
    after Ray's retries gives ``crashed(item, why)``. ``fn`` and the items must pickle (a
    module-level function, or a ``functools.partial`` of one)."""
    ray = _ray()
    tick = step or (lambda n: None)
    if address is not None:
        _reachable(address)
    import signal
    import threading

    main = threading.current_thread() is threading.main_thread()
    before = signal.getsignal(signal.SIGTERM) if main else None
    with _quiet(), contextlib.ExitStack() as stack:
        if main and before is not None:  # ray.init puts its own handler in: the caller's comes back last
            stack.callback(signal.signal, signal.SIGTERM, before)
        try:
            ray.init(
                address=address or "local",  # "local": a new cluster, never one already running here
                num_cpus=cpus if address is None else None,
                include_dashboard=False,
                log_to_driver=False,
                configure_logging=False,
                logging_level=logging.ERROR,
            )
        except Exception as exc:  # ConnectionError, RuntimeError, ValueError: a bad or dead address
            raise _unavailable(
                f"cannot start or reach the Ray cluster{f' at {address}' if address else ''}: "
                + " ".join(str(exc).split())[:300],
                "check --address (the head's host:port, or 'auto'); a cluster with token authentication "
                "needs RAY_AUTH_MODE=token and its token here (ray get-auth-token); or leave --address out",
            ) from None
        pending: list[Any] = []
        from descgen.infra.workers import sigterm_raises

        try:
            stack.enter_context(sigterm_raises())  # ray.init put its own handler in (exit 1, a C++ dump)
            _same_version(ray)
            task = ray.remote(num_cpus=1, max_retries=RETRIES)(_call)
            fn_ref = ray.put(fn)
            index = {}
            for i, item in enumerate(items):
                ref = task.remote(fn_ref, item)
                index[ref] = i
                pending.append(ref)
            while pending:
                ready, pending = ray.wait(pending, num_returns=1)
                for ref in ready:
                    i = index.pop(ref)
                    sink(i, _result(ray, ref, items[i], crashed))
                    tick(weight(items[i]) if weight else 1)
        except BaseException:
            for ref in pending:  # Ctrl-C or SIGTERM: nothing left running on the cluster
                with contextlib.suppress(Exception):
                    ray.cancel(ref, force=True)
            raise
        finally:
            ray.shutdown()


PROBE_S = 5.0


def _reachable(address: str) -> None:
    """Refuse an address nothing answers on, at once: Ray itself retries an unreachable head
    for minutes, printing from its C++ core. ``auto`` (the cluster on this machine) is Ray's to find."""
    import socket

    hostport = address.removeprefix("ray://")
    if address == "auto":
        return
    host, sep, port = hostport.rpartition(":")
    if not sep or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise _unavailable(
            f"--address '{address}' is not host:port", "give the head node as host:port (its GCS port, 6379 by default)"
        )
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=PROBE_S):
            pass
    except OSError as exc:
        raise _unavailable(
            f"nothing answers at --address {address}: {exc.strerror or exc}",
            "start the cluster (ray start --head) or check the head node's host:port",
        ) from None


def _result(ray: Any, ref: Any, item: T, crashed: Callable[[T, str], R]) -> R:
    from ray import exceptions

    try:
        return ray.get(ref)  # type: ignore[no-any-return]
    except exceptions.RayTaskError as exc:  # the function raised: a bug, reported as that item's failure
        cause = exc.cause if getattr(exc, "cause", None) is not None else exc
        return crashed(item, f"the audit raised {type(cause).__name__}: {' '.join(str(cause).split())[:300]}")
    except exceptions.RayError as exc:  # the worker died (memory, a crash), after Ray's retries
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        return crashed(item, f"its Ray worker died ({type(exc).__name__}: {first[:200]}), after {RETRIES} retries")


def _same_version(ray: Any) -> None:
    """The cluster's descgen is this one (a node with another version would audit differently)."""
    try:
        theirs = ray.get(ray.remote(num_cpus=0)(_version).remote(), timeout=120)
    except Exception as exc:  # descgen missing on the node: the function cannot be unpickled there
        raise _unavailable(
            f"the Ray cluster's workers cannot run descgen: {' '.join(str(exc).split())[:300]}",
            "install the same descgen[fleet] on every node",
        ) from None
    if theirs != _version():
        raise _unavailable(
            f"the Ray cluster runs descgen {theirs}, this is {_version()}",
            "install the same descgen[fleet] on every node",
        )
