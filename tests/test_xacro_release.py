"""readers/xacro_file.release: a released minidom document is freed by reference counting
alone, as after minidom's own ``unlink()`` (the oracle), with nothing left for the collector."""

from __future__ import annotations

import gc
import weakref
import xml.dom.minidom as md
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from descgen.read.xacro_file import release

XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- a comment between siblings -->
  <xacro:property name="w" value="0.1"/>
  <xacro:macro name="leg" params="n">
    <link name="${n}"><visual><geometry><box size="${w} 1 1"/></geometry></visual></link>
  </xacro:macro>
  <xacro:leg n="a"/>
  <xacro:leg n="b"/>
  <link name="c">text <b id="x">bold</b> tail</link>
</robot>
"""


def _nodes(doc: Any) -> Iterator[Any]:
    stack = [doc]
    while stack:
        node = stack.pop()
        yield node
        if node.nodeType == node.ELEMENT_NODE:
            yield from node.attributes.values()
        stack.extend(node.childNodes)


def _survivors(make: Callable[[], Any], free: Callable[[Any], None]) -> list[str]:
    """The nodes (by position in the tree walk, and name) of a document made by ``make`` still
    alive after ``free`` and the last reference to it are gone, with the collector off (only
    reference counting frees)."""
    gc.collect()
    gc.disable()
    try:
        doc = make()
        refs = [(f"{i}:{n.nodeName}", weakref.ref(n)) for i, n in enumerate(_nodes(doc))]
        assert len(refs) > 20
        free(doc)
        del doc
        return [name for name, r in refs if r() is not None]
    finally:
        gc.enable()
        gc.collect()


def _expanded(tmp_path: Path) -> Callable[[], Any]:
    import xacro

    src = tmp_path / "r.urdf.xacro"
    src.write_text(XACRO, encoding="utf-8")
    return lambda: xacro.process_file(str(src))


def test_release_frees_a_parsed_document_like_unlink() -> None:
    def make() -> Any:
        return md.parseString(XACRO.encode())

    # the cycles are real: without either, every node outlives the document until a collection
    assert len(_survivors(make, lambda doc: None)) > 20
    assert _survivors(make, lambda doc: doc.unlink()) == []  # minidom's own answer
    assert _survivors(make, release) == []


def test_release_leaves_what_unlink_leaves_of_an_expansion(tmp_path: Path) -> None:
    """xacro detaches nodes (macro definitions, properties, calls) that keep cycles of their
    own and point at the document: unlink leaves the document for the collector, and release
    must leave nothing more (a tree node still held by a parent link would be more)."""
    make = _expanded(tmp_path)
    assert len(_survivors(make, lambda doc: None)) > 20
    assert _survivors(make, release) == _survivors(make, lambda doc: doc.unlink())


def test_release_clears_the_id_cache() -> None:
    def make() -> Any:
        doc = md.parseString(XACRO.encode())
        for b in doc.getElementsByTagName("b"):
            b.setIdAttribute("id")
        assert doc.getElementById("x") is not None  # fills the document's id cache
        return doc

    assert _survivors(make, release) == _survivors(make, lambda doc: doc.unlink()) == []
