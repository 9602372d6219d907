"""Time `descgen simulate` on the example beside the anchor: plain MuJoCo compiling the same
committed URDF and stepping it for the same simulated time with no checks (what any MuJoCo
user pays). Also the four planted faults, which must each fail.

Run: .venv/bin/python benchmarks/bench_simulate.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import mujoco  # noqa: E402
from rows import row  # noqa: E402

from descgen.audit.spec import load_spec  # noqa: E402
from descgen.commands.simulate import DEFAULT_SECONDS, Settings, simulate  # noqa: E402
from descgen.commands.simulate.faults import plant_all  # noqa: E402

SPEC = ROOT / "specs" / "warehouse_arm.yaml"
URDF = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"
REPEATS = 5


def anchor() -> float:
    """Plain MuJoCo: compile the committed URDF, step DEFAULT_SECONDS."""
    t0 = time.perf_counter()
    model = mujoco.MjModel.from_xml_string(URDF.read_text())
    data = mujoco.MjData(model)
    for _ in range(round(DEFAULT_SECONDS / model.opt.timestep)):
        mujoco.mj_step(model, data)
    return time.perf_counter() - t0


def main() -> None:
    robot = load_spec(SPEC).robot
    simulate(robot, Settings())  # warm imports
    t_anchor = min(anchor() for _ in range(REPEATS))
    times = []
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        out = simulate(robot, Settings(pose="ready"))
        times.append(time.perf_counter() - t0)
        assert not out.failed, out.findings
    print(f"plain MuJoCo, compile + {DEFAULT_SECONDS:g} s of steps (anchor): {t_anchor * 1000:8.1f} ms")
    print(f"descgen simulate, example at 'ready' on the floor, best of {REPEATS}: {min(times) * 1000:8.1f} ms")
    row(f"simulate the example at 'ready', best of {REPEATS} (anchor: plain MuJoCo)", min(times), t_anchor, "warm")
    t0 = time.perf_counter()
    results = plant_all(robot, Settings(pose="ready"))
    t_faults = time.perf_counter() - t0
    caught = sum(r.caught for r in results)
    print(f"planted faults: {caught}/{len(results)} caught in {t_faults * 1000:.1f} ms")
    for r in results:
        print(f"  {r.fault.name:<22} {'caught by ' + r.by[0].code if r.caught else 'MISSED'}  ({r.what})")


if __name__ == "__main__":
    main()
