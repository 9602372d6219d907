"""`descgen simulate` on the example beside the anchor: plain MuJoCo compiling the same committed
URDF and stepping it for the same simulated time with no checks (what any MuJoCo user pays);
both in this process after imports, interleaved (benchmarks/harness.py: A B A B …, median and
min of CPU time). Also the four planted faults, which must each fail (printed, no anchor).

Run: .venv/bin/python benchmarks/bench_simulate.py [--quick] [--pairs N]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
import mujoco
from harness import ROOT, in_process

from descgen.audit.spec import load_spec
from descgen.commands.simulate import DEFAULT_SECONDS, Settings, simulate
from descgen.commands.simulate.faults import plant_all

SPEC = ROOT / "specs" / "warehouse_arm.yaml"
URDF = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"


def anchor() -> None:
    """Plain MuJoCo: compile the committed URDF, step DEFAULT_SECONDS."""
    model = mujoco.MjModel.from_xml_string(URDF.read_text())
    data = mujoco.MjData(model)
    for _ in range(round(DEFAULT_SECONDS / model.opt.timestep)):
        mujoco.mj_step(model, data)


def main() -> None:
    harness.parse(__doc__)
    robot = load_spec(SPEC).robot

    def ours() -> None:
        out = simulate(robot, Settings(pose="ready"))
        assert not out.failed, out.findings

    harness.compare(
        f"simulate the example at 'ready', {DEFAULT_SECONDS:g} s",
        lambda: in_process(ours),
        lambda: in_process(anchor),
        kind="warm",
        anchor_name="plain MuJoCo",
    )
    t0 = time.perf_counter()
    results = plant_all(robot, Settings(pose="ready"))
    t_faults = time.perf_counter() - t0
    caught = sum(r.caught for r in results)
    print(f"planted faults: {caught}/{len(results)} caught in {t_faults * 1000:.1f} ms")
    for r in results:
        print(f"  {r.fault.name:<22} {'caught by ' + r.by[0].code if r.caught else 'MISSED'}  ({r.what})")
    harness.done()


if __name__ == "__main__":
    main()
