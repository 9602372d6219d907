"""A fleet's recordings through tf-audit, on this machine's processes and on a local Ray cluster,
beside a plain streaming read (benchmarks/harness.py: interleaved, median and min; wall time,
since the point of both engines is to use every core):

1. ``descgen tf-audit R… --target odom --max-age '100 ms' --jobs C`` (local processes, C = this
   machine's cores), a fresh process;
2. the same with ``--engine ray`` (a local Ray cluster of C CPUs, started and stopped by the
   run: its start is in the figure, as a user running it cold pays it);
3. the anchor: one fresh process streaming every recording with rosbags and decoding what
   tf-audit decodes (/tf, /tf_static, the camera), one after the other (bench_tf.py's STREAM).

Each row is recordings/s (and MB/s of MCAP read). Then the two figures the throughput model
needs, each measured here: the CPU cost of auditing one recording (``--jobs 1``, per recording)
and Ray's cost per task (an empty task, 200 of them, after the cluster is up), and the model of
``docs/performance.md`` for N machines:

    time(R recordings) = start + R x (audit + task) / (N x cores)

Run: .venv/bin/python benchmarks/bench_fleet.py [--quick] [--pairs N]   (--quick: 6 recordings of
20 s; else 20 recordings of 1 minute)
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from bench_tf import STREAM
from harness import BIN, ROOT, Timing


def _one_stream(bags: list[str]) -> str:
    """The anchor's script: bench_tf's STREAM over every recording in one process."""
    body = STREAM.split("n = 0\n", 1)
    head, loop = body[0], body[1]
    loop = loop.replace("with Reader(sys.argv[1]) as r:", "for bag in sys.argv[1:]:\n  with Reader(bag) as r:")
    loop = "\n".join(("  " + line if line.startswith("    ") else line) for line in loop.splitlines())
    return head + "n = 0\n" + loop + "\n"


def _ray_task_cost(cpus: int, n: int = 200) -> tuple[float, float]:
    """(seconds to start a local cluster, seconds per empty task) with descgen's own engine."""
    from descgen.infra.ray_engine import each_on_ray

    t0 = time.perf_counter()
    each_on_ray(int, [0], lambda i, r: None, lambda item, why: 0, cpus=cpus)
    start = time.perf_counter() - t0
    t0 = time.perf_counter()
    each_on_ray(int, list(range(n)), lambda i, r: None, lambda item, why: 0, cpus=cpus)
    total = time.perf_counter() - t0
    return start, max(0.0, total - start) / n


def main() -> None:
    harness.parse(__doc__)
    from descgen.audit.spec import load_spec
    from descgen.commands.tf import scenario

    cores = len(os.sched_getaffinity(0))
    count, seconds = (6, 20.0) if harness.QUICK else (20, 60.0)
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    env = harness.env(None)
    descgen = str(BIN / "descgen")
    with tempfile.TemporaryDirectory() as tmp:
        bags = []
        faults = ("camera-future", "odom-gap", "unknown-frame")
        for i in range(count):
            bag = Path(tmp) / f"r{i:02d}"
            scenario._write(robot, bag, faults[: i % 4], seconds, "mcap", scenario.START_NS + i * 86400 * 10**9, None)
            bags.append(str(bag))
        mb = sum(p.stat().st_size for b in bags for p in Path(b).iterdir()) / 1e6
        print(f"{count} recordings of {seconds:g} s ({mb:.0f} MB of MCAP), {cores} cores")
        audit = [descgen, "tf-audit", *bags, "--target", "odom", "--max-age", "100 ms", "--format", "json"]
        anchor_code = _one_stream(bags)

        def anchor() -> Timing:
            return harness.python(anchor_code, *bags, env=env)[0]

        for name, extra in (
            ("local processes", ["--jobs", str(cores)]),
            ("a local Ray cluster", ["--engine", "ray", "--jobs", str(cores)]),
        ):
            measure = f"tf-audit of {count} recordings on {name} ({cores} cores)"
            result = harness.compare(
                f"{measure}, recordings/s",
                lambda e=extra: harness.process([*audit, *e], env=env, ok=(0, 1)),  # type: ignore[misc]
                anchor,
                kind="cold",
                anchor_name="rosbags read + decode of the same topics, one stream",
                work=count,
                unit="recordings/s",
                clock="wall",
                pairs=3,
            )
            if result.descgen:  # the same runs, as MB/s
                harness.report(
                    f"{measure}, MB/s",
                    result,
                    kind="cold",
                    anchor_name="rosbags read + decode of the same topics, one stream",
                    work=mb,
                    unit="MB/s",
                    clock="wall",
                )
        one = harness.process([*audit, "--jobs", "1"], env=env, ok=(0, 1))
        per = one.cpu / count
        start, task = _ray_task_cost(cores)
        print(f"model inputs: audit {per:.3f} s CPU per recording of {seconds:g} s (--jobs 1, {count} recordings)")
        print(
            f"              Ray local cluster start {start:.1f} s, {1000 * task:.1f} ms wall per empty task (200 tasks)"
        )
        for machines, per_machine in ((1, cores), (4, 16), (16, 16), (64, 16)):
            slots = machines * per_machine
            rate = slots / (per + task)
            print(
                f"  {machines:>3} machine(s) x {per_machine} cores: {rate:,.0f} recordings/s "
                f"({rate * seconds / 3600:,.1f} robot-hours of recording per second), "
                f"1,000 recordings in {start + 1000 * (per + task) / slots:,.1f} s"
            )
    harness.done()


if __name__ == "__main__":
    main()
