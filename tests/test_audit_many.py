"""``descgen audit`` over many descriptions: ``--jobs N`` audits them in separate processes and
reports exactly what one process reports, in the order given; progress is drawn on a terminal
and nowhere else (not in a pipe, not in CI, not with --format json). Oracles: the same audit in
one process, and each description audited alone."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.corpus import descriptions, share
from tests.helpers import ROOT, cli, on_a_terminal

CORPUS = {i: u for i, u, _ in descriptions()}
SMALL = [
    "double_pendulum_description/urdf/double_pendulum.urdf",
    "simple_humanoid_description/urdf/simple_humanoid.urdf",
    "iris_description/robots/iris.urdf",
    "quadruped_description/urdf/quadruped.urdf",
]
pytestmark = pytest.mark.skipif(not all(i in CORPUS for i in SMALL), reason="example-robot-data is not installed")


def _paths(tmp_path: Path) -> list[str]:
    broken = tmp_path / "broken.urdf"
    broken.write_text('<robot name="r"><link name="a">')  # unusable: its READ error, exit 2
    files = [str(CORPUS[i]) for i in SMALL]
    return [*files[:2], str(broken), *files[2:]]


def test_jobs_report_what_one_process_reports_in_the_order_given(tmp_path: Path) -> None:
    paths = _paths(tmp_path)
    one = cli("audit", "--format", "json", *paths)
    three = cli("audit", "--format", "json", "--jobs", "3", *paths)
    assert one.returncode == three.returncode == 2  # the broken file is an input error, the rest still audited
    assert three.stdout == one.stdout
    # and one process reports each description's own audit, in the order given
    alone = [json.loads(cli("audit", "--format", "json", p).stdout)["findings"] for p in paths]
    assert json.loads(one.stdout)["findings"] == [f for fs in alone for f in fs]


def test_a_worker_keeps_the_mesh_facts_it_measured(tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    paths = [str(CORPUS[i]) for i in SMALL[:2]]
    env = {**os.environ, "DESCGEN_CACHE_DIR": str(cache)}
    where = ["--package-path", str(share())]  # their meshes are package://example-robot-data/...
    done = subprocess.run(
        [sys.executable, "-m", "descgen", "audit", "--jobs", "2", *where, *paths],
        capture_output=True,
        text=True,
        env=env,
    )
    assert done.returncode in (0, 1), done.stderr
    (index_file,) = cache.glob("meshes*/stat-index")  # descgen/meshes/cache.py's versioned folder
    index = index_file.read_text()
    # the pool's processes end without atexit: the index is saved as meshes are measured
    assert "double_pendulum" in index and "simple_humanoid" in index


@pytest.mark.parametrize(
    ("extra", "ci", "drawn"),
    [([], False, True), (["--format", "json"], False, False), ([], True, False)],
    ids=["terminal", "json on a terminal", "CI on a terminal"],
)
def test_progress_is_drawn_on_a_terminal_only(tmp_path: Path, extra: list[str], ci: bool, drawn: bool) -> None:
    env = {k: v for k, v in os.environ.items() if k != "CI"} | {"DESCGEN_CACHE_DIR": ""}
    if ci:
        env["CI"] = "true"
    paths = [str(CORPUS[i]) for i in SMALL[:3]]
    shown = on_a_terminal(["audit", *extra, *paths], env)
    # tqdm's bar: "audit:   0%|...| 0/3 [...file/s]" (it redraws at most every 0.1 s, then clears)
    assert ("audit:" in shown and "/3 [" in shown and "file/s" in shown) is drawn, shown[:500]


def test_no_progress_in_a_pipe() -> None:
    paths = [str(CORPUS[i]) for i in SMALL[:3]]
    env = {k: v for k, v in os.environ.items() if k != "CI"} | {"DESCGEN_CACHE_DIR": ""}
    done = subprocess.run(
        [sys.executable, "-m", "descgen", "audit", *paths], capture_output=True, text=True, cwd=ROOT, env=env
    )
    assert "audit:" not in done.stderr and "\r" not in done.stderr
    assert "audited 3 description(s)" in done.stdout


@pytest.mark.parametrize("bad", ["0", "65", "two"])
def test_a_bad_jobs_count_is_exit_2(bad: str) -> None:
    done = cli("audit", "--jobs", bad, str(CORPUS[SMALL[0]]))
    assert done.returncode == 2
    assert "--jobs" in done.stderr and "Traceback" not in done.stderr


def _chains(folder: Path) -> list[str]:
    """100 copies of a 1000-link chain in ``folder``: several seconds of work for two processes."""
    links = "".join(f'<link name="l{i}"/>' for i in range(1000))
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
        '<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for i in range(999)
    )
    text = f'<robot name="r">{links}{joints}</robot>'
    paths = []
    for k in range(100):
        path = folder / f"r{k}.urdf"
        path.write_text(text)
        paths.append(str(path))
    return paths


def _audit_in_background(paths: list[str], start_new_session: bool = False) -> subprocess.Popen[bytes]:
    """``descgen audit --jobs 2 PATHS`` started and left running, SIGINT at its default."""
    import signal

    return subprocess.Popen(
        [sys.executable, "-m", "descgen", "audit", "--jobs", "2", *paths],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "DESCGEN_CACHE_DIR": ""},
        start_new_session=start_new_session,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )


def _wait_for_workers(proc: subprocess.Popen[bytes], timeout: float = 120) -> None:
    """Until the audit's workers exist: its signal handlers are installed before they are forked
    (descgen/infra/workers.py), so a signal sent now meets them, however loaded the machine is."""
    import time

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        assert proc.poll() is None, "the audit ended before its workers started"
        children = subprocess.run(["pgrep", "-P", str(proc.pid)], capture_output=True, text=True).stdout.split()
        if children:
            return
        time.sleep(0.05)
    raise AssertionError("no worker started")


@pytest.mark.e2e
def test_ctrl_c_stops_the_workers_with_exit_130(tmp_path: Path) -> None:
    import signal

    # its own process group, SIGINT not ignored: Ctrl-C reaches the workers too, as in a terminal
    proc = _audit_in_background(_chains(tmp_path), start_new_session=True)
    _wait_for_workers(proc)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err[-500:]
    assert b"Traceback" not in err


@pytest.mark.parametrize(
    ("ci", "drawn"),
    [(None, True), ("", True), ("false", True), ("0", True), ("true", False), ("1", False), ("yes", False)],
)
def test_ci_is_what_ci_services_set(ci: str | None, drawn: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    from types import SimpleNamespace

    from descgen.infra import progress

    monkeypatch.setattr(progress.sys, "stderr", SimpleNamespace(isatty=lambda: True))
    if ci is None:
        monkeypatch.delenv("CI", raising=False)
    else:
        monkeypatch.setenv("CI", ci)
    assert progress.wanted() is drawn
    assert progress.wanted(text_output=False) is False


_DIES: dict[str, object] = {}  # set by the test below; read in the forked workers


def _fragile(path: Path, options: object) -> tuple[list[object], bool]:
    """The audit, except that a worker (not the parent) auditing the chosen file is killed."""
    import signal

    if path == _DIES["path"] and os.getpid() != _DIES["parent"]:
        os.kill(os.getpid(), signal.SIGKILL)
    real = _DIES["real"]
    return real(path, options)  # type: ignore[operator, no-any-return]


def test_a_worker_that_dies_is_replaced_by_the_parent(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # as the out-of-memory killer would: the worker auditing one file is killed outright
    from descgen.read import description as inputs

    paths = [Path(p) for p in _paths(tmp_path)]
    want = inputs.audit_paths(paths, inputs.Options(), jobs=1)
    monkeypatch.setitem(_DIES, "path", paths[1])
    monkeypatch.setitem(_DIES, "parent", os.getpid())
    monkeypatch.setitem(_DIES, "real", inputs._audit_one)
    monkeypatch.setattr(inputs, "_audit_one", _fragile)
    assert inputs.audit_paths(paths, inputs.Options(), jobs=2) == want


@pytest.mark.e2e
def test_sigterm_to_the_parent_alone_leaves_no_worker(tmp_path: Path) -> None:
    import time

    folder = tmp_path / "sigterm-probe"
    folder.mkdir()
    proc = _audit_in_background(_chains(folder))
    _wait_for_workers(proc)
    proc.terminate()  # SIGTERM to the parent only, as Popen.terminate() and CI runners send it
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 143, err[-500:]
    assert b"Traceback" not in err
    time.sleep(0.5)
    left = subprocess.run(["pgrep", "-f", str(folder)], capture_output=True, text=True).stdout.split()
    assert left == [], "workers left running"
