"""The sandbox skips xacro's walk over content xacro would leave as it is (no ``$``, no
``xacro:*`` tag or attribute, no ``xacro:eval-comments``): the expansion must stay byte for
byte what ``xacro.process_file`` gives (the oracle), the walk must really be skipped, and the
sandbox's bounds must still see the skipped text."""

from __future__ import annotations

from pathlib import Path

import pytest
import xacro

from descgen.core.findings import InputError
from descgen.read import xacro_file
from descgen.read.xacro_file import expand, expand_located

XMLNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# Each piece is a way a subtree can look plain while xacro would still change it.
TRICKY = f"""\
<?xml version="1.0"?>
<robot name="r" {XMLNS}>
  <!-- a comment before a plain link stays -->
  <link name="plain"><visual><geometry><box size="1 2 3"/></geometry></visual></link>
  <link name="attr_removed" xacro:note="dropped by xacro"><inertial><mass value="1"/></inertial></link>
  <link name="ns_removed"><visual {XMLNS}><geometry><sphere radius="1"/></geometry></visual></link>
  <link name="text"><c>$$&#123;not an expression}} and $ alone and cost $5</c></link>
  <link name="deep"><a><b><c><d x="${{1 + 1}}"/></c></b></a></link>
  <xacro:property name="v" value="42"/>
  <group>
    <!-- xacro:eval-comments -->
    <!-- evaluated: ${{v}} -->
    <plain>text</plain>
  </group>
  <group><x><xacro:attribute name="added" value="n${{v}}"/></x><y>plain</y></group>
  <group><xacro:element xacro:name="renamed_${{v}}"><inner a="1"/></xacro:element></group>
  <xacro:macro name="m" params="n *blk">
    <link name="${{n}}"><xacro:insert_block name="blk"/><plain_in_body k="v"/></link>
  </xacro:macro>
  <xacro:m n="one"><inertial><mass value="2"/></inertial></xacro:m>
  <xacro:m n="two"><inertial><mass value="2"/></inertial></xacro:m>
  <group><xacro:property name="q" value="7"/></group>
  <link name="q_${{q}}"/>
  <xacro:macro name="no_args"><link name="from_no_args"/></xacro:macro>
  <group><xacro:no_args/></group>
  <xacro:include filename="part.xacro"/>
  <xacro:include filename="plain.xml"/>
  <![CDATA[ ${{v}} stays ]]>
  <?pi ${{v}}?>
</robot>
"""
PART = f"""<?xml version="1.0"?>
<robot {XMLNS}><link name="from_include_${{v}}"><plain/></link><link name="plain_included"/></robot>
"""
PLAIN = '<?xml version="1.0"?>\n<robot><link name="all_plain"><visual><origin xyz="0 0 1"/></visual></link></robot>\n'


def _files(tmp_path: Path) -> Path:
    (tmp_path / "part.xacro").write_text(PART)
    (tmp_path / "plain.xml").write_text(PLAIN)
    top = tmp_path / "r.urdf.xacro"
    top.write_text(TRICKY)
    return top


def _body(xml: bytes) -> bytes:
    return xml.split(b"-->", 4)[-1]  # the banner names the path


def test_tricky_plain_looking_content_expands_as_xacro_does(tmp_path: Path) -> None:
    top = _files(tmp_path)
    theirs = xacro.process_file(str(top)).toxml().encode()
    for ours in (expand(top, "r"), expand(top, "r", trusted=True), expand_located(top, "r").xml):
        assert _body(ours) == _body(theirs)
    # the oracle really did something in each place a wrong skip would miss
    for evaluated in (
        b'x="2"',
        b"evaluated: 42",
        b'added="n42"',
        b"<renamed_42>",
        b"from_include_42",
        b"q_7",
        b"from_no_args",
    ):
        assert evaluated in theirs
    for removed in (b"xacro:note", b"<visual xmlns:xacro"):
        assert removed not in theirs


def test_locations_are_kept_for_skipped_elements(tmp_path: Path) -> None:
    top = _files(tmp_path)
    sources = expand_located(top, "r").sources
    lines = TRICKY.splitlines()
    box_line = next(i for i, text in enumerate(lines, 1) if "<box size" in text)
    assert any(w is not None and w.line == box_line and w.file == "r" for w in sources)


def test_the_walk_is_skipped_for_plain_elements(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "plain.urdf.xacro"
    links = "".join(
        f'<link name="l{i}"><visual><geometry><box size="1 1 1"/></geometry></visual></link>' for i in range(500)
    )
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}>{links}</robot>\n')
    walked: list[str] = []
    original = xacro.eval_all

    def counting(node: object, macros: object, symbols: object) -> object:
        walked.append(getattr(node, "tagName", "?"))
        return original(node, macros, symbols)

    monkeypatch.setattr(xacro, "eval_all", counting)  # what the sandbox wraps
    expected = xacro.process_file(str(path)).toxml().encode()
    walked.clear()
    assert _body(expand(path, "r")) == _body(expected)
    assert walked == ["robot"]  # the root holds xmlns:xacro; every link below it is plain


def test_a_large_plain_urdf_is_not_a_macro_bomb(tmp_path: Path) -> None:
    # xacro asks handle_macro_call of every element it walks; only xacro:* tags are calls.
    # Each element holds a ${}, so none is skipped as plain: 25,001 walked elements
    path = tmp_path / "big.urdf.xacro"
    links = "".join(
        f'<link name="l{i}"><a v="${{1}}"/><b v="${{2}}"/><c v="${{3}}"/><d v="${{4}}"/></link>' for i in range(5000)
    )
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}>{links}</robot>\n')
    out = expand(path, "r")
    assert out.count(b"<link ") == 5000 and out.count(b'<d v="4"/>') == 5000


def test_a_plain_element_in_a_macro_body_still_counts_as_a_call(tmp_path: Path) -> None:
    path = tmp_path / "bomb.urdf.xacro"
    macros = ['<xacro:macro name="m0"><link name="x"/></xacro:macro>']
    macros += [f'<xacro:macro name="m{i}"><xacro:m{i - 1}/><xacro:m{i - 1}/></xacro:macro>' for i in range(1, 16)]
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}>{"".join(macros)}<xacro:m15/></robot>\n')
    with pytest.raises(InputError) as info:
        expand(path, "r")
    assert info.value.findings[0].code == "READ033"


def test_skipped_text_still_counts_toward_the_text_bound(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "text.urdf.xacro"
    path.write_text(
        f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}><link name="a"><t>{"x" * 5000}</t></link></robot>\n'
    )
    assert expand(path, "r")  # within the real bound
    monkeypatch.setattr(xacro_file, "MAX_TEXT", 4000)
    with pytest.raises(InputError) as info:
        expand(path, "r")
    assert info.value.findings[0].code == "READ033"


def test_the_marking_is_iterative_on_a_deep_document() -> None:
    from xml.dom import minidom

    depth = 5000  # deeper than Python's recursion limit
    doc = minidom.parseString("<robot>" + "<a>" * depth + "</a>" * depth + "</robot>")
    xacro_file._mark_static(doc)
    # plain all the way down: no text, and the 5000 <a> below <robot> counted
    assert doc.documentElement.__dict__.get(xacro_file._STATIC) == (0, depth)


def test_macros_of_empty_elements_are_bounded_by_the_element_count(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Empty elements carry no text and are no macro calls: without an element bound a few
    macros (here 20 calls of a 400-element body, 8,000 elements) grow the DOM until the clock
    runs out. Lowered bound so the test is fast; the real one is 200,000."""
    path = tmp_path / "wide.urdf.xacro"
    body = "<a/>" * 400
    calls = "<xacro:e/>" * 20
    path.write_text(
        f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}><xacro:macro name="e">{body}</xacro:macro>{calls}</robot>\n'
    )
    assert expand(path, "r").count(b"<a/>") == 8000  # within the real bound
    monkeypatch.setattr(xacro_file, "MAX_ELEMENTS", 5000)
    with pytest.raises(InputError) as info:
        expand(path, "r")
    assert info.value.findings[0].code == "READ033" and "more than 5000 elements" in info.value.findings[0].message


def test_skipped_elements_still_count_toward_the_element_bound(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """One plain <link> holding 6,000 plain elements is skipped as a whole; its elements count."""
    path = tmp_path / "plain.urdf.xacro"
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}><link name="a">{"<p/>" * 6000}</link></robot>\n')
    assert expand(path, "r").count(b"<p/>") == 6000
    monkeypatch.setattr(xacro_file, "MAX_ELEMENTS", 5000)
    with pytest.raises(InputError) as info:
        expand(path, "r")
    assert "more than 5000 elements" in info.value.findings[0].message
