"""tf-audit as a stream: the same outcomes as reading the whole recording first, bounded
memory, the header read straight from the bytes, and several recordings with --jobs."""

from __future__ import annotations

import json
import tracemalloc
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore

from descgen.audit.spec import load_spec
from descgen.commands.tf import bagaudit, scenario
from descgen.commands.tf.buffer import BufferCore

from .conftest import EXAMPLE
from .helpers import cli

ROBOT = load_spec(EXAMPLE).robot
MS = 1_000_000
TS = get_typestore(Stores.ROS2_JAZZY)


def whole_recording_replay(bag: Path, wait_ns: int, max_age_ns: int | None) -> list[tuple[str, int, str]]:
    """The audit as it was before streaming (the oracle): every message read and fully
    deserialized by rosbags first, transforms sorted by log time, sensor messages by log
    time + wait, then replayed."""
    tf_msgs: list[tuple[int, bool, Any]] = []
    sensors: list[tuple[int, str, Any]] = []
    with Reader(bag) as reader:
        for conn, log_ns, raw in reader.messages():
            msg = TS.deserialize_cdr(raw, conn.msgtype)
            if conn.topic in ("/tf", "/tf_static"):
                tf_msgs.append((log_ns, conn.topic == "/tf_static", msg))
            elif conn.topic == "/camera/camera_info":
                sensors.append((log_ns, conn.topic, msg))
    tf_msgs.sort(key=lambda m: m[0])
    sensors.sort(key=lambda m: m[0] + wait_ns)
    buf, i, out = BufferCore(), 0, []
    for log_ns, topic, msg in sensors:
        while i < len(tf_msgs) and tf_msgs[i][0] <= log_ns + wait_ns:
            for t in tf_msgs[i][2].transforms:
                tr, ro = t.transform.translation, t.transform.rotation
                stamp = t.header.stamp.sec * 10**9 + t.header.stamp.nanosec
                buf.set_transform(
                    t.header.frame_id,
                    t.child_frame_id,
                    stamp,
                    (tr.x, tr.y, tr.z),
                    (ro.x, ro.y, ro.z, ro.w),
                    tf_msgs[i][1],
                )
            i += 1
        stamp = msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec
        outcome, _ = bagaudit._lookup(buf, "odom", msg.header.frame_id, stamp, log_ns + wait_ns, max_age_ns)
        out.append((topic, log_ns, outcome))
    return out


@pytest.fixture(scope="module")
def faulty(tmp_path_factory: pytest.TempPathFactory) -> Path:
    bag = tmp_path_factory.mktemp("stream") / "faulty"
    scenario.write(ROBOT, bag, scenario.FAULTS, duration=8.0)
    return bag


@pytest.mark.parametrize(("wait_ms", "max_age_ms"), [(0, 100), (20, None), (2000, 100), (1, 100)])
def test_streaming_gives_the_whole_recording_outcomes(faulty: Path, wait_ms: int, max_age_ms: int | None) -> None:
    """Catches a message looked up before the transforms logged by its deadline are in (or
    after later ones), results out of order, or a wrong header read from the bytes."""
    max_age = None if max_age_ms is None else max_age_ms * MS
    want = whole_recording_replay(faulty, wait_ms * MS, max_age)
    rep = bagaudit.audit(faulty, "odom", wait_ns=wait_ms * MS, max_age_ns=max_age, keep_results=True)
    assert rep.results == want
    assert rep.counts == Counter(o for _, _, o in want)
    assert {o for _, _, o in want} >= ({"ok", "disconnected", "stale"} if wait_ms < 2000 else {"ok", "disconnected"})


def _peak_bytes(bag: Path) -> int:
    bagaudit.audit(bag, "odom", max_age_ns=100 * MS)  # warm: typestore, imports
    tracemalloc.start()
    try:
        rep = bagaudit.audit(bag, "odom", max_age_ns=100 * MS)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert rep.lookups and rep.results == []  # nothing per lookup is kept unless asked
    return peak


@pytest.mark.slow
def test_peak_memory_does_not_grow_with_the_recording(tmp_path: Path) -> None:
    """Four times the recording, about the same peak (the whole-recording audit held every
    message: its peak grew with the length, about 4x here)."""
    short, long = tmp_path / "short", tmp_path / "long"
    scenario.write(ROBOT, short, (), duration=10.0)
    scenario.write(ROBOT, long, (), duration=40.0)
    assert _peak_bytes(long) < 1.3 * _peak_bytes(short)


def test_several_recordings_with_jobs(tmp_path: Path) -> None:
    a, b = tmp_path / "a", tmp_path / "b"
    scenario.write(ROBOT, a, ("camera-future",), duration=4.0)
    scenario.write(ROBOT, b, (), duration=2.0)
    alone = [bagaudit.audit(p, "odom", max_age_ns=100 * MS).as_dict() for p in (a, b)]
    r = cli("tf-audit", str(a), str(b), "--target", "odom", "--max-age", "100 ms", "--jobs", "2", "--format", "json")
    assert r.returncode == 1, r.stderr  # a holds 30 future-dated messages (k = 60..89, see test_tf_scenario)
    doc = json.loads(r.stdout)
    # each says it cannot tell the robot: the scenario recorded no /robot_description
    unknown = {
        "identity": [{"robot": None, "description": None, "description_sha256": None, "source": "none"}],
        "windows": 1,
    }
    assert doc == {"recordings": {str(a): alone[0] | unknown, str(b): alone[1] | unknown}}
    assert doc["recordings"][str(a)]["future"] == 30 and doc["recordings"][str(b)]["ok"] == 60
    r = cli("tf-audit", str(b), str(b), "--target", "odom", "--jobs", "2")
    assert r.returncode == 0 and r.stdout.count(f"== {b}") == 2
    # every recording is audited: two unreadable ones are both named, with no traceback
    ghost, file = tmp_path / "ghost", tmp_path / "file.txt"
    file.write_text("x")
    r = cli("tf-audit", str(ghost), str(b), str(file), "--target", "odom", "--jobs", "3")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert r.stderr.count("error[BAG014]") == 2 and str(ghost) in r.stderr and str(file) in r.stderr


@pytest.mark.parametrize(("value", "message"), [("0", "0 processes"), ("65", "65 processes"), ("two", "'two' is not")])
def test_jobs_is_a_whole_number_of_processes(value: str, message: str) -> None:
    r = cli("tf-audit", "bag", "--target", "odom", "--jobs", value)
    assert r.returncode == 2 and f"argument --jobs: {message}" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.parametrize(("jobs", "unit"), [("1", "msg/s"), ("2", "B/s")])
def test_progress_on_a_terminal_and_not_in_a_pipe(tmp_path: Path, jobs: str, unit: str) -> None:
    import os
    import subprocess
    import sys

    from .helpers import on_a_terminal

    a, b = tmp_path / "a", tmp_path / "b"
    scenario.write(ROBOT, a, (), duration=2.0)
    scenario.write(ROBOT, b, (), duration=2.0)
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    args = ["tf-audit", str(a), str(b), "--target", "odom", "--jobs", jobs]
    shown = on_a_terminal(args, env)
    assert unit in shown, shown[:400]  # tqdm's bar: messages read, or bytes read (and recordings done) with --jobs
    piped = subprocess.run([sys.executable, "-m", "descgen", *args], capture_output=True, text=True, env=env)
    assert piped.returncode == 0 and unit not in piped.stderr and "\r" not in piped.stderr
    assert on_a_terminal([*args, "--format", "json"], env).count(unit) == 0
