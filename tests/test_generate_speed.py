"""generate at 1000 links (issue 17): the shortcuts of this round give what they skip.

- check 1 compares the Xacro's expansion with the URDF in xmlcompare's equal-tree pass
  (xacro writes attributes sorted, the URDF in template order: the pass used to fail on that
  and hand every element to the slow walk);
- the Xacro sandbox parses with the cyclic collector paused and frees the DOM itself;
- the YAML builder takes plain keys and plain text values inline, in mappings as in lists:
  limits, key errors and positions are the ones counted by hand;
- a spec that names no ``source`` key skips the walk for sources: the model is the one the
  walk gives (the walk forced on is the reference).
"""

from __future__ import annotations

import gc
import sys
import xml.dom.minidom
from pathlib import Path
from typing import Any

import pytest

from descgen.audit.spec import load_spec, load_spec_text
from descgen.core import xmlcompare
from descgen.core.findings import InputError
from descgen.infra import yamlsource
from descgen.prove.xacro_expand import expand
from descgen.read import xacro_file, xacro_skeleton
from descgen.render import render_package
from descgen.spec.build import Builder
from descgen.spec.load import from_document
from descgen.spec.sources import cites_sources

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from synthetic import chain_spec

from .conftest import EXAMPLE

# -- check 1: the expansion equals the URDF in the equal-tree pass -------------------------


@pytest.mark.parametrize("which", ["example", "chain"])
def test_expansion_equals_urdf_without_the_walk(which: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")  # expanded here, not taken from a cache
    if which == "example":
        spec = EXAMPLE
    else:
        spec = tmp_path / "chain.yaml"
        spec.write_text(chain_spec(12, "chain"))
    robot = load_spec(spec).robot
    files = render_package(robot, spec.name)
    # the whole file through xacro, which writes attributes sorted (the skeleton keeps the
    # static parts as the template wrote them, in the URDF's order)
    monkeypatch.setattr(xacro_skeleton, "split", lambda text: None)
    expanded = expand(files, f"urdf/{robot.name}.urdf.xacro")
    a, b = xmlcompare.parse(expanded), xmlcompare.parse(files[f"urdf/{robot.name}.urdf"])
    # the premise: xacro's order is not the URDF's (else this test proves nothing)
    assert any(x.items() != y.items() for x, y in zip(a.iter(), b.iter(), strict=True))

    def walked(*_: Any) -> None:
        raise AssertionError("the equal-tree pass left equal trees to the walk")

    monkeypatch.setattr(xmlcompare, "_difference", walked)
    assert xmlcompare.first_difference(a, b) is None


def test_attributes_in_another_order_with_another_value_still_differ() -> None:
    a = xmlcompare.parse('<r><o xyz="1 2 3" rpy="0 0 0"/></r>')
    b = xmlcompare.parse('<r><o rpy="0 0 1" xyz="1 2 3"/></r>')
    assert xmlcompare.first_difference(a, b) == "/r/o/@rpy: '0 0 0' vs '0 0 1'"


# -- the Xacro sandbox: collector paused while parsing, DOM freed --------------------------

XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="l" value="0.5"/>
  <link name="a"><visual><geometry><box size="${l} 1 1"/></geometry></visual></link>
  <link name="b"/>
</robot>
"""


def _dom_nodes() -> int:
    return sum(1 for o in gc.get_objects() if isinstance(o, xml.dom.minidom.Element))


def test_parse_runs_without_the_collector_and_leaves_it_on(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "r.urdf.xacro"
    path.write_text(XACRO)
    during: list[bool] = []
    mark = xacro_file._mark_static
    monkeypatch.setattr(xacro_file, "_mark_static", lambda doc: (during.append(gc.isenabled()), mark(doc))[1])
    xml_text = xacro_file.expand(path, path.name).decode()
    assert during == [False] and gc.isenabled()
    assert '<box size="0.5 1 1"/>' in xml_text
    path.write_text(XACRO.replace("</robot>", ""))  # xacro's parse fails: the collector is back on
    with pytest.raises(InputError):
        xacro_file.expand(path, path.name)
    assert gc.isenabled()


def test_the_expanded_dom_is_freed_without_a_collection(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf.xacro"
    path.write_text(XACRO.replace('<link name="b"/>', '<link name="b"/>' * 300))
    gc.collect()
    gc.disable()
    try:
        before = _dom_nodes()
        xacro_file.expand(path, path.name)
        left = _dom_nodes() - before  # cycles would wait for the collector, which is off
    finally:
        gc.enable()
    assert left < 50  # the 300 links and their document are gone (xacro keeps a macro table)


# -- the YAML builder's inline paths in mappings, counted by hand --------------------------


def _nested_maps(levels: int) -> str:
    return "{a: " * levels + "x" + "}" * levels


def test_a_text_value_just_inside_the_depth_limit_of_mappings_loads() -> None:
    doc = yamlsource.loads(_nested_maps(yamlsource.MAX_DEPTH), "d.yaml")  # mappings 0..63, x at 64
    node: Any = doc.data
    for _ in range(yamlsource.MAX_DEPTH):
        node = node["a"]
    assert node == "x"


def test_a_text_value_just_beyond_the_depth_limit_of_mappings_fails_at_it() -> None:
    levels = yamlsource.MAX_DEPTH + 1
    with pytest.raises(InputError) as err:
        yamlsource.loads(_nested_maps(levels), "d.yaml")
    (f,) = err.value.findings
    assert "nested too deeply" in f.message
    assert (f.where.line, f.where.col) == (1, 4 * levels + 1)  # "{a: " is 4 characters


def test_the_node_limit_counts_text_values_of_mappings(monkeypatch: pytest.MonkeyPatch) -> None:
    text = "a: x\nb: y\nc: z\n"  # four nodes: the mapping and three values (keys are not counted)
    monkeypatch.setattr(yamlsource, "MAX_NODES", 4)
    assert yamlsource.loads(text, "n.yaml").data == {"a": "x", "b": "y", "c": "z"}
    monkeypatch.setattr(yamlsource, "MAX_NODES", 3)
    with pytest.raises(InputError) as err:
        yamlsource.loads(text, "n.yaml")
    (f,) = err.value.findings
    assert f.code == "YAML003" and (f.where.line, f.where.col) == (3, 4)  # at 'z'


@pytest.mark.parametrize(
    ("text", "message", "line", "col"),
    [
        ("base: &b {x: 1}\nother:\n  <<: *b\n", "YAML merge keys (<<) are not supported", 3, 3),
        ("a: 1\n? [x, y]\n: 2\n", "a mapping key must be a plain name", 2, 3),
        ("a:\n  k: 1\n  j: 2\n  k: 3\n", "duplicate key 'k' (first at line 2)", 4, 3),
        ("a:\n  1: x\n  '1': y\n", "duplicate key '1' (first at line 2)", 3, 3),
    ],
    ids=["merge", "collection key", "duplicate", "int key then text key"],
)
def test_key_errors_at_the_key(text: str, message: str, line: int, col: int) -> None:
    with pytest.raises(InputError) as err:
        yamlsource.loads(text, "k.yaml")
    (f,) = err.value.findings
    assert f.message == message and (f.where.line, f.where.col) == (line, col)


def test_keys_of_other_types_are_named_by_their_text() -> None:
    doc = yamlsource.loads("1: a\ntrue: b\n!!str 2: c\nnull: d\n", "k.yaml")
    assert doc.data == {"1": "a", "true": "b", "2": "c", "null": "d"}
    assert doc.key_marks[("true",)] == (2, 1) and doc.value_marks[("null",)] == (4, 7)


# -- sources: the walk skipped only when no key is 'source' --------------------------------


def _walked(doc: Any) -> Any:
    """The model as the walk for sources gives it (Builder with the walk forced on)."""
    loaded = from_document(doc)
    builder = Builder(doc, loaded.spec, {}, stand_ins=True)
    return builder.build()


def test_example_cites_and_keeps_its_sources() -> None:
    loaded = load_spec(EXAMPLE)
    assert cites_sources(loaded.doc)
    base = next(lk for lk in loaded.robot.links if lk.name == "base_link")
    assert base.source == "M05, M07, M06, M08"  # visual's own and its origin's, then the inertial's, in spec order
    caster = next(lk for lk in loaded.robot.links if lk.name == "caster_link")
    assert caster.source == "M10"


def test_a_source_key_written_escaped_is_seen() -> None:
    text = 'name: r\nlinks:\n  - name: a\n    "sourc\\x65": M9\n'
    loaded = load_spec_text(text, "e.yaml")
    assert cites_sources(loaded.doc)
    assert loaded.robot.links[0].source == "M9"


def test_without_source_keys_the_model_is_the_walks(tmp_path: Path) -> None:
    spec = tmp_path / "chain.yaml"
    spec.write_text(chain_spec(6, "chain"))
    loaded = load_spec(spec)
    assert not cites_sources(loaded.doc)
    walked = _walked(loaded.doc)
    assert [lk.source for lk in walked.links] == [None] * 6
    assert loaded.robot.links == walked.links and loaded.robot.joints == walked.joints
