"""Loading a spec (read, validate, build the SI model) beside reading the same file with
PyYAML's libyaml loader (``yaml.load(..., CSafeLoader)``: data only, no positions, no checks),
interleaved (benchmarks/harness.py: A B A B …, median and min of CPU time).

Rows:
- warm, both in this process after imports: ``load_spec(..., rules=False)`` (the whole-model
  rules are the audit's and have their own benchmark) on the example and on a 1000-link chain
  (benchmarks/synthetic.py; 200 links with ``--quick``), each beside CSafeLoader on the same
  text; the cyclic collector runs as ``descgen`` runs it (cli._fewer_collections);
- cold, fresh processes (CPU of the process tree): importing the spec loader and loading the
  example (rules off), beside a fresh process that imports yaml and reads the example with
  CSafeLoader. Both with a warm bytecode cache; descgen's caches in a temporary folder, warm
  after the uncounted pair.

Run: .venv/bin/python benchmarks/bench_load.py [--quick] [--pairs N]
"""

from __future__ import annotations

import gc
import sys
import tempfile
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from harness import ROOT, FreshCache, in_process, python
from synthetic import chain_spec

from descgen.audit.spec import load_spec

EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"


def main() -> None:
    harness.parse(__doc__)
    # the collector as `descgen` runs it (cli._fewer_collections): a 1000-link spec makes
    # millions of objects, and Python's default threshold would time the collector instead
    gc.set_threshold(10_000, *gc.get_threshold()[1:])
    links = 200 if harness.QUICK else 1000
    with tempfile.TemporaryDirectory() as tmp:
        chain = Path(tmp) / f"chain{links}.yaml"
        chain.write_text(chain_spec(links), encoding="utf-8")
        for label, path in (("the example", EXAMPLE), (f"a {links}-link chain", chain)):
            text = path.read_text(encoding="utf-8")
            harness.compare(
                f"load {label} (spec -> model)",
                lambda p=path: in_process(lambda: load_spec(p, rules=False)),  # type: ignore[misc]
                lambda t=text: in_process(lambda: yaml.load(t, Loader=yaml.CSafeLoader)),  # type: ignore[misc]
                kind="warm",
                anchor_name="CSafeLoader",
            )
    cache = FreshCache()
    env = harness.env(cache.path)
    try:
        harness.compare(
            "import + load the example",
            lambda: python(
                f"from descgen.audit.spec import load_spec; load_spec({str(EXAMPLE)!r}, rules=False)", env=env
            )[0],
            lambda: python(f"import yaml; yaml.load(open({str(EXAMPLE)!r}).read(), Loader=yaml.CSafeLoader)", env=env)[
                0
            ],
            kind="cold",
            anchor_name="python + CSafeLoader",
        )
    finally:
        cache.close()
    harness.done()


if __name__ == "__main__":
    main()
