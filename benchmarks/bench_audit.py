"""`descgen audit` of the example-robot-data corpus beside urdfdom's `check_urdf` over the same
files, interleaved (benchmarks/harness.py: A B A B …, CPU time of the process tree, median and
min), and the audit of a synthetic 1000-link chain.

descgen, every corpus row: ONE fresh process, the console script as a user runs it,
``descgen audit --package-path SHARE URDF…`` over the 69 URDFs (no SRDFs: check_urdf reads
none), every mesh they name resolved and measured (~620 distinct files, 350 MB). Anchor, every
corpus row: a loop of fresh ``check_urdf URDF`` processes over the same 69 URDFs (check_urdf
never opens a mesh). ``--quick``: every seventh URDF (10), the same ones on both sides.

descgen's caches (descgen/core/cache_dir.py: DESCGEN_CACHE_DIR) live in a temporary folder of
this run, so the user's own are neither used nor changed; per row, before each descgen run
(outside its timing):

- every cache off: the folder removed and made again, empty: no persistent mesh facts
  (descgen/meshes/cache.py), no findings (descgen/audit/findings_cache.py, under results/audit),
  no pint definitions or anything else; every mesh is parsed. What a fresh CI runner pays.
- mesh cache warm, findings cache empty (``--jobs 1``, then ``--jobs 2``): results/audit
  removed; every mesh is stat()ed and its facts come from the mesh cache (no mesh read or
  hashed), every URDF is read and every rule runs. What a user pays after editing the
  descriptions; ``--jobs 2`` shows what a second core buys in wall time.
- findings cache warm: nothing removed: each URDF is read and hashed, each mesh reference
  resolved and its file stat()ed, and the findings come from the cache. What a pre-commit hook
  or a CI job that keeps the cache pays for descriptions nobody changed.
- one description edited: one findings entry removed (a different one each run): what a
  pre-commit hook pays after an edit.

And the synthetic 1000-link chain (benchmarks/synthetic.py, rendered by descgen; 200 links with
``--quick``): ``descgen audit chain.urdf`` beside ``check_urdf chain.urdf``, both fresh
processes, findings cache emptied before each descgen run.

Run: .venv/bin/python benchmarks/bench_audit.py [--quick] [--pairs N]
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import harness  # noqa: E402
from harness import BIN, FreshCache, Timing, process  # noqa: E402
from synthetic import chain_spec  # noqa: E402

from tests.corpus import descriptions, share  # noqa: E402


def check_urdf_loop(tool: str, urdfs: list[Path]) -> Timing:
    cpu = wall = 0.0
    for urdf in urdfs:
        # check_urdf exits 255 (-1) on a URDF urdfdom refuses (ur3.urdf has no robot name); it
        # has still read and parsed it, as descgen's audit still audits it
        t = process([tool, str(urdf)], ok=(0, 1, 255))
        cpu, wall = cpu + t.cpu, wall + t.wall
    return Timing(cpu, wall)


def corpus_rows(tool: str, urdfs: list[Path], root: Path | None) -> None:
    cache = FreshCache()
    env = harness.env(cache.path)
    where = ["--package-path", str(root)] if root else []
    files = f"the {len(urdfs)} corpus URDFs"

    def audit(*options: str) -> Timing:
        # exit 1: findings at error severity, every description audited all the same
        return process([str(BIN / "descgen"), "audit", *options, *where, *map(str, urdfs)], env=env, ok=(0, 1))

    def anchor() -> Timing:
        return check_urdf_loop(tool, urdfs)

    edits = iter(range(10_000))

    def edit_one() -> None:
        entries = sorted((cache.path / "results" / "audit").glob("*.json"))
        if entries:
            entries[(next(edits) * 23) % len(entries)].unlink()

    try:
        for measure, options, before in (
            (f"audit of {files}, one process, every cache off", (), cache.empty),
            (
                f"audit of {files}, one process, mesh cache warm, findings cache empty",
                (),
                lambda: cache.empty("results", "audit"),
            ),
            (
                f"audit --jobs 2 of {files}, mesh cache warm, findings cache empty",
                ("--jobs", "2"),
                lambda: cache.empty("results", "audit"),
            ),
            (f"audit of {files}, one process, findings cache warm (nothing changed)", (), lambda: None),
            (f"audit of {files}, one process, one description edited since the last audit", (), edit_one),
        ):
            harness.compare(
                measure,
                lambda o=options: audit(*o),  # type: ignore[misc]
                anchor,
                kind="cold",
                anchor_name="check_urdf loop",
                before_descgen=before,
            )
    finally:
        cache.close()


def chain_row(tool: str) -> None:
    from descgen.audit.spec import load_spec_text
    from descgen.render import render_package

    links = 200 if harness.QUICK else 1000
    name = f"chain{links}"
    robot = load_spec_text(chain_spec(links, name), f"{name}.yaml").robot
    cache = FreshCache()
    env = harness.env(cache.path)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{name}.urdf"
        path.write_text(render_package(robot, f"specs/{name}.yaml")[f"urdf/{name}.urdf"])
        harness.compare(
            f"audit of a synthetic {links}-link chain's URDF",
            lambda: process([str(BIN / "descgen"), "audit", str(path)], env=env, ok=(0, 1)),
            lambda: process([tool, str(path)]),
            kind="cold",
            anchor_name="check_urdf",
            before_descgen=lambda: cache.empty("results", "audit"),
        )
    cache.close()


def main() -> None:
    harness.parse(__doc__)
    tool = "/usr/bin/check_urdf" if Path("/usr/bin/check_urdf").is_file() else "check_urdf"
    urdfs = [u for _, u, _ in descriptions()]
    if harness.QUICK:
        urdfs = urdfs[::7]
    if urdfs:
        corpus_rows(tool, urdfs, share())
    else:
        print("example-robot-data is not installed: no corpus rows")
    chain_row(tool)
    harness.done()


if __name__ == "__main__":
    main()
