"""Time `descgen generate` and `descgen check` beside `xacro`, cold process against cold process.

Rows: the example robot, and synthetic serial chains of 100 and 1000 links (benchmarks/synthetic.py;
no value cites a source, so the generated Xacro has no properties). Anchor: a fresh `xacro`
process on the plain generated URDF of the same robot (what the issue's "2x xacro on the plain
URDF" goal compares with); `xacro` on the generated Xacro is a row of its own (it shows what the
Xacro's properties cost). A warm in-process `generate` of the example (imports done) is a
warm row.

Figures are CPU seconds (user + system of the process and its children: check_urdf, dot), the
median of REPEAT fresh processes (3 at 1000 links) after one uncounted run; CPU is steadier than
wall time on a shared machine. descgen's caches live in a folder of this run (DESCGEN_CACHE_DIR):
pint definitions, compiled templates and mesh facts are warm, as after any first run. The result
cache (descgen/infra/result_cache.py) is said per row:

- ``generate`` runs with it empty: an edited spec gives new files, so nothing in it applies;
- ``check after generate`` runs with what generate left in it: the pre-commit flow (edit the
  spec, generate, commit);
- ``check, result cache empty``: a CI job that keeps no cache between runs;
- ``generate after editing one value`` (the chains): the last length of the spec changed by a
  new amount before each run, the package and caches as the previous run left them: what an
  engineer runs after correcting one measurement (the unchanged package.xml's verdict and the
  unchanged frames drawing are reused; the URDF, the Xacro and every proof of them are new).

Run: .venv/bin/python benchmarks/bench_generate.py [--quick]
"""

from __future__ import annotations

import os
import re
import resource
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

from descgen.commands.generate import generate

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
CACHE = Path(tempfile.mkdtemp(prefix="descgen-bench-cache-"))
# Fresh processes, but with Python's bytecode cache as an installed descgen has it: a shell may
# set PYTHONDONTWRITEBYTECODE (these sessions' does), and then every descgen module is compiled
# again in every process (~0.1 s of a cold start). The cache goes to a temporary folder, not the
# tree, and every command runs once uncounted first.
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {
    "PYTHONPYCACHEPREFIX": tempfile.mkdtemp(prefix="descgen-bench-pycache-"),
    "DESCGEN_CACHE_DIR": str(CACHE),
}


def cpu_seconds(argv: list[str], cwd: Path, ok: tuple[int, ...] = (0,)) -> float:
    """CPU seconds of one fresh process and its children."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(argv, cwd=cwd, capture_output=True, text=True, env=ENV)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in ok:
        raise SystemExit(f"{' '.join(argv)} exited {done.returncode}:\n{done.stderr[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median_cpu(fn: Callable[[], float], repeat: int, setup: Callable[[], None] = lambda: None) -> float:
    """Median of ``repeat`` runs of ``fn`` (each returns its CPU seconds), ``setup`` before each
    outside the measurement, after one uncounted run."""
    setup()
    fn()
    runs = []
    for _ in range(repeat):
        setup()
        runs.append(fn())
    return statistics.median(runs)


def no_results() -> None:
    shutil.rmtree(CACHE / "results", ignore_errors=True)


def edit_one_value(spec_text: str, n: int) -> str:
    """The spec with its last length in mm changed by n micrometres: a new value every call, as
    when an engineer corrects one measurement and runs generate again."""
    matches = list(re.finditer(r"(\d+(?:\.\d+)?) mm", spec_text))
    last = matches[-1]
    value = float(last.group(1)) + n / 1000
    return f"{spec_text[: last.start(1)]}{value:g}{spec_text[last.end(1) :]}"


def bench(label: str, spec_text: str, name: str, repeat: int, warm: bool = False, edit: bool = False) -> None:
    descgen = str(BIN / "descgen")
    xacro = shutil.which("xacro", path=str(BIN)) or "xacro"
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        (tmp / "specs").mkdir()
        spec = tmp / "specs" / f"{name}.yaml"
        spec.write_text(spec_text)
        urdf = tmp / "generated" / f"{name}_description" / "urdf" / f"{name}.urdf"

        def fresh_generate() -> None:  # an edited spec: no package, nothing in the result cache
            shutil.rmtree(tmp / "generated", ignore_errors=True)
            no_results()

        t_gen = median_cpu(lambda: cpu_seconds([descgen, "generate", str(spec)], tmp), repeat, fresh_generate)
        check = [descgen, "check", str(spec)]
        t_check = median_cpu(lambda: cpu_seconds(check, tmp), repeat)  # the cache as generate left it
        t_check_empty = median_cpu(lambda: cpu_seconds(check, tmp), repeat, no_results)
        t_plain = median_cpu(lambda: cpu_seconds([xacro, str(urdf)], tmp), repeat)
        t_xacro = median_cpu(lambda: cpu_seconds([xacro, str(urdf.with_suffix(".urdf.xacro"))], tmp), repeat)
        anchor = "xacro on its URDF"
        row(f"generate, {label}, CPU", t_gen, t_plain, "cold", anchor_name=anchor)
        row(f"check after generate, {label}, CPU", t_check, t_plain, "cold", anchor_name=anchor)
        row(f"check, result cache empty, {label}, CPU", t_check_empty, t_plain, "cold", anchor_name=anchor)
        row(f"xacro on the generated Xacro, {label}, CPU", t_xacro, t_plain, "cold", anchor_name=anchor)
        sandbox_row(label, urdf.with_suffix(".urdf.xacro"), repeat)
        if edit:
            edits = iter(range(1, 10_000))

            def edited() -> None:  # one more value edited, the last run's package and caches kept
                spec.write_text(edit_one_value(spec_text, next(edits)))

            t_edit = median_cpu(lambda: cpu_seconds([descgen, "generate", str(spec)], tmp), repeat, edited)
            row(f"generate after editing one value, {label}, CPU", t_edit, t_plain, "cold", anchor_name=anchor)
            spec.write_text(spec_text)
        if warm:

            def warm_generate() -> float:
                shutil.rmtree(tmp / "generated", ignore_errors=True)
                t0 = time.process_time()
                assert not generate(spec).failed
                return time.process_time() - t0

            os.environ["DESCGEN_CACHE_DIR"] = str(CACHE)  # this process: the bench's caches too
            t_warm = median_cpu(warm_generate, repeat, no_results)
            row(f"generate in process, {label}, CPU (anchor: cold xacro)", t_warm, t_plain, "warm")


def sandbox_row(label: str, path: Path, repeat: int) -> None:
    """Check 1's own cost: its sandboxed expansion (``checks.xacro_expand.expand_scratch``: the
    static parts set aside, the rest through xacro in the sandbox) beside ``xacro.process_file``
    + ``toxml`` on the same file, both in this process after imports (CPU time, median of at
    least 3). The expansion runs on a copy: it writes the file's skeleton in its place."""
    import xacro

    from descgen.prove.xacro_expand import expand_scratch

    def cpu(fn: Callable[[], object]) -> float:
        times = []
        for _ in range(max(repeat, 3)):
            t0 = time.process_time()
            fn()
            times.append(time.process_time() - t0)
        return statistics.median(times)

    with tempfile.TemporaryDirectory() as scratch:
        copy = Path(scratch) / path.name
        shutil.copyfile(path, copy)
        for include in path.parent.glob("*.xacro"):  # the ros2_control include, if any
            shutil.copyfile(include, Path(scratch) / include.name)
        ours = cpu(lambda: expand_scratch(copy, path.name, {}, [Path(scratch)]))
    theirs = cpu(lambda: xacro.process_file(str(path)).toxml())
    row(
        f"check 1's sandboxed expansion of the generated Xacro, {label}",
        ours,
        theirs,
        "warm",
        anchor_name="xacro.process_file",
    )


def main() -> None:
    quick = "--quick" in sys.argv
    repeat = 1 if quick else 3
    header()
    example = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    try:
        bench("the example", example, "warehouse_arm", 5 if not quick else 1, warm=True)
        bench("chain of 100 links", chain_spec(100, "chain100"), "chain100", repeat, edit=True)
        bench("chain of 1000 links", chain_spec(1000, "chain1000"), "chain1000", repeat, edit=True)
    finally:
        shutil.rmtree(CACHE, ignore_errors=True)


if __name__ == "__main__":
    main()
