"""Recordings of the example robot with planted faults: tf-audit reports exactly them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from descgen.audit.spec import load_spec
from descgen.commands.tf import bagaudit, scenario

from .conftest import EXAMPLE
from .helpers import cli

ROBOT = load_spec(EXAMPLE).robot
START = 1_700_000_000 * 1_000_000_000
MS = 1_000_000


def camera_results(rep: bagaudit.Report) -> list[tuple[float, str]]:
    """(exposure time in s from the start, outcome) for every camera message."""
    # the camera exposes at start + k/30 s + 5 ms and is logged 20 ms later
    return [
        ((log - 20 * MS - START) / 1e9, outcome)
        for topic, log, outcome in rep.results
        if topic == "/camera/camera_info"
    ]


# Which camera messages each fault spoils, by hand from the scenario's definition (module
# docstring of descgen/commands/tf/scenario.py): camera message k is exposed at t_k = k/30 s + 5 ms
# (k = 0..299 in 10 s) and logged 20 ms later; the audit looks each one up at its log time.
# - camera-future: stamps +300 ms for t_k in [2 s, 3 s): 2 <= k/30 + 0.005 < 3 gives k = 60..89,
#   each stamped ahead of every transform received by then.
# - odom-gap: the 100 Hz controller sends odom -> base_footprint every 20 ms (logged 2 ms
#   later), none for t in [4 s, 5 s): the last before the gap is at 3.98 s, the next at 5.00 s.
#   k = 119 (3.972 s) lies between 3.96 and 3.98; k = 120 (4.005 s) to k = 149 (4.972 s, logged
#   4.992 s) are past the last sample received by their log time: stale. k = 150 (5.005 s) is
#   looked up at 5.025 s, with the 5.00 s and 5.02 s samples in.
# - unknown-frame: frame_id not in the tree for t_k in [6 s, 7 s): k = 180..209.
SPOILED = {
    "camera-future": ("future", range(60, 90)),
    "odom-gap": ("stale", range(120, 150)),
    "unknown-frame": ("disconnected", range(180, 210)),
}


@pytest.mark.parametrize("fault", list(SPOILED))
def test_each_planted_fault_is_reported_at_its_messages(tmp_path: Path, fault: str) -> None:
    bag = tmp_path / "rec"
    scenario.write(ROBOT, bag, (fault,))
    rep = bagaudit.audit(bag, "odom", max_age_ns=100 * MS, keep_results=True)
    kind, spoiled = SPOILED[fault]
    results = camera_results(rep)
    assert [round(t, 6) for t, _ in results] == [round(k / 30 + 0.005, 6) for k in range(300)]
    assert [k for k, (_, o) in enumerate(results) if o != "ok"] == list(spoiled)
    assert {o for k, (_, o) in enumerate(results) if k in spoiled} == {kind}
    assert rep.counts[kind] == len(spoiled) == 30


def test_clean_recording_is_all_ok_in_both_storages(tmp_path: Path) -> None:
    for storage in ("mcap", "sqlite3"):
        bag = tmp_path / f"clean_{storage}"
        counts = scenario.write(ROBOT, bag, (), duration=3.0, storage=storage)
        assert counts["/camera/camera_info"] == 90 and counts["/tf"] == 300
        assert next(bag.glob("*.mcap" if storage == "mcap" else "*.db3")).is_file()
        rep = bagaudit.audit(bag, "odom", max_age_ns=100 * MS, keep_results=True)
        assert rep.lookups == 90 and rep.counts["ok"] == 90


def test_max_age_catches_interpolation_across_a_gap(tmp_path: Path) -> None:
    bag = tmp_path / "gap"
    scenario.write(ROBOT, bag, ("odom-gap",), duration=6.0)
    # waiting 2 s, the transforms after the gap have arrived: tf2 would interpolate across it
    silent = bagaudit.audit(bag, "odom", wait_ns=2000 * MS)
    assert silent.counts["ok"] == silent.lookups
    flagged = bagaudit.audit(bag, "odom", wait_ns=2000 * MS, max_age_ns=100 * MS, keep_results=True)
    stale = [k for k, (_, o) in enumerate(camera_results(flagged)) if o == "stale"]
    # waiting 2 s, k = 120..149 interpolate between the 3.98 s and 5.00 s samples; stale are
    # those more than 100 ms from both: 4.08 < k/30 + 0.005 < 4.90, k = 123 (4.105 s) to 146 (4.872 s)
    assert stale == list(range(123, 147))


def test_cli_json_and_exit_codes(tmp_path: Path) -> None:
    bag = tmp_path / "rec"
    r = cli("tf-scenario", "specs/warehouse_arm.yaml", "--out", str(bag), "--fault", "camera-future")
    assert r.returncode == 0, r.stderr
    r = cli("tf-audit", str(bag), "--target", "odom", "--max-age", "100 ms", "--format", "json")
    assert r.returncode == 1
    doc = json.loads(r.stdout)
    assert {"lookups", "ok", "disconnected", "stale", "future", "per_topic", "examples"} <= set(doc)
    assert doc["future"] == 30 and doc["ok"] == 270 and doc["lookups"] == 300
    assert doc["per_topic"]["/camera/camera_info"]["future"] == 30
    clean = tmp_path / "clean"
    assert cli("tf-scenario", "specs/warehouse_arm.yaml", "--out", str(clean), "--duration", "2").returncode == 0
    assert cli("tf-audit", str(clean), "--target", "base_footprint").returncode == 0
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "metadata.yaml").write_text("not: a bag\n")
    r = cli("tf-audit", str(broken), "--target", "odom")
    assert r.returncode == 2 and "Traceback" not in r.stderr and "error[BAG001]" in r.stderr
