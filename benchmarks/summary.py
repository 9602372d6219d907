"""The README table: every row the benchmarks of one `make bench` wrote to ``BENCH_ROWS``,
under the machine they ran on (CPU model, cores, Python).

Run: BENCH_ROWS=rows.jsonl .venv/bin/python benchmarks/bench_audit.py; ...;
     .venv/bin/python benchmarks/summary.py rows.jsonl      (`make bench` does all of it)
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from harness import machine
from rows import COLUMNS

KEYS = ("measure", "descgen", "anchor", "ratio", "wall_ratio", "pairs", "kind")


def main(argv: list[str]) -> None:
    path = Path(argv[0] if argv else os.environ.get("BENCH_ROWS", "bench-rows.jsonl"))
    rows = [json.loads(line) for line in path.read_text().splitlines() if line.strip()] if path.is_file() else []
    print(
        f"\nMachine: {machine()}. Each row: descgen and its anchor interleaved (A B A B …) in one run, "
        "CPU time of the process tree, median (min) of the pairs; ratio of the medians, > 1 means descgen "
        "is slower; cold = fresh processes on both sides, warm = in-process after imports.\n"
    )
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    for r in rows:
        print("| " + " | ".join(str(r.get(k, "—")) for k in KEYS) + " |")
    if not rows:
        print(f"(no rows in {path})")


if __name__ == "__main__":
    main(sys.argv[1:])
