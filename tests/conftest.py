from __future__ import annotations

import atexit
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"

# The suite reads nothing of the user's environment; each test sets what it needs. Caches off
# (descgen.core.cache_dir.CACHE_ENV; "" switches them off, subprocesses inherit it), whatever the user
# set; not in CI (progress bars and CI-only behaviour are chosen by the tests that check them);
# XDG folders (platformdirs, matplotlib's config) in a folder of the session's own.
os.environ["DESCGEN_CACHE_DIR"] = ""
for _name in ("CI", "MPLCONFIGDIR", "PYDANTIC_DISABLE_PLUGINS", "ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH"):
    os.environ.pop(_name, None)
_SESSION_HOME = tempfile.mkdtemp(prefix="descgen-tests-xdg-")
atexit.register(shutil.rmtree, _SESSION_HOME, True)
for _name in ("XDG_CACHE_HOME", "XDG_CONFIG_HOME", "XDG_DATA_HOME", "XDG_STATE_HOME"):
    os.environ[_name] = os.path.join(_SESSION_HOME, _name.lower())


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


# --- where every test must run (CI, `make test`), a skip is a failure --------------------------

REQUIRED = os.environ.get("DESCGEN_REQUIRE_TOOLS") == "1"


def _as_failure(report: pytest.TestReport | pytest.CollectReport) -> None:
    reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
    report.outcome = "failed"
    report.longrepr = f"skipped where every test must run (DESCGEN_REQUIRE_TOOLS=1): {reason}"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]):  # type: ignore[no-untyped-def]
    outcome = yield
    report = outcome.get_result()
    if REQUIRED and report.skipped and not hasattr(report, "wasxfail"):
        _as_failure(report)


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector: pytest.Collector):  # type: ignore[no-untyped-def]
    outcome = yield
    report = outcome.get_result()
    if REQUIRED and report.skipped:  # a module-level importorskip or skip(allow_module_level=True)
        _as_failure(report)


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
            "descgen printed finding codes that are not in the catalogue (descgen/codes/__init__.py or an "
            f"audit @rule), so `descgen rules CODE` cannot explain them:\n{lines}"
        )
        if reporter is not None:
            reporter.write_sep("=", "UNREGISTERED FINDING CODES", red=True, bold=True)
            reporter.write_line(text)
        else:
            sys.stderr.write(text + "\n")
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
