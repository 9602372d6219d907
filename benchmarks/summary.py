"""The README table: every row the benchmarks of one `make bench` wrote to ``BENCH_ROWS``,
under the machine they ran on (cores, CPU model, Python).

Run: BENCH_ROWS=rows.jsonl .venv/bin/python benchmarks/bench_audit.py; ...;
     .venv/bin/python benchmarks/summary.py rows.jsonl      (`make bench` does all of it)
"""

from __future__ import annotations

import json
import os
import platform
import sys
from pathlib import Path


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def main(argv: list[str]) -> None:
    path = Path(argv[0] if argv else os.environ.get("BENCH_ROWS", "bench-rows.jsonl"))
    rows = [json.loads(line) for line in path.read_text().splitlines() if line.strip()] if path.is_file() else []
    print(
        f"\nMachine: {os.cpu_count()} cores (nproc), {cpu_model()}, Python {platform.python_version()}; "
        "ratio > 1 means descgen is slower; cold = fresh processes on both sides, warm = in-process after imports.\n"
    )
    print("| measure | descgen | anchor | ratio | cold/warm |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['measure']} | {r['descgen']} | {r['anchor']} | {r['ratio']} | {r['kind']} |")
    if not rows:
        print(f"(no rows in {path})")


if __name__ == "__main__":
    main(sys.argv[1:])
