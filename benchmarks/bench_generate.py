"""Time `descgen generate` on the example robot and a synthetic 200-link chain, beside the
`xacro` command expanding the generated Xacro (the anchor), and print the ratio.

Run: .venv/bin/python benchmarks/bench_generate.py
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from synthetic import chain_spec

from descgen.generate import generate

ROOT = Path(__file__).resolve().parents[1]
REPEAT = 5


def median_seconds(fn, repeat: int = REPEAT) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def bench(label: str, spec_text: str, name: str) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        specs = Path(tmp) / "specs"
        specs.mkdir()
        spec = specs / f"{name}.yaml"
        spec.write_text(spec_text)

        def run_generate() -> None:
            shutil.rmtree(Path(tmp) / "generated", ignore_errors=True)
            outcome = generate(spec)
            assert not outcome.failed, outcome.findings

        t_gen = median_seconds(run_generate)
        xacro_file = Path(tmp) / "generated" / f"{name}_description" / "urdf" / f"{name}.urdf.xacro"
        xacro_bin = shutil.which("xacro", path=str(Path(sys.executable).parent)) or "xacro"

        def run_xacro() -> None:
            subprocess.run([xacro_bin, str(xacro_file)], check=True, capture_output=True)

        t_xacro = median_seconds(run_xacro)
        print(
            f"{label:<28} descgen generate {t_gen * 1000:8.1f} ms   xacro CLI {t_xacro * 1000:8.1f} ms   "
            f"ratio {t_gen / t_xacro:5.2f}x"
        )


def main() -> None:
    print(f"median of {REPEAT} runs; generate includes loading, validation, rendering, every check and writing")
    bench("example (warehouse_arm)", (ROOT / "specs" / "warehouse_arm.yaml").read_text(), "warehouse_arm")
    bench("synthetic 200-link chain", chain_spec(200, "chain200"), "chain200")


if __name__ == "__main__":
    main()
