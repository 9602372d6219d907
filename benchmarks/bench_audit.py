"""`descgen audit` over the example-robot-data corpus beside urdfdom's `check_urdf` over the
same files, one process each (the anchor), and the audit of a synthetic 1000-link chain.

Rows (each corpus row is one fresh Python process that imports descgen and audits all 69
URDFs with their SRDFs; its meshes, ~620 distinct files, 350 MB, are resolved and measured):
- cold cache: the persistent mesh-facts cache (descgen/mesh_cache.py) is empty, so every mesh
  is parsed (binary STL with numpy, DAE/OBJ/ASCII STL with trimesh/pycollada); wall time of
  the whole process, and of its first pass alone.
- warm cache: a second fresh process on the same cache folder: every mesh is stat()ed, the
  stat index (path, size, mtime, inode, ctime -> sha256) gives its hash and the cache its
  facts, so no mesh is read or hashed; wall time of the whole process. This is what a user
  pays on a second run; check_urdf never opens a mesh, so it is the like-for-like row.
- in process: the loop again in the first process, facts already in memory (reading,
  resolving and every rule; no hashing).
- warm: the synthetic 1000-link chain read and audited in process, against check_urdf on its URDF.
The anchor is always check_urdf as cold processes. The cache folder is a temporary one, so
the user's own cache is neither used nor changed.

Run: .venv/bin/python benchmarks/bench_audit.py
"""

from __future__ import annotations

import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from rows import header, row  # noqa: E402
from synthetic import chain_spec  # noqa: E402

LOOP = r"""
import json, sys, time
sys.path.insert(0, sys.argv[1])
from descgen.audit.inputs import Options, audit
from tests.corpus import descriptions, share
corpus, root = descriptions(), share()
passes = []
for _ in range(int(sys.argv[2])):
    t0 = time.perf_counter()
    n = sum(len(audit(u, Options(srdf=s, package_paths=(root,) if root else ()))) for _, u, s in corpus)
    passes.append(time.perf_counter() - t0)
print(json.dumps({"files": len(corpus), "srdfs": sum(1 for c in corpus if c[2]), "passes": passes, "findings": n}))
"""


def _process(passes: int, cache: str) -> tuple[float, dict[str, Any]]:
    """Wall time of one fresh process running ``passes`` passes over the corpus, and its report."""
    env = {**os.environ, "DESCGEN_CACHE_DIR": cache}
    t0 = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", LOOP, str(ROOT), str(passes)], capture_output=True, text=True, check=True, env=env
    )
    return time.perf_counter() - t0, json.loads(done.stdout)


def _corpus_rows(t_check: float | None) -> None:
    with tempfile.TemporaryDirectory() as cache:
        t_cold, cold = _process(3, cache)
        t_warm, warm = _process(1, cache)
    assert cold["findings"] == warm["findings"], "a cached mesh fact changed a finding"
    files = f"{cold['files']} corpus URDFs (+{cold['srdfs']} SRDFs)"
    row(
        f"audit of {files}, fresh process, mesh cache empty (every mesh parsed)",
        t_cold - sum(cold["passes"][1:]),
        t_check,
        "cold",
    )
    row(
        "  of which the audit pass (the rest is starting Python and importing descgen)", cold["passes"][0], None, "cold"
    )
    row(f"audit of {files}, second fresh process, mesh cache warm (meshes stat()ed, not read)", t_warm, t_check, "cold")
    row("  of which the audit pass", warm["passes"][0], None, "cold")
    row(
        f"audit of {files} again in the first process, mesh facts in memory (anchor: cold check_urdf)",
        statistics.median(cold["passes"][1:]),
        t_check,
        "warm",
    )


def main() -> None:
    from descgen.audit import run
    from descgen.readers.urdf import read_urdf_text
    from descgen.render import render_package
    from descgen.spec import load_spec_text
    from tests.corpus import descriptions

    header()
    tool = shutil.which("check_urdf")
    corpus = descriptions()
    t_check = None
    if tool and corpus:
        for _, urdf, _ in corpus[:5]:
            subprocess.run([tool, str(urdf)], capture_output=True)  # OS file cache
        t0 = time.perf_counter()
        for _, urdf, _ in corpus:
            subprocess.run([tool, str(urdf)], capture_output=True)
        t_check = time.perf_counter() - t0
    if corpus:
        _corpus_rows(t_check)
    else:
        print("example-robot-data is not installed: no corpus rows")

    robot = load_spec_text(chain_spec(1000, "chain1000"), "chain1000.yaml").robot
    urdf_text = render_package(robot, "specs/chain1000.yaml")["urdf/chain1000.urdf"].encode()
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        model, _ = read_urdf_text(urdf_text, "chain1000.urdf")
        run(model)
        times.append(time.perf_counter() - t0)
    t_chain_check = None
    if tool:
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "chain1000.urdf"
            path.write_bytes(urdf_text)
            t0 = time.perf_counter()
            subprocess.run([tool, str(path)], capture_output=True)
            t_chain_check = time.perf_counter() - t0
    measure = "read + every rule, synthetic 1000-link chain (median of 5; anchor: cold check_urdf)"
    row(measure, statistics.median(times), t_chain_check, "warm")


if __name__ == "__main__":
    main()
