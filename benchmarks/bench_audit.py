"""Time `descgen audit` over the example-robot-data corpus beside urdfdom's `check_urdf` over
the same files (the anchor), and the audit of a synthetic 1000-link chain (target: well
under a second).

Run: .venv/bin/python benchmarks/bench_audit.py
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from synthetic import chain_spec  # noqa: E402

from descgen.audit import run  # noqa: E402
from descgen.audit.inputs import Options, audit  # noqa: E402
from descgen.readers.urdf import read_urdf_text  # noqa: E402
from descgen.render import render_package  # noqa: E402
from descgen.spec import load_spec_text  # noqa: E402
from tests.corpus import descriptions, share  # noqa: E402


def main() -> None:
    corpus = descriptions()
    root = share()
    audit(corpus[0][1], Options())  # warm imports
    t0 = time.perf_counter()
    for _, urdf, srdf in corpus:
        audit(urdf, Options(srdf=srdf, package_paths=(root,) if root else ()))
    t_audit = time.perf_counter() - t0
    print(
        f"descgen audit, {len(corpus)} corpus URDFs (+{sum(1 for c in corpus if c[2])} SRDFs), in process: "
        f"{t_audit:.2f} s ({t_audit / len(corpus) * 1000:.0f} ms per file)"
    )
    tool = shutil.which("check_urdf")
    if tool:
        t0 = time.perf_counter()
        for _, urdf, _ in corpus:
            subprocess.run([tool, str(urdf)], capture_output=True)
        t_check = time.perf_counter() - t0
        print(
            f"check_urdf, same files, one process each:             {t_check:.2f} s "
            f"({t_check / len(corpus) * 1000:.0f} ms per file); ratio audit/check_urdf {t_audit / t_check:.2f}x"
        )
    else:
        print("check_urdf not installed: no anchor")
    cli = shutil.which("descgen", path=str(Path(sys.executable).parent))
    if cli:
        t0 = time.perf_counter()
        subprocess.run([cli, "audit", *[str(c[1]) for c in corpus]], capture_output=True)
        print(f"descgen audit CLI, all files in one call:             {time.perf_counter() - t0:.2f} s")

    robot = load_spec_text(chain_spec(1000, "chain1000"), "chain1000.yaml").robot
    urdf_text = render_package(robot, "specs/chain1000.yaml")["urdf/chain1000.urdf"].encode()
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        model, found = read_urdf_text(urdf_text, "chain1000.urdf")
        findings = run(model)
        times.append(time.perf_counter() - t0)
    print(
        f"synthetic 1000-link chain: read + every rule, median of 5: {sorted(times)[2] * 1000:.0f} ms "
        f"({len(findings) + len(found)} findings)"
    )


if __name__ == "__main__":
    with tempfile.TemporaryDirectory():
        main()
