"""`descgen import` beside the `xacro` command line on the same file (the anchor: what every ROS
user runs on a description), cold process against cold process: a fresh `descgen import`
process per robot (read, write the spec to stdout, prove the round trip, audit) beside a fresh
`xacro` process per robot, CPU time of each process tree (benchmarks/harness.py).

Rows:
- the vendored Xacro corpus's UR ur5e (tests/data/xacro_corpus, ``ur_type:=ur5e``), imported
  with ``--package-path`` only; its `xacro` anchor resolves ``$(find pkg)`` in the same folders
  (the pip xacro has no ament index here), which is all the wrapper changes. Interleaved pairs
  (A B A B …), median and min.
- example-robot-data's Panda (URDF and SRDF, STL meshes) beside `xacro` on its URDF: the same.
- the whole example-robot-data corpus (69 URDFs, each with its SRDF when it has one, the corpus
  as package path): robot by robot, descgen's process then xacro's on the same URDF, one pass
  (a pass is ~150 s of CPU on 2 cores: 7 of them would be 18 minutes); the row shows the totals
  of the pass, and its pairs column the robots. ``--quick``: every fourteenth robot (5).
- extra files given on the command line: as the ur5e, with the given package path and args.

descgen's caches live in one temporary DESCGEN_CACHE_DIR for the run: pint's definitions and
compiled templates are warm after the first process; a robot's mesh facts are cold on its first
import (the corpus pass) and warm after the uncounted pair (the paired rows). xacro has none.

Run: .venv/bin/python benchmarks/bench_import.py [FILE.urdf.xacro ... --package-path DIR
[--xacro-arg N:=V]...] [--quick] [--pairs N]
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import harness  # noqa: E402
from harness import BIN, FreshCache, Result, Timing, process  # noqa: E402

from tests.corpus import descriptions, share  # noqa: E402

XACRO_CORPUS = ROOT / "tests" / "data" / "xacro_corpus"
UR5E = XACRO_CORPUS / "ur_description" / "urdf" / "ur_mocked.urdf.xacro"

# xacro's own command line, with `$(find pkg)` answered from BENCH_PACKAGE_PATH (a folder
# holding the package, as --package-path): the anchor for a Xacro package outside a ROS install
_XACRO_WITH_FIND = """
import os, sys
import xacro, xacro.substitution_args as sa
roots = os.environ["BENCH_PACKAGE_PATH"].split(os.pathsep)
def find(pkg):
    for root in roots:
        if os.path.isfile(os.path.join(root, pkg, "package.xml")):
            return os.path.join(root, pkg)
    raise LookupError(pkg)
sa._eval_find = find
sa._eval_dict["find"] = find
sys.argv = ["xacro", *sys.argv[1:]]
xacro.main()
"""

CACHE = FreshCache()
ENV = harness.env(CACHE.path)
XACRO = str(BIN / "xacro") if (BIN / "xacro").is_file() else "xacro"


class Job:
    """One robot: its file, SRDF, package paths and Xacro arguments."""

    def __init__(self, ident: str, path: Path, srdf: Path | None, paths: tuple[Path, ...], args: dict[str, str]):
        self.ident, self.path, self.srdf, self.paths, self.args = ident, path, srdf, paths, args

    def descgen(self) -> Timing:
        argv = [str(BIN / "descgen"), "import", str(self.path)]
        argv += ["--srdf", str(self.srdf)] if self.srdf else []
        for p in self.paths:
            argv += ["--package-path", str(p)]
        for k, v in self.args.items():
            argv += ["--xacro-arg", f"{k}:={v}"]
        # exit 2: a description import refuses (a finding, not a crash); it still read and audited it
        return process(argv, env=ENV, ok=(0, 1, 2))

    def xacro(self) -> Timing:
        args = [f"{k}:={v}" for k, v in self.args.items()]
        if self.path.name.endswith(".xacro") and self.paths:
            env = ENV | {"BENCH_PACKAGE_PATH": os.pathsep.join(map(str, self.paths))}
            return process([sys.executable, "-c", _XACRO_WITH_FIND, str(self.path), *args], env=env)
        return process([XACRO, str(self.path), *args], env=ENV)


def paired(job: Job, label: str) -> None:
    harness.compare(f"import of {label}", job.descgen, job.xacro, kind="cold", anchor_name="xacro")


def corpus_pass(jobs: list[Job]) -> None:
    """Robot by robot, descgen then xacro, one pass; the row shows the totals. A robot whose
    descgen process crashes is left out on both sides (and fails the script at its end)."""
    result = Result()
    ours, theirs = Timing(0.0, 0.0), Timing(0.0, 0.0)
    crashed = []
    print(f"{'robot':<64} {'import CPU s':>12} {'xacro CPU s':>11} {'ratio':>6}")
    for job in jobs:
        try:
            d = job.descgen()
        except SystemExit as exc:
            crashed.append(job.ident)
            print(f"{job.ident:<64} crashed: {str(exc).strip().splitlines()[-1]}", flush=True)
            continue
        a = job.xacro()
        print(f"{job.ident:<64} {d.cpu:12.3f} {a.cpu:11.3f} {d.cpu / a.cpu:6.1f}", flush=True)
        ours = Timing(ours.cpu + d.cpu, ours.wall + d.wall)
        theirs = Timing(theirs.cpu + a.cpu, theirs.wall + a.wall)
    if crashed:
        harness.FAILED.append(f"import of {', '.join(crashed)}")
    result.descgen.append(ours)
    result.anchor.append(theirs)
    counted = len(jobs) - len(crashed)
    left_out = f", {len(crashed)} that crashed left out" if crashed else ""
    harness.report(
        f"import of {counted} example-robot-data robots, one process each, robot by robot "
        f"(total of one pass{left_out}; pairs: robots)",
        result,
        kind="cold",
        anchor_name="xacro",
        pairs=counted,
    )


def main() -> None:
    def add(ap: argparse.ArgumentParser) -> None:
        ap.add_argument("files", nargs="*", type=Path)
        ap.add_argument("--package-path", action="append", type=Path, default=[])
        ap.add_argument("--xacro-arg", action="append", default=[], help="N:=V, for the extra files")

    args = harness.parse(__doc__, add)
    root = share()
    corpus = [Job(ident, urdf, srdf, (root,) if root else (), {}) for ident, urdf, srdf in descriptions()]
    try:
        if UR5E.is_file():
            ur = Job("ur5e", UR5E, None, (XACRO_CORPUS,), {"ur_type": "ur5e", "name": "ur5e"})
            paired(ur, "xacro_corpus: ur_description ur_mocked ur_type:=ur5e")
        panda = [j for j in corpus if j.ident == "panda_description/urdf/panda.urdf"]
        if panda:
            paired(panda[0], "example-robot-data's Panda (URDF + SRDF, STL meshes)")
        xargs = dict(a.split(":=", 1) for a in args.xacro_arg)
        for p in args.files:
            paired(Job(str(p), p, None, tuple(args.package_path), xargs), str(p))
        if corpus:
            corpus_pass(corpus[::14] if harness.QUICK else corpus)
        else:
            print("example-robot-data is not installed: no corpus row")
    finally:
        CACHE.close()
    harness.done()


if __name__ == "__main__":
    main()
