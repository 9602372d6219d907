"""Time `descgen generate` and `descgen check` beside `xacro`, cold process against cold process.

Rows: the example robot, and synthetic serial chains of 100 and 1000 links (benchmarks/synthetic.py;
no value cites a source, so the generated Xacro has no properties). Anchor: a fresh `xacro`
process on the plain generated URDF of the same robot (what the issue's "2x xacro on the plain
URDF" goal compares with); `xacro` on the generated Xacro is a row of its own (it shows what the
Xacro's properties cost). A warm in-process `generate` of the example (imports done) is a
warm row. Medians of 3 fresh processes (1 at 1000 links, which takes ~10 s per run).

Run: .venv/bin/python benchmarks/bench_generate.py [--quick]
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rows import header, row
from synthetic import chain_spec

from descgen.generate import generate

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
# Fresh processes, but with Python's bytecode cache as an installed descgen has it: a shell may
# set PYTHONDONTWRITEBYTECODE (these sessions' does), and then every descgen module is compiled
# again in every process (~0.1 s of a cold start). The cache goes to a temporary folder, not the
# tree, and every command runs once uncounted first (see bench's ``warmup``).
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {
    "PYTHONPYCACHEPREFIX": tempfile.mkdtemp(prefix="descgen-bench-pycache-")
}


def median_seconds(fn: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def run(argv: list[str], cwd: Path, ok: tuple[int, ...] = (0,)) -> None:
    done = subprocess.run(argv, cwd=cwd, capture_output=True, text=True, env=ENV)
    if done.returncode not in ok:
        raise SystemExit(f"{' '.join(argv)} exited {done.returncode}:\n{done.stderr[-2000:]}")


def bench(label: str, spec_text: str, name: str, repeat: int, warm: bool = False, warmup: bool = False) -> None:
    descgen = str(BIN / "descgen")
    xacro = shutil.which("xacro", path=str(BIN)) or "xacro"
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        (tmp / "specs").mkdir()
        spec = tmp / "specs" / f"{name}.yaml"
        spec.write_text(spec_text)
        package = tmp / "generated" / f"{name}_description"

        def cold_generate() -> None:
            shutil.rmtree(tmp / "generated", ignore_errors=True)
            run([descgen, "generate", str(spec)], tmp)

        urdf = package / "urdf" / f"{name}.urdf"
        if warmup:  # uncounted: the OS file cache and the bytecode cache of every module used
            cold_generate()
            run([descgen, "check", str(spec)], tmp)
            run([xacro, str(urdf)], tmp)
        t_gen = median_seconds(cold_generate, repeat)
        t_check = median_seconds(lambda: run([descgen, "check", str(spec)], tmp), repeat)
        t_plain = median_seconds(lambda: run([xacro, str(urdf)], tmp), repeat)
        t_xacro = median_seconds(lambda: run([xacro, str(urdf.with_suffix(".urdf.xacro"))], tmp), repeat)
        row(f"generate, {label}", t_gen, t_plain, "cold", anchor_name="xacro on its URDF")
        row(f"check, {label}", t_check, t_plain, "cold", anchor_name="xacro on its URDF")
        row(f"xacro on the generated Xacro, {label}", t_xacro, t_plain, "cold", anchor_name="xacro on its URDF")
        if warm:

            def warm_generate() -> None:
                shutil.rmtree(tmp / "generated", ignore_errors=True)
                assert not generate(spec).failed

            warm_generate()  # imports and caches, then time
            t_warm = median_seconds(warm_generate, repeat)
            row(f"generate in process, {label} (anchor: cold xacro)", t_warm, t_plain, "warm")


def main() -> None:
    quick = "--quick" in sys.argv
    repeat = 1 if quick else 3
    header()
    example = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    bench("the example", example, "warehouse_arm", repeat, warm=True, warmup=True)
    bench("chain of 100 links", chain_spec(100, "chain100"), "chain100", repeat)
    bench("chain of 1000 links", chain_spec(1000, "chain1000"), "chain1000", 1)


if __name__ == "__main__":
    main()
