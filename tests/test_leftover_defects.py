"""Defects left from before (issue 34, item 10), each as its reproducer:

- ``validate`` of a spec whose widened plausibility ranges let an inertia overflow was a
  ``numpy.linalg.LinAlgError`` traceback;
- ``audit`` of a URDF with ``xyz="1e308"`` twice was a traceback (``cannot convert float NaN to
  integer``);
- ``tf-audit --format json`` of several recordings printed nothing when one was unreadable;
- SIGKILL of the parent of ``--jobs`` workers left them running forever, blocked on a pipe.

(``control --out DIR`` with ``DIR/control_run`` a link is in tests/test_output_paths.py.)
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from descgen.core.model import Inertia
from descgen.physics import principal

from .helpers import cli

BIG = """\
name: big
plausibility:
  mass: {max: 1e300 kg}
  size: {max: 1e300 m}
  offset: {max: 1e300 m}
links:
  - name: base_link
    collision:
      - geometry: {box: {size: [1e200 m, 1e200 m, 1e200 m]}}
    inertial: {mass: 1e300 kg, from: collision}
"""


def test_an_overflowing_inertia_is_a_located_error(tmp_path: Path) -> None:
    (tmp_path / "big.yaml").write_text(BIG)
    r = cli("validate", "big.yaml", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    # at the inertial's 'from:' (line 10), with a hint
    assert "big.yaml:10:" in r.stderr and "error[INER032]" in r.stderr and "hint:" in r.stderr, r.stderr


@pytest.mark.parametrize("shape", ["sphere: {diameter: 1e200 m}", "cylinder: {diameter: 1e200 m, length: 1e200 m}"])
def test_an_overflowing_round_shape_is_a_located_error(tmp_path: Path, shape: str) -> None:
    # found by the independent check of issue 34: r**2 raised OverflowError where r*r is inf
    text = BIG.replace("box: {size: [1e200 m, 1e200 m, 1e200 m]}", shape).replace("mass: 1e300 kg", "mass: 1 kg")
    (tmp_path / "big.yaml").write_text(text)
    for command in ("validate", "poses"):
        r = cli(command, "big.yaml", cwd=tmp_path)
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
        assert "error[" in r.stderr


# a sphere of radius 1e200 m (no plausibility to widen in a URDF), and a tensor of 1e308 entries
HUGE_SPHERE = (
    '<robot name="r"><link name="a"><inertial>{unit}</inertial>'
    '<collision><geometry><sphere radius="1e200"/></geometry></collision></link></robot>'
)
HUGE_TENSOR = (
    '<robot name="r"><link name="a"><inertial><mass value="1"/>'
    '<inertia ixx="1e308" iyy="1e308" izz="1e308" ixy="1e308" ixz="0" iyz="0"/></inertial></link></robot>'
)


@pytest.mark.parametrize("urdf", ["sphere", "tensor"])
@pytest.mark.parametrize("command", ["audit", "frames", "faults"])
def test_values_near_the_float_limit_in_a_urdf_are_no_traceback(tmp_path: Path, urdf: str, command: str) -> None:
    text = HUGE_SPHERE.replace("{unit}", '<mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>')
    (tmp_path / "r.urdf").write_text(text if urdf == "sphere" else HUGE_TENSOR)
    r = cli(command, "r.urdf", cwd=tmp_path)  # the suite runs without a findings cache
    assert r.returncode in (0, 1, 2) and "Traceback" not in r.stderr, r.stderr


def test_a_sweep_of_a_link_beyond_the_floats_says_so(tmp_path: Path) -> None:
    (tmp_path / "far.urdf").write_text(URDF_FAR)
    r = cli("sweep", "far.urdf", cwd=tmp_path)
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    assert "info[SWEEP003]: j1 is not swept: a link it moves lies beyond the float range" in r.stderr


def test_a_simulation_of_a_link_beyond_the_floats_is_a_finding(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    (tmp_path / "far.urdf").write_text(URDF_FAR)
    r = cli("simulate", "far.urdf", cwd=tmp_path)
    assert r.returncode in (1, 2) and "Traceback" not in r.stderr, r.stderr
    assert "error[SIM" in r.stderr


def test_principal_moments_of_a_non_finite_tensor_are_nan() -> None:
    t = Inertia(float("inf"), 1.0, 0.0, float("inf"), 0.0, 1.0)
    assert all(v != v for v in principal.moments(t))  # nan, not LAPACK's LinAlgError
    values, vectors = principal.axes(t)
    assert all(v != v for v in values) and len(vectors) == 3


_UNIT = '<mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
URDF_FAR = f"""<robot name="r">
  <link name="a"><inertial>{_UNIT}</inertial></link>
  <link name="b"><inertial><origin xyz="1e308 0 0"/>{_UNIT}</inertial>
    <collision><origin xyz="1e308 0 0"/><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="c"><inertial>{_UNIT}</inertial>
    <collision><origin xyz="1e308 0 0"/><geometry><box size="1 1 1"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="1e308 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="fixed"><parent link="b"/><child link="c"/><origin xyz="1e308 0 0"/></joint>
</robot>
"""


@pytest.mark.parametrize("command", ["audit", "faults", "frames"])
def test_a_pose_beyond_the_floats_is_no_traceback(tmp_path: Path, command: str) -> None:
    (tmp_path / "far.urdf").write_text(URDF_FAR)
    r = cli(command, "far.urdf", cwd=tmp_path)
    assert r.returncode in (0, 1, 2), r.stdout + r.stderr
    assert "Traceback" not in r.stderr


def test_max_abs_harmonic_of_non_finite_terms() -> None:
    from descgen.physics.bodies import max_abs_harmonic

    # inf - inf: a subtree's moment at x = 1e308 + 1e308 is nan, and floor(nan) raised
    for a, b in ((float("nan"), 1.0), (1.0, float("nan")), (float("inf"), float("-inf"))):
        got = max_abs_harmonic(a, b, -1.0, 1.0)
        assert got != got or got == float("inf")  # undefined or unbounded, never a ValueError


# --------------------------------------------------------------------------- tf-audit, several recordings


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    spec = Path(__file__).resolve().parents[1] / "specs" / "warehouse_arm.yaml"
    bag = tmp_path_factory.mktemp("bags") / "rec"
    assert cli("tf-scenario", spec, "--out", bag, "--duration", "1 s").returncode == 0
    return bag


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_tf_audit_json_keeps_the_good_recordings(recording: Path, tmp_path: Path, jobs: str) -> None:
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "metadata.yaml").write_text("not: [a, recording\n")
    r = cli(
        "tf-audit",
        recording,
        broken,
        "--target",
        "base_footprint",
        "--wait",
        "50 ms",
        "--format",
        "json",
        "--jobs",
        jobs,
    )
    assert r.returncode == 2, r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    doc = json.loads(r.stdout)
    good = doc["recordings"][str(recording)]
    assert good["lookups"] == 30 and good["ok"] == 30
    bad = doc["recordings"][str(broken)]
    assert bad["errors"] and all(e["severity"] == "error" and e["hint"] for e in bad["errors"])
    assert str(broken) in r.stderr and "error[" in r.stderr  # and located on stderr, as ever
    # the text report likewise keeps the good recording
    t = cli("tf-audit", recording, broken, "--target", "base_footprint", "--wait", "50 ms")
    assert t.returncode == 2 and "30 lookups into 'base_footprint': 30 ok" in t.stdout, t.stdout + t.stderr


# --------------------------------------------------------------------------- workers outlive no parent

_PARENT = textwrap.dedent(
    """
    import os, sys, time
    from descgen.infra import workers

    def slow(n):
        os.write(1, f"{os.getpid()}\\n".encode())  # one write below PIPE_BUF: two workers' lines never mix
        time.sleep(120)  # far longer than the test: a worker alive at the end was not killed
        return n

    workers.map_in_processes(slow, [1, 2], jobs=2)
    """
)


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().split(")")[-1].split()[0] != "Z"
    except FileNotFoundError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="PR_SET_PDEATHSIG is Linux's")
def test_workers_die_with_their_parent() -> None:
    if len(os.sched_getaffinity(0)) < 2:
        pytest.skip("one CPU: the work runs in the parent, there is no worker")
    parent = subprocess.Popen(
        [sys.executable, "-c", _PARENT], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert parent.stdout is not None and parent.stderr is not None
    lines = [parent.stdout.readline() for _ in range(2)]
    if not all(line.strip().isdigit() for line in lines):
        parent.kill()
        pytest.fail(f"the parent did not start its workers: {lines} {parent.stderr.read()[-2000:]}")
    pids = [int(line) for line in lines]
    try:
        parent.send_signal(signal.SIGKILL)
        parent.wait(10)
        deadline = time.monotonic() + 10
        while any(_alive(p) for p in pids) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(_alive(p) for p in pids), "a worker outlived its SIGKILLed parent"
    finally:
        for p in pids:
            if _alive(p):
                os.kill(p, signal.SIGKILL)
