"""tf at C++ pace, each figure beside its anchor measured in the same run:

1. lookups/s of our tf buffer beside tf2's C++ BufferCore (Debian python3-tf2) on the same
   workload (a 10-frame chain, 100 samples per link, random lookups), rounds interleaved,
   medians;
2. tf-audit of a 1-minute and a 30-minute synthetic recording of the example robot: wall
   time beside a plain streaming read of the same recording with rosbags (bytes only, and
   bytes + deserialize of every message), and peak memory (tracemalloc peak of the audit
   call, and the process's max RSS), each in a fresh process.

Run: .venv/bin/python benchmarks/bench_tf.py [--minutes 30]   (`make bench` passes --minutes 10: the
30-minute recording takes several minutes to write and to audit four times on 2 cores)
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
ROUNDS = 5

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

# One measurement of one recording, run in a fresh process (argv: kind, bag).
MEASURE = r"""
import resource, sys, time, tracemalloc
from pathlib import Path
kind, bag = sys.argv[1], Path(sys.argv[2])
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore
from descgen.commands.tf import bagaudit
ts = get_typestore(Stores.ROS2_JAZZY)
if kind == "peak":
    tracemalloc.start()
t0 = time.perf_counter()
if kind == "read":
    with Reader(bag) as r:
        n = sum(1 for _ in r.messages())
elif kind == "deserialize":
    with Reader(bag) as r:
        for c, _, raw in r.messages():
            ts.deserialize_cdr(raw, c.msgtype)
else:
    bagaudit.audit(bag, "odom", max_age_ns=100_000_000)
wall = time.perf_counter() - t0
peak = tracemalloc.get_traced_memory()[1] if kind == "peak" else 0
print(wall, peak, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
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


def buffer_rates() -> None:
    from descgen.commands.tf.buffer import BufferCore

    w = workload()
    buf = BufferCore()
    for p, c, s, t, q in w["sets"]:  # type: ignore[misc]
        buf.set_transform(p, c, s, tuple(t), tuple(q))
    n = len(w["lookups"])
    have_tf2 = Path("/usr/bin/python3").exists()
    ours, theirs = [], []
    for _ in range(ROUNDS):  # interleaved, so both see the same machine load
        t0 = time.perf_counter()
        for a, s, x in w["lookups"]:  # type: ignore[misc]
            buf.lookup(a, s, x)
        ours.append(n / (time.perf_counter() - t0))
        if have_tf2:
            r = subprocess.run(
                ["/usr/bin/python3", "-c", TF2_TIMER], input=json.dumps(w), capture_output=True, text=True
            )
            have_tf2 = r.returncode == 0
            if have_tf2:
                theirs.append(n / float(r.stdout))
    print(f"tf buffer: 10-frame chain, 100 samples per link, {n} random lookups, median of {ROUNDS} rounds")
    print(f"  descgen BufferCore (Python): {statistics.median(ours):10.0f} lookups/s")
    if theirs:
        ratio = statistics.median(ours) / statistics.median(theirs)
        print(f"  tf2 BufferCore (C++, anchor): {statistics.median(theirs):9.0f} lookups/s   ours/tf2 {ratio:.2f}x")
    from rows import row

    anchor = statistics.median(theirs) if theirs else None
    row("tf buffer lookups, 10-frame chain", statistics.median(ours), anchor, "warm", "lookups/s", "tf2 C++")
    if not theirs:
        print("  tf2 BufferCore: python3-tf2 not available")


def measure(kind: str, bag: Path) -> tuple[float, int, int]:
    r = subprocess.run([sys.executable, "-c", MEASURE, kind, str(bag)], capture_output=True, text=True, cwd=ROOT)
    if r.returncode:
        raise SystemExit(r.stderr)
    wall, peak, rss = r.stdout.split()
    return float(wall), int(peak), int(rss)


def audit_figures(minutes: float) -> None:
    from descgen.audit.spec import load_spec
    from descgen.commands.tf import scenario

    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for length in (1.0, minutes):
            bag = Path(tmp) / f"rec_{length:g}min"
            t0 = time.perf_counter()
            # the library's writer, not `descgen tf-scenario` (which caps --duration at 600 s)
            counts = scenario._write(robot, bag, (), length * 60.0, "mcap")
            t_write = time.perf_counter() - t0
            size = sum(p.stat().st_size for p in bag.iterdir()) / 1e6
            read, _, read_rss = measure("read", bag)
            deser, _, _ = measure("deserialize", bag)
            audit, _, audit_rss = measure("audit", bag)
            _, peak, _ = measure("peak", bag)
            rows.append((length, sum(counts.values()), size, t_write, read, read_rss, deser, audit, audit_rss, peak))
    print("tf-audit (camera lookups into odom, --max-age 100 ms) beside a streaming read with rosbags")
    for length, n, size, t_write, read, read_rss, deser, audit, audit_rss, peak in rows:
        print(f"  {length:g}-minute recording: {n} messages, {size:.0f} MB MCAP (written in {t_write:.0f} s)")
        print(f"    read (bytes only, anchor):   {read:6.2f} s, max RSS {read_rss / 1e6:5.0f} MB")
        print(f"    read + deserialize (anchor): {deser:6.2f} s")
        print(
            f"    tf-audit:                    {audit:6.2f} s, max RSS {audit_rss / 1e6:5.0f} MB, "
            f"tracemalloc peak {peak / 1e6:.1f} MB; {audit / read:.1f}x the bytes-only read, "
            f"{audit / deser:.2f}x read + deserialize"
        )
    from rows import row

    for length, _, _, _, _, _, deser, audit, *_ in rows:
        measure_ = f"tf-audit of a {length:g}-minute recording (fresh processes)"
        row(measure_, audit, deser, "cold", anchor_name="rosbags read+deserialize")
    (_, *_, peak1), (_, *_, peak30) = rows
    rss1, rss30 = rows[0][8], rows[1][8]
    print(
        f"  memory, {minutes:g} min / 1 min: tracemalloc peak {peak30 / peak1:.2f}x, max RSS {rss30 / rss1:.2f}x "
        "(goal: within 1.3x)"
    )


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--minutes", type=float, default=30.0, help="length of the long recording")
    args = ap.parse_args()
    buffer_rates()
    audit_figures(args.minutes)


if __name__ == "__main__":
    main()
