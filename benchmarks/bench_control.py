"""`descgen control`'s loop on the example robot at its 100 Hz update rate beside real time
(the anchor: 60 s of simulated time must take less than 60 s), and the evidence writing after
it, timed apart: the loop's figure never includes matplotlib, which is imported only when the
plots are written (tests/test_speed_answers.py checks that in a fresh interpreter).

Run: .venv/bin/python benchmarks/bench_control.py
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from rows import header, row

from descgen.audit.spec import load_spec
from descgen.commands.control.evidence import write_evidence
from descgen.commands.control.manager import Point
from descgen.commands.control.run import run
from descgen.commands.control.system import Plant
from descgen.commands.control.trajectory import Trajectory

ROOT = Path(__file__).resolve().parents[1]
SECONDS = 60.0


def main() -> None:
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    package = ROOT / "generated" / "warehouse_arm_description"
    joints = ["lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]
    points = [Point(float(t), (0.15 * (t % 2), 0.5 * (t % 3) - 0.5, 0.2, -1.0 * (t % 2))) for t in range(1, 61)]
    trajectory = Trajectory("arm_controller", joints, points)
    header()
    for plant in ("mock", "sim"):
        t0 = time.perf_counter()
        out = run(package, robot, trajectory, SECONDS, Plant(plant))
        loop = time.perf_counter() - t0
        assert plant != "mock" or "matplotlib" not in sys.modules, "the loop imported matplotlib"
        rate = out.cm.update_rate
        row(f"control loop, {plant} plant, {SECONDS:g} s at {rate:g} Hz (anchor: real time)", loop, SECONDS, "warm")
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            write_evidence(out, Path(tmp) / "bare", robot, plots=False)
            bare = time.perf_counter() - t0
            t0 = time.perf_counter()
            write_evidence(out, Path(tmp) / "plots", robot, plots=True)
            plotted = time.perf_counter() - t0
        row(f"  then its evidence, {plant} plant, without plots", bare, None, "warm")
        first = " (importing matplotlib)" if plant == "mock" else ""
        row(f"  then its evidence, {plant} plant, with plots{first}", plotted, None, "warm")


if __name__ == "__main__":
    main()
