"""Cold start: a command imports only what it uses. ``descgen --help`` and ``validate`` run in
a fresh interpreter and must not have imported the heavy optional libraries (trimesh and
scipy come with yourdfpy or meshes, matplotlib with control plots, pinocchio with tests,
mujoco with simulate), nor, for --help, pint, pydantic or numpy."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.conftest import EXAMPLE, ROOT

HEAVY = {"trimesh", "scipy", "matplotlib", "pinocchio", "mujoco", "yourdfpy", "rosbags", "networkx"}

# runs the commands in-process in a fresh interpreter and reports the top-level packages loaded
_PROBE = """
import json, sys
from descgen.cli import main
seen = {}
for name, argv in (("help", ["--help"]), ("validate", ["validate", sys.argv[1]])):
    try:
        main(argv)
    except SystemExit as exc:
        code = exc.code
    else:
        code = 0
    seen[name] = {"code": code, "modules": sorted({m.split(".")[0] for m in sys.modules})}
print("PROBE" + json.dumps(seen))
"""


@pytest.fixture(scope="module")
def probe() -> dict[str, dict[str, object]]:
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, str(EXAMPLE)], capture_output=True, text=True, cwd=ROOT, timeout=120
    )
    line = next(x for x in done.stdout.splitlines() if x.startswith("PROBE"))
    result: dict[str, dict[str, object]] = json.loads(line[len("PROBE") :])
    return result


@pytest.mark.e2e
def test_help_imports_no_heavy_library(probe: dict[str, dict[str, object]]) -> None:
    help_run = probe["help"]
    assert help_run["code"] == 0
    loaded = set(help_run["modules"])  # type: ignore[call-overload]
    assert loaded & (HEAVY | {"pint", "pydantic", "numpy"}) == set()


@pytest.mark.e2e
def test_validate_imports_no_heavy_library(probe: dict[str, dict[str, object]]) -> None:
    validate = probe["validate"]
    assert validate["code"] == 0  # the example is valid: the probe really validated
    loaded = set(validate["modules"])  # type: ignore[call-overload]
    assert {"pint", "pydantic"} <= loaded  # it did parse quantities and models
    assert loaded & HEAVY == set()


def test_pint_is_imported_without_scipy_and_scipy_still_works_after() -> None:
    code = (
        "import sys; from descgen import units; units.to_si('19.1 in / 2', 'length');"
        "assert 'scipy' not in sys.modules, 'pint probed scipy';"
        "import scipy.spatial; print('ok')"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert done.stdout.strip() == "ok", done.stderr
