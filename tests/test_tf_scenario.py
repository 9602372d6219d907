"""Recordings of the example robot with planted faults: tf-audit reports exactly them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from descgen.spec import load_spec
from descgen.tf import bagaudit, scenario

from .conftest import EXAMPLE
from .helpers import run_cli

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


@pytest.mark.parametrize(
    ("fault", "kind"), [("camera-future", "future"), ("odom-gap", "stale"), ("unknown-frame", "disconnected")]
)
def test_each_planted_fault_is_reported_at_its_messages(tmp_path: Path, fault: str, kind: str) -> None:
    bag = tmp_path / "rec"
    scenario.write(ROBOT, bag, (fault,))
    rep = bagaudit.audit(bag, "odom", max_age_ns=100 * MS)
    lo, hi = scenario.WINDOWS[fault]
    results = camera_results(rep)
    assert len(results) == 300
    bad = [(t, o) for t, o in results if o != "ok"]
    assert bad, "the fault was not reported"
    assert {o for _, o in bad} == {kind}
    assert all(lo - 0.03 <= t < hi + 0.03 for t, _ in bad), bad  # only messages in the fault's window
    inside = [o for t, o in results if lo + 0.03 <= t < hi - 0.03]
    assert inside and all(o == kind for o in inside)
    assert rep.counts[kind] == len(bad)


def test_clean_recording_is_all_ok_in_both_storages(tmp_path: Path) -> None:
    for storage in ("mcap", "sqlite3"):
        bag = tmp_path / f"clean_{storage}"
        counts = scenario.write(ROBOT, bag, (), duration=3.0, storage=storage)
        assert counts["/camera/camera_info"] == 90 and counts["/tf"] == 300
        assert next(bag.glob("*.mcap" if storage == "mcap" else "*.db3")).is_file()
        rep = bagaudit.audit(bag, "odom", max_age_ns=100 * MS)
        assert rep.lookups == 90 and rep.counts["ok"] == 90


def test_max_age_catches_interpolation_across_a_gap(tmp_path: Path) -> None:
    bag = tmp_path / "gap"
    scenario.write(ROBOT, bag, ("odom-gap",), duration=6.0)
    # waiting 2 s, the transforms after the gap have arrived: tf2 would interpolate across it
    silent = bagaudit.audit(bag, "odom", wait_ns=2000 * MS)
    assert silent.counts["ok"] == silent.lookups
    flagged = bagaudit.audit(bag, "odom", wait_ns=2000 * MS, max_age_ns=100 * MS)
    stale = [t for t, o in camera_results(flagged) if o == "stale"]
    assert stale and all(4.0 < t < 5.0 for t in stale)




def test_cli_json_and_exit_codes(tmp_path: Path) -> None:
    bag = tmp_path / "rec"
    r = run_cli("tf-scenario", "specs/warehouse_arm.yaml", "--out", str(bag), "--fault", "camera-future")
    assert r.returncode == 0, r.stderr
    r = run_cli("tf-audit", str(bag), "--target", "odom", "--max-age", "100 ms", "--format", "json")
    assert r.returncode == 1
    doc = json.loads(r.stdout)
    assert {"lookups", "ok", "disconnected", "stale", "future", "per_topic", "examples"} <= set(doc)
    assert doc["future"] == 30 and doc["ok"] == 270 and doc["lookups"] == 300
    assert doc["per_topic"]["/camera/camera_info"]["future"] == 30
    clean = tmp_path / "clean"
    assert run_cli("tf-scenario", "specs/warehouse_arm.yaml", "--out", str(clean), "--duration", "2").returncode == 0
    assert run_cli("tf-audit", str(clean), "--target", "base_footprint").returncode == 0
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "metadata.yaml").write_text("not: a bag\n")
    r = run_cli("tf-audit", str(broken), "--target", "odom")
    assert r.returncode == 2 and "Traceback" not in r.stderr and "error[BAG001]" in r.stderr
