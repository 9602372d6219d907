"""Autoescaped template output goes through render/escaping.py (escape_text, compiled in by
its code generator) instead of markupsafe's ``escape``: the oracle is markupsafe itself,
value by value, and jinja2's stock code generator, package by package (every file the same
text, with spec text built to be escaped planted in names, materials and file names)."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import jinja2
import pytest
from markupsafe import Markup, escape

import descgen.render as render
from descgen.audit.spec import load_spec, load_spec_text
from descgen.render.escaping import escape_text

from .helpers import EXAMPLE_TEXT, plant

ROOT = Path(__file__).resolve().parents[1]


class _Html:
    def __html__(self) -> str:
        return "<b>kept & unescaped</b>"

    def __repr__(self) -> str:  # a stable test id: pytest-xdist's workers must collect the same names
        return "_Html()"


VALUES: list[Any] = [
    "",
    "link_1",
    "0 0 0.05",
    "  ",
    "a & b",
    "<tag>",
    "x > y",
    "it's",
    'say "hi"',
    "&amp; already",
    "&<>'\"",
    "'",
    "ü — ∑ 𝄞 <",
    "\u2028\t\n",
    Markup("<i>safe</i>"),
    Markup("plain"),
    _Html(),
    0,
    -1.5e-07,
    None,
    True,
    ("a", "<b>"),
]


@pytest.mark.parametrize("value", VALUES, ids=repr)
def test_escape_text_is_markupsafe(value: Any) -> None:
    ours = escape_text(value)
    assert type(ours) is str
    assert ours == str(escape(value))


def test_escape_text_of_a_str_subclass_is_markupsafe() -> None:
    class Name(str):
        pass

    assert escape_text(Name("<x>")) == str(escape(Name("<x>"))) == "&lt;x&gt;"


def test_undefined_fails_as_under_escape() -> None:
    env = jinja2.Environment(undefined=jinja2.StrictUndefined)
    undefined = env.undefined(name="missing")
    with pytest.raises(jinja2.UndefinedError) as theirs:
        escape(undefined)
    with pytest.raises(jinja2.UndefinedError) as ours:
        escape_text(undefined)
    assert str(ours.value) == str(theirs.value)


def _stock(monkeypatch: pytest.MonkeyPatch) -> None:
    """render_package with jinja2's own code generator (escape per output) and no compiled cache."""
    monkeypatch.setattr(render, "_Environment", jinja2.Environment)
    monkeypatch.setattr(render, "_SandboxedEnvironment", jinja2.sandbox.ImmutableSandboxedEnvironment)
    monkeypatch.setattr(render, "_bytecode_cache", lambda sandboxed: None)


# text that markupsafe changes, where the spec lets it stand (names are plain; these are not)
ESCAPED = "a&b <c> 'd' \"e\""
PLANTED = [
    (
        "material: chassis_grey\n        source: M05",
        f"material: chassis_grey\n        source: M05\n        name: {json.dumps(ESCAPED)}",
    ),
    ("chassis_grey", json.dumps(ESCAPED)),
    ("maintainer: WA-1 integration team", f"maintainer: {json.dumps(ESCAPED)}"),
]


def _hostile_text() -> str:
    text = EXAMPLE_TEXT
    for old, new in PLANTED:
        text = plant(old, new, text, count=text.count(old))
    return text


@pytest.mark.parametrize("which", ["example", "hostile"])
def test_package_renders_as_with_jinjas_code_generator(which: str, monkeypatch: pytest.MonkeyPatch) -> None:
    if which == "example":
        robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    else:
        robot = load_spec_text(_hostile_text(), "hostile.yaml").robot
    ours = render.render_package(robot, "spec.yaml")
    for sandboxed in (False, True):
        assert render.render_package(robot, "spec.yaml", sandboxed=sandboxed) == ours
    with monkeypatch.context() as m:
        _stock(m)
        theirs = render.render_package(robot, "spec.yaml")
        assert render.render_package(robot, "spec.yaml", sandboxed=True) == theirs
    assert ours == theirs
    if which == "hostile":  # the oracle really escaped the planted text
        urdf = next(v for k, v in theirs.items() if k.endswith(".urdf"))
        assert re.search(r"a&amp;b &lt;c&gt;", urdf)


def test_templates_compile_to_escape_text() -> None:
    """The code generator really is in use (else the tests above compare jinja2 with itself)."""
    env = render.environment()
    source = env.loader.get_source(env, "_elements.xml.j2")[0]  # type: ignore[union-attr]
    code = env.compile(source, "_elements.xml.j2", raw=True)
    assert "environment.escape_text(" in code and "escape(l_" not in code
    stock = jinja2.Environment(autoescape=True).compile(source, raw=True)
    assert "escape(l_" in stock
