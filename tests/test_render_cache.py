"""The compiled-template cache (descgen/render/__init__.py): same files with and without it, and a
changed template is recompiled, never served from the cache."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from descgen import render
from descgen.audit.spec import load_spec
from descgen.render import default_templates, render_package

from .conftest import EXAMPLE

# "without the cache" means what it says: no compiled copy shared by the tests either (conftest.py)
pytestmark = pytest.mark.cold_templates


def _fresh(monkeypatch: pytest.MonkeyPatch, folder: str) -> None:
    monkeypatch.setenv("DESCGEN_CACHE_DIR", folder)
    render._bytecode_cache.cache_clear()


def test_cached_templates_render_the_same_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    robot = load_spec(EXAMPLE).robot
    _fresh(monkeypatch, "")
    plain = render_package(robot, EXAMPLE.name)
    _fresh(monkeypatch, str(tmp_path))
    first = render_package(robot, EXAMPLE.name)  # compiles and stores
    stored = list(tmp_path.rglob("*.cache"))
    assert stored, "nothing was cached"
    _fresh(monkeypatch, str(tmp_path))
    second = render_package(robot, EXAMPLE.name)  # loads what was stored
    assert plain == first == second
    _fresh(monkeypatch, "")


def test_a_changed_template_is_recompiled(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    robot = load_spec(EXAMPLE).robot
    overrides = tmp_path / "templates"
    overrides.mkdir()
    shutil.copy(default_templates() / "frames.md.j2", overrides / "frames.md.j2")
    _fresh(monkeypatch, str(tmp_path / "cache"))
    before = render_package(robot, EXAMPLE.name, overrides)["evidence/frames.md"]
    text = (overrides / "frames.md.j2").read_text(encoding="utf-8")
    (overrides / "frames.md.j2").write_text(text + "CHANGED-TEMPLATE\n", encoding="utf-8")
    _fresh(monkeypatch, str(tmp_path / "cache"))
    after = render_package(robot, EXAMPLE.name, overrides)["evidence/frames.md"]
    assert "CHANGED-TEMPLATE" not in before and "CHANGED-TEMPLATE" in after
    _fresh(monkeypatch, "")


@pytest.mark.parametrize("first_sandboxed", [True, False])
def test_sandboxed_and_plain_renders_do_not_share_compiled_code(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, first_sandboxed: bool
) -> None:
    """A spec with ``templates:`` renders the default templates in the sandbox, whose compiled
    calls go through ``environment.call`` (its checks); plain code calls directly. Loaded by the
    other environment, sandbox code crashes a plain render (AttributeError: no 'call'), and
    plain code would run in the sandbox unchecked. The oracle: each render with caching off."""
    robot = load_spec(EXAMPLE).robot
    empty = tmp_path / "no-overrides"
    empty.mkdir()
    _fresh(monkeypatch, "")
    expected = {sb: render_package(robot, EXAMPLE.name, empty, sb) for sb in (True, False)}
    order = (first_sandboxed, not first_sandboxed)
    for sandboxed in order:
        _fresh(monkeypatch, str(tmp_path / "cache"))
        assert render_package(robot, EXAMPLE.name, empty, sandboxed) == expected[sandboxed]
    _fresh(monkeypatch, "")
