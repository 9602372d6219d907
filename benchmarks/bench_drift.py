"""descgen drift beside a plain streaming read of the same recording (benchmarks/harness.py:
A B A B …, CPU time of the process tree, cold processes on both sides).

The recording: the example arm's tool frame measured by a tracker at 100 Hz for N minutes
(``geometry_msgs/PoseStamped`` on /tracker/pose) with /joint_states at 97 Hz, made from the URDF
with a planted 0.5 deg elbow offset and 0.2 mm noise (tests/drift_data.py: pinocchio's forward
kinematics). descgen: ``descgen drift SPEC --recording BAG --pose-topic /tracker/pose --frame
tool_link`` in a fresh process (read, interpolate, residuals, change point, fit, report). The
anchor: a fresh process that streams the same recording with rosbags and decodes every message of
the two topics drift reads, and does nothing else.

Run: .venv/bin/python benchmarks/bench_drift.py [--quick] [--minutes M]
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path

import harness
from harness import BIN, ROOT, python

sys.path.insert(0, str(ROOT / "tests"))

STREAM = r"""
import sys
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore
ts = get_typestore(Stores.ROS2_JAZZY)
n = 0
TOPICS = ("/joint_states", "/tracker/pose")
with Reader(sys.argv[1]) as r:
    for c, _, raw in r.messages(connections=[c for c in r.connections if c.topic in TOPICS]):
        ts.deserialize_cdr(raw, c.msgtype)
        n += 1
print(n)
"""


def rows(minutes: float) -> None:
    import drift_data as dd

    urdf = (ROOT / "generated/warehouse_arm_description/urdf/warehouse_arm.urdf").read_text()
    joints = ("lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint")
    env = harness.env(None)
    lengths = (0.5,) if harness.QUICK else (1.0, minutes)
    with tempfile.TemporaryDirectory() as tmp:
        for length in lengths:
            n = int(length * 60 * 100)
            t0 = time.perf_counter()
            rec = dd.samples(
                urdf,
                "tool_link",
                base="arm_base_link",
                offsets={"elbow_joint": math.radians(0.5)},
                joints=joints,
                n=n,
                noise_m=0.0002,
                duration_s=length * 60,
            )
            bag = Path(tmp) / f"drift_{length:g}min"
            counts = dd.write_bag(bag, rec, joint_rate_hz=97)
            size = sum(p.stat().st_size for p in bag.iterdir()) / 1e6
            print(
                f"{length:g}-minute recording: {sum(counts.values()):,} messages ({counts}), {size:.1f} MB MCAP, "
                f"written in {time.perf_counter() - t0:.0f} s"
            )
            harness.compare(
                f"drift of a {length:g}-minute recording ({n:,} poses)",
                lambda b=bag: harness.process(  # type: ignore[misc]
                    [
                        str(BIN / "descgen"),
                        "drift",
                        str(ROOT / "specs/warehouse_arm.yaml"),
                        "--recording",
                        str(b),
                        "--pose-topic",
                        "/tracker/pose",
                        "--frame",
                        "tool_link",
                    ],
                    env=env,
                    ok=(0, 1),
                ),
                lambda b=bag: python(STREAM, str(b), env=env)[0],  # type: ignore[misc]
                kind="cold",
                work=n,
                unit="poses/s",
                anchor_name="rosbags read + decode of the same two topics",
            )


def main() -> None:
    args = harness.parse(
        __doc__,
        lambda ap: ap.add_argument("--minutes", type=float, default=10.0, help="length of the long recording"),
    )
    rows(args.minutes)
    harness.done()


if __name__ == "__main__":
    main()
