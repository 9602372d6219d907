"""Time the proofs that `generate` runs on the example robot: the independent re-parse
(yourdfpy for the URDF; lxml and pyyaml for the SRDF, ros2_control block and controllers
YAML), urdfdom's check_urdf, and the known-pose table. Target (issue): under 1 s in total.
No anchor: these are descgen's own figures, timed by the one harness (benchmarks/harness.py:
median and min of CPU time over the runs).

Rows: each check warm, in this process after one uncounted call (CPU of this process and of
check_urdf's); all of them in turn; and a fresh process loading and rendering the example and
running the re-parse and poses once (importing yourdfpy and trimesh behind it; check_urdf left
out), CPU time of the process tree.

Run: .venv/bin/python benchmarks/bench_proofs.py [--quick] [--pairs N]
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from harness import ROOT, in_process, python

COLD = """
from pathlib import Path
from descgen.audit.spec import load_spec
from descgen.render import render_package
from descgen.prove import known_poses, urdf_roundtrip, srdf_roundtrip, ros2_control_roundtrip, controllers_roundtrip
robot = load_spec("specs/warehouse_arm.yaml").robot
files = render_package(robot, "specs/warehouse_arm.yaml")
for check in (urdf_roundtrip, srdf_roundtrip, ros2_control_roundtrip, controllers_roundtrip, known_poses):
    assert check(files, robot, Path("/pkg")) == []
"""


def main() -> None:
    harness.parse(__doc__)
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
    checks = [
        ("yourdfpy re-parse of the URDF", urdf_roundtrip),
        ("SRDF read-back", srdf_roundtrip),
        ("ros2_control read-back", ros2_control_roundtrip),
        ("controllers YAML read-back", controllers_roundtrip),
        ("check_urdf (urdfdom, its process included)", check_urdf),
        ("known poses (forward kinematics)", known_poses),
    ]
    for name, check in checks:
        harness.alone(
            f"proof of the example: {name} (no anchor)",
            lambda c=check: in_process(lambda: c(files, robot, Path("/pkg"))),  # type: ignore[misc]
            kind="warm",
        )

    def every() -> None:
        for _, check in checks:
            check(files, robot, Path("/pkg"))

    harness.alone(
        "proofs of the example, all in turn (target: < 1 s; no anchor)", lambda: in_process(every), kind="warm"
    )
    harness.alone(
        "load + render + re-parse + poses of the example, fresh process (no anchor)",
        lambda: python(COLD, env=harness.env(None))[0],
        kind="cold",
    )
    harness.done()


if __name__ == "__main__":
    main()
