"""Process settings the CLI makes for speed: one OpenBLAS thread (cli._one_blas_thread, set
before numpy loads) and a less eager cyclic collector (cli._fewer_collections); neither
overrides the user's own setting. Observed in a fresh interpreter, the real case."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from tests.conftest import EXAMPLE, ROOT

_PROBE = """
import os, sys
from descgen.cli import main
main(["validate", sys.argv[1]])
import numpy
print("BLAS=" + os.environ.get("OPENBLAS_NUM_THREADS", "unset"))
"""


@pytest.mark.parametrize(("given", "expected"), [(None, "1"), ("3", "3")])
def test_validate_runs_numpy_with_one_blas_thread_unless_told(given: str | None, expected: str) -> None:
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if given is not None:
        env["OPENBLAS_NUM_THREADS"] = given
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, str(EXAMPLE)], capture_output=True, text=True, cwd=ROOT, env=env, timeout=60
    )
    assert done.stdout.strip().splitlines()[-1] == f"BLAS={expected}", done.stderr[-2000:]


_GC_PROBE = """
import gc, sys
if sys.argv[2] != "default":
    gc.set_threshold(int(sys.argv[2]), 10, 10)
from descgen.cli import main
main(["validate", sys.argv[1]])
print("GC=" + str(gc.get_threshold()[0]))
"""


@pytest.mark.parametrize(("given", "expected"), [("default", "10000"), ("500", "500")])
def test_the_collector_runs_less_often_unless_tuned(given: str, expected: str) -> None:
    done = subprocess.run(
        [sys.executable, "-c", _GC_PROBE, str(EXAMPLE), given], capture_output=True, text=True, cwd=ROOT, timeout=60
    )
    assert done.stdout.strip().splitlines()[-1] == f"GC={expected}", done.stderr[-2000:]
