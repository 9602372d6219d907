"""Every Markdown descgen writes, read by a real CommonMark parser (markdown-it-py, with GFM
tables): a value from the input (the spec's file name, link and joint names, sources, notes)
never becomes raw HTML, a link or an image, never closes the code span or fence it sits in,
and never starts a block (issue 34, item 6). The reproducer is the issue's: a spec saved as
``a`<img src=x onerror=alert(1)>`.yaml`` put an ``<img onerror>`` into evidence/README.md."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import markdown_it
import pytest

from descgen.render.formatting import mdcell, mdcode, mddest, mdfence, mdspan, mdtext

from .conftest import ROOT

SPEC = ROOT / "specs" / "warehouse_arm.yaml"
IMG = "<img src=x onerror=alert(1)>"
HOSTILE = [
    f"a`{IMG}`.yaml",
    IMG,
    "``` <b>x</b>",
    "`` `",
    "`",
    " `x` ",
    "a|b`c|`d",
    "[x](javascript:alert(1))",
    "![x](http://evil.example/x.png)",
    "<http://evil.example>",
    "<!-- x -->",
    "&lt;img src=x onerror=alert(1)&gt;",
    "# heading",
    "> quote",
    "- item",
    "1. item",
    "    indented",
    "***",
    "<div>",
    "a\nb<script>",
    "x\\",
    "*emph* _u_ __b__ ~~s~~",
    "[ref]: http://evil.example",
    "a\u2028b",
    "tool_link",
]
NO_SPACES = [h for h in HOSTILE if not re.search(r"\s", h)]


def parse(md: str) -> list[Any]:
    """Tokens (inline children flattened) as GitHub renders: CommonMark, raw HTML on, GFM tables."""
    md_parser = markdown_it.MarkdownIt("commonmark", {"html": True}).enable(["table", "strikethrough"])
    out = []
    for t in md_parser.parse(md):
        out.append(t)
        out.extend(t.children or ())
    return out


def injected(md: str, allowed_comments: tuple[str, ...] = ()) -> list[str]:
    """Raw HTML, links and images in ``md`` (descgen's own comments in ``allowed_comments``)."""
    bad = []
    for t in parse(md):
        if t.type in ("html_inline", "html_block"):
            if not any(t.content.startswith(c) for c in allowed_comments) or t.content.count("-->") != 1:
                bad.append(f"{t.type}: {t.content!r}")
        elif t.type in ("link_open", "image") or t.type == "autolink":
            bad.append(f"{t.type}: {t.attrs}")
    return bad


def text_of(md: str) -> str:
    """What a reader sees of one paragraph or cell: its text and code, joined."""
    return "".join(t.content for t in parse(md) if t.type in ("text", "code_inline"))


# -- the helpers ------------------------------------------------------------------------------


@pytest.mark.parametrize("value", HOSTILE)
def test_mdtext_is_plain_text_read_back_as_written(value: str) -> None:
    for md in (mdtext(value), f"> {mdtext(value)}", f"## {mdtext(value)}", f"Text: {mdtext(value)}."):
        assert not injected(md), (md, injected(md))
        assert [t.type for t in parse(md) if t.type.endswith("_open")] == [
            t.type for t in parse(md.replace(mdtext(value), "x")) if t.type.endswith("_open")
        ], md  # no block or emphasis of its own
    assert text_of(mdtext(value)) == " ".join(value.split()).replace("\u2028", "\\u2028")


@pytest.mark.parametrize("value", HOSTILE)
def test_mdspan_is_one_code_span_holding_the_value(value: str) -> None:
    md = f"Run {mdspan(value)} now."
    assert not injected(md), (md, injected(md))
    spans = [t.content for t in parse(md) if t.type == "code_inline"]
    shown = value.replace("\n", "\\n").replace("\u2028", "\\u2028")
    assert spans == [shown], (md, spans)


@pytest.mark.parametrize("value", HOSTILE)
def test_mdcell_and_mdcode_stay_in_their_cell(value: str) -> None:
    md = f"| a | b | c |\n|---|---|---|\n| {mdcell(value)} | {mdcode(value)} | end |\n"
    assert not injected(md), (md, injected(md))
    cells = [t for t in parse(md) if t.type == "td_open"]
    assert len(cells) == 3, md
    inline = [t for t in parse(md) if t.type == "inline"][-3:]
    assert inline[2].content == "end"
    code = [c.content for c in inline[1].children or () if c.type == "code_inline"]
    shown = value.replace("\n", "\\n").replace("\u2028", "\\u2028")
    assert code == [shown], (md, code)
    assert "".join(c.content for c in inline[0].children or () if c.type == "text") == " ".join(value.split()), md


@pytest.mark.parametrize("value", HOSTILE)
def test_mdfence_holds_any_text(value: str) -> None:
    body = f"line one\n{value}\n```\n~~~\n{value}"
    md = "\n".join(mdfence(body, "text")) + "\nafter\n"
    assert not injected(md), (md, injected(md))
    fences = [t for t in parse(md) if t.type == "fence"]
    assert len(fences) == 1 and fences[0].content == body + "\n" and fences[0].info == "text"


@pytest.mark.parametrize("value", NO_SPACES)
def test_mddest_keeps_a_link_to_the_file(value: str) -> None:
    md = f"[{mdtext(value)}]({mddest(value)})"
    links = [t for t in parse(md) if t.type == "link_open"]
    assert len(links) == 1 and len(injected(md)) == 1, md  # the one link descgen wrote
    from urllib.parse import unquote

    assert unquote(links[0].attrs["href"]) == value.replace("\u2028", "\\u2028"), md


def test_plain_names_print_as_they_always_did() -> None:
    """The committed evidence does not change: a plain name gets no escape it did not have."""
    assert mdtext("warehouse_arm") == "warehouse_arm"
    assert mdtext("urdf/warehouse_arm.urdf") == "urdf/warehouse_arm.urdf"
    assert mdspan("descgen report specs/warehouse_arm.yaml") == "`descgen report specs/warehouse_arm.yaml`"
    assert mdcode("tool_link") == "`tool_link`"
    assert mdcell("robot_state_publisher") == "robot\\_state\\_publisher"
    assert mddest("../urdf/warehouse_arm.urdf") == "../urdf/warehouse_arm.urdf"
    assert mdfence("a\nb", "text") == ["```text", "a", "b", "```", ""]


# -- the templates: hostile link and joint names ----------------------------------------------

# what the schema allows in a link or joint name (no whitespace, no $): each Markdown trick
NAME = "tl`<img/src=x/onerror=alert(1)>`|[x](javascript:alert(1))&amp;*_#"


def _hostile_robot(tmp_path: Path) -> Any:
    from descgen.audit.spec import load_spec

    text = SPEC.read_text(encoding="utf-8")
    text = text.replace("tool_link", '"' + NAME.replace("\\", "\\\\") + '"')
    text = text.replace("source: K3", 'source: "K3 <img src=x onerror=alert(1)> [x](y) `"')
    spec = tmp_path / "arm.yaml"
    spec.write_text(text, encoding="utf-8")
    loaded = load_spec(spec)
    assert any(lk.name == NAME for lk in loaded.robot.links)
    return loaded.robot


OWN_COMMENTS = ("<!-- generated from", "<!-- descgen spec-sha256=", "<!-- sweep input-sha256=")


@pytest.mark.slow
def test_generated_markdown_holds_hostile_names_as_text(tmp_path: Path, pin: Any) -> None:
    from dataclasses import replace

    from descgen.meshes.paths import package_name
    from descgen.physics import collision
    from descgen.prove import sweep as sweep_evidence
    from descgen.render import render_package

    robot = _hostile_robot(tmp_path)
    sem = robot.semantic
    assert sem is not None and sem.collision_matrix is not None
    urdf = render_package(robot, "arm.yaml", only={f"urdf/{robot.name}.urdf"})[f"urdf/{robot.name}.urdf"]
    matrix = collision.compute(robot, urdf, {}, package_name(robot), sem.collision_matrix, None, False)
    robot = replace(robot, semantic=replace(sem, matrix=matrix))  # as generate does
    files = render_package(robot, f"a`{IMG}`.yaml", sweep=sweep_evidence.context)
    md = {rel: text for rel, text in files.items() if rel.endswith(".md")}
    assert set(md) >= {f"evidence/{n}.md" for n in ("known_poses", "frames", "collision_matrix", "sweep")}
    for rel, text in md.items():
        assert not injected(text, OWN_COMMENTS), (rel, injected(text, OWN_COMMENTS))
    # the name is in the tables as code, whole: not split into cells, not cut short
    codes = [t.content for t in parse(md["evidence/known_poses.md"]) if t.type == "code_inline"]
    assert NAME.replace("|", "\\|") in codes or NAME in codes, codes


# -- the evidence page: the spec's file name ----------------------------------------------------


def test_the_evidence_page_holds_a_hostile_spec_file_name_as_text(tmp_path: Path) -> None:
    from descgen.audit.spec import load_spec
    from descgen.commands import evidence_page
    from descgen.prove import CHECKS
    from descgen.render import render_package

    (tmp_path / "specs").mkdir()
    name = f"a`{IMG}`.yaml"
    spec = tmp_path / "specs" / name
    spec.write_text(SPEC.read_text(encoding="utf-8"), encoding="utf-8")
    shown = f"specs/{name}"
    robot = load_spec(spec, display=shown).robot
    files = render_package(robot, name)
    package = tmp_path / "generated" / "warehouse_arm_description"
    package.mkdir(parents=True)
    proofs: list[tuple[str, list[Any]]] = [(check_name, []) for check_name, _ in CHECKS]
    page = evidence_page.build(spec, shown, files, robot, package, ("", ""), 0, False, proofs)
    bad = [b for b in injected(page) if not re.fullmatch(r"image: \{'src': 'poses/\w+\.png', 'alt': ''\}", b)]
    assert not bad, bad
    # the command is one code span, with the whole file name in it
    spans = [t.content for t in parse(page) if t.type == "code_inline"]
    assert f"descgen report {shown}" in spans, spans


# -- the control evidence: lifecycle.md and interfaces.md -------------------------------------


@pytest.mark.slow
def test_control_evidence_holds_a_hostile_joint_name_as_text(tmp_path: Path, pin: Any) -> None:
    from tests.helpers import cli

    # no "/": ros2_control names an interface "<joint>/<interface>"
    joint = "lw<script>|[x](javascript:alert(1))```&amp;"
    (tmp_path / "specs" / "trajectories").mkdir(parents=True)
    text = SPEC.read_text(encoding="utf-8").replace("left_wheel_joint", '"' + joint + '"')
    (tmp_path / "specs" / "arm.yaml").write_text(text, encoding="utf-8")
    trajectory = (ROOT / "specs" / "trajectories" / "ready.yaml").read_text(encoding="utf-8")
    (tmp_path / "specs" / "trajectories" / "ready.yaml").write_text(trajectory, encoding="utf-8")
    generated = cli("generate", "specs/arm.yaml", cwd=tmp_path)
    assert generated.returncode == 0, generated.stderr[-2000:]
    out = tmp_path / "run"
    ran = cli("control", "specs/arm.yaml", "--trajectory", "specs/trajectories/ready.yaml", "--out", out, cwd=tmp_path)
    assert ran.returncode == 0 and "Traceback" not in ran.stderr, ran.stderr[-2000:]
    lifecycle = (out / "lifecycle.md").read_text(encoding="utf-8")
    interfaces = (out / "interfaces.md").read_text(encoding="utf-8")
    for md in (lifecycle, interfaces):
        assert not injected(md), injected(md)
    # the claims table keeps its four columns on every row, the hostile joint's included
    rows = [t for t in parse(lifecycle) if t.type == "tr_open"]
    cells = [t for t in parse(lifecycle) if t.type in ("td_open", "th_open")]
    assert len(cells) == 4 * len(rows)
    # both listings stay code: the joint's interfaces are inside a fence, whole
    blocks = [t.content for t in parse(interfaces) if t.type == "fence"]
    assert len(blocks) == 2 and f"{joint}/velocity" in blocks[0]
