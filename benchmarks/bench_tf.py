"""tf at C++ pace, each figure beside its anchor, interleaved (benchmarks/harness.py: A B A B …,
median and min of CPU time):

1. lookups/s of descgen's tf buffer beside tf2's C++ BufferCore (Debian python3-tf2, through
   its Python binding) on the same workload: a 31-frame tree with five branches (a root and
   five chains of six frames), every transform with a non-identity rotation and a translation,
   100 samples per frame at 20 Hz, and random lookups between any two frames at random times
   (interpolated). Each side is timed around its lookup loop alone (CPU time of the loop; tf2's
   in its own process, which prints it), after both buffers hold the same transforms; before
   timing, the first lookups of both sides are compared and must agree.
2. tf-audit of a 1-minute and a longer synthetic recording of the example robot
   (``descgen tf-audit --target odom --max-age '100 ms'``, a fresh process) beside a fresh
   process streaming the same recording with rosbags and decoding exactly the messages
   tf-audit decodes: /tf, /tf_static and the sensor topics it looks up (every topic with a
   header but /joint_states; here /camera/camera_info), not /joint_states, which tf-audit never
   reads. CPU time of each process tree. Peak memory of the audit (tracemalloc peak of the
   audit call, and the process's max RSS) is printed for each recording, from one more process.

Run: .venv/bin/python benchmarks/bench_tf.py [--minutes 30] [--quick] [--pairs N]   (`make bench`
passes --minutes 10; --quick: a 0.5- and a 1-minute recording and fewer lookups)
"""

from __future__ import annotations

import json
import math
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from harness import BIN, ROOT, Timing, in_process, python

TF2_PYTHON = "/usr/bin/python3"
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
first = []
for a, s, x in queries[:20]:
    t, r = b.lookup_transform_core(a, s, x).transform.translation, b.lookup_transform_core(a, s, x).transform.rotation
    first.append([t.x, t.y, t.z, r.x, r.y, r.z, r.w])
c0, t0 = time.process_time(), time.perf_counter()
for a, s, x in queries:
    b.lookup_transform_core(a, s, x)
print(json.dumps({"cpu": time.process_time() - c0, "wall": time.perf_counter() - t0, "first": first}))
"""

# the anchor of tf-audit: stream the recording, decode what tf-audit decodes (argv: bag)
STREAM = r"""
import sys
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore
ts = get_typestore(Stores.ROS2_JAZZY)
def looked_up(c):  # tf-audit's topics: /tf, /tf_static, every other topic with a header but joint states
    if c.topic in ("/tf", "/tf_static"):
        return True
    fields = [name for name, _ in ts.fielddefs[c.msgtype][1]]
    return c.msgtype != "sensor_msgs/msg/JointState" and "header" in fields
n = 0
with Reader(sys.argv[1]) as r:
    for c, _, raw in r.messages(connections=[c for c in r.connections if looked_up(c)]):
        ts.deserialize_cdr(raw, c.msgtype)
        n += 1
print(n)
"""

PEAK = r"""
import resource, sys, tracemalloc
from pathlib import Path
from descgen.commands.tf import bagaudit
tracemalloc.start()
bagaudit.audit(Path(sys.argv[1]), "odom", max_age_ns=100_000_000)
print(tracemalloc.get_traced_memory()[1], resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
"""


def _quaternion(rng: random.Random) -> list[float]:
    """A random unit quaternion (x, y, z, w), never near the identity."""
    while True:
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(v * v for v in q))
        q = [v / n for v in q]
        if abs(q[3]) < 0.95:
            return q


def workload(branches: int = 5, depth: int = 6, samples: int = 100, lookups: int = 20000) -> dict[str, Any]:
    """A root and ``branches`` chains of ``depth`` frames (31 frames by default), each transform
    rotated and translated, ``samples`` stamps per frame at 20 Hz; random lookups."""
    rng = random.Random(1)
    edges = []
    for b in range(branches):
        parent = "root"
        for d in range(depth):
            child = f"b{b}_{d}"
            edges.append((parent, child))
            parent = child
    frames = ["root", *(c for _, c in edges)]
    sets = []
    for parent, child in edges:
        for k in range(samples):
            stamp = 1_000_000_000 + k * 50_000_000
            t = [rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(0.05, 0.5)]
            sets.append((parent, child, stamp, t, _quaternion(rng)))
    span = (samples - 1) * 50_000_000
    qs = []
    while len(qs) < lookups:
        a, s = rng.choice(frames), rng.choice(frames)
        if a != s:
            qs.append((a, s, 1_000_000_000 + rng.randrange(span)))
    return {"sets": sets, "lookups": qs, "frames": len(frames)}


def buffer_rates() -> None:
    from descgen.commands.tf.buffer import BufferCore

    w = workload(lookups=5000 if harness.QUICK else 20000)
    buf = BufferCore()
    for p, c, s, t, q in w["sets"]:
        assert buf.set_transform(p, c, s, tuple(t), tuple(q)) is None
    n = len(w["lookups"])
    text = json.dumps(w)

    def ours() -> Timing:
        return in_process(lambda: [buf.lookup(a, s, x) for a, s, x in w["lookups"]])

    def theirs() -> Timing:
        r = subprocess.run([TF2_PYTHON, "-c", TF2_TIMER], input=text, capture_output=True, text=True, check=True)
        out = json.loads(r.stdout)
        return Timing(out["cpu"], out["wall"])

    measure = f"tf buffer lookups, {w['frames']}-frame tree of 5 branches with rotations, {n:,} random lookups"
    try:
        r = subprocess.run([TF2_PYTHON, "-c", TF2_TIMER], input=text, capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        print("tf2 BufferCore: python3-tf2 not available; no anchor")
        harness.alone(measure, ours, kind="warm", work=n, unit="lookups/s")
        return
    for (a, s, x), theirs_first in zip(w["lookups"], json.loads(r.stdout)["first"], strict=False):
        mine = buf.lookup(a, s, x)
        got = [*mine.translation, *mine.rotation]
        sign = 1.0 if got[6] * theirs_first[6] >= 0 else -1.0  # q and -q are one rotation
        close = all(abs(u - v) < 1e-6 for u, v in zip(got[:3], theirs_first[:3], strict=True))
        close = close and all(abs(sign * u - v) < 1e-6 for u, v in zip(got[3:], theirs_first[3:], strict=True))
        assert close, f"lookup {a} <- {s} at {x}: descgen {got}, tf2 {theirs_first}"
    print("tf buffer: the first 20 lookups agree with tf2's to 1e-6")
    harness.compare(measure, ours, theirs, kind="warm", work=n, unit="lookups/s", anchor_name="tf2 C++")


def audit_rows(minutes: float) -> None:
    from descgen.audit.spec import load_spec
    from descgen.commands.tf import scenario

    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    env = harness.env(None)
    descgen = str(BIN / "descgen")
    lengths = (0.5, 1.0) if harness.QUICK else (1.0, minutes)
    peaks = []
    with tempfile.TemporaryDirectory() as tmp:
        for length in lengths:
            bag = Path(tmp) / f"rec_{length:g}min"
            t0 = time.perf_counter()
            # the library's writer, not `descgen tf-scenario` (which caps --duration at 600 s)
            counts = scenario._write(robot, bag, (), length * 60.0, "mcap")
            size = sum(p.stat().st_size for p in bag.iterdir()) / 1e6
            _, decoded = python(STREAM, str(bag), env=env)
            print(
                f"{length:g}-minute recording: {sum(counts.values()):,} messages ({counts}), {size:.0f} MB MCAP, "
                f"written in {time.perf_counter() - t0:.0f} s; the anchor decodes {int(decoded):,} of them"
            )
            harness.compare(
                f"tf-audit of a {length:g}-minute recording",
                lambda b=bag: harness.process(  # type: ignore[misc]
                    [descgen, "tf-audit", str(b), "--target", "odom", "--max-age", "100 ms"], env=env, ok=(0, 1)
                ),
                lambda b=bag: python(STREAM, str(b), env=env)[0],  # type: ignore[misc]
                kind="cold",
                anchor_name="rosbags read + decode of the same topics",
            )
            _, out = python(PEAK, str(bag), env=env)
            peak, rss = map(int, out.split())
            peaks.append((length, peak, rss))
            print(f"  tf-audit memory: tracemalloc peak {peak / 1e6:.1f} MB, max RSS {rss / 1e6:.0f} MB")
    (l1, p1, r1), (l2, p2, r2) = peaks
    print(
        f"memory, {l2:g} min / {l1:g} min: tracemalloc peak {p2 / p1:.2f}x, max RSS {r2 / r1:.2f}x (goal: within 1.3x)"
    )


def main() -> None:
    args = harness.parse(
        __doc__,
        lambda ap: ap.add_argument("--minutes", type=float, default=30.0, help="length of the long recording"),
    )
    buffer_rates()
    audit_rows(args.minutes)
    harness.done()


if __name__ == "__main__":
    main()
