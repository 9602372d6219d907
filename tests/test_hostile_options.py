"""Hostile option values, recordings and trajectories (issue 18): every one ends in exit 2
with a one-line `FILE:LINE:COL: error[CODE]` message and a hint, quickly, with nothing written;
never a traceback, a hang, or an "ok" that checked nothing."""

from __future__ import annotations

import argparse
import contextlib
import csv
import io
import os
import pickle
import select
import signal
import sqlite3
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from descgen.cli import main
from descgen.commands.tf import scenario
from descgen.core import units

from .conftest import EXAMPLE, ROOT
from .helpers import errors_of, line_of, plant, run_cli

# warm the libraries the commands import lazily: every child forked by `within` inherits them
with contextlib.suppress(ImportError):
    import matplotlib.pyplot  # noqa: F401
import rosbags.rosbag2
import rosbags.typesys  # noqa: F401

import descgen.commands.control.run
import descgen.commands.tf.bagaudit  # noqa: F401

SPEC = str(EXAMPLE)
READY = ROOT / "specs" / "trajectories" / "ready.yaml"


def within(seconds: float, fn: Callable[[], Any]) -> tuple[Any, str, str]:
    """``fn()`` in a forked copy of this process: (its value, its stdout, its stderr).

    Fails if it has not returned in ``seconds``: a big-integer power holds the GIL inside one
    C call, so neither a thread nor a signal could stop it; a child process can be killed.
    Whatever ``fn`` raises fails the test with the child's traceback.
    """
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: run, send the outcome, and leave without pytest's exit handlers
        os.close(read_end)
        try:
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                try:
                    outcome: tuple[str, Any] = ("ok", fn())
                except BaseException:
                    outcome = ("raised", traceback.format_exc())
            with os.fdopen(write_end, "wb") as pipe:
                pipe.write(pickle.dumps((outcome, out.getvalue(), err.getvalue())))
        finally:
            os._exit(0)
    os.close(write_end)
    deadline = time.monotonic() + seconds
    data = b""
    with os.fdopen(read_end, "rb") as pipe:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([pipe], [], [], left)[0]:
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                pytest.fail(f"still running after {seconds} s")
            chunk = os.read(pipe.fileno(), 1 << 16)
            if not chunk:
                break
            data += chunk
    os.waitpid(pid, 0)
    (status, value), out_text, err_text = pickle.loads(data)
    assert status == "ok", value
    return value, out_text, err_text


def cli(*argv: str, bounded: bool = False) -> tuple[int, str, str]:
    """``descgen ARGV`` in process, through ``main``: (exit code, stdout, stderr).
    ``bounded``: in a forked child that must finish within 30 s (for input that once hung)."""
    if bounded:
        code, out, err = within(30.0, lambda: main(list(argv)))
    else:
        out_buf, err_buf = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out_buf), contextlib.redirect_stderr(err_buf):
            code = main(list(argv))
        out, err = out_buf.getvalue(), err_buf.getvalue()
    assert "Traceback" not in err
    return code, out, err


def refused(code: str, *argv: str, bounded: bool = False) -> str:
    """Run, expect exit 2 with exactly one finding of ``code`` and its hint; return stderr."""
    rc, _out, err = cli(*argv, bounded=bounded)
    lines = err.splitlines()
    assert rc == 2, err
    assert len(lines) == 2 and f"error[{code}]" in lines[0] and lines[1].startswith("  hint: "), err
    return err


# --------------------------------------------------------------------------- quantities


@pytest.mark.parametrize(
    "text",
    [
        "9**9**9 kg",  # chained power: 9**(9**9) has 370 million digits
        "2^3^4^5 kg",  # the same with carets (pint reads ^ as **)
        "(9**99)**99**2 kg",
        "(9**999)**999 kg",  # a power of a power
        "9⁹⁹⁹⁹⁹⁹⁹⁹ kg",  # superscripts become 9**(99999999) inside pint
        "2**(9**9) kg",  # an exponent that is itself an expression
        "10**1000000 kg",  # one plain, huge exponent
        "7" * 60 + " kg",  # too many digits
        "1 " + "kg*" * 80 + "kg",  # too long
    ],
)
def test_hostile_quantity_text_is_refused_fast(text: str) -> None:
    def read() -> str:
        with pytest.raises(units.QuantityError) as exc:
            units.to_si(text, "mass")
        return exc.value.code

    assert within(2.0, read)[0] == "UNIT020"


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("0.01 kg*m^2", "inertia", 0.01),
        ("2 kg*m**2", "inertia", 2.0),
        ("1200 g*cm^2", "inertia", 1.2e-4),  # 1.2 kg * 1e-4 m^2
        ("(10 mm)^2 * 3 kg", "inertia", 3e-4),  # (0.01 m)^2 * 3 kg
        ("3 kg m² / s²", "torque", 3.0),  # pint turns the superscripts into **(2)
        ("10^-3 km", "length", 1.0),
        ("10**+3 mm", "length", 1.0),
        ("1.5e-3 km", "length", 1.5),  # exponent notation is not a power
        ("100 1/s", "linear_stiffness_gain", 100.0),
        ("2 m/s**2 * 3 s", "linear_velocity", 6.0),
    ],
)
def test_unit_powers_and_exponent_notation_still_read(text: str, kind: str, expected: float) -> None:
    assert units.to_si(text, kind) == pytest.approx(expected, rel=1e-12)


def test_hostile_power_in_a_spec_is_a_located_error(tmp_path: Path) -> None:
    text = plant("mass: {value: 28.0 kg, source: M06}", "mass: {value: 9**9**9 kg, source: M06}")
    found, _, _ = within(10.0, lambda: errors_of(text, tmp_path))
    hits = [f for f in found if f.code == "UNIT020"]
    assert hits and hits[0].where.line == line_of(text, "9**9**9 kg"), found


# --------------------------------------------------------------------------- tf-audit


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    bag = tmp_path_factory.mktemp("bags") / "rec"
    assert cli("tf-scenario", SPEC, "--out", str(bag), "--duration", "1 s")[0] == 0
    return bag


@pytest.mark.parametrize(
    ("option", "value", "code"),
    [
        ("--wait", "1e300 s", "UNIT021"),  # crashed: 1e309 ns is not an integer
        ("--wait", "-1 s", "UNIT021"),
        ("--wait", "2 h", "UNIT021"),
        ("--wait", "9**9**9 s", "UNIT020"),  # hung in pint
        ("--wait", "nan s", "UNIT002"),
        ("--max-age", "1e300 s", "UNIT021"),
        ("--max-age", "3 kg", "UNIT003"),
        ("--wait", "50", "UNIT001"),  # no unit: 50 ms or 50 s? (only --duration reads bare seconds)
    ],
)
def test_tf_audit_time_options_are_bounded(recording: Path, option: str, value: str, code: str) -> None:
    err = refused(code, "tf-audit", str(recording), "--target", "odom", option, value, bounded=True)
    assert err.startswith(f"<command line>: error[{code}]: {option}:"), err


def test_tf_audit_good_recording_still_passes(recording: Path) -> None:
    rc, out, err = cli("tf-audit", str(recording), "--target", "base_footprint", "--wait", "50 ms")
    # 1 s of camera at 30 Hz (frames at 5 ms + k/30 s, k = 0..29), each looked up once
    assert rc == 0 and out.startswith("30 lookups into 'base_footprint': 30 ok"), out + err


def _write_bag(path: Path, topics: dict[str, str], messages: list[tuple[str, Any]]) -> None:
    """A rosbag2 folder with the given (topic -> type) connections and messages, by rosbags."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        conns = {t: w.add_connection(t, ty, typestore=ts) for t, ty in topics.items()}
        for i, (topic, msg) in enumerate(messages):
            w.write(conns[topic], 1_000 + i, ts.serialize_cdr(msg, topics[topic]))


def _tf_message() -> Any:
    from rosbags.typesys import Stores, get_typestore

    t = get_typestore(Stores.ROS2_JAZZY).types
    tr = t["geometry_msgs/msg/TransformStamped"](
        header=t["std_msgs/msg/Header"](stamp=t["builtin_interfaces/msg/Time"](sec=1, nanosec=0), frame_id="odom"),
        child_frame_id="base_link",
        transform=t["geometry_msgs/msg/Transform"](
            translation=t["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0),
            rotation=t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        ),
    )
    return t["tf2_msgs/msg/TFMessage"](transforms=[tr])


def test_tf_audit_with_nothing_to_look_up_is_not_ok(tmp_path: Path) -> None:
    only_tf = tmp_path / "only_tf"
    _write_bag(
        only_tf,
        {"/tf": "tf2_msgs/msg/TFMessage", "/camera/camera_info": "sensor_msgs/msg/CameraInfo"},
        [("/tf", _tf_message())],
    )
    # no sensor message at all (the camera topic is recorded but empty): was "0 lookups ... ok", exit 0
    err = refused("BAG010", "tf-audit", str(only_tf), "--target", "odom")
    assert "nothing to look up" in err
    err = refused("BAG010", "tf-audit", str(only_tf), "--target", "odom", "--topic", "/camera/camera_info")
    assert "/camera/camera_info" in err
    # /tf has no header to look up: was a traceback-like "cannot read the recording"
    err = refused("BAG013", "tf-audit", str(only_tf), "--target", "odom", "--topic", "/tf")
    assert "/tf" in err


def test_tf_audit_topic_or_target_not_in_recording(recording: Path) -> None:
    err = refused("BAG002", "tf-audit", str(recording), "--target", "odom", "--topic", "/nope")
    assert "/nope" in err
    # a target frame nobody publishes: every lookup "disconnected" is a typo, not a finding (was exit 1)
    err = refused("BAG012", "tf-audit", str(recording), "--target", "odomm")
    assert "'odomm'" in err and "base_link" in err


def _corrupt(kind: str, recording: Path, tmp: Path) -> Path:
    import shutil

    if kind == "missing":
        return tmp / "absent"
    if kind == "file":
        (tmp / "bag.mcap").write_bytes(b"\x89MCAP0\r\n")
        return tmp / "bag.mcap"
    if kind == "empty":
        (tmp / "empty").mkdir()
        return tmp / "empty"
    bag = tmp / "bag"
    shutil.copytree(recording, bag)
    data = next(bag.glob("*.mcap"))
    if kind == "garbage-metadata":
        (bag / "metadata.yaml").write_text("rosbag2_bagfile_information: {{{ [\n")
    elif kind == "metadata-not-a-mapping":
        (bag / "metadata.yaml").write_text("rosbag2_bagfile_information: 5\n")
    elif kind == "metadata-folder":
        (bag / "metadata.yaml").unlink()
        (bag / "metadata.yaml").mkdir()
    elif kind == "truncated-mcap":
        data.write_bytes(data.read_bytes()[: data.stat().st_size // 2])
    elif kind == "garbage-mcap":
        data.write_bytes(bytes(range(256)) * 20)
    elif kind == "missing-mcap":
        data.unlink()
    return bag


@pytest.mark.parametrize(
    ("kind", "code"),
    [
        ("missing", "BAG014"),
        ("file", "BAG014"),
        ("empty", "BAG014"),
        ("metadata-folder", "BAG014"),
        ("garbage-metadata", "BAG001"),
        ("metadata-not-a-mapping", "BAG001"),
        ("truncated-mcap", "BAG001"),
        ("garbage-mcap", "BAG001"),
        ("missing-mcap", "BAG001"),
    ],
)
def test_corrupt_recordings_are_input_errors(recording: Path, tmp_path: Path, kind: str, code: str) -> None:
    bag = _corrupt(kind, recording, tmp_path)
    err = refused(code, "tf-audit", str(bag), "--target", "odom")
    assert err.startswith(str(bag)), err


def test_corrupt_sqlite_recording_is_an_input_error(tmp_path: Path) -> None:
    bag = tmp_path / "sq"
    assert cli("tf-scenario", SPEC, "--out", str(bag), "--duration", "0.5", "--storage", "sqlite3")[0] == 0
    db = next(bag.glob("*.db3"))
    with sqlite3.connect(db) as con:  # the oracle: sqlite itself reads it before we break it
        assert con.execute("select count(*) from messages").fetchone()[0] > 0
    db.write_bytes(b"SQLite format 3\x00" + b"\xff" * 2000)
    refused("BAG001", "tf-audit", str(bag), "--target", "odom")


# --------------------------------------------------------------------------- tf-scenario


@pytest.mark.parametrize(
    ("duration", "code"),
    [("abc", "UNIT002"), ("nan", "UNIT002"), ("1e9", "UNIT021"), ("-2 s", "UNIT021"), ("3 kg", "UNIT003")],
)
def test_tf_scenario_duration_is_checked(tmp_path: Path, duration: str, code: str) -> None:
    out = tmp_path / "rec"
    err = refused(code, "tf-scenario", SPEC, "--out", str(out), "--duration", duration, bounded=True)
    assert "--duration" in err and not out.exists() and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("duration", ["2 s", "2s", "2", "2000 ms"])
def test_tf_scenario_duration_with_or_without_unit(tmp_path: Path, duration: str) -> None:
    rc, out, err = cli("tf-scenario", SPEC, "--out", str(tmp_path / "rec"), "--duration", duration)
    # 2 s at the spec's update_rate of 100 Hz, camera at 30 Hz
    assert rc == 0 and "/joint_states 200, /tf 200, /camera/camera_info 60" in out, out + err


def test_tf_scenario_out_under_a_file_or_missing_folder(tmp_path: Path) -> None:
    (tmp_path / "afile").write_text("x")
    err = refused("BAG011", "tf-scenario", SPEC, "--out", str(tmp_path / "afile" / "rec"))
    assert "is not a folder" in err
    err = refused("BAG011", "tf-scenario", SPEC, "--out", str(tmp_path / "no" / "rec"))
    assert "does not exist" in err
    refused("BAG003", "tf-scenario", SPEC, "--out", str(tmp_path / "afile"))
    assert [p.name for p in tmp_path.iterdir()] == ["afile"]


def test_tf_scenario_failing_midway_leaves_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    real = scenario._write

    def full_disk(robot: Any, out: Path, *args: Any) -> dict[str, int]:
        real(robot, out, *args)  # the whole recording is on disk, then the disk "fills"
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(scenario, "_write", full_disk)
    err = refused("BAG011", "tf-scenario", SPEC, "--out", str(tmp_path / "rec"), "--duration", "0.5 s")
    assert "No space left on device" in err
    assert list(tmp_path.iterdir()) == []  # neither rec nor a staging folder


# --------------------------------------------------------------------------- control


def control(tmp_path: Path, trajectory: Path, *extra: str, bounded: bool = False) -> tuple[int, str]:
    """``descgen control`` on the example (its committed package), evidence into tmp_path."""
    out_dir = str(tmp_path / "ev")
    rc, out, err = cli("control", SPEC, "--trajectory", str(trajectory), "--out", out_dir, *extra, bounded=bounded)
    return rc, out + err


POINT = '{time_from_start: "1 s", positions: ["0 deg"]}'


@pytest.mark.parametrize(
    ("body", "code", "needle"),
    [
        ("joints: [elbow_joint]\npoints: 5\n", "CTRL020", "points: 5"),  # was a TypeError traceback
        (f"joints: elbow_joint\npoints:\n  - {POINT}\n", "CTRL030", "joints: elbow_joint"),
        (f"joints: [[1]]\npoints:\n  - {POINT}\n", "CTRL020", "[1]]"),
        ('joints: [elbow_joint]\npoints:\n  - {time_from_start: "1 s", positions: "0 deg"}\n', "CTRL020", '"0 deg"}'),
        ("joints: [elbow_joint]\npoints:\n  - 7\n", "CTRL020", "- 7"),
        ('joints: [elbow_joint]\npoints:\n  - {positions: ["0 deg"]}\n', "CTRL020", "- {positions"),
        ("joints: [elbow_joint]\npoints: []\n", "CTRL030", "[]"),  # was "ok": nothing ran
        ("joints: [elbow_joint]\n", "CTRL030", "controller"),
        (
            f'joints: [elbow_joint]\npoints:\n  - {POINT}\n  - {{time_from_start: "0.5 s", positions: ["0 deg"]}}\n',
            "CTRL031",
            '"0.5 s"',
        ),  # unsorted: was "ok"
        (f"joints: [elbow_joint]\npoints:\n  - {POINT}\n  - {POINT}\n", "CTRL031", 5),  # the second point
        ('joints: [elbow_joint]\npoints:\n  - {time_from_start: "-1 s", positions: ["0 deg"]}\n', "UNIT021", '"-1 s"'),
        ('joints: [elbow_joint]\npoints:\n  - {time_from_start: "1e9 s", positions: ["0 deg"]}\n', "UNIT021", '"1e9'),
        ('joints: [elbow_joint]\npoints:\n  - {time_from_start: "9**9**9 s", positions: ["0 deg"]}\n', "UNIT020", '"9'),
        (f"joints: [elbow_joint]\npoints:\n  - {POINT}\nspeed: 2\n", "CTRL020", "speed"),
    ],
)
def test_bad_trajectories_are_located_input_errors(tmp_path: Path, body: str, code: str, needle: str | int) -> None:
    text = "controller: arm_controller\n" + body
    path = tmp_path / "t.yaml"
    path.write_text(text)
    rc, err = control(tmp_path, path, bounded=True)
    line = needle if isinstance(needle, int) else line_of(text, needle)
    assert rc == 2, err
    first = err.splitlines()[0]
    assert first.startswith(f"{path}:{line}:") and f"error[{code}]" in first, err
    assert not (tmp_path / "ev").exists()


def test_joint_the_controller_does_not_command_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "t.yaml"
    path.write_text(f"controller: arm_controller\njoints: [left_wheel_joint]\npoints:\n  - {POINT}\n")
    rc, err = control(tmp_path, path)  # was "ok": the arm controller ignored the goal
    assert rc == 2 and f"{path}:1:1: error[CTRL033]" in err and "left_wheel_joint" in err, err


@pytest.mark.parametrize(
    ("fault", "needle"),
    [
        ("elbow_joint", "is not JOINT:=KIND"),  # was a ValueError traceback
        ("elbow_joint:=wobble", "unknown fault kind 'wobble'"),  # was silently accepted
        ("elbow_jiont:=stuck", "'elbow_jiont' is not a joint under ros2_control"),  # was silently accepted
        (":=stuck", "is not JOINT:=KIND"),
    ],
)
def test_plant_fault_is_checked(tmp_path: Path, fault: str, needle: str) -> None:
    rc, err = control(tmp_path, READY, "--plant", "sim", "--plant-fault", fault)
    assert rc == 2 and "error[CTRL032]: --plant-fault" in err and needle in err, err


def test_plant_fault_on_the_mock_would_not_show(tmp_path: Path) -> None:
    rc, err = control(tmp_path, READY, "--plant-fault", "elbow_joint:=stuck")
    assert rc == 2 and "error[CTRL032]" in err and "--plant sim" in err, err


def _last_time(folder: Path) -> float:
    with (folder / "desired_vs_measured.csv").open() as f:
        return max(float(row["time_s"]) for row in csv.DictReader(f))


@pytest.mark.parametrize("duration", ["1.5s", "1.5", "1500 ms"])
def test_control_duration_with_or_without_unit(tmp_path: Path, duration: str) -> None:
    rc, err = control(tmp_path, READY, "--duration", duration)
    assert rc == 0, err
    assert _last_time(tmp_path / "ev") == 1.5  # the run ends at the 1.5 s asked for (was a ValueError for "3s")


@pytest.mark.parametrize(
    ("duration", "code"),
    [("abc", "UNIT002"), ("nan", "UNIT002"), ("1e9", "UNIT021"), ("0", "UNIT021"), ("9**9**9 s", "UNIT020")],
)
def test_control_duration_is_checked(tmp_path: Path, duration: str, code: str) -> None:
    rc, err = control(tmp_path, READY, "--duration", duration, bounded=True)
    assert rc == 2 and f"<command line>: error[{code}]: --duration:" in err, err
    assert not (tmp_path / "ev").exists()


def test_control_out_under_a_file(tmp_path: Path) -> None:
    (tmp_path / "afile").write_text("x")
    rc, _out, err = cli(
        "control",
        SPEC,
        "--trajectory",
        str(READY),
        "--duration",
        "0.5 s",
        "--out",
        str(tmp_path / "afile" / "ev"),
    )
    assert rc == 2 and "error[CTRL034]" in err and "afile" in err, err


# --------------------------------------------------------------------------- every option


NOSPEC = "no/such/spec.yaml"  # parse-time checks must refuse before any spec is read
ARGPARSE = "argparse"  # argparse's own usage error (a bad choice, a flag given a value)

# (command, option, argv with {bag} {afile} {tmp} placeholders, what stderr must hold)
# Every option of every command appears at least once (checked below); a value a `type=`
# callable refuses is given with a spec that does not exist, so a check that runs after the
# spec is read (or not at all) shows up as a different error.
BAD_OPTIONS: list[tuple[str, str, list[str], str]] = [
    ("validate", "spec", ["validate", NOSPEC], "error[YAML002]"),
    ("fix", "spec", ["fix", NOSPEC], "error[YAML002]"),
    ("fix", "--dry-run", ["fix", SPEC, "--dry-run=1"], "argument --dry-run: ignored explicit argument"),
    ("import-calibration", "spec", ["import-calibration", NOSPEC, "{afile}", "--format", "ur"], "error[YAML002]"),
    ("import-calibration", "file", ["import-calibration", SPEC, "{tmp}/none.yaml", "--format", "ur"], "error[CAL010]"),
    ("import-calibration", "--format", ["import-calibration", NOSPEC, "{afile}", "--format", "dh"], "invalid choice"),
    (
        "import-calibration",
        "--source",
        ["import-calibration", NOSPEC, "{afile}", "--format", "ur", "--source", "a b"],
        "is not a name",
    ),
    (
        "import-calibration",
        "--prefix",
        ["import-calibration", NOSPEC, "{afile}", "--format", "ur", "--prefix", "a b"],
        "is not a name prefix",
    ),
    (
        "import-calibration",
        "--sensor",
        ["import-calibration", NOSPEC, "{afile}", "--format", "ur", "--sensor", "$x"],
        "is not a name",
    ),
    (
        "import-calibration",
        "--date",
        ["import-calibration", NOSPEC, "{afile}", "--format", "ur", "--date", "2026-13-01"],
        "is not a calendar date",
    ),
    (
        "import-calibration",
        "--dry-run",
        ["import-calibration", NOSPEC, "{afile}", "--format", "ur", "--dry-run=1"],
        "ignored explicit argument",
    ),
    (
        "import-calibration",
        "--replace",
        ["import-calibration", NOSPEC, "{afile}", "--format", "ur", "--replace=1"],
        "ignored explicit argument",
    ),
    ("drift", "spec", ["drift", NOSPEC, "--samples", "{afile}", "--frame", "tool_link"], "error[YAML002]"),
    (
        "drift",
        "--recording",
        ["drift", SPEC, "--recording", "{tmp}/none", "--pose-topic", "/p", "--frame", "tool_link"],
        "error[CAL012]",
    ),
    ("drift", "--samples", ["drift", SPEC, "--samples", "{afile}", "--frame", "tool_link"], "error[CAL012]"),
    (
        "drift",
        "--pose-topic",
        ["drift", SPEC, "--recording", "{tmp}", "--frame", "tool_link"],
        "error[CAL012]: --recording needs --pose-topic",
    ),
    ("drift", "--frame", ["drift", SPEC, "--samples", "{afile}", "--frame", "nope"], "error[CAL012]: --frame 'nope'"),
    (
        "drift",
        "--base",
        ["drift", SPEC, "--samples", "{afile}", "--frame", "tool_link", "--base", "nope"],
        "error[CAL012]: --base 'nope'",
    ),
    (
        "drift",
        "--parameters",
        ["drift", SPEC, "--samples", "{afile}", "--frame", "tool_link", "--parameters", "nope"],
        "error[CAL012]: --parameters matches no parameter",
    ),
    (
        "drift",
        "--tolerance",
        ["drift", NOSPEC, "--samples", "{afile}", "--frame", "x", "--tolerance", "5 kg"],
        "error[UNIT",
    ),
    (
        "drift",
        "--format",
        ["drift", NOSPEC, "--samples", "{afile}", "--frame", "x", "--format", "xml"],
        "invalid choice",
    ),
    (
        "drift",
        "--package-path",
        ["drift", NOSPEC, "--samples", "{afile}", "--frame", "x", "--package-path", "{tmp}/none"],
        "' does not exist",
    ),
    ("validate", "--format", ["validate", NOSPEC, "--format", "xml"], "argument --format: invalid choice: 'xml'"),
    ("generate", "spec", ["generate", NOSPEC, "--out", "{tmp}/o"], "error[YAML002]"),
    ("generate", "--out", ["generate", NOSPEC, "--out", ""], "argument --out: an empty path names nothing"),
    ("generate", "--templates", ["generate", NOSPEC, "--templates", "{afile}"], "error[GEN010]: --templates"),
    ("generate", "--force", ["generate", NOSPEC, "--force=yes"], "argument --force: ignored explicit argument 'yes'"),
    ("check", "spec", ["check", NOSPEC], "error[YAML002]"),
    ("check", "--out", ["check", NOSPEC, "--out", " "], "argument --out: an empty path names nothing"),
    ("check", "--templates", ["check", NOSPEC, "--templates", "{tmp}/none"], "error[GEN010]: --templates"),
    ("validate", "--package-path", ["validate", NOSPEC, "--package-path", "{tmp}/none"], "' does not exist"),
    ("poses", "--package-path", ["poses", NOSPEC, "--package-path", "{tmp}/none"], "' does not exist"),
    ("report", "--package-path", ["report", NOSPEC, "--package-path", "{afile}"], "' is not a folder"),
    (
        "tf-scenario",
        "--package-path",
        ["tf-scenario", NOSPEC, "--out", "{tmp}/b", "--package-path", "{tmp}/none"],
        "' does not exist",
    ),
    (
        "control",
        "--package-path",
        ["control", NOSPEC, "--trajectory", "{afile}", "--package-path", "{tmp}/none"],
        "' does not exist",
    ),
    ("generate", "--package-path", ["generate", NOSPEC, "--package-path", "{afile}"], "' is not a folder"),
    ("check", "--package-path", ["check", NOSPEC, "--package-path", "{tmp}/none"], "' does not exist"),
    ("check", "--thorough", ["check", NOSPEC, "--thorough=1"], "argument --thorough: ignored explicit argument '1'"),
    ("check", "--format", ["check", NOSPEC, "--format", "json"], "argument --format: invalid choice: 'json'"),
    ("sweep", "path", ["sweep", "{tmp}/none.urdf"], "error[READ001]"),
    ("sweep", "--state", ["sweep", SPEC, "--state", "nope"], "error[SWEEP004]: --state 'nope'"),
    ("sweep", "--steps", ["sweep", NOSPEC, "--steps", "0"], "argument --steps: 0 is not between 1 and 3600"),
    ("sweep", "--srdf", ["sweep", SPEC, "--srdf", "{tmp}/none.srdf"], "error[READ001]"),
    ("sweep", "--controllers", ["sweep", SPEC, "--controllers", "{tmp}/none.yaml"], "error[READ001]"),
    ("sweep", "--xacro-arg", ["sweep", NOSPEC, "--xacro-arg", "x"], "error[READ005]: --xacro-arg"),
    ("sweep", "--launch-arg", ["sweep", NOSPEC, "--launch-arg", "x"], "error[CTRL054]: --launch-arg"),
    ("sweep", "--package-path", ["sweep", NOSPEC, "--package-path", "{tmp}/none"], "' does not exist"),
    ("sweep", "--trust-xacro", ["sweep", NOSPEC, "--trust-xacro=1"], "argument --trust-xacro: ignored"),
    ("sweep", "--format", ["sweep", NOSPEC, "--format", "xml"], "argument --format: invalid choice: 'xml'"),
    ("sweep", "--strict", ["sweep", NOSPEC, "--strict=1"], "argument --strict: ignored explicit argument '1'"),
    ("audit", "path", ["audit", "{tmp}/none.urdf"], "error[READ001]"),
    ("audit", "--srdf", ["audit", SPEC, "--srdf", "{tmp}/none.srdf"], "error[READ001]"),
    ("audit", "--controllers", ["audit", SPEC, "--controllers", "{tmp}/none.yaml"], "error[READ001]"),
    (
        "audit",
        "--controllers",
        ["audit", NOSPEC, "--controllers", "a.yaml", "--controllers", "b.yaml"],
        "error[GRAPH010]: --controllers is given 2 times",
    ),
    ("audit", "--srdf", ["audit", NOSPEC, "--srdf", "a.srdf", "--srdf", "b.srdf"], "error[GRAPH010]: --srdf is given"),
    ("audit", "--together", ["audit", NOSPEC, "--together=1"], "argument --together: ignored explicit argument '1'"),
    ("audit", "--xacro-arg", ["audit", NOSPEC, "--xacro-arg", "use_gripper"], "error[READ005]: --xacro-arg"),
    ("audit", "--launch-arg", ["audit", NOSPEC, "--launch-arg", "joint_prefix"], "error[CTRL054]: --launch-arg"),
    ("audit", "--package-path", ["audit", NOSPEC, "--package-path", "{tmp}/none"], "argument --package-path: '"),
    ("audit", "--baseline", ["audit", NOSPEC, "--baseline", ""], "argument --baseline: an empty path names nothing"),
    ("audit", "--no-waivers", ["audit", NOSPEC, "--no-waivers=1"], "argument --no-waivers: ignored explicit argument"),
    (
        "audit",
        "--write-baseline",
        ["audit", NOSPEC, "--write-baseline", ""],
        "argument --write-baseline: an empty path names nothing",
    ),
    ("audit", "--moveit-config", ["audit", NOSPEC, "--moveit-config", "{afile}"], "' is not a folder"),
    ("audit", "--trust-xacro", ["audit", NOSPEC, "--trust-xacro=no"], "argument --trust-xacro: ignored explicit"),
    ("audit", "--format", ["audit", NOSPEC, "--format", "html"], "argument --format: invalid choice: 'html'"),
    ("audit", "--strict", ["audit", NOSPEC, "--strict=0"], "argument --strict: ignored explicit argument '0'"),
    ("audit", "--jobs", ["audit", NOSPEC, "--jobs", "100000"], "argument --jobs: 100000 processes is outside 1 to 64"),
    ("import", "path", ["import", "{tmp}/none.urdf"], "error[READ001]"),
    ("import", "--srdf", ["import", NOSPEC, "--srdf", ""], "argument --srdf: an empty path names nothing"),
    ("import", "--controllers", ["import", NOSPEC, "--controllers", " "], "argument --controllers: an empty path"),
    ("import", "--xacro-arg", ["import", NOSPEC, "--xacro-arg", "x"], "error[READ005]: --xacro-arg"),
    ("import", "--launch-arg", ["import", NOSPEC, "--launch-arg", "a:=b\nc: 1"], "error[CTRL054]: --launch-arg"),
    ("import", "--package-path", ["import", NOSPEC, "--package-path", "{tmp}/none"], "argument --package-path: '"),
    ("import", "--trust-xacro", ["import", NOSPEC, "--trust-xacro=1"], "argument --trust-xacro: ignored explicit"),
    ("import", "--output", ["import", NOSPEC, "--output", ""], "argument -o/--output: an empty path names nothing"),
    ("import", "--units", ["import", NOSPEC, "--units", "mm,furlong"], "error[IMP008]: --units: 'furlong'"),
    ("import", "--force", ["import", NOSPEC, "--force=yes"], "argument --force: ignored explicit argument 'yes'"),
    (
        "import",
        "--no-waivers",
        ["import", NOSPEC, "--no-waivers=yes"],
        "argument --no-waivers: ignored explicit argument 'yes'",
    ),
    ("import", "--variant", ["import", NOSPEC, "--variant", "sim:use_gazebo:=true"], "error[IMP027]: --variant"),
    ("import", "--fix", ["import", NOSPEC, "--fix=yes"], "argument --fix: ignored explicit argument 'yes'"),
    ("faults", "path", ["faults", "{tmp}/none.urdf"], "error[READ001]"),
    ("faults", "--srdf", ["faults", SPEC, "--srdf", "{tmp}"], "error[READ040]"),
    ("faults", "--controllers", ["faults", SPEC, "--controllers", ""], "argument --controllers: an empty path"),
    ("faults", "--xacro-arg", ["faults", NOSPEC, "--xacro-arg", ":=1"], "error[READ005]: --xacro-arg"),
    ("faults", "--launch-arg", ["faults", NOSPEC, "--launch-arg", ":=1"], "error[CTRL054]: --launch-arg"),
    ("faults", "--package-path", ["faults", NOSPEC, "--package-path", "{afile}"], "' is not a folder"),
    ("faults", "--trust-xacro", ["faults", NOSPEC, "--trust-xacro=1"], "argument --trust-xacro: ignored explicit"),
    ("faults", "--format", ["faults", NOSPEC, "--format", "sarif"], "argument --format: invalid choice: 'sarif'"),
    ("frames", "path", ["frames", NOSPEC], "error[READ001]"),
    ("frames", "--srdf", ["frames", SPEC, "--srdf", ""], "argument --srdf: an empty path names nothing"),
    ("frames", "--controllers", ["frames", SPEC, "--controllers", "{tmp}/none.yaml"], "error[READ001]"),
    ("frames", "--xacro-arg", ["frames", NOSPEC, "--xacro-arg", "x=1"], "error[READ005]: --xacro-arg"),
    ("frames", "--launch-arg", ["frames", NOSPEC, "--launch-arg", "x=1"], "error[CTRL054]: --launch-arg"),
    ("frames", "--package-path", ["frames", NOSPEC, "--package-path", "{tmp}/none"], "' does not exist"),
    ("frames", "--trust-xacro", ["frames", NOSPEC, "--trust-xacro=yes"], "argument --trust-xacro: ignored explicit"),
    ("frames", "--format", ["frames", NOSPEC, "--format", "dot"], "argument --format: invalid choice: 'dot'"),
    ("simulate", "path", ["simulate", NOSPEC], "error[READ001]"),
    ("simulate", "--seconds", ["simulate", NOSPEC, "--seconds", "1 h"], "error[UNIT021]: --seconds"),
    ("simulate", "--pose", ["simulate", SPEC, "--pose", "nope"], "error[SIM014]: --pose 'nope'"),
    ("simulate", "--base", ["simulate", NOSPEC, "--base", "wall"], "argument --base: invalid choice: 'wall'"),
    ("simulate", "--srdf", ["simulate", SPEC, "--srdf", ""], "argument --srdf: an empty path names nothing"),
    ("simulate", "--controllers", ["simulate", SPEC, "--controllers", "{tmp}/none.yaml"], "error[READ001]"),
    ("simulate", "--xacro-arg", ["simulate", NOSPEC, "--xacro-arg", "x=1"], "error[READ005]: --xacro-arg"),
    ("simulate", "--launch-arg", ["simulate", NOSPEC, "--launch-arg", "a:=" + "v" * 5000], "error[CTRL054]: --launch"),
    ("simulate", "--package-path", ["simulate", NOSPEC, "--package-path", "{tmp}/none"], "' does not exist"),
    ("simulate", "--trust-xacro", ["simulate", NOSPEC, "--trust-xacro=yes"], "argument --trust-xacro: ignored"),
    ("simulate", "--format", ["simulate", NOSPEC, "--format", "csv"], "argument --format: invalid choice: 'csv'"),
    ("tf-audit", "bag", ["tf-audit", "{afile}", "--target", "odom"], "error[BAG014]"),
    ("tf-audit", "--target", ["tf-audit", "{bag}", "--target", "no_frame"], "error[BAG012]"),
    ("tf-audit", "--topic", ["tf-audit", "{bag}", "--target", "odom", "--topic", "/none"], "error[BAG002]"),
    ("tf-audit", "--wait", ["tf-audit", "{afile}", "--target", "odom", "--wait", "5 kg"], "error[UNIT003]: --wait"),
    ("tf-audit", "--max-age", ["tf-audit", "{afile}", "--target", "o", "--max-age", "2 h"], "[UNIT021]: --max-age"),
    ("tf-audit", "--format", ["tf-audit", "{afile}", "--target", "o", "--format", "csv"], "invalid choice: 'csv'"),
    ("tf-audit", "--jobs", ["tf-audit", "{afile}", "--target", "o", "--jobs", "0"], "argument --jobs: 0 processes"),
    ("tf-audit", "--engine", ["tf-audit", "{afile}", "--target", "o", "--engine", "spark"], "invalid choice: 'spark'"),
    ("tf-audit", "--address", ["tf-audit", "{bag}", "--target", "odom", "--address", "h:1"], "[BAG016]: --address"),
    ("tf-audit", "--window", ["tf-audit", "{afile}", "--target", "o", "--window", "0.5 s"], "[UNIT021]: --window"),
    ("tf-audit", "--out", ["tf-audit", "{bag}", "--target", "odom", "--out", "{afile}"], "error[BAG015]"),
    ("tf-audit", "--force", ["tf-audit", "{afile}", "--target", "o", "--force=1"], "argument --force: ignored"),
    ("tf-audit", "--robot", ["tf-audit", "{afile}", "--target", "o", "--robot", "r07"], "give GLOB=ROBOT"),
    ("fleet-report", "findings", ["fleet-report", "{afile}", "--out", "{tmp}/rep"], "error[BAG020]"),
    ("fleet-report", "--out", ["fleet-report", "{afile}", "--out", "{afile}"], "error[BAG021]"),
    ("fleet-report", "--threshold", ["fleet-report", "{afile}", "--threshold", "150"], "outside 0 to 100"),
    ("fleet-report", "--format", ["fleet-report", "{afile}", "--format", "xml"], "invalid choice: 'xml'"),
    ("tf-scenario", "--start", ["tf-scenario", NOSPEC, "--out", "{tmp}/r", "--start", "noon"], "not an ISO 8601"),
    ("tf-scenario", "--description", ["tf-scenario", NOSPEC, "--out", "{tmp}/r", "--description=1"], "ignored"),
    ("tf-scenario", "spec", ["tf-scenario", NOSPEC, "--out", "{tmp}/rec"], "error[YAML002]"),
    ("tf-scenario", "--out", ["tf-scenario", SPEC, "--out", "{afile}"], "error[BAG003]"),
    ("tf-scenario", "--fault", ["tf-scenario", NOSPEC, "--out", "{tmp}/r", "--fault", "x"], "invalid choice: 'x'"),
    ("tf-scenario", "--duration", ["tf-scenario", NOSPEC, "--out", "{tmp}/r", "--duration", "1 m"], "error[UNIT003]"),
    ("tf-scenario", "--storage", ["tf-scenario", NOSPEC, "--out", "{tmp}/r", "--storage", "db"], "choice: 'db'"),
    ("control", "spec", ["control", NOSPEC, "--trajectory", str(READY)], "error[YAML002]"),
    ("control", "--trajectory", ["control", SPEC, "--trajectory", "{tmp}/none.yaml"], "error[YAML002]"),
    ("control", "--duration", ["control", NOSPEC, "--trajectory", "t", "--duration", "2 Hz"], "error[UNIT003]"),
    ("control", "--plant", ["control", NOSPEC, "--trajectory", "t", "--plant", "real"], "invalid choice: 'real'"),
    (
        "control",
        "--plant-fault",
        ["control", NOSPEC, "--trajectory", "t", "--plant", "sim", "--plant-fault", "elbow_joint:=wobble"],
        "error[CTRL032]: --plant-fault 'elbow_joint:=wobble': unknown fault kind 'wobble'",
    ),
    ("control", "--package", ["control", SPEC, "--trajectory", str(READY), "--package", "{tmp}"], "error[CTRL021]"),
    ("control", "--out", ["control", SPEC, "--trajectory", str(READY), "--out", "{afile}/ev"], "error[CTRL034]"),
    ("report", "spec", ["report", NOSPEC], "error[YAML002]"),
    ("report", "--out", ["report", NOSPEC, "--out", ""], "argument --out: an empty path names nothing"),
    ("view", "path", ["view", "{tmp}/none.urdf"], "error[READ001]"),
    ("view", "--port", ["view", NOSPEC, "--port", "70000"], "argument --port: 70000 is outside 0"),
    ("view", "--host", ["view", NOSPEC, "--host", "example.com"], "argument --host: 'example.com' is not an IP"),
    ("view", "--package-path", ["view", NOSPEC, "--package-path", "{tmp}/none"], "argument --package-path:"),
    ("poses", "spec", ["poses", NOSPEC], "error[YAML002]"),
    ("poses", "--format", ["poses", NOSPEC, "--format", "xml"], "argument --format: invalid choice: 'xml'"),
    ("rules", "code", ["rules", "NOPE999"], "error[RULE001]: no code NOPE999 in the catalogue"),
    ("rules", "--group", ["rules", "--group", "audit"], "argument --group: invalid choice: 'audit'"),
]


def _options_of_every_command() -> set[tuple[str, str]]:
    """(command, option or positional) for every argument the parser declares."""
    from descgen.cli import parser

    sub = next(a for a in parser()._actions if isinstance(a, argparse._SubParsersAction))
    return {
        (name, a.option_strings[-1] if a.option_strings else a.dest)
        for name, p in sub.choices.items()
        for a in p._actions
        if not isinstance(a, argparse._HelpAction)
    }


def test_every_option_of_every_command_has_a_bad_value_case() -> None:
    assert _options_of_every_command() == {(c, o) for c, o, _, _ in BAD_OPTIONS}


def _exit_of(argv: list[str]) -> tuple[int, str]:
    """``main(argv)`` in process: (exit code, stderr); argparse's SystemExit counts as a return."""
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    return code, err.getvalue()


@pytest.mark.parametrize(("command", "option", "argv", "needle"), BAD_OPTIONS, ids=lambda v: str(v)[:40])
def test_bad_value_of_every_option_is_exit_2_with_a_message(
    recording: Path, tmp_path: Path, command: str, option: str, argv: list[str], needle: str
) -> None:
    (tmp_path / "afile").write_text("x")
    before = sorted(tmp_path.rglob("*"))
    given = [a.format(bag=recording, afile=tmp_path / "afile", tmp=tmp_path) for a in argv]
    code, err = _exit_of(given)
    assert code == 2 and "Traceback" not in err, err
    assert needle in err, err
    if "[" in needle:  # a finding: one line at its place, then its hint
        first, hint = err.splitlines()[:2]
        assert needle in first and ": error[" in first and hint.startswith("  hint: "), err
    else:  # argparse: usage, then the command and the argument named
        assert err.startswith("usage: descgen") and f"descgen {command}: error: argument" in err, err
    assert sorted(tmp_path.rglob("*")) == before  # nothing written


def test_option_values_are_checked_before_the_command_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    """A bad --duration is refused while parsing: the spec is never read."""
    import descgen.audit.spec

    def never(*_: object, **__: object) -> None:
        raise AssertionError("the spec was read before the options were checked")

    monkeypatch.setattr(descgen.audit.spec, "load_spec", never)
    code, err = _exit_of(["control", SPEC, "--trajectory", str(READY), "--duration", "-1 s"])
    assert code == 2 and err.startswith("<command line>: error[UNIT021]: --duration:"), err
    code, err = _exit_of(["tf-scenario", SPEC, "--out", "x", "--duration", "1 kg"])
    assert code == 2 and err.startswith("<command line>: error[UNIT003]: --duration:"), err


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["--xacro-arg", "a:=b:=c"], ("a", "b:=c")),  # the first := splits, as xacro does
        (["--xacro-arg", "reach:="], ("reach", "")),
    ],
)
def test_xacro_arg_values_read_as_name_and_value(argv: list[str], expected: tuple[str, str]) -> None:
    from descgen.cli import parser

    args = parser().parse_args(["audit", SPEC, *argv])
    assert args.xacro_arg == [expected]


@pytest.mark.parametrize(
    ("option", "value", "expected_ns"),
    [("--wait", "50ms", 50_000_000), ("--wait", "0.25 s", 250_000_000), ("--max-age", "1.5 min", 90_000_000_000)],
)
def test_time_options_parse_to_nanoseconds(option: str, value: str, expected_ns: int) -> None:
    from descgen.cli import parser

    args = parser().parse_args(["tf-audit", "bag", "--target", "odom", option, value])
    assert getattr(args, option[2:].replace("-", "_")) == expected_ns  # hand values: 50 ms = 5e7 ns, ...


# --------------------------------------------------------------------------- end to end


@pytest.mark.e2e
def test_hostile_options_end_to_end(tmp_path: Path) -> None:
    r = run_cli("tf-scenario", SPEC, "--out", str(tmp_path / "rec"), "--duration", "9**9**9")
    assert r.returncode == 2 and "Traceback" not in r.stderr and "error[UNIT020]: --duration" in r.stderr
    assert not (tmp_path / "rec").exists()
