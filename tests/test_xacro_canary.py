"""No spec or imported text runs as code when the generated packages are expanded by the REAL
xacro (issue 34, items 1 and 2): the description's Xacro (what display.launch.py runs), the
MoveIt package's SRDF and its URDF Xacro (what MoveItConfigsBuilder loads, both through
``xacro.process_file``).

The payloads are ones that do run code in the installed xacro (2.1.1), proven first on a raw
Xacro (the positive control below): xacro refuses names starting with ``__`` and ends a
``$(...)`` at the first ``)``, so the classic ``__import__`` payloads would prove nothing.
Each payload touches a canary file; after every expansion no canary may exist. A hostile
value is either refused by ``validate``/``generate`` (exit 2, with a line) or expanded by
xacro into the same text it was in the spec.

The fuzzer at the end plants them in every free-text field of specs/warehouse_arm.yaml
(fixed seed, a bounded sample), in pass-through XML, SRDF reasons and an imported URDF/SRDF.
"""

from __future__ import annotations

import random
import secrets
import shutil
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml
from lxml import etree

from descgen.commands.generate import plan
from descgen.core.findings import InputError

from .helpers import EXAMPLE_TEXT, ROOT, cli, get_at, set_at, string_leaves

XACRO_NS = "http://www.ros.org/wiki/xacro"


# --------------------------------------------------------------------------- payloads


def expr_payload(canary: Path) -> str:
    """``${...}`` that creates ``canary`` through xacro's exposed ``python.vars``/``python.type``
    (no name starting with ``__``, no ``}``; short enough for a 200-character field)."""
    return (
        f"${{[p('{canary}').touch() for s in [python.vars(python.type)['__subclasses__']] "
        "for c in s(python.type(0).mro()[1]) if 'PurePath' in python.repr(c) "
        "for p in s(c) if '.Path' in python.repr(p)]}"
    )


def eval_payload(canary: Path) -> str:
    """``$(eval ...)`` that creates ``canary`` with the builtin ``open`` (``$(eval)`` evaluates
    with the real builtins); the call's ``)`` comes from a nested ``${}``, since a ``$(...)``
    ends at the first ``)``."""
    return f"$(eval open('{canary}','w'${{'\\x29'}})"


def payloads(canary: Path) -> list[str]:
    e, v = expr_payload(canary), eval_payload(canary)
    # each at most 200 characters (an SRDF reason's bound)
    return [e, v, "$" + e, "$" + v, "$$" + v, f"a {v} b ${{1+1}} c", "$", "$$", "$x", "$$x", "${", "$(", "}", ")"]


@pytest.fixture
def canary() -> Iterator[Path]:
    # a short folder of its own (the payload must fit a 200-character field), named without
    # '__' ($(eval) refuses any '__' in its text)
    folder = Path(tempfile.gettempdir()) / f"c{secrets.token_hex(3)}"  # hex: never "__"
    folder.mkdir(mode=0o700)
    path = folder / "C"
    assert "__" not in str(path) and ")" not in str(path) and "}" not in str(path)
    try:
        yield path
        assert not path.exists(), "a generated file ran code when xacro expanded it"
    finally:
        shutil.rmtree(folder, ignore_errors=True)


# --------------------------------------------------------------------------- the real xacro


def real_xacro(path: Path, packages: dict[str, Path], args: dict[str, str] | None = None) -> etree._Element:
    """``path`` expanded by xacro's own ``process_file`` (no sandbox), ``$(find)`` answered
    from ``packages`` as ament_index would in an install space."""
    import xacro
    import xacro.substitution_args as sa

    old = sa._eval_find
    sa._eval_find = lambda pkg: str(packages[pkg])
    try:
        doc = xacro.process_file(str(path), mappings=dict(args or {}))
    finally:
        sa._eval_find = old
    return etree.fromstring(doc.toxml().encode("utf-8"), etree.XMLParser(remove_blank_text=True))


def test_the_payloads_run_code_in_the_real_xacro(tmp_path: Path) -> None:
    """Positive control: each payload, written raw where xacro evaluates (an attribute, a text,
    a comment after ``xacro:eval-comments``), creates its canary, so a test that finds no canary
    after expanding a generated file means the file kept the payload inert."""
    for i, where in enumerate(["attr", "text", "comment"]):
        for j, make in enumerate([expr_payload, eval_payload]):
            canary = tmp_path / f"c{i}{j}"
            p = make(canary).replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")
            body = {
                "attr": f'<a v="{p}"/>',
                "text": f"<a>{p}</a>",
                "comment": f"<a><!-- xacro:eval-comments --><!-- {make(canary)} --></a>",
            }[where]
            src = tmp_path / f"t{i}{j}.xacro"
            src.write_text(f'<robot name="r" xmlns:xacro="{XACRO_NS}"><link name="l"/>{body}</robot>')
            real_xacro(src, {})
            assert canary.exists(), (where, make.__name__)


# --------------------------------------------------------------------------- generate, then expand


def write_spec(folder: Path, text: str) -> Path:
    (folder / "specs").mkdir(parents=True, exist_ok=True)
    spec = folder / "specs" / "robot.yaml"
    spec.write_text(text, encoding="utf-8")
    return spec


def small_matrix(text: str) -> str:
    # the fuzz is about escaping, sampling is tests/test_collision_matrix.py's
    return text.replace("samples: 10000", "samples: 100")


def generate_files(spec: Path, proven: bool = True) -> tuple[dict[str, str], dict[str, str], str] | None:
    """(description files, MoveIt files, robot name), or None when the spec is refused; a
    refusal must say where. ``proven``: every check passed (a spec validate accepts is one
    generate writes)."""
    try:
        p = plan(spec, spec.parent.parent / "generated")
    except InputError as exc:
        assert exc.findings and all(f.where is not None and f.where.file for f in exc.findings), exc.findings
        return None
    if proven:
        assert not [f for f in p.findings if f.severity == "error"], [f for f in p.findings if f.severity == "error"]
    return p.files, p.moveit_files, p.robot.name


def expand_all(
    folder: Path, description: dict[str, str], moveit: dict[str, str], robot: str, variants: tuple[str, ...] = ()
) -> dict[str, etree._Element]:
    """Lay both packages out and expand with the real xacro what ROS expands: the description's
    Xacro (each hardware variant asked for), the MoveIt package's SRDF and URDF Xacro."""
    desc, cfg = folder / f"{robot}_description", folder / f"{robot}_moveit_config"
    for root, files in ((desc, description), (cfg, moveit)):
        for rel, text in files.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text, encoding="utf-8")
    packages = {desc.name: desc, cfg.name: cfg}
    out = {"xacro": real_xacro(desc / "urdf" / f"{robot}.urdf.xacro", packages)}
    for v in variants:
        out[f"xacro:{v}"] = real_xacro(desc / "urdf" / f"{robot}.urdf.xacro", packages, {"hardware": v})
    if moveit:
        out["srdf"] = real_xacro(cfg / "config" / f"{robot}.srdf", packages)
        if f"config/{robot}.urdf.xacro" in moveit:
            out["moveit_urdf"] = real_xacro(cfg / "config" / f"{robot}.urdf.xacro", packages)
    return out


def plain_xml(text: str) -> etree._Element:
    return etree.fromstring(text.encode("utf-8"), etree.XMLParser(remove_blank_text=True))


# --------------------------------------------------------------------------- pass-through XML


def passthrough_cases(canary: Path) -> dict[str, str]:
    e, v = expr_payload(canary), eval_payload(canary)
    ea, va = (x.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;") for x in (e, v))
    return {
        "attribute": f'<gazebo reference="{ea}"><a b="{va}"/></gazebo>',
        "text": f"<gazebo><material>{e}</material><m>{v}</m></gazebo>",
        "tail": f"<gazebo><a/>{e}<b/>{v}</gazebo>",
        "eval-comments": f"<gazebo><!-- xacro:eval-comments --><!-- {e} --><!--{v}--></gazebo>",
        "eval-comments-nested": f"<gazebo><plugin><!--xacro:eval-comments--><!--{v}--></plugin></gazebo>",
        "dollar-dollar": f'<gazebo a="${ea}" b="$${va}"><c>$${e}</c>$$</gazebo>',
        "character-reference": "<gazebo><a>&#36;{x}</a><b c='&#36;&#40;eval 1&#41;'/></gazebo>",
        "processing-instruction": f"<gazebo><?pi {e} ?><a/></gazebo>",
        # outside the element (found by the independent check of issue 34): validated too
        "xml-declaration": '<?xml version="1.0"?><gazebo/>',
        "stylesheet-before": '<?xml-stylesheet href="x"?><gazebo/>',
        "eval-comments-before": f"<!-- xacro:eval-comments --><!-- {e} --><gazebo/>",
        "cdata": f"<gazebo><![CDATA[{e}]]></gazebo>",
        "xacro-element": f'<gazebo xmlns:xacro="{XACRO_NS}"><xacro:if value="true"><a>{e}</a></xacro:if></gazebo>',
        "xacro-include": f'<gazebo xmlns:xacro="{XACRO_NS}"><xacro:include filename="{canary}.xacro"/></gazebo>',
        "other-prefix": f'<gazebo xmlns:x="{XACRO_NS}"><x:element x:name="a"/></gazebo>',
        "default-namespace": f'<gazebo xmlns="{XACRO_NS}"><a/></gazebo>',
        "xacro-prefix-elsewhere": '<gazebo xmlns:xacro="urn:x"><a xacro:if="false"/></gazebo>',
        "xacro-attribute": f'<gazebo xmlns:xacro="{XACRO_NS}" xacro:targetNamespace="urn:y"><a/></gazebo>',
    }


REFUSED = {
    "processing-instruction",  # pinocchio's urdfdom (tinyxml2) refuses the URDF
    "xml-declaration",
    "stylesheet-before",
    "eval-comments-before",
    "eval-comments",
    "eval-comments-nested",
    "cdata",
    "xacro-element",
    "xacro-include",
    "other-prefix",
    "default-namespace",
    "xacro-prefix-elsewhere",
    "xacro-attribute",
}


def _with_passthrough(xml: str, variants: bool) -> str:
    text = small_matrix(EXAMPLE_TEXT)
    if not variants:  # the example has hardware variants: without them, the default Xacro only
        start = text.index("    variants:\n")
        end = text.index("  update_rate:")
        text = text[:start] + text[end:]
    return text + "\npassthrough:\n  - xml: " + yaml.safe_dump(xml, width=2**31).removesuffix("\n...\n").strip() + "\n"


def _canonical(e: etree._Element) -> Any:
    """An element as data: tag, attributes, text and children (comments and PIs as such)."""
    if not isinstance(e.tag, str):
        return (str(type(e).__name__), e.text or "", (e.tail or "").strip())
    return (
        e.tag,
        sorted(e.attrib.items()),
        (e.text or "").strip(),
        [_canonical(c) for c in e],
        (e.tail or "").strip(),
    )


@pytest.mark.parametrize("case", list(passthrough_cases(Path("/x"))))
def test_pass_through_is_refused_or_expands_to_itself(case: str, canary: Path, tmp_path: Path) -> None:
    """Every hostile pass-through element: ``validate`` refuses it on its line, or the real
    xacro expands the generated Xacro (every hardware variant) to the element as written."""
    xml = passthrough_cases(canary)[case]
    spec = write_spec(tmp_path, _with_passthrough(xml, variants=True))
    made = generate_files(spec)
    if case in REFUSED:
        # xacro would act on it (comment evaluation, a xacro: name), lxml and minidom disagree
        # on it (CDATA) or pinocchio refuses it (a PI): refused at validate, on the pass-through's line
        with pytest.raises(InputError) as exc:
            plan(spec, tmp_path / "generated")
        (f,) = exc.value.findings
        assert f.code == "IMP010" and f.where.line == spec.read_text().splitlines().index("passthrough:") + 2
        return
    assert made is not None
    files, moveit, robot = made
    docs = expand_all(tmp_path / "out", files, moveit, robot, ("gazebo", "real"))
    want = plain_xml(xml)
    for name, doc in docs.items():
        if name == "srdf":
            continue
        got = [e for e in doc if e.tag == want.tag and "gz_ros2_control" not in etree.tostring(e, encoding="unicode")]
        assert len(got) == 1, name
        # comments aside (xacro drops an eval-comments switch), the element is the spec's
        strip = etree.XMLParser(remove_blank_text=True, remove_comments=True)
        assert _canonical(etree.fromstring(etree.tostring(got[0]), strip)) == _canonical(
            etree.fromstring(xml.encode(), strip)
        ), name


def test_pass_through_with_hardware_variants_generates(tmp_path: Path) -> None:
    """Item 12: a plain pass-through element in a spec with hardware variants validates, so
    generate writes it (the gazebo variant's sim plugin and the element both)."""
    spec = write_spec(tmp_path, _with_passthrough('<transmission name="t"><type>x</type></transmission>', True))
    p = plan(spec, tmp_path / "generated")
    assert not [f for f in p.findings if f.severity == "error"], p.findings


def test_a_material_listed_twice_is_refused_by_validate(tmp_path: Path) -> None:
    """Item 12: urdfdom refuses repeated robot-level materials, so generate failed (GEN070, in
    pinocchio's URDF reader) on a spec validate accepted: validate refuses it at the second entry."""
    entry = "  - {name: sensor_blue, rgba: [0.10, 0.25, 0.60, 1.0]}\n"
    text = small_matrix(EXAMPLE_TEXT).replace(entry, entry + entry, 1)
    spec = write_spec(tmp_path, text)
    ran = cli("validate", spec)
    line = text.splitlines().index(entry.rstrip("\n")) + 2
    assert ran.returncode == 2 and f"{spec}:{line}:5: error[SPEC026]" in ran.stderr, ran.stderr


# --------------------------------------------------------------------------- SRDF reasons


def _with_reason(reason: str) -> str:
    pair = (
        "  disable_collisions:\n    - {link1: base_link, link2: camera_link, reason: "
        + yaml.safe_dump(reason, width=2**31, default_style='"').strip().removesuffix("\n...")
        + "}\n"
    )
    return small_matrix(EXAMPLE_TEXT).replace("  group_states:\n", pair + "  group_states:\n", 1)


@pytest.mark.parametrize("which", range(14))
def test_srdf_reason_stays_a_reason_for_moveit(which: int, canary: Path, tmp_path: Path) -> None:
    """Item 2: a ``disable_collisions`` reason reaches config/<robot>.srdf, which
    MoveItConfigsBuilder expands with xacro: it must expand to the reason as written."""
    reason = payloads(canary)[which]
    spec = write_spec(tmp_path, _with_reason(reason))
    made = generate_files(spec)
    assert made is not None  # a reason is free text: written escaped for xacro, never refused
    files, moveit, robot = made
    docs = expand_all(tmp_path / "out", files, moveit, robot)
    for srdf in (docs["srdf"], plain_xml(files[f"srdf/{robot}.srdf"])):
        (pair,) = [
            d
            for d in srdf.iter("disable_collisions")
            if {d.get("link1"), d.get("link2")} == {"base_link", "camera_link"}
        ]
        assert pair.get("reason") == reason


# --------------------------------------------------------------------------- import


TINY = """<?xml version="1.0"?>
<robot name="tiny">
  <link name="base_link">
    <inertial><mass value="2.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
  </link>
  <link name="arm">
    <collision><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision>
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0005"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="40" velocity="1.5"/>
  </joint>
  GAZEBO
</robot>
"""

TINY_SRDF = """<?xml version="1.0"?>
<robot name="tiny">
  <group name="arm"><chain base_link="base_link" tip_link="arm"/></group>
  <disable_collisions link1="base_link" link2="arm" reason="REASON"/>
</robot>
"""


def test_an_imported_urdf_and_srdf_stay_data(canary: Path, tmp_path: Path) -> None:
    """The same through ``descgen import``: text inert in a plain URDF (a ``<gazebo>`` element)
    and in an SRDF reason must stay inert in the Xacro and the MoveIt SRDF descgen writes."""
    e, v = expr_payload(canary), eval_payload(canary)
    ea, va = (x.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;") for x in (e, v))
    switch = "<!--xacro:eval-comments-->"
    gazebo = f'<gazebo reference="{ea}"><material>{e}</material><a b="{va}"/>{switch}<!--{v}--></gazebo>'
    gazebo2 = f"<gazebo><plugin>{v}</plugin><!-- {e} --></gazebo>"
    urdf = tmp_path / "tiny.urdf"
    urdf.write_text(TINY.replace("GAZEBO", gazebo + "\n  " + gazebo2))
    srdf = tmp_path / "tiny.srdf"
    srdf.write_text(TINY_SRDF.replace("REASON", va))
    project = tmp_path / "project"
    (project / "specs").mkdir(parents=True)
    spec = project / "specs" / "tiny.yaml"
    ran = cli("import", urdf, "--srdf", srdf, "-o", spec)
    assert ran.returncode in (0, 2), ran.stderr
    if ran.returncode == 2:
        assert ":" in ran.stderr  # a located refusal
        return
    data = yaml.safe_load(spec.read_text())
    # the eval-comments switch is not kept (IMP004: a warning), the other element is
    assert [p["xml"].startswith("<gazebo><plugin>") for p in data["passthrough"]] == [True]
    assert "<gazebo> is not kept" in ran.stderr
    # the MoveIt package too (its planning joint needs an acceleration limit): the imported
    # SRDF reason reaches config/tiny.srdf
    data["moveit"] = {}
    data["joints"][0]["limit"]["acceleration"] = "1 rad/s^2"
    spec.write_text(yaml.safe_dump(data, sort_keys=False))
    made = generate_files(spec)
    assert made is not None
    files, moveit, robot = made
    docs = expand_all(tmp_path / "out", files, moveit, robot)
    (plugin,) = docs["xacro"].iter("plugin")
    assert plugin.text == v
    (pair,) = docs["srdf"].iter("disable_collisions")
    assert pair.get("reason") == v


def test_xacro_document_expands_back_to_itself(canary: Path, tmp_path: Path) -> None:
    """The MoveIt SRDF's escape (render.formatting.xacro_document), on every place a ``$`` can
    be: double- and single-quoted attributes, text, a comment (with the eval-comments switch),
    a processing instruction and CDATA; the real xacro gives back the same document."""
    from descgen.render.formatting import xacro_document

    e, v = expr_payload(canary), eval_payload(canary)
    ea, va = (x.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;") for x in (e, v))
    va = va.replace("'", "&#39;")  # in a single-quoted attribute
    doc = (
        f'<?xml version="1.0"?>\n<robot name="r"><a b="{ea}" c=\'{va}\'>{e}$$</a><!-- xacro:eval-comments -->'
        f"<!-- {v} --><?pi {e} ?><d><![CDATA[{e}]]></d>$</robot>"
    )
    src = tmp_path / "r.srdf"
    src.write_text(xacro_document(doc))
    got = real_xacro(src, {})
    want = plain_xml(doc)
    assert [(x.tag, dict(x.attrib), x.text) for x in got.iter("a")] == [
        (x.tag, dict(x.attrib), x.text) for x in want.iter("a")
    ]
    assert got.findtext("d") == e and (got[-1].tail or "").strip() == "$"
    assert xacro_document("<robot/>") == "<robot/>"  # nothing to escape: the same text


# --------------------------------------------------------------------------- the fuzzer


def _extended_example() -> dict[str, Any]:
    """The example spec with every free-text field the example leaves out filled in: a
    disabled pair's reason, a pass-through element, a visual's name, a texture, a hardware
    parameter, a controller parameter."""
    data = yaml.safe_load(small_matrix(EXAMPLE_TEXT))
    data["semantic"]["disable_collisions"] = [{"link1": "base_link", "link2": "camera_link", "reason": "User"}]
    data["passthrough"] = [{"xml": "<gazebo reference='base_link'><material>Gazebo/Grey</material></gazebo>"}]
    data["links"][1]["visual"][0]["name"] = "chassis"
    data["materials"][3]["texture"] = "tex.png"
    data["ros2_control"]["hardware"]["params"] = {"note": "n"}
    data["ros2_control"]["controllers"][1]["params"]["note"] = "n"
    return data


FREE_TEXT = {"description", "source", "reason", "xml", "maintainer", "license", "email", "texture", "note", "version"}


def test_fuzz_hostile_text_never_runs_in_the_real_xacro(canary: Path, tmp_path: Path) -> None:
    """Fixed seed, bounded (16 leaves, about 10 s): a payload in a free-text field of
    the example spec (appended, replacing, or inside the pass-through XML) is refused with a
    line or never runs when xacro expands the packages."""
    rng = random.Random(34)
    base = _extended_example()
    leaves = string_leaves(base)
    # free text (what no name pattern guards) above all, and a few of the other strings
    free = [p for p in leaves if p[-1] in FREE_TEXT or p[-2:-1] == ("source",) or p[:1] == ("materials",)]
    chosen = rng.sample(free, k=min(12, len(free)))
    chosen += rng.sample([p for p in leaves if p not in free], k=4)
    # the fields that reach the files xacro expands: always among them
    for must in (("passthrough", 0, "xml"), ("semantic", "disable_collisions", 0, "reason"), ("description",)):
        if must not in chosen:
            chosen.append(must)
    hostile = payloads(canary)
    start = time.process_time()
    for n, leaf in enumerate(chosen):
        payload = rng.choice(hostile[:6])
        data = yaml.safe_load(yaml.safe_dump(base))
        if leaf[0] == "passthrough":
            pe = payload.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")
            comment = payload.replace("--", "- -")
            # a comment too, inert without the eval-comments switch (which is refused: see above)
            value = f'<gazebo a="{pe}"><b>{pe}</b><!--{comment}--></gazebo>'
        else:
            value = get_at(data, leaf) + " " + payload if rng.random() < 0.5 else payload
        set_at(data, leaf, value)
        folder = tmp_path / f"f{n}"
        spec = write_spec(folder, yaml.safe_dump(data, allow_unicode=True, sort_keys=False))
        # expanded even when a check failed: the text must be inert whatever generate decides
        made = generate_files(spec, proven=False)
        if made is not None:
            files, moveit, robot = made
            expand_all(folder / "out", files, moveit, robot)
        assert not canary.exists(), leaf
    assert time.process_time() - start < 30, "the fuzz is bounded"


def test_the_committed_example_expands_in_the_real_xacro() -> None:
    """The committed packages expand with the real xacro too (nothing escaped twice)."""
    gen = ROOT / "generated"
    desc, cfg = gen / "warehouse_arm_description", gen / "warehouse_arm_moveit_config"
    packages = {desc.name: desc, cfg.name: cfg}
    real_xacro(desc / "urdf" / "warehouse_arm.urdf.xacro", packages)
    srdf = real_xacro(cfg / "config" / "warehouse_arm.srdf", packages)
    assert srdf.find("disable_collisions") is not None
