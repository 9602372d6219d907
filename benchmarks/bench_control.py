"""Loop iterations per second of the ros2_control model for the example robot at its 100 Hz
update rate, and how many times faster than real time that is (the anchor: real time).

Run: .venv/bin/python benchmarks/bench_control.py
"""

from __future__ import annotations

import time
from pathlib import Path

from descgen.control.manager import Point
from descgen.control.run import run
from descgen.control.system import Plant
from descgen.control.trajectory import Trajectory
from descgen.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    package = ROOT / "generated" / "warehouse_arm_description"
    joints = ["lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]
    points = [Point(float(t), (0.15 * (t % 2), 0.5 * (t % 3) - 0.5, 0.2, -1.0 * (t % 2))) for t in range(1, 61)]
    trajectory = Trajectory("arm_controller", joints, points)
    for plant in ("mock", "sim"):
        t0 = time.perf_counter()
        out = run(package, robot, trajectory, 60.0, Plant(plant))
        elapsed = time.perf_counter() - t0
        iterations = round(60.0 * out.cm.update_rate)
        print(
            f"{plant:<5} plant: {iterations} loop iterations (60 s at {out.cm.update_rate:g} Hz) in {elapsed:.2f} s: "
            f"{iterations / elapsed:.0f} iterations/s, {60.0 / elapsed:.0f}x real time"
        )


if __name__ == "__main__":
    main()
