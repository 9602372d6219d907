"""The fast paths of rendering and read-back at 1000 links (issue 17) give the answers of the
paths they skip: xmlcompare's equal-tree pass and lazy path against the element walk it
replaced (kept here as the reference), the read-back reader's one-match vectors against hand
values and urdfdom's refusals, proof 2's plain-float matrices against numpy's ``allclose``
and against planted faults, and the formatting caches against independent references
(``unicodedata``, ``float`` parsing)."""

from __future__ import annotations

import math
import random
import re
import sys
import unicodedata
from pathlib import Path

import numpy as np
import pytest
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.core.xmlcompare import first_difference, parse, same_value
from descgen.prove.urdf_roundtrip import _rows_close, urdf_roundtrip
from descgen.read import urdf_readback as rb
from descgen.render import formatting, render_package

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from synthetic import chain_spec

from .conftest import EXAMPLE

ROBOT = load_spec(EXAMPLE).robot
FILES = render_package(ROBOT, "specs/warehouse_arm.yaml")
URDF = FILES["urdf/warehouse_arm.urdf"]


# -- xmlcompare: the walk it was, as the reference ---------------------------------------


def _reference(a: etree._Element, b: etree._Element, path: str = "") -> str | None:
    """xmlcompare.first_difference before the fast paths (eager labels, no equal-tree pass)."""

    def label(e: etree._Element) -> str:
        name = e.get("name")
        return f"{e.tag!s}[@name='{name!s}']" if name is not None else str(e.tag)

    here = f"{path}/{label(a)}"
    if a.tag != b.tag:
        return f"{here}: element <{a.tag}> vs <{b.tag}>"
    for k in sorted(set(a.attrib) | set(b.attrib)):
        va, vb = a.get(k), b.get(k)
        if va is None or vb is None:
            return f"{here}/@{k!s}: present only in {'first' if vb is None else 'second'}"
        if not same_value(str(va), str(vb)):
            return f"{here}/@{k!s}: {va!r} vs {vb!r}"
    ta, tb = (a.text or "").strip(), (b.text or "").strip()
    if not same_value(ta, tb):
        return f"{here}/text(): {ta!r} vs {tb!r}"
    ca = [c for c in a if isinstance(c.tag, str)]
    cb = [c for c in b if isinstance(c.tag, str)]
    for x, y in zip(ca, cb, strict=False):
        diff = _reference(x, y, here)
        if diff:
            return diff
    if len(ca) != len(cb):
        extra = (ca if len(ca) > len(cb) else cb)[min(len(ca), len(cb))]
        return f"{here}: {label(extra)} present only in {'first' if len(ca) > len(cb) else 'second'}"
    return None


def _edits() -> list[tuple[str, str]]:
    """(name, edited URDF): one change each, of every kind the walk reports or must ignore."""
    joint = '<joint name="lift_joint"'
    assert joint in URDF
    out = [
        ("unchanged", URDF),
        ("number written otherwise", URDF.replace('rpy="0 0 0"', 'rpy="0.0 0 0e0"', 1)),
        ("number changed", URDF.replace('rpy="0 0 0"', 'rpy="0 0 0.001"', 1)),
        ("attribute added", URDF.replace(joint, joint + ' extra="1"', 1)),
        ("attribute removed", URDF.replace(' type="prismatic"', "", 1)),
        (
            "attributes reordered",
            URDF.replace('name="lift_joint" type="prismatic"', 'type="prismatic" name="lift_joint"'),
        ),
        ("tag renamed", URDF.replace("<mass ", "<masse ", 1)),
        ("element added", URDF.replace("</robot>", '  <link name="extra"/>\n</robot>')),
        ("element removed", URDF.replace('  <link name="base_footprint"/>\n', "", 1)),
        ("comment added", URDF.replace(joint, "<!-- note -->" + joint, 1)),
        ("processing instruction added", URDF.replace(joint, "<?pi x?>" + joint, 1)),
        ("layout changed", URDF.replace("\n    <", "\n\t\t<")),
        ("text added", URDF.replace("<mass ", "x<mass ", 1)),
    ]
    assert all(text != URDF for name, text in out[1:] if name != "unchanged")
    return out


@pytest.mark.parametrize(("name", "edited"), _edits(), ids=[n for n, _ in _edits()])
def test_first_difference_is_the_walks_answer(name: str, edited: str) -> None:
    a, b = parse(URDF), parse(edited)
    assert first_difference(a, b) == _reference(a, b)
    assert first_difference(b, a, "/x") == _reference(b, a, "/x")


def test_same_preorder_other_shape_is_a_difference() -> None:
    """Tags, attributes and texts equal node for node in document order, but another tree:
    the child counts tell them apart (an equal-tree pass without them would call them equal)."""
    a = parse("<r><a/><b/></r>")
    b = parse("<r><a><b/></a></r>")
    assert first_difference(a, b) == _reference(a, b) == "/r/a: b present only in second"


def test_first_difference_on_a_1000_link_chain_names_the_edited_joint(tmp_path: Path) -> None:
    spec = tmp_path / "chain.yaml"
    spec.write_text(chain_spec(1000, "chain"))
    urdf = render_package(load_spec(spec).robot, "chain.yaml")["urdf/chain.urdf"]
    edited = urdf.replace('<joint name="joint777" type="revolute">', '<joint name="joint777" type="prismatic">')
    assert edited != urdf
    a, b = parse(urdf), parse(edited)
    assert first_difference(a, parse(urdf)) is None
    want = "/robot[@name='chain']/joint[@name='joint777']/@type: 'revolute' vs 'prismatic'"
    assert first_difference(a, b) == _reference(a, b) == want


# -- the read-back reader's vectors ------------------------------------------------------


def _origin_of(xyz: str) -> rb.Matrix:
    visual = f'<visual><origin xyz="{xyz}"/><geometry><sphere radius="1"/></geometry></visual>'
    text = f'<robot name="r"><link name="a">{visual}</link></robot>'
    return rb.read(text).links[0].visuals[0].origin


@pytest.mark.parametrize(
    ("written", "want"),
    [
        ("1 2 3", (1.0, 2.0, 3.0)),
        ("  -1.5   +.25 3e2  ", (-1.5, 0.25, 300.0)),
        ("1&#9;2&#10;3", (1.0, 2.0, 3.0)),  # tab and newline kept by character references
        ("0.1 -0 7.", (0.1, 0.0, 7.0)),
    ],
)
def test_vectors_read_as_written(written: str, want: tuple[float, float, float]) -> None:
    origin = _origin_of(written)
    assert tuple(row[3] for row in origin[:3]) == want


@pytest.mark.parametrize(
    ("written", "message"),
    [
        ("1,5 2 3", "<origin> xyz is not a number: '1,5'"),
        ("nan 0 0", "<origin> xyz is not a number: 'nan'"),
        ("1 2 inf", "<origin> xyz is not a number: 'inf'"),
        ("1 2", "<origin> xyz needs 3 numbers, has 2: '1 2'"),
        ("1 2 3 4", "<origin> xyz needs 3 numbers, has 4: '1 2 3 4'"),
        ("0x1 2 3", "<origin> xyz is not a number: '0x1'"),
    ],
)
def test_vectors_urdfdom_refuses_stay_refused(written: str, message: str) -> None:
    with pytest.raises(rb.ReadbackError) as exc:
        _origin_of(written)
    assert str(exc.value) == message and exc.value.line == 1


# -- proof 2's matrices ------------------------------------------------------------------

EYE = tuple(tuple(float(v) for v in row) for row in np.eye(4))


@pytest.mark.parametrize(
    "other",
    [
        EYE,
        tuple(tuple(v + (0.9e-9 if i == j == 1 else 0.0) for j, v in enumerate(r)) for i, r in enumerate(EYE)),
        tuple(tuple(v + (1.1e-9 if i == j == 1 else 0.0) for j, v in enumerate(r)) for i, r in enumerate(EYE)),
        EYE[:3],
        tuple(r[:3] for r in EYE),
        ((math.inf, 0.0, 0.0, 0.0), *EYE[1:]),
        ((math.nan, 0.0, 0.0, 0.0), *EYE[1:]),
    ],
)
def test_rows_close_is_numpys_allclose(other: tuple[tuple[float, ...], ...]) -> None:
    for a, b in ((EYE, other), (other, EYE), (other, other)):
        x, y = np.asarray(a), np.asarray(b)
        want = x.shape == y.shape and bool(np.allclose(x, y, rtol=0, atol=1e-9))
        assert _rows_close(a, b) == want


def test_planted_faults_in_a_long_chain_are_found_where_planted(tmp_path: Path) -> None:
    """Every joint origin, link origin and inertia written wrong in a 60-link chain is one
    finding at that element and field; the clean file has none."""
    spec = tmp_path / "chain.yaml"
    spec.write_text(chain_spec(60, "chain"))
    robot = load_spec(spec).robot
    files = render_package(robot, "chain.yaml")
    rel = "urdf/chain.urdf"
    assert urdf_roundtrip(files, robot, tmp_path) == []
    root = etree.fromstring(files[rel].encode())
    planted: set[str] = set()
    for k, e in enumerate(root.iter("joint", "link")):
        name = e.get("name")
        if e.tag == "joint" and k % 3 == 0:
            e.find("origin").set("rpy", "0 0 0.2618")  # 15 deg is 0.2617993877991494
            planted.add(f"joint:{name}/origin")
        elif e.tag == "link" and k % 4 == 1:
            e.find("collision/origin").set("xyz", "0 0 0.0501")
            planted.add(f"link:{name}/collision[0]/origin")
        elif e.tag == "link" and k % 4 == 3:
            e.find("inertial/inertia").set("iyz", "1e-6")
            planted.add(f"link:{name}/inertial/inertia")
    bad = dict(files, **{rel: etree.tostring(root, encoding="unicode")})
    found = urdf_roundtrip(bad, robot, tmp_path)
    where = {re.search(r" differs at (.+?): model ", f.message).group(1) for f in found}  # type: ignore[union-attr]
    assert where == planted and len(found) == len(planted) > 30
    shown = next(f.message for f in found if "/inertial/inertia" in f.message)
    assert "model [[" in shown  # the model's tensor shown as the array it is


# -- formatting -------------------------------------------------------------------------


def test_num_reads_back_and_equal_keys_share_one_text() -> None:
    rng = random.Random(17)
    values = [rng.uniform(-10, 10) for _ in range(2000)] + [0.1, 1e-300, 123456789.0, 1e15, 2.0**53]
    for v in values * 2:  # the second pass answers from the cache
        text = formatting.num(v)
        assert float(text) == v and text == formatting.num(-v if v == 0 else v)
    assert formatting.num(-0.0) == formatting.num(0.0) == formatting.num(0) == "0"
    assert formatting.num(1) == formatting.num(1.0) == formatting.num(True) == "1"
    assert formatting.num(np.float64(0.5)) == "0.5" and formatting.num(np.array(0.25)) == "0.25"
    for bad in (math.nan, math.inf, -math.inf):
        for _ in range(2):
            with pytest.raises(ValueError, match="non-finite"):
                formatting.num(bad)


def test_vec_is_its_numbers_whatever_the_container() -> None:
    rng = random.Random(3)
    for _ in range(500):
        v = tuple(rng.choice([0.0, -0.0, 1, 0.05, rng.uniform(-1, 1)]) for _ in range(3))
        want = " ".join(repr(float(x)) if float(x) != int(x) else str(int(x)) for x in v)
        for _ in range(2):  # computed, then from the cache
            assert formatting.vec(v) == formatting.vec(list(v)) == want
    assert formatting.vec((1, 2.0, -0.0)) == formatting.vec((1.0, 2, 0.0)) == "1 2 0"
    for _ in range(2):
        with pytest.raises(ValueError, match="non-finite"):
            formatting.vec((0.0, math.nan, 1.0))


def test_num_cache_stays_bounded() -> None:
    for i in range(formatting._NUM_MAX + 10):
        assert formatting.num(i + 0.5) == repr(i + 0.5)
    assert len(formatting._NUM) <= formatting._NUM_MAX


def _visible_reference(s: str) -> str:
    hidden = {"Cc", "Cf", "Cs", "Zl", "Zp"}
    out = []
    for ch in s:
        if ch in "\n\t\r":
            out.append({"\n": "\\n", "\t": "\\t", "\r": "\\r"}[ch])
        elif unicodedata.category(ch) in hidden or ch in "\ufffe\uffff":
            c = ord(ch)
            out.append(f"\\x{c:02x}" if c < 0x100 else f"\\u{c:04x}" if c < 0x10000 else f"\\U{c:08x}")
        else:
            out.append(ch)
    return "".join(out)


def test_visible_escapes_every_hidden_character() -> None:
    for c in [*range(0x300), 0x2028, 0x2029, 0x200E, 0x202E, 0xFEFF, 0xFFFE, 0x1F916]:
        s = f"a{chr(c)}b"
        assert formatting.visible(s) == _visible_reference(s), hex(c)
    assert formatting.visible("plain_name-0.1") == "plain_name-0.1"


@pytest.mark.parametrize(
    ("name", "want"),
    [
        ("link0", "`link0`"),
        ("a`b", "``a`b``"),
        ("`x", "`` `x ``"),
        ("a|b", "`a\\|b`"),
        ("``", "``` `` ```"),
        ("é|`", "`` é\\|` ``"),
    ],
)
def test_mdcode_fences_by_the_longest_backtick_run(name: str, want: str) -> None:
    """CommonMark code spans: a fence longer than any backtick run inside, a space of padding
    when the text starts or ends with a backtick; GFM tables need ``|`` escaped."""
    assert formatting.mdcode(name) == want
