"""Time `descgen import` per robot of the example-robot-data corpus (in process: read, write
the spec, prove the round trip, audit) beside the `xacro` command line on the same file (the
anchor: what every ROS user runs on a description), and print the ratio.

Run: .venv/bin/python benchmarks/bench_import.py [FILE.urdf.xacro ... --package-path DIR]
(extra files are imported with the given package path, e.g. a Xacro package you own).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from descgen.audit.inputs import Options  # noqa: E402
from descgen.findings import InputError  # noqa: E402
from descgen.importer.run import ImportOptions, import_description  # noqa: E402
from tests.corpus import descriptions, share  # noqa: E402


def _xacro() -> list[str]:
    beside = Path(sys.executable).parent / "xacro"
    found = str(beside) if beside.is_file() else shutil.which("xacro")
    if found is None:
        sys.exit("the xacro command is not installed (pip install xacro)")
    return [found]


def _time_xacro(cmd: list[str], path: Path) -> float:
    t0 = time.perf_counter()
    subprocess.run([*cmd, str(path)], check=False, capture_output=True)
    return time.perf_counter() - t0


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
    args = ap.parse_args(argv)
    extra, paths = args.files, tuple(args.package_path)
    root = share()
    jobs = [
        (ident, urdf, Options(srdf=srdf, package_paths=(root,) if root else ())) for ident, urdf, srdf in descriptions()
    ]
    jobs += [(str(p), p, Options(package_paths=paths)) for p in extra]
    cmd = _xacro()
    if jobs:
        _time_import(jobs[0][1], jobs[0][2])  # warm imports
    total_i = total_x = 0.0
    print(f"{'robot':<64} {'import s':>9} {'xacro s':>8} {'ratio':>6}  verdict")
    for ident, path, options in jobs:
        t_i, verdict = _time_import(path, options)
        t_x = _time_xacro(cmd, path)
        total_i, total_x = total_i + t_i, total_x + t_x
        print(f"{ident:<64} {t_i:9.3f} {t_x:8.3f} {t_i / t_x:6.1f}  {verdict}")
    if jobs:
        print(f"{'total (' + str(len(jobs)) + ' robots)':<64} {total_i:9.3f} {total_x:8.3f} {total_i / total_x:6.1f}")


if __name__ == "__main__":
    main(sys.argv[1:])
