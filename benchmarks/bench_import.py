"""Time `descgen import` per robot of the example-robot-data corpus (in process: read, write
the spec, prove the round trip, audit) beside the `xacro` command line on the same file (the
anchor: what every ROS user runs on a description), and print the ratio.

The vendored Xacro corpus's UR ur5e (tests/data/xacro_corpus, `ur_type:=ur5e`) is timed too,
imported with `--package-path` only; its `xacro` anchor resolves `$(find pkg)` in the same
folders (the pip xacro has no ament index here), which is all the wrapper changes.

Run: .venv/bin/python benchmarks/bench_import.py [FILE.urdf.xacro ... --package-path DIR
[--xacro-arg N:=V]...] (extra files are imported with the given package path and arguments).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from rows import row  # noqa: E402

from descgen.commands.importer.run import ImportOptions, import_description  # noqa: E402
from descgen.core.findings import InputError  # noqa: E402
from descgen.read.description import Options  # noqa: E402
from tests.corpus import descriptions, share  # noqa: E402


def _xacro() -> list[str]:
    beside = Path(sys.executable).parent / "xacro"
    found = str(beside) if beside.is_file() else shutil.which("xacro")
    if found is None:
        sys.exit("the xacro command is not installed (pip install xacro)")
    return [found]


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


def _time_xacro(cmd: list[str], path: Path, options: Options) -> float:
    args = [f"{k}:={v}" for k, v in options.xacro_args.items()]
    env = None
    if options.package_paths:
        cmd = [sys.executable, "-c", _XACRO_WITH_FIND]
        env = dict(os.environ, BENCH_PACKAGE_PATH=os.pathsep.join(map(str, options.package_paths)))
    t0 = time.perf_counter()
    done = subprocess.run([*cmd, str(path), *args], check=False, capture_output=True, env=env)
    took = time.perf_counter() - t0
    if done.returncode != 0:
        sys.exit(f"xacro failed on {path}: {done.stderr.decode(errors='replace').strip()}")
    return took


def _time_import(path: Path, options: Options) -> tuple[float, str]:
    t0 = time.perf_counter()
    try:
        outcome = import_description(path, ImportOptions(options))
        verdict = "proven" if outcome.proven else ("invalid" if outcome.invalid else "differs")
    except InputError:
        verdict = "unusable"
    return time.perf_counter() - t0, verdict


def main(argv: list[str]) -> None:
    import argparse

    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="*", type=Path)
    ap.add_argument("--package-path", action="append", type=Path, default=[])
    ap.add_argument("--xacro-arg", action="append", default=[], help="N:=V, for the extra files")
    args = ap.parse_args(argv)
    extra, paths = args.files, tuple(args.package_path)
    xargs = dict(a.split(":=", 1) for a in args.xacro_arg)
    root = share()
    jobs = [
        (ident, urdf, Options(srdf=srdf, package_paths=(root,) if root else ())) for ident, urdf, srdf in descriptions()
    ]
    if UR5E.is_file():
        ur = Options(xacro_args={"ur_type": "ur5e", "name": "ur5e"}, package_paths=(XACRO_CORPUS,))
        jobs.append(("xacro_corpus: ur_description ur_mocked ur_type:=ur5e", UR5E, ur))
    jobs += [(str(p), p, Options(xacro_args=xargs, package_paths=paths)) for p in extra]
    cmd = _xacro()
    if jobs:
        _time_import(jobs[0][1], jobs[0][2])  # warm imports
    total_i = total_x = 0.0
    xacro_rows = []
    print(f"{'robot':<64} {'import s':>9} {'xacro s':>8} {'ratio':>6}  verdict")
    for ident, path, options in jobs:
        t_i, verdict = _time_import(path, options)
        t_x = _time_xacro(cmd, path, options)
        total_i, total_x = total_i + t_i, total_x + t_x
        print(f"{ident:<64} {t_i:9.3f} {t_x:8.3f} {t_i / t_x:6.1f}  {verdict}")
        if path.name.endswith(".xacro"):
            xacro_rows.append((ident, t_i, t_x))
    if jobs:
        print(f"{'total (' + str(len(jobs)) + ' robots)':<64} {total_i:9.3f} {total_x:8.3f} {total_i / total_x:6.1f}")
        row(
            f"import of {len(jobs)} corpus robots, in process (anchor: xacro, one process each)",
            total_i,
            total_x,
            "warm",
        )
        for ident, t_i, t_x in xacro_rows:
            row(f"import of {ident}, in process (anchor: xacro, one process)", t_i, t_x, "warm")


if __name__ == "__main__":
    main(sys.argv[1:])
