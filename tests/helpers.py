"""Test helpers: plant a change in the example spec and find where it went."""

from __future__ import annotations

import contextlib
import fcntl
import io
import os
import pty
import select
import signal
import struct
import subprocess
import sys
import termios
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from descgen.audit.spec import load_spec
from descgen.core.findings import Finding, InputError

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE_TEXT = (ROOT / "specs" / "warehouse_arm.yaml").read_text()


def plant(old: str, new: str, text: str = EXAMPLE_TEXT, count: int = 1) -> str:
    assert text.count(old) >= count, f"{old!r} not in the spec"
    return text.replace(old, new, count)


def line_of(text: str, needle: str) -> int:
    """1-based line of the first occurrence of ``needle`` (the oracle for locations)."""
    idx = text.index(needle)
    return text.count("\n", 0, idx) + 1


def errors_of(text: str, tmp_path: Path, name: str = "robot.yaml") -> list[Finding]:
    path = tmp_path / name
    path.write_text(text)
    try:
        load_spec(path)
    except InputError as exc:
        return [f for f in exc.findings if f.blocks]  # the refusal carries the spec's warnings too
    return []


def run_cli(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    """The descgen command in a subprocess, as a user runs it: for the few end-to-end tests
    (interpreter start, ``python -m descgen``, real pipes). Everything else uses :func:`cli`."""
    return subprocess.run(
        [sys.executable, "-m", "descgen", *args], capture_output=True, text=True, cwd=cwd, timeout=300
    )


@dataclass
class Ran:
    """What :func:`cli` saw: the same three fields a ``CompletedProcess`` has."""

    returncode: int
    stdout: str
    stderr: str


class HangError(Exception):
    """The in-process command ran past its time limit (the subprocess timeout's stand-in)."""


@contextlib.contextmanager
def _time_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`HangError` after ``seconds``, so a hang fails the test instead of stalling the run.
    Only the main thread gets signals; elsewhere (never in pytest or its xdist workers) no limit."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def expire(signum: int, frame: object) -> None:
        raise HangError(f"descgen ran longer than {seconds:g} s")

    old = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def cli(*args: str | Path, cwd: Path = ROOT, timeout: float = 300) -> Ran:
    """``descgen ARGS`` through ``descgen.cli.main`` in this process (no 1-2 s interpreter start).

    argparse's ``SystemExit`` becomes the exit code, as in a shell. Any other exception escapes
    and fails the test, which is what a traceback in a subprocess's stderr would have meant.
    """
    from descgen import cli as descgen_cli

    out, err = io.StringIO(), io.StringIO()
    with (
        contextlib.chdir(cwd),
        contextlib.redirect_stdout(out),
        contextlib.redirect_stderr(err),
        _time_limit(timeout),
    ):
        try:
            code = descgen_cli.main([str(a) for a in args])
        except SystemExit as exc:  # argparse: --help (0) and usage errors (2)
            code = exc.code if isinstance(exc.code, int) else 1 if exc.code else 0
    return Ran(code, out.getvalue(), err.getvalue())


# semantic_components/imu_sensor.hpp (jazzy): the ten interfaces an IMUSensorBroadcaster reads,
# written out here by hand as the oracle for descgen/physics/control_claims.py
JAZZY_IMU_INTERFACES = [
    "orientation.x",
    "orientation.y",
    "orientation.z",
    "orientation.w",
    "angular_velocity.x",
    "angular_velocity.y",
    "angular_velocity.z",
    "linear_acceleration.x",
    "linear_acceleration.y",
    "linear_acceleration.z",
]


def pint_si(text: str, kind: str, monkeypatch: pytest.MonkeyPatch) -> float | str:
    """The SI value of ``text`` (or the refusal code) with descgen's pint-free path switched
    off, so pint decides: the oracle for units._simple_si."""
    from descgen.core import units

    with monkeypatch.context() as m:
        m.setattr(units, "_simple_si", lambda _text, _kind: None)
        try:
            return units._to_si(text, kind)
        except units.QuantityError as exc:
            return exc.code


def on_a_terminal(args: list[str], env: dict[str, str], cwd: Path = ROOT) -> str:
    """stderr of ``descgen ARGS`` when stderr is a terminal (a pseudo-terminal), stdout a pipe."""
    leader, follower = pty.openpty()
    # a terminal of 24 x 80, as a user's (a new pty is 0 x 0, where tqdm draws nothing)
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
    proc = subprocess.Popen(
        [sys.executable, "-m", "descgen", *args], stdout=subprocess.PIPE, stderr=follower, cwd=cwd, env=env
    )
    os.close(follower)
    chunks = []
    while True:
        ready, _, _ = select.select([leader], [], [], 60)
        if not ready:
            break
        try:
            data = os.read(leader, 65536)
        except OSError:  # the terminal closed with the process
            break
        if not data:
            break
        chunks.append(data)
    proc.communicate(timeout=60)
    os.close(leader)
    return b"".join(chunks).decode("utf-8", "replace")


def user_project(tmp_path: Path, name: str = "robot_ws") -> Path:
    """A user's project folder away from the repository: the example's specs/ and the
    committed generated/, as a team's repository holds them."""
    import shutil

    project = tmp_path / name
    project.mkdir()
    shutil.copytree(ROOT / "specs", project / "specs")
    shutil.copytree(ROOT / "generated", project / "generated")
    return project


def string_leaves(node: object, path: tuple[object, ...] = ()) -> list[tuple[object, ...]]:
    """The path of every string in a loaded YAML document (keys and list indices)."""
    if isinstance(node, dict):
        return [p for k, v in node.items() for p in string_leaves(v, (*path, k))]
    if isinstance(node, list):
        return [p for i, v in enumerate(node) for p in string_leaves(v, (*path, i))]
    return [path] if isinstance(node, str) else []


def set_at(data: object, path: tuple[object, ...], value: object) -> None:
    """``data[path[0]][path[1]]... = value`` in a loaded YAML document."""
    for key in path[:-1]:
        data = data[key]  # type: ignore[index]
    data[path[-1]] = value  # type: ignore[index]


def get_at(data: object, path: tuple[object, ...]) -> object:
    for key in path:
        data = data[key]  # type: ignore[index]
    return data


def view_until_url_then_ctrl_c(path: Path) -> tuple[int, str]:
    """``descgen view PATH --port 0`` started, waited for until it prints its URL (a readiness
    signal, not a sleep), then stopped with Ctrl-C: (exit code, stderr)."""
    import time

    proc = subprocess.Popen(
        [sys.executable, "-m", "descgen", "view", str(path), "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
    )
    try:
        line = ""
        deadline = time.monotonic() + 60
        while "descgen view:" not in line and time.monotonic() < deadline:
            line = proc.stdout.readline()  # type: ignore[union-attr]
        assert "http://127.0.0.1:" in line, line
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    return proc.returncode, err
