"""Lookups per second of our tf buffer beside tf2's C++ BufferCore (Debian python3-tf2, the
anchor) on the same workload, and tf-audit throughput on a 10-minute synthetic recording.

Run: .venv/bin/python benchmarks/bench_tf.py
"""

from __future__ import annotations

import json
import random
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

TF2_TIMER = r"""
import json, sys, time
import genpy, tf2_py as tf2
from geometry_msgs.msg import TransformStamped
w = json.load(sys.stdin)
b = tf2.BufferCore(genpy.Duration(10))
for p, c, s, t, q in w["sets"]:
    m = TransformStamped(); m.header.frame_id = p; m.child_frame_id = c
    m.header.stamp = genpy.Time(s // 10**9, s % 10**9)
    m.transform.translation.x, m.transform.translation.y, m.transform.translation.z = t
    m.transform.rotation.x, m.transform.rotation.y, m.transform.rotation.z, m.transform.rotation.w = q
    b.set_transform(m, "bench")
queries = [(a, s, genpy.Time(x // 10**9, x % 10**9)) for a, s, x in w["lookups"]]
t0 = time.perf_counter()
for a, s, x in queries:
    b.lookup_transform_core(a, s, x)
print(time.perf_counter() - t0)
"""


def workload(frames: int = 10, samples: int = 100, lookups: int = 20000) -> dict[str, list[object]]:
    rng = random.Random(1)
    sets = []
    for i in range(1, frames):
        for k in range(samples):
            stamp = 1_000_000_000 + k * 50_000_000
            sets.append((f"f{i - 1}", f"f{i}", stamp, [rng.random(), rng.random(), rng.random()], [0.0, 0.0, 0.0, 1.0]))
    span = (samples - 1) * 50_000_000
    qs = [
        (f"f{rng.randrange(frames)}", f"f{rng.randrange(frames)}", 1_000_000_000 + rng.randrange(span))
        for _ in range(lookups)
    ]
    qs = [q for q in qs if q[0] != q[1]]
    return {"sets": sets, "lookups": qs}


def main() -> None:
    from descgen.tf.buffer import BufferCore

    w = workload()
    buf = BufferCore()
    for p, c, s, t, q in w["sets"]:  # type: ignore[misc]
        buf.set_transform(p, c, s, tuple(t), tuple(q))
    t0 = time.perf_counter()
    for a, s, x in w["lookups"]:  # type: ignore[misc]
        buf.lookup(a, s, x)
    ours = time.perf_counter() - t0
    n = len(w["lookups"])
    print(f"lookups on a 10-frame chain, 100 samples per link, {n} random lookups")
    print(f"  descgen BufferCore (Python): {n / ours:10.0f} lookups/s")
    if Path("/usr/bin/python3").exists():
        r = subprocess.run(["/usr/bin/python3", "-c", TF2_TIMER], input=json.dumps(w), capture_output=True, text=True)
        if r.returncode == 0:
            theirs = float(r.stdout)
            print(f"  tf2 BufferCore (C++):        {n / theirs:10.0f} lookups/s   ratio C++/ours {ours / theirs:.1f}x")
        else:
            print("  tf2 BufferCore: python3-tf2 not available")
    from descgen.spec import load_spec
    from descgen.tf import bagaudit, scenario

    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    with tempfile.TemporaryDirectory() as tmp:
        bag = Path(tmp) / "ten_minutes"
        t0 = time.perf_counter()
        counts = scenario.write(robot, bag, (), duration=600.0)
        t_write = time.perf_counter() - t0
        total = sum(counts.values())
        t0 = time.perf_counter()
        rep = bagaudit.audit(bag, "odom", max_age_ns=100_000_000)
        t_audit = time.perf_counter() - t0
        size = sum(p.stat().st_size for p in bag.iterdir()) / 1e6
        print(f"10-minute recording: {total} messages ({size:.0f} MB MCAP), written in {t_write:.1f} s")
        print(
            f"  tf-audit: {t_audit:.1f} s for {total} messages ({total / t_audit:.0f} messages/s, "
            f"{rep.lookups / t_audit:.0f} camera lookups/s, {600 / t_audit:.0f}x real time)"
        )
        shutil.rmtree(bag, ignore_errors=True)


if __name__ == "__main__":
    main()
