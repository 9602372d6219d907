"""Time `descgen generate` and `descgen check` beside `xacro`, cold process against cold process.

Rows: the example robot, and synthetic serial chains of 200 and 1000 links. Anchors, each a
fresh `xacro` process like descgen's: `xacro` on the plain generated URDF (what the issue's
"2x xacro on the plain URDF" goal compares with) and on the generated Xacro. A warm
in-process `generate` (imports done, registry built) is printed for information only; the
ratios compare cold with cold.

Run: .venv/bin/python benchmarks/bench_generate.py [--quick]
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from synthetic import chain_spec

from descgen.generate import generate

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent


def median_seconds(fn: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def run(argv: list[str], cwd: Path, ok: tuple[int, ...] = (0,)) -> None:
    done = subprocess.run(argv, cwd=cwd, capture_output=True, text=True)
    if done.returncode not in ok:
        raise SystemExit(f"{' '.join(argv)} exited {done.returncode}:\n{done.stderr[-2000:]}")


def bench(label: str, spec_text: str, name: str, repeat: int) -> None:
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

        t_gen = median_seconds(cold_generate, repeat)
        t_check = median_seconds(lambda: run([descgen, "check", str(spec)], tmp), repeat)
        urdf = package / "urdf" / f"{name}.urdf"
        t_plain = median_seconds(lambda: run([xacro, str(urdf)], tmp), repeat)
        t_xacro = median_seconds(lambda: run([xacro, str(urdf.with_suffix(".urdf.xacro"))], tmp), repeat)

        def warm_generate() -> None:
            shutil.rmtree(tmp / "generated", ignore_errors=True)
            assert not generate(spec).failed

        warm_generate()  # imports and caches, then time
        t_warm = median_seconds(warm_generate, repeat)
    print(
        f"{label:<22} generate {t_gen:6.2f} s  check {t_check:6.2f} s | xacro plain URDF {t_plain:6.2f} s"
        f"  ratio generate {t_gen / t_plain:5.1f}x  check {t_check / t_plain:5.1f}x"
        f" | xacro on the Xacro {t_xacro:6.2f} s | warm in-process generate {t_warm:6.2f} s"
    )


def main() -> None:
    quick = "--quick" in sys.argv
    repeat = 1 if quick else 3
    print(f"cold processes, median of {repeat}; generate = load, validate, render, every proof, write")
    bench("example (warehouse_arm)", (ROOT / "specs" / "warehouse_arm.yaml").read_text(), "warehouse_arm", repeat)
    bench("chain of 200 links", chain_spec(200, "chain200"), "chain200", repeat)
    bench("chain of 1000 links", chain_spec(1000, "chain1000"), "chain1000", 1)


if __name__ == "__main__":
    main()
