"""Fuzzing the path from a spec to the files: a hostile string anywhere in the example spec
(or in its file name) is either refused by ``validate`` or reaches every output as data.

The property, per mutated spec:
- loading it raises InputError or succeeds; nothing else;
- when it loads, rendering and proving it (``generate.plan``) raises nothing, and no
  generation check (GEN*) fails: a spec that validates is one that generate can write;
- every output parses back with its own language's parser (lxml for XML, PyYAML for YAML,
  ``ast`` for Python) and the Python launch files hold the same top-level statements as the
  clean build's (a payload that became a statement would add one).

The sample is bounded (a generate plan takes ~0.3 s) so that CI runs it on every build.
"""

from __future__ import annotations

import ast
import shutil
from pathlib import Path
from typing import Any

import yaml
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from lxml import etree

from descgen.commands.generate import plan
from descgen.core.findings import InputError

from .helpers import EXAMPLE_TEXT, ROOT, get_at, set_at, string_leaves

EXAMPLE = yaml.safe_load(EXAMPLE_TEXT)

PAYLOADS = [
    "\nimport os; os.system('touch /tmp/descgen-pwned')\n",
    "x -->\n<evil/>",
    "]]>",
    "a\"b'c",
    "| col |",
    "`code`",
    "${__import__('os')}",
    "$(env HOME)",
    "back\\slash",
    "{{ 7*7 }}",
    "tab\there",
    "line\u2028sep",
    "&#10;error[X]",
    "\x1b[31mred",
    "é—ü 🤖",
    "x" * 3000,
    # names real robots have and the spec accepts for links, joints and frames (issue 12):
    # the Xacro derives property names from them, which must stay identifiers
    "flange-tool0",
    "link_0.0",
    "2dof_planar",
]


LEAVES = string_leaves(EXAMPLE)


def _outputs_parse(files: dict[str, str]) -> dict[str, list[str]]:
    """Parse every output; return the top-level statement kinds of each Python file."""
    statements: dict[str, list[str]] = {}
    for rel, text in files.items():
        if rel.endswith((".urdf", ".xacro", ".srdf", ".xml")):
            etree.fromstring(text.encode("utf-8"))
        elif rel.endswith((".yaml", ".rviz")):
            yaml.safe_load(text)
        elif rel.endswith(".py"):
            statements[rel] = [type(s).__name__ for s in ast.parse(text).body]
    return statements


def _build(tmp: Path, data: Any, name: str = "robot.yaml") -> dict[str, str] | None:
    specs = tmp / "specs"
    if specs.exists():
        shutil.rmtree(specs)
    specs.mkdir(parents=True)
    shutil.copytree(ROOT / "specs" / "trajectories", specs / "trajectories")
    matrix = (data.get("semantic") or {}).get("collision_matrix") if isinstance(data, dict) else None
    if isinstance(matrix, dict) and isinstance(matrix.get("samples"), int):
        matrix["samples"] = 100  # the fuzz is about escaping; sampling is tests/test_collision_matrix.py's
    spec = specs / name
    spec.write_text(yaml.safe_dump(data, allow_unicode=True, sort_keys=False), encoding="utf-8")
    try:
        p = plan(spec, tmp / "generated")
    except InputError:
        return None
    failed = [f for f in p.findings if f.severity == "error" and f.code.startswith("GEN")]
    assert not failed, failed
    return p.files


_CLEAN: dict[str, list[str]] = {}


def _clean(tmp: Path) -> dict[str, list[str]]:
    if not _CLEAN:
        files = _build(tmp / "clean", EXAMPLE)
        assert files is not None
        _CLEAN.update(_outputs_parse(files))
    return _CLEAN


FUZZ = settings(
    max_examples=25,
    deadline=None,
    phases=[Phase.explicit, Phase.reuse, Phase.generate],
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)


@FUZZ
@given(leaf=st.sampled_from(LEAVES), payload=st.sampled_from(PAYLOADS), append=st.booleans())
def test_a_hostile_string_is_refused_or_stays_data(
    tmp_path: Path, leaf: tuple[Any, ...], payload: str, append: bool
) -> None:
    data = yaml.safe_load(EXAMPLE_TEXT)
    set_at(data, leaf, (get_at(data, leaf) + payload) if append else payload)
    files = _build(tmp_path, data)
    if files is None:
        return
    assert _outputs_parse(files) == _clean(tmp_path)


@FUZZ
@given(payload=st.sampled_from([p for p in PAYLOADS if "/" not in p and "\x00" not in p and len(p) < 200]))
def test_a_hostile_spec_file_name_stays_data(tmp_path: Path, payload: str) -> None:
    files = _build(tmp_path, yaml.safe_load(EXAMPLE_TEXT), f"robot{payload}.yaml")
    assert files is not None
    assert _outputs_parse(files) == _clean(tmp_path)
