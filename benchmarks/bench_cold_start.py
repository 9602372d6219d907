"""Cold start: `descgen --help`, `validate` and `check` on the example as fresh processes,
beside the `xacro` CLI expanding the example's generated Xacro (the anchor), same run.

Each figure is the median wall time of fresh processes; CPU time (user + system) is printed
too because it is steadier on a loaded machine. Disk caches are warm (the OS file cache and
descgen's pint definition cache, built by the first run after install): this is the cost a
pre-commit hook pays on every commit.

Run: .venv/bin/python benchmarks/bench_cold_start.py
"""

from __future__ import annotations

import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
SPEC = ROOT / "specs" / "warehouse_arm.yaml"
XACRO_FILE = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf.xacro"
REPEAT = 7


def timed(argv: list[str]) -> tuple[float, float]:
    """(wall, cpu) seconds of one fresh process. Exit 1 counts (check reports a stale file
    and still does all its work); 2 or a crash does not."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(argv)} exited {done.returncode}:\n{done.stderr[-2000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median(argv: list[str]) -> tuple[float, float]:
    timed(argv)  # warm the OS file cache and descgen's pint cache
    runs = [timed(argv) for _ in range(REPEAT)]
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)


def main() -> None:
    descgen = str(BIN / "descgen")
    xacro = shutil.which("xacro", path=str(BIN)) or "xacro"
    anchor_wall, anchor_cpu = median([xacro, str(XACRO_FILE)])
    print(f"fresh processes, median of {REPEAT}, {os.cpu_count()} cores; anchor: xacro CLI on the example's Xacro")
    print(f"{'command':<22} {'wall':>8} {'cpu':>8}   {'anchor wall':>11} {'cpu':>8}   ratio wall  cpu")
    for label, argv in (
        ("descgen --help", [descgen, "--help"]),
        ("descgen validate", [descgen, "validate", str(SPEC)]),
        ("descgen check", [descgen, "check", str(SPEC)]),
    ):
        wall, cpu = median(argv)
        print(
            f"{label:<22} {wall:7.3f}s {cpu:7.3f}s   {anchor_wall:10.3f}s {anchor_cpu:7.3f}s"
            f"   {wall / anchor_wall:8.1f}x {cpu / anchor_cpu:5.1f}x"
        )


if __name__ == "__main__":
    main()
