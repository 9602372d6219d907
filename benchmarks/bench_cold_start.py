"""Cold start: `descgen --help`, `validate` and `check` on the example as fresh processes, each
interleaved with its anchor (benchmarks/harness.py: A B A B …, CPU time of the process tree,
median and min): the `xacro` CLI expanding the example's generated Xacro, a fresh process.

Caches, per row (descgen's live in a temporary DESCGEN_CACHE_DIR, so the user's own are
neither used nor changed; Python's bytecode cache is warm, as an installed descgen has it):

- ``--help``, ``validate``, ``check``, ``check --thorough``: warm, after the uncounted pair:
  the OS file cache, pint's definitions, compiled templates, and descgen's result cache
  (descgen/infra/result_cache.py: the Xacro expansions, catkin_pkg's verdicts, the sweep's
  table of an unchanged package). What a pre-commit hook pays on every commit.
- ``check, result cache empty``: that one cache emptied before every descgen run (outside its
  timing): a CI job that keeps pint's and the templates' caches but not the results.
- ``check, every cache off``: a new, empty DESCGEN_CACHE_DIR before every descgen run: what a
  fresh CI runner pays (the caches are written during the run, as there).

``check --thorough`` adds yourdfpy's read-back (trimesh, scipy). xacro has no cache; its
bytecode is warm as descgen's is.

Run: .venv/bin/python benchmarks/bench_cold_start.py [--quick] [--pairs N]
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness
from harness import BIN, ROOT, FreshCache, process

SPEC = ROOT / "specs" / "warehouse_arm.yaml"
XACRO_FILE = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf.xacro"


def main() -> None:
    harness.parse(__doc__)
    cache = FreshCache()
    descgen = str(BIN / "descgen")
    xacro = [str(BIN / "xacro") if (BIN / "xacro").is_file() else "xacro", str(XACRO_FILE)]
    env = harness.env(cache.path)

    def anchor() -> harness.Timing:
        return process(xacro, env=env)

    rows: list[tuple[str, list[str], str]] = [
        ("`--help`", ["--help"], "warm"),
        ("`validate` on the example", ["validate", str(SPEC)], "warm"),
        ("`check` on the example", ["check", str(SPEC)], "warm"),
        ("`check` on the example, result cache empty", ["check", str(SPEC)], "results"),
        ("`check` on the example, every cache off", ["check", str(SPEC)], "all"),
    ]
    if not harness.QUICK:
        rows.append(("`check --thorough` on the example", ["check", "--thorough", str(SPEC)], "warm"))
    try:
        for measure, args, caches in rows:
            before = {
                "warm": lambda: None,
                "results": lambda: cache.empty("results"),
                "all": lambda: cache.empty(),
            }[caches]
            # exit 1 counts: check reports a stale file and still does all its work; 2 or a crash does not
            harness.compare(
                measure,
                lambda a=args: process([descgen, *a], env=env, ok=(0, 1)),  # type: ignore[misc]
                anchor,
                kind="cold",
                anchor_name="xacro",
                before_descgen=before,
            )
    finally:
        cache.close()
    harness.done()


if __name__ == "__main__":
    main()
