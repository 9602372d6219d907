"""Cold start: `descgen --help`, `validate` and `check` on the example as fresh processes,
beside the `xacro` CLI expanding the example's generated Xacro (the anchor), same run.

Each figure is the median of REPEAT fresh processes (one more run first, not counted). Wall
time and CPU time (user + system of the process and its children: check_urdf, dot) are both
printed; CPU is steadier on a loaded machine, and the goal (issue 17: validate <= 6x, check <=
5x xacro) is stated in CPU. Caches are warm, and that is said in the output: the OS file cache
(after the uncounted run), descgen's pint definition cache, Python's bytecode caches. This is
the cost a pre-commit hook pays on every commit; a first run after install pays more.
``check --thorough`` adds yourdfpy's read-back (trimesh, scipy) and is shown for comparison.

Run: .venv/bin/python benchmarks/bench_cold_start.py
"""

from __future__ import annotations

import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rows import row

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
SPEC = ROOT / "specs" / "warehouse_arm.yaml"
XACRO_FILE = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf.xacro"
REPEAT = 7
# Python's bytecode cache as an installed descgen has it, even when the shell sets
# PYTHONDONTWRITEBYTECODE (then every descgen module is compiled again in every process, ~0.1 s);
# written to a temporary folder, not the tree, and filled by each command's uncounted run
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {
    "PYTHONPYCACHEPREFIX": tempfile.mkdtemp(prefix="descgen-bench-pycache-")
}


def timed(argv: list[str]) -> tuple[float, float]:
    """(wall, cpu) seconds of one fresh process. Exit 1 counts (check reports a stale file
    and still does all its work); 2 or a crash does not."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, env=ENV)
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
    load = os.getloadavg()[0]
    print(
        f"fresh processes, median of n={REPEAT} after 1 uncounted run, {os.cpu_count()} cores, load {load:.2f}; "
        "warm: OS file cache, pint cache, bytecode"
    )
    print("anchor: xacro CLI expanding the example's generated Xacro, measured in the same run")
    table: list[tuple[str, float, float]] = []
    print(f"{'command':<24} {'n':>2} {'wall':>8} {'cpu':>8}   {'anchor wall':>11} {'cpu':>8}   ratio wall   cpu")
    for label, argv in (
        ("descgen --help", [descgen, "--help"]),
        ("descgen validate", [descgen, "validate", str(SPEC)]),
        ("descgen check", [descgen, "check", str(SPEC)]),
        ("descgen check --thorough", [descgen, "check", "--thorough", str(SPEC)]),
    ):
        wall, cpu = median(argv)
        print(
            f"{label:<24} {REPEAT:>2} {wall:7.3f}s {cpu:7.3f}s   {anchor_wall:10.3f}s {anchor_cpu:7.3f}s"
            f"   {wall / anchor_wall:9.1f}x {cpu / anchor_cpu:5.1f}x"
        )
        table.append((f"`{label[len('descgen ') :]}` on the example, CPU", cpu, anchor_cpu))
    for measure, cpu, anchor in table:  # the README table's rows (benchmarks/summary.py)
        row(measure, cpu, anchor, "cold", anchor_name="xacro")
    # the load at the end too: other work during the run shows as wall time (and noisier CPU)
    print(f"load at the end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
