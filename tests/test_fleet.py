"""A fleet's recordings: tf-audit on Ray and on local processes, time windows, the findings
table (Parquet) and fleet-report.

The fleet: 5 robots x 4 days = 20 recordings of the example robot (8 s each, the camera at 30 Hz:
240 lookups each), with faults planted where descgen/commands/tf/scenario.py documents them:
camera-future gives 30 future-dated lookups, odom-gap 30 stale ones, unknown-frame 30
disconnected ones (the camera messages of one second). Expected counts are those, by hand.
The table is read back by DuckDB, not by descgen.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import duckdb
import pytest

from descgen.audit.spec import load_spec
from descgen.commands.fleet import run as fleet_run
from descgen.commands.tf import bagaudit, scenario

from .conftest import EXAMPLE
from .helpers import cli

ROOT = Path(__file__).resolve().parents[1]
ROBOT = load_spec(EXAMPLE).robot
URDF_V1 = (ROOT / "generated/warehouse_arm_description/urdf/warehouse_arm.urdf").read_text()
URDF_V2 = URDF_V1.replace("</robot>", "<!-- camera bracket, revision 2 -->\n</robot>")
V1, V2 = (hashlib.sha256(u.encode()).hexdigest() for u in (URDF_V1, URDF_V2))
NS, MS = 1_000_000_000, 1_000_000
DAY1 = 1_793_836_800 * NS  # 2026-11-05T00:00:00Z (20,762 days of 86,400 s)
DAYS = ("2026-11-05", "2026-11-06", "2026-11-07", "2026-11-08")

# (robot, day) -> planted faults; day 3 and 4 of r3 and r4 run description v2
FAULTS = {(2, 1): ("odom-gap",), (3, 3): ("unknown-frame",), (3, 4): ("unknown-frame",), (4, 4): ("camera-future",)}
KIND = {"odom-gap": "stale", "unknown-frame": "disconnected", "camera-future": "future"}
MAPPING = [f"--robot=r{r}_*=r{r}" for r in range(5)]


def _name(robot: int, day: int) -> str:
    return f"r{robot}_d{day}"


def _description(robot: int, day: int) -> str | None:
    if robot == 1 and day == 4:
        return None  # recorded without robot_state_publisher: the mapping alone names it
    return URDF_V2 if robot in (3, 4) and day >= 3 else URDF_V1


def expected(robot: int, day: int) -> dict[str, int]:
    """By hand: 240 camera messages; each planted fault fails the 30 of its second."""
    counts = {"lookups": 240, "ok": 240, "disconnected": 0, "stale": 0, "future": 0}
    for fault in FAULTS.get((robot, day), ()):
        counts[KIND[fault]] += 30
        counts["ok"] -= 30
    return counts


@pytest.fixture(scope="module")
def fleet(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    folder = tmp_path_factory.mktemp("fleet")
    paths = []
    for robot in range(5):
        for day in range(1, 5):
            path = folder / _name(robot, day)
            start = DAY1 + (day - 1) * 86400 * NS + (8 * 3600 + robot * 60) * NS  # 08:0r UTC
            scenario.write(
                ROBOT, path, FAULTS.get((robot, day), ()), 8.0, start_ns=start, description=_description(robot, day)
            )
            paths.append(path)
    return paths


@pytest.fixture(scope="module")
def local_table(fleet: list[Path], tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, Any]]:
    out = tmp_path_factory.mktemp("tables") / "local.parquet"
    r = cli("tf-audit", *fleet, "--target", "odom", "--max-age", "100 ms", "--jobs", "2", *MAPPING, "--out", out,
            "--format", "json")  # fmt: skip
    assert r.returncode == 1, r.stderr  # planted faults
    return out, json.loads(r.stdout)


def _rows(table: Path) -> list[tuple[Any, ...]]:
    return duckdb.sql(f"SELECT * FROM '{table}' ORDER BY ALL").fetchall()


def _without_windows(doc: dict[str, Any]) -> dict[str, Any]:
    return {k: {x: y for x, y in v.items() if x != "windows"} for k, v in doc["recordings"].items()}


# --------------------------------------------------------------------------- the done-when


def test_ray_gives_the_local_findings_and_the_table_adds_up(
    fleet: list[Path], local_table: tuple[Path, dict[str, Any]], tmp_path: Path
) -> None:
    """20 recordings on a real local Ray cluster of 2 CPUs (ray.init(num_cpus=2), as --jobs 2
    asks), cut in 3 s windows, give what local processes give in one pass each: the same
    report per recording, the same rows in the table."""
    table, local = local_table
    out = tmp_path / "ray.parquet"
    r = cli("tf-audit", *fleet, "--target", "odom", "--max-age", "100 ms", "--engine", "ray", "--jobs", "2",
            "--window", "3 s", *MAPPING, "--out", out, "--format", "json")  # fmt: skip
    assert r.returncode == 1, r.stderr
    on_ray = json.loads(r.stdout)
    assert _without_windows(on_ray) == _without_windows(local)
    assert {v["windows"] for v in on_ray["recordings"].values()} == {3}  # 8 s in windows of 3 s
    assert _rows(out) == _rows(table)

    # every recording's counts are the planted ones, and the table adds up to them
    for robot in range(5):
        for day in range(1, 5):
            path = str(fleet[robot * 4 + day - 1])
            want = expected(robot, day)
            assert {k: local["recordings"][path][k] for k in want} == want, path
            summed = duckdb.sql(
                f"SELECT sum(lookups), sum(ok), sum(disconnected), sum(stale), sum(future) FROM '{table}' "
                f"WHERE kind = 'summary' AND recording = '{path}'"
            ).fetchall()[0]
            assert summed == tuple(want[k] for k in ("lookups", "ok", "disconnected", "stale", "future"))
            failed = dict(
                duckdb.sql(
                    f"SELECT outcome, count(*) FROM '{table}' WHERE kind = 'lookup' AND recording = '{path}' GROUP BY 1"
                ).fetchall()
            )
            assert failed == {k: want[k] for k in ("disconnected", "stale", "future") if want[k]}


def test_the_text_report_counts_are_the_tables(fleet: list[Path], local_table: tuple[Path, dict[str, Any]]) -> None:
    """The text report (read with a regular expression) and the Parquet rows (read by DuckDB)
    give every recording the same counts."""
    table, _ = local_table
    r = cli("tf-audit", *fleet, "--target", "odom", "--max-age", "100 ms", "--jobs", "2", *MAPPING)
    assert r.returncode == 1
    texts = re.findall(
        r"== (\S+)\n(\d+) lookups into 'odom': (\d+) ok, (\d+) disconnected, (\d+) stale, (\d+) future-dated", r.stdout
    )
    assert len(texts) == 20
    for path, *counts in texts:
        summary = duckdb.sql(
            f"SELECT sum(lookups), sum(ok), sum(disconnected), sum(stale), sum(future) FROM '{table}' "
            f"WHERE kind = 'summary' AND recording = '{path}'"
        ).fetchall()[0]
        assert summary == tuple(int(c) for c in counts), path
        failures = duckdb.sql(f"SELECT count(*) FROM '{table}' WHERE kind = 'lookup' AND recording = '{path}'")
        assert failures.fetchall() == [(int(counts[0]) - int(counts[1]),)]


_AUDIT = fleet_run.run_task


def _crash_on_r2_d3(task: fleet_run.Task, kwargs: dict[str, Any]) -> fleet_run.TaskResult:
    """The audit, except that the worker auditing r2_d3 dies as a segfault would end it."""
    if task.path.name == "r2_d3":
        os.kill(os.getpid(), signal.SIGKILL)
    return _AUDIT(task, kwargs)


@pytest.mark.parametrize("engine", ["local", "ray"])
def test_a_recording_that_crashes_its_worker_is_reported_and_the_rest_complete(
    fleet: list[Path], local_table: tuple[Path, dict[str, Any]], monkeypatch: pytest.MonkeyPatch, engine: str
) -> None:
    _, local = local_table
    monkeypatch.setattr(fleet_run, "run_task", _crash_on_r2_d3)
    if engine == "ray":  # Ray's workers import by name: this test module is shipped by value
        import ray.cloudpickle

        ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    try:
        r = cli("tf-audit", *fleet, "--target", "odom", "--max-age", "100 ms", "--engine", engine, "--jobs", "2",
                *MAPPING, "--format", "json")  # fmt: skip
    finally:
        if engine == "ray":
            ray.cloudpickle.unregister_pickle_by_value(sys.modules[__name__])
    assert r.returncode == 2, r.stderr
    crashed = str(fleet[2 * 4 + 2])
    assert r.stderr.count("error[BAG017]") == 1 and crashed in r.stderr and "Traceback" not in r.stderr
    doc = json.loads(r.stdout)["recordings"]
    assert doc[crashed]["errors"][0]["code"] == "BAG017"
    rest = {k: v for k, v in local["recordings"].items() if k != crashed}
    assert {k: v for k, v in doc.items() if k != crashed} == rest


# --------------------------------------------------------------------------- windows


def test_windows_give_what_one_pass_gives(tmp_path: Path) -> None:
    """Every fault in one recording, cut in 1 s windows: the same lookups, in the same order,
    with the same outcomes, failures and examples as one pass."""
    bag = tmp_path / "faulty"
    scenario.write(ROBOT, bag, ("camera-future", "odom-gap", "unknown-frame"), 8.0)
    kw = {"max_age_ns": 100 * MS, "keep_results": True, "keep_failures": True}
    one = bagaudit.audit(bag, "odom", **kw)
    (cut,) = fleet_run.audit_fleet([str(bag)], "odom", window_ns=NS, **kw)
    assert cut.windows == 8 and not cut.note and cut.report is not None
    assert cut.report.as_dict() == one.as_dict()
    assert cut.report.results == one.results and cut.report.failures == one.failures
    assert {k: (v.counts, v.first_ns, v.last_ns, v.latency_sum_ns) for k, v in cut.report.spans.items()} == {
        k: (v.counts, v.first_ns, v.last_ns, v.latency_sum_ns) for k, v in one.spans.items()
    }
    assert one.counts == {"ok": 150, "future": 30, "stale": 30, "disconnected": 30}  # by hand: 240 - 3 x 30


def _types() -> Any:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_JAZZY)


def _write(path: Path, messages: list[tuple[int, str, Any]]) -> None:
    from rosbags.rosbag2 import StoragePlugin, Writer

    ts = _types()
    kinds = {"/tf": "tf2_msgs/msg/TFMessage", "/point": "geometry_msgs/msg/PointStamped"}
    kinds["/robot_description"] = "std_msgs/msg/String"
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        conns = {t: w.add_connection(t, k, typestore=ts) for t, k in kinds.items() if any(m[1] == t for m in messages)}
        for log, topic, msg in messages:
            w.write(conns[topic], log, ts.serialize_cdr(msg, kinds[topic]))


def _stamp(ns: int) -> Any:
    return _types().types["builtin_interfaces/msg/Time"](sec=ns // NS, nanosec=ns % NS)


def _header(ns: int, frame: str) -> Any:
    return _types().types["std_msgs/msg/Header"](stamp=_stamp(ns), frame_id=frame)


def _tf(ns: int) -> Any:
    t = _types().types
    tr = t["geometry_msgs/msg/TransformStamped"](
        header=_header(ns, "odom"),
        child_frame_id="base_link",
        transform=t["geometry_msgs/msg/Transform"](
            translation=t["geometry_msgs/msg/Vector3"](x=ns / NS, y=0.0, z=0.0),
            rotation=t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
        ),
    )
    return t["tf2_msgs/msg/TFMessage"](transforms=[tr])


def _point(ns: int) -> Any:
    t = _types().types
    return t["geometry_msgs/msg/PointStamped"](
        header=_header(ns, "base_link"), point=t["geometry_msgs/msg/Point"](x=0.0, y=0.0, z=0.0)
    )


TINY = '<robot name="tiny"><link name="base_link"/></robot>'


def _stopped_publisher(path: Path) -> None:
    """odom -> base_link published for 2 s only; points in base_link at 1 s, 15 s and 16 s.
    tf2 keeps the last samples of a link that stopped, however old: the points at 15 s and
    16 s are stale (after the latest data), not disconnected."""
    t0 = 1_000 * NS
    messages: list[tuple[int, str, Any]] = [
        (t0, "/robot_description", _types().types["std_msgs/msg/String"](data=TINY))
    ]
    messages += [(t0 + k * 100 * MS, "/tf", _tf(t0 + k * 100 * MS)) for k in range(21)]
    messages += [(t0 + s * NS, "/point", _point(t0 + s * NS)) for s in (1, 15, 16)]
    _write(path, sorted(messages, key=lambda m: m[0]))


def test_a_window_that_would_miss_an_old_transform_is_audited_in_one_pass(tmp_path: Path) -> None:
    bag = tmp_path / "stopped"
    _stopped_publisher(bag)
    one = bagaudit.audit(bag, "odom", keep_results=True)
    assert [o for _, _, o in one.results] == ["ok", "stale", "stale"]  # by hand, above
    (cut,) = fleet_run.audit_fleet([str(bag)], "odom", window_ns=5 * NS, keep_results=True)
    # the window from 15 s reads transforms from 5 s on: it would have said "disconnected"
    assert cut.windows == 1 and "audited in one pass: its 4 windows did not see" in cut.note
    assert cut.report is not None and cut.report.results == one.results
    r = cli("tf-audit", bag, "--target", "odom", "--window", "5 s")
    assert r.returncode == 1 and "audited in one pass" in r.stdout


# --------------------------------------------------------------------------- identity


def test_the_robot_and_description_come_from_the_recording_or_the_mapping(tmp_path: Path) -> None:
    bag = tmp_path / "unit_07"
    _stopped_publisher(bag)
    sha = hashlib.sha256(TINY.encode()).hexdigest()
    r = cli("tf-audit", bag, "--target", "odom", "--format", "json")
    assert json.loads(r.stdout)["identity"] == [
        {"robot": "tiny", "description": sha[:12], "description_sha256": sha, "source": "/robot_description"}
    ]
    r = cli("tf-audit", bag, "--target", "odom", "--robot", "unit_*=r07@v3", "--format", "json")
    assert json.loads(r.stdout)["identity"] == [
        {"robot": "r07", "description": "v3", "description_sha256": sha, "source": "--robot and /robot_description"}
    ]
    plain = tmp_path / "plain"
    scenario.write(ROBOT, plain, (), 1.0)
    r = cli("tf-audit", plain, "--target", "odom")
    assert "robot unknown: no /robot_description in the recording and no --robot mapping matches it" in r.stdout
    out = tmp_path / "t.parquet"
    cli("tf-audit", plain, "--target", "odom", "--out", out)
    assert duckdb.sql(f"SELECT DISTINCT identity, robot, description FROM '{out}'").fetchall() == [("none", None, None)]


# --------------------------------------------------------------------------- fleet-report


def test_fleet_report_names_the_robots_and_versions_that_regressed_and_since_when(
    local_table: tuple[Path, dict[str, Any]], tmp_path: Path
) -> None:
    import matplotlib.image

    table, _ = local_table
    r = cli("fleet-report", table, "--out", tmp_path / "rep", "--format", "json")
    assert r.returncode == 1, r.stderr  # regressions found
    doc = json.loads(r.stdout)
    robots = {x["subject"]: x for x in doc["regressed_robots"]}
    assert set(robots) == {"r3", "r4"}  # r2's odom gap on day 1 recovered: not a regression
    assert (robots["r3"]["since"], robots["r3"]["healthy_until"]) == (DAYS[2], DAYS[1])
    assert (robots["r3"]["versions"], robots["r3"]["before"]) == ([V2[:12]], [V1[:12]])
    assert [(x["topic"], x["frame"], x["outcome"], x["count"]) for x in robots["r3"]["lookups"]] == [
        ("/camera/camera_info", "camera_optical", "disconnected", 60)  # 30 a day, days 3 and 4
    ]
    assert (robots["r4"]["since"], robots["r4"]["healthy_until"], robots["r4"]["versions"]) == (
        DAYS[3],
        DAYS[2],
        [V2[:12]],
    )
    assert [(x["subject"], x["since"], x["before"], x["versions"]) for x in doc["regressed_descriptions"]] == [
        (V2[:12], DAYS[2], [V1[:12]], ["r3"])
    ]
    days = {(d["robot"], d["day"]): d for d in doc["days"]}
    assert len(days) == 20 and days[("r3", DAYS[2])]["disconnected"] == 30 and days[("r3", DAYS[2])]["lookups"] == 240
    assert days[("r1", DAYS[3])]["descriptions"] == ["(unknown)"]  # recorded without a description
    page = (tmp_path / "rep" / "README.md").read_text()
    assert "| r3 | 2026\\-11\\-07 |" not in page  # dates are plain text in cells
    assert f"| r3 | {DAYS[2]} | {V2[:12]} | 1 | 240 | 30 | 0 | 0 | 12.50% |" in page  # 30 / 240, by hand
    assert "robot r3 regressed on 2026-11-07 (passing until 2026-11-06)" in page
    for png in ("failure_rate_by_robot.png", "failures_by_description.png"):
        assert matplotlib.image.imread(tmp_path / "rep" / png).shape[0] > 100
    # a threshold above r3's and r4's 12.5 %: nothing regressed
    r = cli("fleet-report", table, "--out", tmp_path / "rep", "--threshold", "20")
    assert r.returncode == 0 and "no robot and no description version regressed" in r.stdout


def test_fleet_report_holds_hostile_names_as_text(tmp_path: Path) -> None:
    from .test_markdown_escaping import injected, text_of

    bag = tmp_path / "b"
    scenario.write(ROBOT, bag, ("unknown-frame",), 8.0)
    out = tmp_path / "t.parquet"
    name = "r*[x](javascript:alert(1))*<img src=x onerror=alert(1)>|$\\alpha$"
    assert cli("tf-audit", bag, "--target", "odom", "--robot", f"b={name}", "--out", out).returncode == 1
    r = cli("fleet-report", out, "--out", tmp_path / "rep")
    assert r.returncode == 1 and "Traceback" not in r.stderr
    page = (tmp_path / "rep" / "README.md").read_text()
    from descgen.commands.fleet.page import MARK

    assert injected(page, allowed_comments=(MARK,)) == [  # the page's own two plots, and nothing from the name
        "image: {'src': 'failure_rate_by_robot.png', 'alt': ''}",
        "image: {'src': 'failures_by_description.png', 'alt': ''}",
    ]
    assert name.replace("\\", "") in text_of(page).replace("\\", "")  # shown as the text it is


def test_fleet_report_refuses_what_is_not_a_findings_table(tmp_path: Path) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    other = tmp_path / "other.parquet"
    pq.write_table(pa.table({"kind": ["summary"]}), other)
    r = cli("fleet-report", other, "--out", tmp_path / "rep")
    assert r.returncode == 2 and "error[BAG020]" in r.stderr and "not a tf-audit findings table" in r.stderr
    (tmp_path / "busy").mkdir()
    (tmp_path / "busy" / "notes.txt").write_text("mine")
    r = cli("fleet-report", other, "--out", tmp_path / "busy")
    assert r.returncode == 2 and "error[BAG021]" in r.stderr and (tmp_path / "busy" / "notes.txt").read_text() == "mine"
    assert not (tmp_path / "rep").exists()


# --------------------------------------------------------------------------- --out, engines


def test_the_table_is_written_whole_or_not_at_all(tmp_path: Path) -> None:
    out = tmp_path / "t.parquet"
    r = cli("tf-audit", tmp_path / "ghost", "--target", "odom", "--out", out)
    assert r.returncode == 2 and "error[BAG014]" in r.stderr and not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # no temporary file left
    bag = tmp_path / "b"
    scenario.write(ROBOT, bag, (), 1.0)
    out.write_text("old")
    r = cli("tf-audit", bag, "--target", "odom", "--out", out)
    assert r.returncode == 2 and "error[BAG015]" in r.stderr and out.read_text() == "old"
    assert cli("tf-audit", bag, "--target", "odom", "--out", out, "--force").returncode == 0
    assert duckdb.sql(f"SELECT kind, lookups, ok FROM '{out}'").fetchall() == [("summary", 30, 30)]  # 1 s at 30 Hz
    link = tmp_path / "link.parquet"
    link.symlink_to(tmp_path / "elsewhere.parquet")
    r = cli("tf-audit", bag, "--target", "odom", "--out", link, "--force")
    assert r.returncode == 2 and "a symbolic link" in r.stderr and not (tmp_path / "elsewhere.parquet").exists()


def test_engine_ray_without_ray_says_how_to_install_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    bag = tmp_path / "b"
    scenario.write(ROBOT, bag, (), 1.0)
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray raises ImportError
    r = cli("tf-audit", bag, bag, "--target", "odom", "--engine", "ray")
    assert r.returncode == 2 and "error[BAG016]" in r.stderr and "descgen[fleet]" in r.stderr
    r = cli("tf-audit", bag, "--target", "odom", "--engine", "ray", "--address", "127.0.0.1:1")
    assert r.returncode == 2 and "error[BAG016]" in r.stderr


@contextlib.contextmanager
def _head_node() -> Iterator[str]:
    """A Ray head started as a team starts one (ray start --head), on a free port; killed after."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    ray = Path(sys.executable).with_name("ray")
    head = subprocess.Popen(
        [str(ray), "start", "--head", "--block", "--num-cpus", "2", "--port", str(port), "--include-dashboard=false",
         "--disable-usage-stats"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                assert time.monotonic() < deadline and head.poll() is None, "the Ray head did not start"
                time.sleep(0.2)
        yield f"127.0.0.1:{port}"
    finally:
        os.killpg(head.pid, signal.SIGKILL)  # its GCS and raylet; their idle workers exit after them
        head.wait(timeout=30)


def test_address_joins_a_running_cluster(
    fleet: list[Path], local_table: tuple[Path, dict[str, Any]], monkeypatch: pytest.MonkeyPatch
) -> None:
    _, local = local_table
    monkeypatch.setenv("RAY_AUTH_MODE", "token")  # the head's token (~/.ray/auth_token), as Ray documents
    with _head_node() as address:
        some = fleet[12:16]  # r3, failing on days 3 and 4
        # named relative to here: the workers run elsewhere, the recordings are named as given
        r = cli("tf-audit", *(p.name for p in some), "--target", "odom", "--max-age", "100 ms", "--engine", "ray",
                "--address", address, *MAPPING, "--format", "json", cwd=some[0].parent)  # fmt: skip
    assert r.returncode == 1, r.stderr
    assert json.loads(r.stdout)["recordings"] == {p.name: local["recordings"][str(p)] for p in some}


# --------------------------------------------------------------------------- what the reviews found


def _table(path: Path, rows: list[dict[str, Any]]) -> Path:
    """A findings table of hand-written summary rows (the schema is tf-audit's own)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from descgen.commands.fleet.table import COLUMNS, schema

    cols = {name: [r.get(name) for r in rows] for name, _ in COLUMNS}
    pq.write_table(pa.Table.from_pydict(cols, schema=schema(pa)), path)
    return path


def _summary(robot: str | None, version: str, hour: float, lookups: int, stale: int, rec: str) -> dict[str, Any]:
    t = DAY1 + int(hour * 3600 * NS)
    return {
        "kind": "summary", "recording": rec, "robot": robot, "description": version,
        "identity": "--robot" if robot else "none", "target": "odom", "topic": "/camera/camera_info",
        "time": t, "time_end": t, "lookups": lookups, "ok": lookups - stale, "disconnected": 0, "stale": stale,
        "future": 0,
    }  # fmt: skip


def test_a_description_updated_in_the_middle_of_a_day_is_a_version_regression(tmp_path: Path) -> None:
    """r1 and r2 pass on v1 in the morning, fail on v2 that afternoon and the next day: v2
    regressed from v1 on day 1 (the day-level rule never compared them: each day held two
    versions), and the plot's counts are v2's alone."""
    rows = []
    for robot in ("r1", "r2"):
        rows += [
            _summary(robot, "v1", 8, 100, 0, f"{robot}_a"),
            _summary(robot, "v2", 14, 100, 30, f"{robot}_b"),
            _summary(robot, "v2", 24 + 8, 100, 30, f"{robot}_c"),
        ]
    table = _table(tmp_path / "t.parquet", rows)
    r = cli("fleet-report", table, "--out", tmp_path / "rep", "--format", "json")
    assert r.returncode == 1, r.stderr
    doc = json.loads(r.stdout)
    keys = ("subject", "since", "healthy_until", "before", "versions")
    regressed = [tuple(x[k] for k in keys) for x in doc["regressed_descriptions"]]
    assert regressed == [("v2", DAYS[0], DAYS[0], ["v1"], ["r1", "r2"])]
    assert {x["subject"]: x["versions"] for x in doc["regressed_robots"]} == {"r1": ["v2"], "r2": ["v2"]}


def test_unknown_robots_are_not_one_robot_and_a_table_given_twice_counts_once(tmp_path: Path) -> None:
    rows = [
        _summary(None, "(unknown)", 8, 100, 30, "a"),  # failing, unknown
        _summary(None, "(unknown)", 24 + 8, 100, 0, "b"),  # passing the next day, another unknown robot
        _summary("r1", "v1", 8, 100, 0, "c"),
    ]
    table = _table(tmp_path / "t.parquet", rows)
    r = cli("fleet-report", table, table, "--out", tmp_path / "rep", "--format", "json")
    doc = json.loads(r.stdout)
    assert [x["subject"] for x in doc["regressed_robots"]] == ["(unknown) a"]  # b's pass does not hide a's failure
    assert doc["recordings"] == 3 and sum(d["lookups"] for d in doc["days"]) == 300  # once, not twice
    assert doc["repeated"] == ["a", "b", "c"]
    twice = _table(tmp_path / "twice.parquet", rows + rows)  # tf-audit r0 r0: one table, the rows twice
    doc = json.loads(cli("fleet-report", twice, "--out", tmp_path / "rep", "--format", "json").stdout)
    assert sum(d["lookups"] for d in doc["days"]) == 300


def test_a_fleet_with_nothing_audited_does_not_pass(tmp_path: Path) -> None:
    crashed = {"kind": "unaudited", "recording": "r0", "identity": "none", "target": "odom", "detail": "BAG017: x"}
    r = cli("fleet-report", _table(tmp_path / "t.parquet", [crashed]), "--out", tmp_path / "rep")
    assert r.returncode == 1 and "the tables hold no audited lookup" in r.stdout
    assert "1 recordings were not audited" in r.stdout


def test_fleet_report_never_replaces_a_page_it_did_not_write(tmp_path: Path) -> None:
    table = _table(tmp_path / "t.parquet", [_summary("r1", "v1", 8, 100, 0, "c")])
    mine = tmp_path / "mydocs"
    mine.mkdir()
    (mine / "README.md").write_text("# my notes\n")
    r = cli("fleet-report", table, "--out", mine)
    assert r.returncode == 2 and "error[BAG021]" in r.stderr and (mine / "README.md").read_text() == "# my notes\n"
    assert cli("fleet-report", table, "--out", tmp_path / "rep").returncode == 0
    assert cli("fleet-report", table, "--out", tmp_path / "rep").returncode == 0  # its own page: rewritten


def test_names_reach_the_terminal_escaped(tmp_path: Path) -> None:
    name = "arm\x9b2J\u202ekcab"
    table = _table(tmp_path / "t.parquet", [_summary(name, "v1", 8, 100, 30, "c")])
    r = cli("fleet-report", table, "--out", tmp_path / "rep")
    assert r.returncode == 1 and "\x9b" not in r.stdout and "\u202e" not in r.stdout
    assert "arm\\x9b2J\\u202ekcab" in r.stdout


@pytest.mark.parametrize("how", [["--jobs", "1"], ["--jobs", "2"], ["--window", "2 s"]])
def test_a_path_the_system_refuses_is_one_error_on_every_engine(tmp_path: Path, how: list[str]) -> None:
    good = tmp_path / "good"
    scenario.write(ROBOT, good, (), 1.0)
    long = tmp_path / ("a" * 300)  # ENAMETOOLONG: was a traceback, or a worker "that died"
    r = cli("tf-audit", good, long, "--target", "odom", *how)
    assert r.returncode == 2 and "Traceback" not in r.stderr and "error[BAG014]" in r.stderr, r.stderr
    assert "File name too long" in r.stderr and f"== {good}" in r.stdout


def test_a_version_is_judged_by_the_recordings_either_side_of_the_change(tmp_path: Path) -> None:
    """One failed lookup on v1 nine days before the change does not hide v2's regression."""
    rows = [_summary("r1", "v1", 8, 100, 1, "d0")]
    rows += [_summary("r1", "v1", 24 * d + 8, 100, 0, f"d{d}") for d in range(1, 10)]
    rows += [_summary("r1", "v2", 24 * d + 8, 100, 30, f"d{d}") for d in (10, 11)]
    r = cli("fleet-report", _table(tmp_path / "t.parquet", rows), "--out", tmp_path / "rep", "--format", "json")
    assert [x["subject"] for x in json.loads(r.stdout)["regressed_descriptions"]] == ["v2"]


def test_a_rerun_that_audited_a_recording_wins_in_any_order(tmp_path: Path) -> None:
    crashed = {"kind": "unaudited", "recording": "b", "identity": "none", "target": "odom", "detail": "BAG017: x"}
    old = _table(tmp_path / "old.parquet", [_summary("r1", "v1", 8, 100, 0, "a"), crashed])
    new = _table(tmp_path / "new.parquet", [_summary("r1", "v1", 9, 100, 0, "b")])
    for order in ((old, new), (new, old)):
        r = cli("fleet-report", *order, "--out", tmp_path / "rep", "--format", "json")
        doc = json.loads(r.stdout)
        assert r.returncode == 0 and doc["unaudited"] == [] and doc["recordings"] == 2, order


def test_one_recording_with_jobs_runs_in_a_worker(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    bag = tmp_path / "r2_d3"  # the name _crash_on_r2_d3 kills
    scenario.write(ROBOT, bag, (), 1.0)
    monkeypatch.setattr(fleet_run, "run_task", _crash_on_r2_d3)
    r = cli("tf-audit", bag, "--target", "odom", "--jobs", "2", "--out", tmp_path / "t.parquet")
    assert r.returncode == 2 and "error[BAG017]" in r.stderr and "--jobs 1" in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r2_d3"]  # nothing audited: no table, no temporary file


def test_a_lookup_without_a_frame_is_named_so_on_the_page(tmp_path: Path) -> None:
    """A header with an empty frame_id (joint states looked up by --topic) on the page: "``"
    would be two backticks, not an empty code span."""
    from .test_markdown_escaping import text_of

    failed = _summary("r1", "v1", 8, 10, 10, "a") | {"stale": 0, "disconnected": 10, "ok": 0}
    lookup = {"kind": "lookup", "recording": "a", "robot": "r1", "description": "v1", "identity": "--robot",
              "target": "odom", "topic": "/joint_states", "frame": "", "outcome": "disconnected",
              "time": DAY1 + 8 * 3600 * NS}  # fmt: skip
    r = cli("fleet-report", _table(tmp_path / "t.parquet", [failed, lookup]), "--out", tmp_path / "rep")
    assert r.returncode == 1
    line = next(x for x in (tmp_path / "rep" / "README.md").read_text().splitlines() if "/joint_states" in x)
    assert text_of(line) == "/joint_states in an empty frame_id: 1 disconnected since 2026-11-05 08:00:00 UTC"
