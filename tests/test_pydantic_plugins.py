"""descgen/infra/pydantic_plugins.py: the command line's stand-in for pydantic's plugin loader finds no
plugins, yields to the user's PYDANTIC_DISABLE_PLUGINS when it leaves plugins on, and hands any
other name to pydantic's real loader. Each case runs in a fresh interpreter (the stand-in is
process-wide)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from tests.conftest import ROOT

_PROBE = """
import sys
from descgen.infra.pydantic_plugins import LOADER, no_plugin_lookup
with no_plugin_lookup():
    from pydantic import BaseModel
    class M(BaseModel):
        x: int
    print("valid", M(x="3").x)
    print("loader", type(sys.modules[LOADER]).__name__)
    print("metadata", "importlib.metadata" in sys.modules)
    if sys.argv[1:] == ["other-name"]:
        print("group", sys.modules[LOADER].PYDANTIC_ENTRY_POINT_GROUP)
        print("loader", type(sys.modules[LOADER]).__name__)
# afterwards: no finder left, and no stand-in for the next import of the loader
print("after", type(sys.modules.get(LOADER)).__name__, any(type(f).__name__ == "_Finder" for f in sys.meta_path))
"""


def _run(env_value: str | None, *args: str) -> list[str]:
    env = {k: v for k, v in os.environ.items() if k != "PYDANTIC_DISABLE_PLUGINS"}
    if env_value is not None:
        env["PYDANTIC_DISABLE_PLUGINS"] = env_value
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, *args], capture_output=True, text=True, cwd=ROOT, env=env, timeout=60
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout.splitlines()


@pytest.mark.parametrize("value", [None, "__all__", "1", "true"])
def test_no_plugins_wanted_no_lookup(value: str | None) -> None:
    assert _run(value) == ["valid 3", "loader _NoPlugins", "metadata False", "after NoneType False"]


def test_plugins_left_on_by_the_user_are_looked_up() -> None:
    assert _run("logfire") == ["valid 3", "loader module", "metadata True", "after module False"]


def test_any_other_name_loads_the_real_loader() -> None:
    assert _run(None, "other-name") == [
        "valid 3",
        "loader _NoPlugins",
        "metadata False",
        "group pydantic",
        "loader module",
        "after module False",
    ]
