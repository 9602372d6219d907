"""Time the proofs that `generate` runs on the example robot: the independent re-parse
(yourdfpy for the URDF; lxml and pyyaml for the SRDF, ros2_control block and controllers
YAML), urdfdom's check_urdf, and the known-pose table. Target (issue): under 1 s in total.

Reports each check warm (median of 20) and the first call in a fresh process, which pays
for importing yourdfpy (and trimesh behind it).

Run: .venv/bin/python benchmarks/bench_proofs.py
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

from rows import row  # noqa: E402

COLD = """
import time
from pathlib import Path
from descgen.audit.spec import load_spec
from descgen.render import render_package
from descgen.prove import known_poses, urdf_roundtrip, srdf_roundtrip, ros2_control_roundtrip, controllers_roundtrip
robot = load_spec("specs/warehouse_arm.yaml").robot
files = render_package(robot, "specs/warehouse_arm.yaml")
t = time.perf_counter()
for check in (urdf_roundtrip, srdf_roundtrip, ros2_control_roundtrip, controllers_roundtrip, known_poses):
    assert check(files, robot, Path("/pkg")) == []
print(time.perf_counter() - t)
"""


def main() -> None:
    from descgen.audit.spec import load_spec
    from descgen.prove import (
        check_urdf,
        controllers_roundtrip,
        known_poses,
        ros2_control_roundtrip,
        srdf_roundtrip,
        urdf_roundtrip,
    )
    from descgen.render import render_package

    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    files = render_package(robot, "specs/warehouse_arm.yaml")
    total = 0.0
    for name, check in [
        ("yourdfpy re-parse of the URDF", urdf_roundtrip),
        ("SRDF read-back", srdf_roundtrip),
        ("ros2_control read-back", ros2_control_roundtrip),
        ("controllers YAML read-back", controllers_roundtrip),
        ("check_urdf (urdfdom)", check_urdf),
        ("known poses (forward kinematics)", known_poses),
    ]:
        check(files, robot, Path("/pkg"))  # warm up
        times = []
        for _ in range(20):
            t = time.perf_counter()
            check(files, robot, Path("/pkg"))
            times.append(time.perf_counter() - t)
        med = statistics.median(times)
        total += med
        print(f"{name:<36} {med * 1000:8.2f} ms")
    print(f"{'total, warm':<36} {total * 1000:8.2f} ms   (target: < 1000 ms)")
    cold = subprocess.run([sys.executable, "-c", COLD], capture_output=True, text=True, cwd=ROOT, check=True)
    print(
        f"{'re-parse + poses, first call (cold)':<36} {float(cold.stdout) * 1000:8.2f} ms   "
        "(includes importing yourdfpy/trimesh; check_urdf excluded)"
    )
    row("proofs of the example, warm total (target: < 1 s; no anchor)", total, None, "warm")
    row("re-parse + poses, first call in a fresh process (no anchor)", float(cold.stdout), None, "cold")


if __name__ == "__main__":
    main()
