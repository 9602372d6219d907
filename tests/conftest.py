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


# --- templates compiled once per session --------------------------------------------------------
#
# With caching off, descgen compiles its 40-odd templates on every render (a new jinja2 environment
# each time): half of an in-process generate or check, hundreds of times a run. The tests share
# one compiled copy per worker instead, in memory: jinja2's bytecode cache, keyed by template name
# and file and checked against the source's checksum (a changed or overriding template is compiled
# again), one per environment kind as descgen keeps them (sandboxed code is never run plain). It
# reads nothing of the user's: the user's cache stays off. A test that sets DESCGEN_CACHE_DIR gets
# descgen's own folder cache, as before; a test marked ``cold_templates`` compiles every template
# on every render, as descgen does with caching off (tests/test_render_cache.py compares the two).


_COLD_TEMPLATES = False  # set for a test marked cold_templates


def _share_compiled_templates() -> None:
    """Wrap descgen.render._bytecode_cache once descgen.render is imported (not before: importing
    it here would load jinja2 and the renderers into every worker before any test asks)."""
    render = sys.modules.get("descgen.render")
    if render is None or getattr(render._bytecode_cache, "shared_by_the_tests", False):
        return
    import jinja2

    class SessionTemplates(jinja2.BytecodeCache):
        def __init__(self) -> None:
            self.code: dict[str, bytes] = {}

        def load_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
            code = self.code.get(bucket.key)
            if code is not None:
                bucket.bytecode_from_string(code)  # dropped by jinja2 when the source's checksum differs

        def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
            self.code[bucket.key] = bucket.bytecode_to_string()

    original = render._bytecode_cache
    shared = {True: SessionTemplates(), False: SessionTemplates()}

    def bytecode_cache(sandboxed: bool) -> jinja2.BytecodeCache | None:
        found = original(sandboxed)
        return found if found is not None or _COLD_TEMPLATES else shared[sandboxed]

    bytecode_cache.cache_clear = original.cache_clear  # type: ignore[attr-defined]
    bytecode_cache.shared_by_the_tests = True  # type: ignore[attr-defined]
    render._bytecode_cache = bytecode_cache


@pytest.fixture(autouse=True)
def _compiled_templates(request: pytest.FixtureRequest):  # type: ignore[no-untyped-def]
    global _COLD_TEMPLATES
    _share_compiled_templates()
    _COLD_TEMPLATES = request.node.get_closest_marker("cold_templates") is not None
    yield
    _COLD_TEMPLATES = False


# --- the tests that wait minutes on the registry start first, one per worker ---------------------

# pip resolving descgen's dependencies from the registry and installing them (the wheel; pre-commit's
# environment of the hook): minutes spent mostly waiting on the network. Started last, they keep
# one worker busy after the others are done; started first, the rest of the suite runs beside them.
LONG_WAITS = (
    "tests/test_wheel.py::test_the_wheel_installs_and_runs_every_command",
    "tests/test_ci_integrations.py::test_pre_commit_hook_from_a_clean_clone",
)


# the tests of one corpus robot run one after the other, so that one worker reads it once for all:
# its import (tests/corpus.py: imported, once per process) and its meshes (descgen keeps their
# facts in memory, by content), instead of each worker parsing the meshes again. Led by the first
# module's tests, in their order; the rest where they were.
SAME_ROBOT = ("tests/test_import_corpus.py::", "tests/test_import_oracle.py::", "tests/test_audit_corpus.py::")


def _ident(item: pytest.Item) -> str | None:
    callspec = getattr(item, "callspec", None)
    return callspec.params.get("ident") if callspec is not None else None


def _robot_by_robot(items: list[pytest.Item]) -> list[pytest.Item]:
    leader, followers = SAME_ROBOT[0], SAME_ROBOT[1:]
    led = {_ident(i) for i in items if i.nodeid.startswith(leader)} - {None}
    following: dict[str | None, list[pytest.Item]] = {}
    for item in items:
        if item.nodeid.startswith(followers) and _ident(item) in led:
            following.setdefault(_ident(item), []).append(item)
    out: list[pytest.Item] = []
    for item in items:
        ident = _ident(item)
        if item.nodeid.startswith(followers) and ident in led:
            continue
        out.append(item)
        if item.nodeid.startswith(leader):
            out += following.pop(ident, [])
    return out


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    items[:] = _robot_by_robot(items)
    first = [item for item in items if item.nodeid in LONG_WAITS]
    if not first:
        return
    rest = [item for item in items if item.nodeid not in LONG_WAITS]
    workers = int(getattr(config, "workerinput", {}).get("workercount", 1))
    # xdist's load scheduler (--dist load, what -n gives) first hands worker k the k-th run of
    # consecutive tests, a quarter of its share each (xdist/scheduler/load.py): one such test at
    # the head of each run. Any other order only costs time.
    chunk = max(len(items) // workers // 4, 2)
    for k, item in enumerate(first):
        rest.insert(min((k % workers) * chunk + k // workers, len(rest)), item)
    items[:] = rest


# --- every finding code seen in the session is in the catalogue (tests/codes_seen.py) ---------


def pytest_configure(config: pytest.Config) -> None:
    from . import codes_seen

    config.addinivalue_line(
        "markers", "cold_templates: every render compiles its templates (no session-wide compiled copy, conftest.py)"
    )

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
            "descgen printed finding codes that are not in the catalogue (descgen/codes/ or an audit @rule), "
            f"so `descgen rules CODE` cannot explain them, or that it lists as retired or redirected:\n{lines}"
        )
        if reporter is not None:
            reporter.write_sep("=", "UNREGISTERED FINDING CODES", red=True, bold=True)
            reporter.write_line(text)
        else:
            sys.stderr.write(text + "\n")
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
