"""Loading a spec (read, validate, build the SI model) beside reading the same file with
PyYAML's libyaml loader (``yaml.load(..., CSafeLoader)``: data only, no positions, no checks).

Rows, each in CPU seconds (steadier than wall time on a shared machine), median of REPEAT:
- warm, in one process after imports: ``load_spec(..., rules=False)`` (the whole-model rules
  are the audit's and have their own benchmark) on the example and on a 1000-link chain
  (benchmarks/synthetic.py), each beside CSafeLoader on the same text in the same run;
- cold, fresh processes: importing the spec loader and loading the example (rules off),
  beside a fresh process that imports yaml and reads the example with CSafeLoader.
Fresh processes use a bytecode cache (as an installed descgen has) and run once uncounted;
the warm rows run the cyclic collector as ``descgen`` does (cli._fewer_collections).

Run: .venv/bin/python benchmarks/bench_load.py
"""

from __future__ import annotations

import gc
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rows import header, row
from synthetic import chain_spec

from descgen.audit.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
REPEAT = 7
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"} | {
    "PYTHONPYCACHEPREFIX": tempfile.mkdtemp(prefix="descgen-bench-pycache-")
}


def cpu(fn: Callable[[], object], repeat: int = REPEAT) -> float:
    fn()  # uncounted: caches (units, tags) as a second spec in the same process finds them
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return statistics.median(times)


def cold(code: str, repeat: int = REPEAT) -> float:
    def once() -> float:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=ENV, check=True, capture_output=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)

    once()
    return statistics.median(once() for _ in range(repeat))


def main() -> None:
    # the collector as `descgen` runs it (cli._fewer_collections): a 1000-link spec makes
    # millions of objects, and Python's default threshold would time the collector instead
    gc.set_threshold(10_000, *gc.get_threshold()[1:])
    print(f"CPU seconds, medians of {REPEAT}, {os.cpu_count()} cores, load {os.getloadavg()[0]:.2f}")
    header()
    with tempfile.TemporaryDirectory() as tmp:
        chain = Path(tmp) / "chain1000.yaml"
        chain.write_text(chain_spec(1000), encoding="utf-8")
        for label, path, repeat in (("the example", EXAMPLE, REPEAT), ("a 1000-link chain", chain, 3)):
            text = path.read_text(encoding="utf-8")
            mine = cpu(lambda p=path: load_spec(p, rules=False), repeat)  # type: ignore[misc]
            anchor = cpu(lambda t=text: yaml.load(t, Loader=yaml.CSafeLoader), repeat)  # type: ignore[misc]
            row(f"load {label} (spec -> model), CPU", mine, anchor, "warm", anchor_name="CSafeLoader")
    mine = cold(f"from descgen.audit.spec import load_spec; load_spec({str(EXAMPLE)!r}, rules=False)")
    anchor = cold(f"import yaml; yaml.load(open({str(EXAMPLE)!r}).read(), Loader=yaml.CSafeLoader)")
    row("import + load the example, CPU", mine, anchor, "cold", anchor_name="python + CSafeLoader")
    print(f"load at the end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
