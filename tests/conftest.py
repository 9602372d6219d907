from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"

# tests write only to their tmp_path: no pint definition cache in the user's cache folder
# (descgen.cache_dir.CACHE_ENV; "" switches the cache off, subprocesses inherit it)
os.environ.setdefault("DESCGEN_CACHE_DIR", "")


def require_tool(name: str) -> str:
    """The path of a system tool; skip when absent, fail when CI requires it."""
    path = shutil.which(name)
    if path:
        return path
    if os.environ.get("DESCGEN_REQUIRE_TOOLS") == "1":
        pytest.fail(f"{name} is required (DESCGEN_REQUIRE_TOOLS=1) but not on PATH")
    pytest.skip(f"{name} not installed")


@pytest.fixture(scope="session")
def pin():  # type: ignore[no-untyped-def]
    """pinocchio, for the tests that compare with it (the others in their modules run without it);
    skipped when absent, a failure when CI requires it. Not function-scoped: hypothesis refuses
    those in @given tests."""
    try:
        import pinocchio
    except ImportError:
        if os.environ.get("DESCGEN_REQUIRE_TOOLS") == "1":
            pytest.fail("pinocchio is required (DESCGEN_REQUIRE_TOOLS=1) but cannot be imported")
        pytest.skip("pinocchio not installed")
    return pinocchio


@pytest.fixture
def example_text() -> str:
    return EXAMPLE.read_text()


# --- every finding code seen in the session is in the catalogue (tests/codes_seen.py) ---------


def pytest_configure(config: pytest.Config) -> None:
    from . import codes_seen

    codes_seen.shared_dir()  # the controller makes it before xdist starts workers (they inherit it)
    codes_seen.install()


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    from . import codes_seen

    codes_seen.uninstall()
    codes_seen.dump()
    if hasattr(session.config, "workerinput"):
        return  # an xdist worker: the controller checks the union
    missing = codes_seen.unregistered(codes_seen.collect())
    shutil.rmtree(codes_seen.shared_dir(), ignore_errors=True)
    if missing:
        lines = "\n".join(f"  {code} (made in {where})" for code, where in missing.items())
        reporter = session.config.pluginmanager.get_plugin("terminalreporter")
        text = (
            "descgen printed finding codes that are not in the catalogue (descgen/codes.py or an "
            f"audit @rule), so `descgen rules CODE` cannot explain them:\n{lines}"
        )
        if reporter is not None:
            reporter.write_sep("=", "UNREGISTERED FINDING CODES", red=True, bold=True)
            reporter.write_line(text)
        else:
            sys.stderr.write(text + "\n")
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
