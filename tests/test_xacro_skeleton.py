"""Check 1 expands a Xacro with its static parts set aside (readers/xacro_skeleton.py, through
checks/xacro_expand.expand_scratch): the result must be the tree xacro gives for the whole
file. Oracle: ``xacro.process_file`` on the same file (xacro's own evaluator, no sandbox),
compared as data (xmlcompare.first_difference: elements, attributes, texts in order)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import xacro
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from descgen.core.findings import InputError
from descgen.core.xmlcompare import first_difference, parse
from descgen.prove.xacro_expand import expand_scratch
from descgen.read import xacro_file, xacro_skeleton
from tests.corpus import share
from tests.helpers import ROOT

XMLNS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# Every piece is something a wrong skeleton would get wrong: an element set aside that xacro
# changes, a block whose structure a macro reads, a placeholder xacro clones or drops.
SKELETAL = f"""\
<?xml version="1.0"?>
<!-- a comment before the root -->
<robot name="r" {XMLNS}>
  <!-- before a plain link -->
  <link name="plain"><visual><origin xyz="0 0 1" rpy="0 0 0"/><geometry><box size="1 2 3"/></geometry></visual></link>
  <link name="attr_removed" xacro:note="dropped by xacro"><inertial><mass value="1"/></inertial></link>
  <link name="charref"><c v="&#36;{{1 + 1}}"/><d>&#36;{{2 * 3}}</d></link>
  <link name="escaped"><c>$${{not an expression}} and cost $5</c><plain k="&lt;&amp;&gt;"/></link>
  <xacro:property name="v" value="42"/>
  <group>
    <!-- xacro:eval-comments -->
    <!-- evaluated: ${{v}} -->
    <plain>text</plain>
  </group>
  <group><x><xacro:attribute name="added" value="n${{v}}"/><kept/></x><y>plain</y></group>
  <group><xacro:element xacro:name="renamed_${{v}}"><inner a="1"/></xacro:element></group>
  <xacro:macro name="one" params="n *blk">
    <link name="${{n}}"><xacro:insert_block name="blk"/><xacro:insert_block name="blk"/><body k="v"/></link>
  </xacro:macro>
  <xacro:one n="first"><block><mass value="2"/></block></xacro:one>
  <xacro:one n="second"><block><mass value="3"/></block></xacro:one>
  <xacro:macro name="many" params="**content">
    <wrapped><xacro:insert_block name="content"/></wrapped>
  </xacro:macro>
  <xacro:many><content><a x="1"/><b><c y="2"/></b>tail text</content></xacro:many>
  <xacro:if value="false"><gone><plain/></gone></xacro:if>
  <xacro:if value="true"><kept_if><plain/></kept_if></xacro:if>
  <xacro:unless value="true"><gone_unless/></xacro:unless>
  <xacro:include filename="part.xacro"/>
  <xacro:include filename="plain.xml"/>
  <joint name="j" type="fixed"><parent link="plain"/><child link="charref"/></joint>
</robot>
"""
PART = f"""<?xml version="1.0"?>
<robot {XMLNS}><link name="from_include_${{v}}"><plain/></link><link name="plain_included"/></robot>
"""
PLAIN = '<?xml version="1.0"?>\n<robot><link name="all_plain"><visual><origin xyz="0 0 1"/></visual></link></robot>\n'


def _write(folder: Path, top: str) -> Path:
    (folder / "part.xacro").write_text(PART)
    (folder / "plain.xml").write_text(PLAIN)
    path = folder / "r.urdf.xacro"
    path.write_text(top)
    return path


def _same_as_xacro(path: Path, args: dict[str, str] | None = None) -> None:
    """Ours is xacro's tree, or fails where xacro fails (a block evaluated twice can be)."""
    before = path.read_bytes()
    try:
        theirs = parse(xacro.process_file(str(path), mappings=dict(args or {})).toxml())
    except Exception:  # xacro's own failure: the sandbox must fail too, not pass a skeleton
        with pytest.raises(InputError):
            expand_scratch(path, path.name, args or {}, [path.parent])
        return
    ours = parse(expand_scratch(path, path.name, args or {}, [path.parent]))
    assert path.read_bytes() == before  # the file is written back as it was
    assert first_difference(ours, theirs) is None, first_difference(ours, theirs)


def test_what_xacro_changes_is_expanded_and_the_rest_set_aside(tmp_path: Path) -> None:
    path = _write(tmp_path, SKELETAL)
    skeleton = xacro_skeleton.split(SKELETAL)
    assert skeleton is not None
    # set aside: the plain link, the joint, and plain elements inside walked ones
    aside = {e.get("name") or e.tag for run in skeleton.parts for e in run if isinstance(e.tag, str)}
    assert {"plain", "j"} <= aside
    assert {"body", "y", "kept", "mass", "inertial"} <= aside  # mass: inside a block; inertial: in attr_removed
    # never set aside: anything holding a $ (also as a character reference), a xacro:*
    # attribute, the eval-comments group, and a macro call's blocks (read by position)
    for walked in ("attr_removed", "charref", "escaped", "block", "content", "x"):
        assert walked not in aside, walked
    _same_as_xacro(path)
    out = expand_scratch(path, "r", {}, [tmp_path])
    for evaluated in ('v="2"', ">6<", "evaluated: 42", 'added="n42"', "<renamed_42>", "from_include_42"):
        assert evaluated in out, evaluated  # the oracle's work really happened in each place
    assert out.count('<mass value="2"/>') == 2 and "xacro:note" not in out and "<gone" not in out


def test_a_dollar_written_only_as_a_character_reference_is_expanded(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf.xacro"
    path.write_text(f'<robot name="r" {XMLNS}><a v="&#36;{{1 + 1}}"/><b>&#x24;{{3 * 3}}</b><c/></robot>')
    _same_as_xacro(path)
    out = expand_scratch(path, "r", {}, [tmp_path])
    assert 'v="2"' in out and ">9<" in out


def test_what_cannot_be_mirrored_is_expanded_whole(tmp_path: Path) -> None:
    cases = {
        "cdata": SKELETAL.replace("<y>plain</y>", "<y><![CDATA[ ${v} stays ]]></y>"),
        "inner namespace": SKELETAL.replace("<visual>", f"<visual {XMLNS}>", 1),
        "doctype": SKELETAL.replace("<robot ", '<!DOCTYPE robot [<!ENTITY e "${v}">]>\n<robot ', 1),
        "a name only libxml2 takes": SKELETAL.replace("<kept/>", "<\u037fkept/>"),  # expat refuses it
        "latin-1": SKELETAL.replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="ISO-8859-1"?>'),
    }
    for name, text in cases.items():
        assert xacro_skeleton.split(text) is None, name
        if name == "doctype":  # refused by the sandbox, as before
            with pytest.raises(InputError, match="DOCTYPE"):
                expand_scratch(_write(tmp_path, text), "r", {}, [tmp_path])
        elif name != "latin-1":  # xacro reads the file as text in the locale's encoding
            _same_as_xacro(_write(tmp_path, text))
    assert xacro_skeleton.split('<robot name="r"><!-- nothing below --></robot>') is None  # nothing to set aside


def test_static_siblings_are_set_aside_as_one_run_up_to_text_xacro_evaluates(tmp_path: Path) -> None:
    text = f"""<robot name="r" {XMLNS}>
  <xacro:property name="v" value="5"/>
  <!-- before the run: stays -->
  <a/>plain text<!-- inside the run --><b k="1"/>
  <c/>then ${{v}} evaluated<d/>
  <e/><!-- after the last element: stays -->
  <xacro:if value="true"><f/></xacro:if>
</robot>"""
    skeleton = xacro_skeleton.split(text)
    assert skeleton is not None
    runs = [[n.tag if isinstance(n.tag, str) else "comment" for n in run] for run in skeleton.parts]
    # one run up to the evaluated tail, another after it, and <f/>, a block of xacro:if
    assert runs == [["a", "comment", "b", "c"], ["d", "e"]]
    path = tmp_path / "r.urdf.xacro"
    path.write_text(text)
    _same_as_xacro(path)
    out = expand_scratch(path, "r", {}, [tmp_path])
    assert "then 5 evaluated" in out and "plain text" in out and "<f/>" in out


def test_a_changed_placeholder_is_not_joined() -> None:
    text = f'<robot {XMLNS}><a x="1"/><b y="${{1}}"/></robot>'
    skeleton = xacro_skeleton.split(text)
    assert skeleton is not None and len(skeleton.parts) == 1 and len(skeleton.parts[0]) == 1
    tag = skeleton.tag
    assert tag.startswith(xacro_skeleton.PLACEHOLDER) and tag in skeleton.text
    assert xacro_skeleton.join(f'<robot><{tag} n="0"/><b y="1"/></robot>', skeleton, 100, 10**6) is not None
    changed = (
        f'<{tag} n="1"/>',
        f'<{tag} n="x"/>',
        f"<{tag}/>",
        f'<{tag} n="0"><c/></{tag}>',
        f'<g xmlns="http://u"><{tag} n="0"/></g>',  # under a default namespace xacro's output declared
    )
    for stand_in in changed:
        again = xacro_skeleton.split(text)
        assert again is not None and again.tag != tag  # a new token for every split
        assert xacro_skeleton.join(f"<robot>{stand_in.replace(tag, again.tag)}</robot>", again, 100, 10**6) is None


def test_placeholders_cannot_be_forged_or_hidden_by_the_file(tmp_path: Path) -> None:
    """What xacro makes of the file (xacro:element, xacro:attribute, an included macro) cannot
    be taken for a placeholder, nor put one out of join's reach."""
    include = tmp_path / "inc.xacro"
    include.write_text(
        f'<robot {XMLNS}><xacro:macro name="wrap" params="*b">'
        '<ns xmlns="http://other"><xacro:insert_block name="b"/></ns></xacro:macro></robot>'
    )
    for body in (
        f'<xacro:element xacro:name="{xacro_skeleton.PLACEHOLDER}${{\'x\'}}" n="0"/>',
        '<g><xacro:attribute name="xml${\'ns\'}" value="http://u"/><a><b/></a></g>',
        '<xacro:include filename="inc.xacro"/><xacro:wrap><blk><link name="in_ns"/></blk></xacro:wrap>',
    ):
        path = tmp_path / "r.urdf.xacro"
        path.write_text(f'<robot name="r" {XMLNS}><link name="a"><visual/></link>{body}</robot>')
        _same_as_xacro(path)


def test_characters_minidom_writes_raw_are_left_to_xacro(tmp_path: Path) -> None:
    """Python 3.11's minidom writes a tab, newline or CR in an attribute, and a CR in a text, as
    the character; xacro's output read again has a space or a newline there."""
    path = tmp_path / "r.urdf.xacro"
    path.write_text(
        f'<robot name="r" {XMLNS}><link name="a&#10;b"/><p>x&#13;y</p><q v="t&#9;u"/><link name="${{1}}"/></robot>'
    )
    _same_as_xacro(path)
    out = parse(expand_scratch(path, "r", {}, [tmp_path]))
    assert out[0].get("name") == "a b" and out[1].text == "x\ny" and out[2].get("v") == "t u"


def test_a_file_that_reads_itself_reads_the_file(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf.xacro"
    path.write_text(
        f'<robot name="r" {XMLNS}><g><a/></g><n v="${{len(str(xacro.load_yaml(\'r.urdf.xacro\')))}}"/></robot>'
    )
    _same_as_xacro(path)


def test_what_the_sandbox_bounds_still_refuses(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A macro that clones a large static part is refused at its size, before any copy; a file
    over the sandbox's file bound is refused as before; xacro's locale decides non-ASCII files."""
    path = tmp_path / "r.urdf.xacro"
    big = "x" * 5000
    calls = "<xacro:m/>" * 20
    path.write_text(
        f'<robot name="r" {XMLNS}><xacro:macro name="m" params=""><g><big v="{big}"/></g></xacro:macro>{calls}</robot>'
    )
    assert expand_scratch(path, "r", {}, [tmp_path]).count(big) == 20
    monkeypatch.setattr(xacro_file, "MAX_TEXT", 50_000)  # 20 copies of 5,000 characters
    with pytest.raises(InputError, match="more text"):
        expand_scratch(path, "r", {}, [tmp_path])
    monkeypatch.undo()
    monkeypatch.setattr(xacro_file, "MAX_FILE_BYTES", 1000)
    with pytest.raises(InputError, match="larger than"):
        expand_scratch(path, "r", {}, [tmp_path])
    monkeypatch.undo()
    from descgen.prove import xacro_expand

    split = xacro_skeleton.split
    calls_made: list[str] = []
    monkeypatch.setattr(xacro_skeleton, "split", lambda text: calls_made.append(text) or split(text))
    monkeypatch.setattr(xacro_expand, "_utf8_locale", lambda: False)
    path.write_text(f'<robot name="r" {XMLNS}><link name="é"/><link name="${{1}}"/></robot>')
    expand_scratch(path, "r", {}, [tmp_path])
    assert calls_made == []  # non-ASCII under another encoding: xacro alone reads the file
    path.write_text(f'<robot name="r" {XMLNS}><link name="e"/><link name="${{1}}"/></robot>')
    expand_scratch(path, "r", {}, [tmp_path])
    assert len(calls_made) == 1


def test_the_element_bound_still_holds_for_parts_set_aside(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    link = '<link name="l{}"><visual><geometry><box size="1 1 1"/></geometry></visual></link>'
    links = "".join(link.format(i) for i in range(40))
    path = tmp_path / "r.urdf.xacro"
    path.write_text(f'<?xml version="1.0"?>\n<robot name="r" {XMLNS}>{links}</robot>\n')
    assert expand_scratch(path, "r", {}, [tmp_path]).count("<box ") == 40
    monkeypatch.setattr(xacro_file, "MAX_ELEMENTS", 100)  # 161 elements: the skeleton alone has 2
    with pytest.raises(InputError, match="more than 100 elements"):
        expand_scratch(path, "r", {}, [tmp_path])


def test_the_generated_xacro_expands_alike(tmp_path: Path) -> None:
    package = tmp_path / "warehouse_arm_description"
    shutil.copytree(ROOT / "generated" / "warehouse_arm_description", package)
    top = package / "urdf" / "warehouse_arm.urdf.xacro"
    skeleton = xacro_skeleton.split(top.read_text())
    assert skeleton is not None and len(skeleton.parts) > 10
    _same_as_xacro(top)  # the default variant: xacro alone answers it (no $(find) without ament)
    for hardware in ("gazebo", "real"):  # $(find) of the package: the whole file, sandboxed
        args = {"hardware": hardware}
        whole = parse(xacro_file.expand(top, "r", args, package_paths=[tmp_path]))
        ours = parse(expand_scratch(top, "r", args, [tmp_path]))
        assert first_difference(ours, whole) is None, (hardware, first_difference(ours, whole))


def test_example_robot_data_urdfs_expand_alike(tmp_path: Path) -> None:
    root = share()
    urdfs = sorted(root.rglob("*.urdf")) if root is not None else []
    assert len(urdfs) >= 60
    set_aside = 0
    for f in urdfs:
        copy = tmp_path / f.name
        shutil.copyfile(f, copy)
        set_aside += xacro_skeleton.split(copy.read_text()) is not None
        _same_as_xacro(copy)
    assert set_aside >= 60  # the skeleton really was used (not for a robot of comments only)


# --- random documents: pieces xacro changes and pieces it does not, nested --------------------

HEADER = f"""<?xml version="1.0"?>
<robot name="r" {XMLNS}>
  <xacro:property name="v" value="7"/>
  <xacro:macro name="twice" params="*b">
    <w1><xacro:insert_block name="b"/><xacro:insert_block name="b"/></w1>
  </xacro:macro>
  <xacro:macro name="inside" params="**b"><w2><xacro:insert_block name="b"/></w2></xacro:macro>
"""


def _pieces() -> st.SearchStrategy[str]:
    leaf = st.sampled_from(
        [
            '<p a="1 2 3"/>',
            "<q>plain text</q>",
            '<d x="${v * 2}"/>',
            "<t>${v + 1}</t>",
            "<e>$${kept}</e>",
            '<c v="&#36;{v}"/>',
            "<!-- a comment -->",
            "some text",
            "text with ${v} in it",
            '<n xacro:drop="1"><p/></n>',
        ]
    )

    def nest(children: st.SearchStrategy[list[str]]) -> st.SearchStrategy[str]:
        return st.one_of(
            children.map(lambda c: f"<g>{''.join(c)}</g>"),
            children.map(lambda c: f'<h k="v">{"".join(c)}</h>'),
            children.map(lambda c: f'<xacro:if value="${{v > 3}}">{"".join(c)}</xacro:if>'),
            children.map(lambda c: f'<xacro:unless value="true">{"".join(c)}</xacro:unless>'),
            children.map(lambda c: f'<xacro:element xacro:name="el_${{v}}">{"".join(c)}</xacro:element>'),
            children.map(lambda c: f"<xacro:twice><blk>{''.join(c)}</blk></xacro:twice>"),
            children.map(lambda c: f"<xacro:inside><blk>{''.join(c)}</blk></xacro:inside>"),
            children.map(lambda c: f'<g><xacro:attribute name="at" value="n${{v}}"/>{"".join(c)}</g>'),
        )

    return st.recursive(leaf, lambda inner: nest(st.lists(inner, min_size=0, max_size=4)), max_leaves=12)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(_pieces(), min_size=1, max_size=6))
def test_random_documents_expand_as_xacro_does(tmp_path: Path, pieces: list[str]) -> None:
    path = tmp_path / "random.urdf.xacro"
    path.write_text(HEADER + "".join(f"<top>{p}</top>" for p in pieces) + "\n</robot>\n")
    _same_as_xacro(path)
