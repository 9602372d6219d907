"""`descgen audit` over the example-robot-data corpus beside urdfdom's `check_urdf` over the
same files, one process each (the anchor), and the audit of a synthetic 1000-link chain.

Rows (each corpus row is one fresh Python process that imports descgen and audits all 69
URDFs with their SRDFs; its meshes, ~620 distinct files, 350 MB, are resolved and measured):
- cold cache: the persistent mesh-facts cache (descgen/meshes/cache.py) is empty, so every mesh
  is parsed (binary STL with numpy, DAE/OBJ/ASCII STL with trimesh/pycollada); wall time of
  the whole process, and of its first pass alone.
- warm mesh cache: a second fresh process on the same cache folder, with the audit's findings
  cache emptied first: every mesh is stat()ed, the stat index (path, size, mtime, inode,
  ctime -> sha256) gives its hash and the cache its facts, so no mesh is read or hashed, and
  every URDF is read and every rule runs; wall time of the whole process. This is what a user
  pays after editing the descriptions; check_urdf never opens a mesh, so it is the
  like-for-like row for auditing.
- findings cache warm: the same, with the findings the previous process kept
  (descgen/audit/findings_cache.py): each URDF and SRDF is read and hashed, each mesh
  reference resolved again and its file stat()ed, and the findings come from the cache. What
  a pre-commit hook or a CI job that keeps the cache pays for descriptions nobody changed.
- one description edited: the findings cache warm but for one description, whose entry the
  process drops first (a different one each run): what a pre-commit hook pays after an edit.
- in process: the loop again in the first process, facts already in memory (reading,
  resolving and every rule; no hashing; the findings cache emptied before each pass).
- warm: the synthetic 1000-link chain read and audited in process, against check_urdf on its URDF.
- `descgen audit --jobs 1` and `--jobs 2`: the console script over the 69 URDFs alone (no SRDFs,
  as check_urdf), findings cache empty, mesh cache warm; wall time is what --jobs buys.
The anchor is always check_urdf as cold processes. The cache folder is a temporary one, so
the user's own cache is neither used nor changed. Each whole-process row is printed twice:
wall time, and CPU time (user + system of the process and its children, from getrusage, as
bench_cold_start.py does), which is steadier when other work loads the machine; the anchor
is measured the same way. The passes inside a process are timed by the process itself
(perf_counter for wall, process_time for CPU).

Run: .venv/bin/python benchmarks/bench_audit.py
"""

from __future__ import annotations

import json
import os
import resource
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
import json, os, shutil, sys, time
sys.path.insert(0, sys.argv[1])
from descgen.read.description import Options, audit
from tests.corpus import descriptions, share
corpus, root = descriptions(), share()
if len(sys.argv) > 3:  # one description "edited": its findings entry gone, every other one kept
    from descgen.audit.findings_cache import inputs
    _, u, s = corpus[int(sys.argv[3]) % len(corpus)]
    key = inputs(u, s, None, {}, (root,) if root else ()).key
    os.remove(os.path.join(os.environ["DESCGEN_CACHE_DIR"], "results", "audit", key + ".json"))
passes, cpus = [], []
for i in range(int(sys.argv[2])):
    if i:  # a repeated pass audits for real, not from the findings the pass before kept (the mesh cache stays)
        shutil.rmtree(os.path.join(os.environ["DESCGEN_CACHE_DIR"], "results", "audit"), ignore_errors=True)
    t0, c0 = time.perf_counter(), time.process_time()
    n = sum(len(audit(u, Options(srdf=s, package_paths=(root,) if root else ()))) for _, u, s in corpus)
    passes.append(time.perf_counter() - t0)
    cpus.append(time.process_time() - c0)
report = {"files": len(corpus), "srdfs": sum(1 for c in corpus if c[2]), "passes": passes, "cpus": cpus}
print(json.dumps(report | {"findings": n}))
"""


def _children_cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def _process(
    passes: int, cache: str, keep_findings: bool = False, edited: int | None = None
) -> tuple[float, float, dict[str, Any]]:
    """Wall and CPU time of one fresh process running ``passes`` passes over the corpus, and its
    report; the findings cache is emptied first unless ``keep_findings``; ``edited``: the index
    of the one description whose findings the process drops before its pass (as if edited)."""
    if not keep_findings:
        shutil.rmtree(Path(cache) / "results" / "audit", ignore_errors=True)
    # one BLAS thread, as `descgen`'s CLI sets before numpy loads (cli._one_blas_thread): this
    # process calls the library, and OpenBLAS's idle worker threads would cost CPU the CLI never pays
    env = {"OPENBLAS_NUM_THREADS": "1", **os.environ, "DESCGEN_CACHE_DIR": cache}
    c0, t0 = _children_cpu(), time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", LOOP, str(ROOT), str(passes), *([] if edited is None else [str(edited)])],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    )
    return time.perf_counter() - t0, _children_cpu() - c0, json.loads(done.stdout)


Anchor = tuple[float, float] | None  # check_urdf over the corpus: (wall, cpu)


def _corpus_rows(check: Anchor) -> None:
    t_check, c_check = check if check else (None, None)
    with tempfile.TemporaryDirectory() as cache:
        t_cold, c_cold, cold = _process(3, cache)
        warm_runs = [_process(1, cache) for _ in range(3)]
        _process(1, cache)  # fills the findings cache
        kept_runs = [_process(1, cache, keep_findings=True) for _ in range(3)]
        # a different description each run, spread over the corpus (its size decides the miss's cost)
        edit_runs = [_process(1, cache, keep_findings=True, edited=k * 23) for k in range(5)]
    kept = sorted(kept_runs, key=lambda k: k[1])[len(kept_runs) // 2][2]
    assert all(cold["findings"] == k[2]["findings"] for k in kept_runs), "the findings cache changed a finding"
    warm = sorted(warm_runs, key=lambda w: w[1])[len(warm_runs) // 2][2]  # the median run's own report
    t_warm = statistics.median(w[0] for w in warm_runs)
    c_warm = statistics.median(w[1] for w in warm_runs)
    assert all(cold["findings"] == w[2]["findings"] for w in warm_runs), "a cached mesh fact changed a finding"
    files = f"{cold['files']} corpus URDFs (+{cold['srdfs']} SRDFs)"
    first = f"audit of {files}, fresh process, mesh cache empty (every mesh parsed)"
    row(first, t_cold - sum(cold["passes"][1:]), t_check, "cold")
    row(f"{first}, CPU", c_cold - sum(cold["cpus"][1:]), c_check, "cold")
    row(
        "  of which the audit pass (the rest is starting Python and importing descgen)", cold["passes"][0], None, "cold"
    )
    second = (
        f"audit of {files}, second fresh process, mesh cache warm, findings cache empty"
        " (meshes stat()ed, not read; every rule runs; median of 3)"
    )
    row(second, t_warm, t_check, "cold")
    row(f"{second}, CPU", c_warm, c_check, "cold")
    row("  of which the audit pass", warm["passes"][0], None, "cold")
    row("  of which the audit pass, CPU", warm["cpus"][0], None, "cold")
    hit = f"audit of {files}, fresh process, findings cache warm (descriptions unchanged; median of 3)"
    row(hit, statistics.median(k[0] for k in kept_runs), t_check, "cold")
    row(f"{hit}, CPU", statistics.median(k[1] for k in kept_runs), c_check, "cold")
    row("  of which the audit pass, CPU", kept["cpus"][0], None, "cold")
    assert all(cold["findings"] == e[2]["findings"] for e in edit_runs), "a partly cached audit changed a finding"
    edit = (
        f"audit of {files}, fresh process, one description edited since the last audit (its findings"
        " computed, every other one's replayed; median of 5, a different one each)"
    )
    row(edit, statistics.median(e[0] for e in edit_runs), t_check, "cold")
    row(f"{edit}, CPU", statistics.median(e[1] for e in edit_runs), c_check, "cold")
    again = f"audit of {files} again in the first process, mesh facts in memory (anchor: cold check_urdf)"
    row(again, statistics.median(cold["passes"][1:]), t_check, "warm")
    row(f"{again}, CPU", statistics.median(cold["cpus"][1:]), c_check, "warm")


def _cli_rows(urdfs: list[Path], check: Anchor) -> None:
    """`descgen audit URDF...` as a user runs it, the URDFs alone (no SRDFs, as check_urdf
    reads them), findings cache emptied before each run and the mesh cache warm: one process,
    then `--jobs 2` (this machine's cores). Wall time is what --jobs buys; CPU shows its cost."""
    t_check, c_check = check if check else (None, None)
    tool = str(Path(sys.executable).parent / "descgen")
    from tests.corpus import share

    where = ["--package-path", str(share())] if share() else []
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "DESCGEN_CACHE_DIR": cache}
        subprocess.run([tool, "audit", *where, *map(str, urdfs)], capture_output=True, env=env)  # mesh facts
        for jobs in ("1", "2"):
            runs = []
            for _ in range(3):
                shutil.rmtree(Path(cache) / "results" / "audit", ignore_errors=True)
                c0, t0 = _children_cpu(), time.perf_counter()
                subprocess.run([tool, "audit", "--jobs", jobs, *where, *map(str, urdfs)], capture_output=True, env=env)
                runs.append((time.perf_counter() - t0, _children_cpu() - c0))
            what = f"`descgen audit --jobs {jobs}` of the {len(urdfs)} corpus URDFs alone, findings cache empty"
            what += " (median of 3)"
            row(what, statistics.median(r[0] for r in runs), t_check, "cold")
            row(f"{what}, CPU", statistics.median(r[1] for r in runs), c_check, "cold")


def main() -> None:
    from descgen.audit import run
    from descgen.audit.spec import load_spec_text
    from descgen.read.urdf import read_urdf_text
    from descgen.render import render_package
    from tests.corpus import descriptions

    tool = shutil.which("check_urdf")
    corpus = descriptions()
    check: Anchor = None
    if tool and corpus:
        for _, urdf, _ in corpus[:5]:
            subprocess.run([tool, str(urdf)], capture_output=True)  # OS file cache
        runs = []
        for _ in range(3):
            c0, t0 = _children_cpu(), time.perf_counter()
            for _, urdf, _ in corpus:
                subprocess.run([tool, str(urdf)], capture_output=True)
            runs.append((time.perf_counter() - t0, _children_cpu() - c0))
        check = statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)
        print(f"anchor: check_urdf over the same files, one process each, median of 3; load {os.getloadavg()[0]:.2f}")
    header()
    if corpus:
        _corpus_rows(check)
        _cli_rows([u for _, u, _ in corpus], check)
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
