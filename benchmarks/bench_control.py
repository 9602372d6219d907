"""`descgen control`'s loop on the example robot at its 100 Hz update rate beside real time
(the anchor is fixed: 60 s of simulated time must take less than 60 s of wall time; 10 s with
``--quick``), and the evidence writing after it, timed apart: the loop's figure never includes
matplotlib, which is imported only when the plots are written (tests/test_speed_answers.py
checks that in a fresh interpreter). Timed by the one harness (benchmarks/harness.py: median
and min over the runs); the loop's row is wall time (its anchor is real time), the evidence
rows CPU time, in this process after imports.

Run: .venv/bin/python benchmarks/bench_control.py [--quick] [--pairs N]
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from harness import ROOT, in_process

from descgen.audit.spec import load_spec
from descgen.commands.control.evidence import write_evidence
from descgen.commands.control.manager import Point
from descgen.commands.control.run import Outcome, run
from descgen.commands.control.system import Plant
from descgen.commands.control.trajectory import Trajectory
from descgen.core.model import Robot


def one_plant(plant: str, seconds: float, robot: Robot, package: Path, trajectory: Trajectory) -> None:
    outs: list[Outcome] = []
    harness.alone(
        f"control loop, {plant} plant, {seconds:g} s of control at 100 Hz, wall time (anchor: real time)",
        lambda: in_process(lambda: outs.append(run(package, robot, trajectory, seconds, Plant(plant)))),
        kind="warm",
        clock="wall",
        reference=seconds,
        anchor_name="real time",
        warmup=0,
    )
    assert plant != "mock" or "matplotlib" not in sys.modules, "the loop imported matplotlib"
    out, n = outs[-1], iter(range(1_000))
    with tempfile.TemporaryDirectory() as tmp:
        harness.alone(
            f"  then its evidence, {plant} plant, without plots",
            lambda: in_process(lambda: write_evidence(out, Path(tmp) / f"bare{next(n)}", robot, plots=False)),
            kind="warm",
            warmup=0,
        )
        first = " (matplotlib imported by the first run)" if plant == "mock" else ""
        harness.alone(
            f"  then its evidence, {plant} plant, with plots{first}",
            lambda: in_process(lambda: write_evidence(out, Path(tmp) / f"plots{next(n)}", robot, plots=True)),
            kind="warm",
            warmup=0,
        )


def main() -> None:
    harness.parse(__doc__)
    seconds = 10.0 if harness.QUICK else 60.0
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    package = ROOT / "generated" / "warehouse_arm_description"
    joints = ["lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]
    points = [
        Point(float(t), (0.15 * (t % 2), 0.5 * (t % 3) - 0.5, 0.2, -1.0 * (t % 2))) for t in range(1, int(seconds) + 1)
    ]
    trajectory = Trajectory("arm_controller", joints, points)
    for plant in ("mock", "sim"):
        one_plant(plant, seconds, robot, package, trajectory)
    harness.done()


if __name__ == "__main__":
    main()
