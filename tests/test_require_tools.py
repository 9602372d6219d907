"""Where every test must run (DESCGEN_REQUIRE_TOOLS=1: CI and ``make test``), a test module whose
module-level ``pytest.importorskip`` finds its tool missing fails instead of skipping
(tests/conftest.py turns the skip into a failure); elsewhere it skips. Shown on the real modules
that import pinocchio or mujoco at module level, with both made unimportable, in a pytest of their
own that only collects them (none of their tests runs)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests import codes_seen
from tests.helpers import ROOT

MODULES = {
    "tests/test_sweep.py": "pinocchio",
    "tests/test_collision_published.py": "pinocchio",
    "tests/test_collision_mimic.py": "pinocchio",
    "tests/test_simulate.py": "mujoco",
}
# a plugin loaded before any conftest or test module: importing either tool raises ImportError,
# as when it is not installed
BLOCKER = "import sys\n\nfor name in ('pinocchio', 'mujoco'):\n    sys.modules[name] = None\n"


def _collect(tmp_path: Path, required: bool) -> subprocess.CompletedProcess[str]:
    (tmp_path / "without_tools.py").write_text(BLOCKER)
    # not this session's: its finding-code folder (the child would remove it when done), xdist's
    # worker variables, the user's PYTEST_ADDOPTS, the requirement itself
    env = {
        k: v
        for k, v in os.environ.items()
        if k != codes_seen.ENV and not k.startswith("PYTEST_") and k != "DESCGEN_REQUIRE_TOOLS"
    }
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    env["COLUMNS"] = "1000"  # summary lines whole
    if required:
        env["DESCGEN_REQUIRE_TOOLS"] = "1"
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-p",
            "without_tools",
            "-p",
            "no:cacheprovider",
            "--collect-only",
            "-q",
            *MODULES,
        ],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )


@pytest.mark.parametrize("required", [True, False], ids=["required", "optional"])
def test_a_module_level_importorskip_fails_where_every_test_must_run(tmp_path: Path, required: bool) -> None:
    done = _collect(tmp_path, required)
    out = done.stdout + done.stderr
    assert "Traceback" not in done.stderr, done.stderr[-3000:]
    if required:
        assert done.returncode == pytest.ExitCode.INTERRUPTED, out[-3000:]  # errors during collection
        for module, tool in MODULES.items():
            line = re.search(rf"^ERROR {re.escape(module)} - (.*)$", done.stdout, re.M)
            assert line is not None, (module, out[-3000:])
            assert "skipped where every test must run (DESCGEN_REQUIRE_TOOLS=1)" in line.group(1), line.group(0)
            assert tool in line.group(1), line.group(0)
        assert f"{len(MODULES)} errors" in done.stdout, out[-3000:]
    else:  # the control: without the requirement the same modules skip, and nothing fails
        assert done.returncode == pytest.ExitCode.NO_TESTS_COLLECTED, out[-3000:]
        assert "error" not in done.stdout.lower(), out[-3000:]
        for module, tool in MODULES.items():
            line = re.search(rf"^SKIPPED \[1\] {re.escape(module)}:\d+: (.*)$", done.stdout, re.M)
            assert line is not None and tool in line.group(1), (module, out[-3000:])
