"""Cold start: `descgen --help`, `validate` and `check` on the example as fresh processes,
beside the `xacro` CLI expanding the example's generated Xacro (the anchor), same run.

Each figure is the median of REPEAT fresh processes (one more run first, not counted). Wall
time and CPU time (user + system of the process and its children: check_urdf, dot) are both
printed; CPU is steadier on a loaded machine, and the goal (issue 17: validate <= 6x, check <=
5x xacro) is stated in CPU. Caches are warm, and that is said in the output: the OS file cache
(after the uncounted run), descgen's pint definition cache and compiled templates, Python's
bytecode caches, and descgen's result cache (descgen/infra/result_cache.py: the Xacro expansions,
catkin_pkg's verdicts and the sweep table of an unchanged package). This is the cost a
pre-commit hook pays on every commit; a first run after install pays more. ``check, result
cache empty`` is the same check with that one cache emptied before every run: what a CI job
pays that does not keep the cache folder between jobs. descgen's caches live in a temporary
folder (DESCGEN_CACHE_DIR), so the user's own are neither used nor changed.
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
CACHE = Path(tempfile.mkdtemp(prefix="descgen-bench-cache-"))
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {
    "PYTHONPYCACHEPREFIX": tempfile.mkdtemp(prefix="descgen-bench-pycache-"),
    "DESCGEN_CACHE_DIR": str(CACHE),
}


def timed(argv: list[str], empty_results: bool = False) -> tuple[float, float]:
    """(wall, cpu) seconds of one fresh process. Exit 1 counts (check reports a stale file
    and still does all its work); 2 or a crash does not. ``empty_results``: the result cache
    is removed first (outside the timing)."""
    if empty_results:
        shutil.rmtree(CACHE / "results", ignore_errors=True)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, env=ENV)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(argv)} exited {done.returncode}:\n{done.stderr[-2000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median(argv: list[str], empty_results: bool = False) -> tuple[float, float]:
    timed(argv)  # warm the OS file cache and descgen's caches
    runs = [timed(argv, empty_results) for _ in range(REPEAT)]
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)


def main() -> None:
    descgen = str(BIN / "descgen")
    xacro = shutil.which("xacro", path=str(BIN)) or "xacro"
    anchor_wall, anchor_cpu = median([xacro, str(XACRO_FILE)])
    load = os.getloadavg()[0]
    print(
        f"fresh processes, median of n={REPEAT} after 1 uncounted run, {os.cpu_count()} cores, load {load:.2f}; "
        "warm: OS file cache, pint cache, compiled templates, bytecode, result cache (unless said)"
    )
    print("anchor: xacro CLI expanding the example's generated Xacro, measured in the same run")
    table: list[tuple[str, float, float]] = []
    print(f"{'command':<34} {'n':>2} {'wall':>8} {'cpu':>8}   {'anchor wall':>11} {'cpu':>8}   ratio wall   cpu")
    for label, argv, empty in (
        ("descgen --help", [descgen, "--help"], False),
        ("descgen validate", [descgen, "validate", str(SPEC)], False),
        ("descgen check", [descgen, "check", str(SPEC)], False),
        ("descgen check, result cache empty", [descgen, "check", str(SPEC)], True),
        ("descgen check --thorough", [descgen, "check", "--thorough", str(SPEC)], False),
    ):
        wall, cpu = median(argv, empty)
        print(
            f"{label:<34} {REPEAT:>2} {wall:7.3f}s {cpu:7.3f}s   {anchor_wall:10.3f}s {anchor_cpu:7.3f}s"
            f"   {wall / anchor_wall:9.1f}x {cpu / anchor_cpu:5.1f}x"
        )
        command = label[len("descgen ") :].split(",")[0]
        table.append((f"`{command}` on the example{', result cache empty' if empty else ''}, CPU", cpu, anchor_cpu))
    for measure, cpu, anchor in table:  # the README table's rows (benchmarks/summary.py)
        row(measure, cpu, anchor, "cold", anchor_name="xacro")
    # the load at the end too: other work during the run shows as wall time (and noisier CPU)
    print(f"load at the end {os.getloadavg()[0]:.2f}")
    shutil.rmtree(CACHE, ignore_errors=True)


if __name__ == "__main__":
    main()
