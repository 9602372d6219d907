"""The expanded document is written as text by readers/xacro_file.to_xml, a faster walk than
minidom's ``toxml()`` with xacro's ``fixed_writexml``: it must give the same text character
for character (the oracle: ``toxml()`` of the same document, which is what the xacro CLI and
``xacro.process_file`` users get)."""

from __future__ import annotations

import xml.dom.minidom as md
from pathlib import Path
from typing import Any

import pytest
import xacro

from descgen.read.xacro_file import expand, to_xml

ROOT = Path(__file__).resolve().parents[1]
XMLNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# every way the writer branches: attributes to sort and escape (&, <, >, ", quotes, tabs and
# newlines as character references, empty), a lone text child (kept even when it is only
# whitespace), whitespace-only text among elements (dropped), mixed text, comments, CDATA (a
# lone child goes through the many-children branch), a processing instruction, non-ASCII
HOSTILE = f"""<?xml version="1.0"?>
<!-- before the root -->
<robot name="r" {XMLNS} zeta="z" alpha="a &amp; &lt;b&gt; &quot;q&quot; 'apos'">
  <xacro:property name="v" value="4&lt;2"/>
  <link name="${{v}}" empty="" ws="a&#10;b&#9;c&#13;d"><only>   </only><t>x &amp; y &lt; z &gt; w "q"</t></link>
  <mixed>head<a/>  middle &amp; more  <b k="1"/>tail</mixed>
  <blank>

  </blank>
  <cdata_only><![CDATA[ <raw> & ${{v}} ]]></cdata_only>
  <cdata_mixed>t<![CDATA[c]]><e/></cdata_mixed>
  <!-- inside: ${{v}} -->
  <?target some data?>
  <unicode name="Gelenk ü — ∑ 𝄞"/>
  <xacro:macro name="m" params="n"><made_by_macro n="${{n}}" z="1" a="2">text ${{n}}</made_by_macro></xacro:macro>
  <xacro:m n="one"/>
  <deep><a><b><c><d><e f="g"/></d></c></b></a></deep>
</robot>
<!-- after the root -->
<?after root?>
"""


def _both(path: Path) -> tuple[str, str]:
    doc = xacro.process_file(str(path))
    return to_xml(doc), str(doc.toxml())


def test_hostile_document_is_written_as_toxml_writes_it(tmp_path: Path) -> None:
    top = tmp_path / "r.urdf.xacro"
    top.write_text(HOSTILE, encoding="utf-8")
    ours, theirs = _both(top)
    assert ours == theirs
    # the oracle really had each case to write
    for piece in ('alpha="a &amp; &lt;b&gt; &quot;q&quot;', "<only>   </only>", "<![CDATA[", "<?target", "𝄞"):
        assert piece in theirs


@pytest.mark.parametrize(
    "xacro_file",
    [
        "generated/warehouse_arm_description/urdf/warehouse_arm.urdf.xacro",
        "generated/warehouse_arm_description/urdf/warehouse_arm.ros2_control.xacro",
    ],
)
def test_generated_xacro_is_written_as_toxml_writes_it(xacro_file: str) -> None:
    ours, theirs = _both(ROOT / xacro_file)
    assert ours == theirs and len(theirs) > 1000


def test_expansion_is_xacros_text(tmp_path: Path) -> None:
    """The sandbox's expansion (static subtrees skipped, written by to_xml) is what xacro's own
    process_file and toxml give for the same file, banner aside (it names the path)."""
    top = tmp_path / "r.urdf.xacro"
    top.write_text(HOSTILE, encoding="utf-8")
    theirs = xacro.process_file(str(top)).toxml()
    ours = expand(top, "r.urdf.xacro").decode("utf-8")
    assert ours.split("-->", 4)[-1] == theirs.split("-->", 4)[-1]


def test_without_xacros_writer_it_falls_back_to_toxml(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """minidom's own Element.writexml (no sorting, no dropped whitespace): to_xml must not
    write xacro's layout for a writer that is not xacro's."""
    top = tmp_path / "r.urdf.xacro"
    top.write_text(HOSTILE, encoding="utf-8")
    doc = xacro.process_file(str(top))
    with_xacro = to_xml(doc)
    monkeypatch.setattr(md.Element, "writexml", _stdlib_writexml())
    plain = doc.toxml()
    assert plain != with_xacro  # the two writers really differ on this document
    assert to_xml(doc) == plain


def _stdlib_writexml() -> Any:
    import importlib.util

    spec = importlib.util.find_spec("xml.dom.minidom")
    assert spec is not None and spec.loader is not None
    fresh = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fresh)  # a copy of the module xacro has not patched
    return fresh.Element.writexml
