"""Time the self-collision matrix (10,000 samples) on the example and on a 7-axis arm with
meshes (example-robot-data's Panda) beside its anchor: the raw pinocchio/coal loop,
computeCollisions with every link pair active over the same 10,000 configurations (what any
implementation that samples pays at least once per sample; ours stops checking a pair as
soon as it can be neither Never nor Always, and never checks Adjacent pairs).

Cold: a fresh process (imports, pinocchio model and meshes, sampling). Warm: the same
process again, the per-process memo cleared.

Run: .venv/bin/python benchmarks/bench_collision.py
"""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import corpus_matrix as cm
from rows import row

from descgen.audit.spec import load_spec
from descgen.physics.sweep.contacts import pinocchio_urdf

SPEC = cm.ROOT / "specs" / "warehouse_arm.yaml"

COLD = """
import sys, time
t = time.perf_counter()
sys.path.insert(0, {bench!r})
import corpus_matrix as cm
c = {load}
cm.matrix(c)
print(time.perf_counter() - t)
"""


def example() -> cm.Corpus:
    robot = load_spec(SPEC).robot
    return cm.Corpus("warehouse_arm", robot, pinocchio_urdf(robot), {})


def cold(load: str) -> float:
    code = COLD.format(bench=str(Path(__file__).resolve().parent), load=load)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=cm.ROOT)
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    loads = {
        "warehouse_arm (primitives)": ("example", example, "__import__('bench_collision').example()"),
        "panda (7 axes + hand, STL meshes)": ("panda", lambda: cm.load("panda"), "cm.load('panda')"),
    }
    found: list[tuple[str, float, float, float]] = []
    print("| robot | descgen cold | descgen warm | anchor: raw computeCollisions, all pairs | warm / anchor |")
    print("|---|---|---|---|---|")
    for title, (_, make, code) in loads.items():
        c = make()
        cold_s = cold(code)
        t = time.perf_counter()
        cm.matrix(c, seed=cm.SEED)
        warm = time.perf_counter() - t
        t = time.perf_counter()
        cm.raw_counts(c, seed=cm.SEED)
        anchor = time.perf_counter() - t
        print(f"| {title} | {cold_s:.2f} s | {warm:.2f} s | {anchor:.2f} s | {warm / anchor:.3f}× |", flush=True)
        found.append((title, cold_s, warm, anchor))
    for title, cold_s, warm, anchor in found:  # the README table's rows (benchmarks/summary.py)
        row(f"collision matrix, 10,000 samples, {title}", warm, anchor, "warm", anchor_name="computeCollisions")
        measure = f"collision matrix, 10,000 samples, {title}, fresh process"
        row(measure, cold_s, anchor, "cold", anchor_name="warm computeCollisions")


if __name__ == "__main__":
    main()
