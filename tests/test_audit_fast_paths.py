"""The corpus audit's fast paths (issue 17: a cold audit toward check_urdf's pace) answer
exactly what the code they replaced answered.

Oracles: the replaced code, written out again here (the farthest-point loop, the mesh-shape
walk), the full robot span (extent._span, which the floor must never exceed), INER011 run
with the floor switched off (every link then goes to the full span, as before), and the URDF
reader with empty number caches (what each file got before the caches were kept across
files). Nothing is timed.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from descgen.audit.rules import inertia as inertia_rules
from descgen.audit.rules import meshes as mesh_rules
from descgen.core.findings import InputError
from descgen.core.model import (
    Box,
    Collision,
    Cylinder,
    Inertia,
    Inertial,
    Joint,
    Link,
    Mesh,
    Pose,
    Robot,
    Sphere,
    Visual,
)
from descgen.meshes import load as meshes
from descgen.meshes.facts import MeshFacts
from descgen.physics import extent
from descgen.physics.rigid import Vec, dot, norm
from descgen.read import urdf as urdf_reader

ROOT = Path(__file__).resolve().parents[1]

angle = st.floats(-7.0, 7.0, allow_nan=False)
coord = st.floats(-2.0, 2.0, allow_nan=False)
size = st.floats(0.001, 1.0, allow_nan=False)
vec = st.tuples(coord, coord, coord)
pose = st.builds(Pose, vec, st.tuples(angle, angle, angle))
primitive = st.one_of(
    st.builds(Box, st.tuples(size, size, size)),
    st.builds(Cylinder, size, size),
    st.builds(Sphere, size),
)
shape = st.one_of(st.builds(Visual, primitive, pose), st.builds(Collision, primitive, pose))


# -- the farthest point from an axis ---------------------------------------------------------------


def _farthest_before(hulls: list[extent.Hull], point: Vec, axis: Vec, indices: range) -> float:
    """extent.farthest_from_axis as it was written before it was unrolled."""
    best = 0.0
    for h in hulls:
        far = 0.0
        for p in extent.corners(h, indices):
            d = (p[0] - point[0], p[1] - point[1], p[2] - point[2])
            along = dot(d, axis)
            far = max(far, norm((d[0] - along * axis[0], d[1] - along * axis[1], d[2] - along * axis[2])))
        best = max(best, far + h.pad)
    return best


@settings(max_examples=300, deadline=None)
@given(
    st.lists(shape, min_size=1, max_size=5),
    vec,
    vec,
    st.sampled_from([range(64), extent._SAMPLED]),
    st.lists(st.integers(0, 4), max_size=4),
)
def test_the_unrolled_farthest_distance_is_the_same_float(
    shapes: list[Visual | Collision], point: Vec, axis: Vec, indices: range, repeats: list[int]
) -> None:
    hulls = [h for s in shapes if (h := extent.shape_hull(s)) is not None]
    with_repeats = hulls + [hulls[k % len(hulls)] for k in repeats]  # a visual and a collision alike
    want = _farthest_before(with_repeats, point, axis, indices)
    assert extent.farthest_from_axis(with_repeats, point, axis, indices) == want
    assert extent.farthest_from_axis(extent.distinct(with_repeats), point, axis, indices) == want


def test_distinct_keeps_the_first_of_each_hull_in_order() -> None:
    a, b = extent.shape_hull(Visual(Box((0.1, 0.2, 0.3)))), extent.shape_hull(Visual(Sphere(0.1)))
    assert a is not None and b is not None
    assert extent.distinct([a, b, a, b]) == [a, b]
    assert extent.distinct([a]) == [a]


# -- the span floor and INER011 --------------------------------------------------------------------


@st.composite
def trees(draw: st.DrawFn) -> Robot:
    """Small trees whose links carry primitives and meshes (a mesh sends INER011 to the span)."""
    n = draw(st.integers(1, 6))
    joints = []
    for k in range(n):
        parent = draw(st.integers(0, k))
        kind = draw(st.sampled_from(["revolute", "prismatic", "fixed"]))
        joints.append(Joint(f"j{k}", kind, f"l{parent}", f"l{k + 1}", draw(pose), (0.0, 0.0, 1.0)))
    links = []
    for k in range(n + 1):
        shapes = draw(st.lists(shape, max_size=3))
        if draw(st.booleans()):
            shapes.append(Visual(Mesh(f"package://p/m{k}.stl"), draw(pose)))
        visuals = tuple(s for s in shapes if isinstance(s, Visual))
        collisions = tuple(s for s in shapes if isinstance(s, Collision))
        links.append(Link(f"l{k}", visuals, collisions))
    return Robot("r", links=tuple(links), joints=tuple(joints))


@settings(max_examples=200, deadline=None)
@given(trees())
def test_the_span_floor_never_exceeds_the_span(robot: Robot) -> None:
    assert extent.span_floor(robot) <= extent._span(robot)


def _with_inertials(robot: Robot, ratios: list[float], masses: list[float]) -> Robot:
    """Each link given a tensor whose half trace is ``ratio`` times mass * span^2: around the
    rule's margin of 3, where the floor alone may and may not decide."""
    span = extent._span(robot)
    links = []
    for k, lk in enumerate(robot.links):
        m = masses[k % len(masses)]
        moment = ratios[k % len(ratios)] * m * span**2 * 2 / 3  # three equal moments: half trace = 1.5 moment
        links.append(
            Link(
                lk.name, lk.visuals, lk.collisions, Inertial(m, Pose(), Inertia(moment, 0.0, 0.0, moment, 0.0, moment))
            )
        )
    return Robot(robot.name, links=tuple(links), joints=robot.joints)


@settings(max_examples=200, deadline=None)
@given(
    trees(),
    st.lists(st.floats(0.5, 8.0), min_size=1, max_size=4),
    st.lists(st.floats(1e-3, 1e3), min_size=1, max_size=3),
)
def test_iner011_with_the_span_floor_reports_what_the_full_span_reports(
    bare: Robot, ratios: list[float], masses: list[float]
) -> None:
    robot = _with_inertials(bare, ratios, masses)
    fast = list(inertia_rules.inertia_too_large_for_size(robot))
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(inertia_rules, "span_floor", lambda r: 0.0)  # no floor: every link to the full span
        slow = list(inertia_rules.inertia_too_large_for_size(robot))
    assert fast == slow


def test_iner011_still_reports_a_link_the_floor_cannot_clear() -> None:
    # two links 1 m apart, the second with a mesh and a tensor 10x what its mass gives at that span
    mesh = Visual(Mesh("package://p/m.stl"))
    heavy = Inertial(1.0, Pose(), Inertia(10.0, 0.0, 0.0, 10.0, 0.0, 10.0))
    robot = Robot(
        "r",
        links=(Link("a"), Link("b", (mesh,), (), heavy)),
        joints=(Joint("j", "fixed", "a", "b", Pose((1.0, 0.0, 0.0))),),
    )
    found = list(inertia_rules.inertia_too_large_for_size(robot))
    assert [f.code for f in found] == ["INER011"]
    assert "(1: 1 m" in found[0].message  # the printed span is the robot's (1 m), hand computed
    assert "15 times" in found[0].message  # half trace 15 / (1 kg * 1 m^2)


# -- the measured mesh shapes of a robot -----------------------------------------------------------


def _shapes_before(robot: Robot, facts: dict[str, MeshFacts]) -> Iterator[tuple[object, ...]]:
    """rules/meshes.py's walk before it was gathered once per robot."""
    for lk in robot.links:
        for s in lk.shapes():
            g = s.geometry
            if isinstance(g, Mesh) and g.filename in facts:
                yield lk, s, g, facts[g.filename]


def test_mesh_shapes_are_the_walk_they_replace(monkeypatch: pytest.MonkeyPatch) -> None:
    measured = MeshFacts((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    broken = MeshFacts(problem="no triangles")
    facts = {"a.stl": measured, "b.dae": broken}  # c.obj did not resolve: no facts
    links = (
        Link("l0", (Visual(Mesh("a.stl")), Visual(Box((1.0, 1.0, 1.0)))), (Collision(Mesh("c.obj")),)),
        Link("l1"),
        Link("l2", (Visual(Mesh("b.dae")),), (Collision(Mesh("a.stl"), Pose((0.0, 0.0, 1.0))),)),
    )
    robot = Robot("r", links=links)
    monkeypatch.setattr(meshes, "facts_of_robot", lambda r: facts)
    got = meshes.mesh_shapes(robot)
    assert got == list(_shapes_before(robot, facts))
    assert len(got) == 3
    assert meshes.mesh_shapes(robot) is got  # gathered once for the rules that walk them
    other = Robot("r", links=links[:1])  # equal name, other links: not the first robot's list
    assert meshes.mesh_shapes(other) == list(_shapes_before(other, facts))
    monkeypatch.setattr(meshes, "facts_of_robot", lambda r: {})
    assert meshes.mesh_shapes(Robot("r", links=links)) == []


def test_the_union_of_one_box_is_that_box() -> None:
    box = ((-0.0, 1.0, -2.0), (0.5, 2.0, -1.0))
    assert mesh_rules._union([box]) == box
    two = mesh_rules._union([box, ((-1.0, 1.5, -3.0), (0.0, 1.8, 0.0))])
    assert two == ((-1.0, 1.0, -3.0), (0.5, 2.0, 0.0))  # by hand
    assert mesh_rules._union([box, None]) is None and mesh_rules._union([]) is None


# -- the URDF reader's number caches, kept across files --------------------------------------------


def _urdf(body: str) -> bytes:
    return f'<robot name="r"><link name="base"/>{body}</robot>'.encode()


A = _urdf(
    '<link name="a"><inertial><origin xyz="1 2 3" rpy="0 0 0.5"/><mass value="2.5"/>'
    '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
    '<joint name="j" type="revolute"><parent link="base"/><child link="a"/>'
    '<origin xyz="1 2 3" rpy="0 0 nan"/><limit lower="-1" upper="1" effort="1 2" velocity="2.5"/></joint>'
)
# the texts A read as valid numbers, here where they are wrong (3 numbers for one) or fine
B = _urdf(
    '<link name="b"><inertial><mass value="1 2 3"/><origin xyz="2.5" rpy="0 0 0.5"/>'
    '<inertia ixx="2.5" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
    '<joint name="k" type="fixed"><parent link="base"/><child link="b"/><origin xyz="1 2 3" rpy="0 0 nan"/></joint>'
)


def _fresh(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("_PARSED", "_NUMBERS", "_POSES"):
        monkeypatch.setattr(urdf_reader, name, {})


def test_a_file_reads_the_same_after_another_one(monkeypatch: pytest.MonkeyPatch) -> None:
    _fresh(monkeypatch)
    alone = urdf_reader.read_urdf_text(B, "b.urdf")
    _fresh(monkeypatch)
    urdf_reader.read_urdf_text(A, "a.urdf")
    after = urdf_reader.read_urdf_text(B, "b.urdf")
    assert after == alone
    codes = sorted(f.code for f in alone[1])
    assert codes == ["READ010", "READ010", "READ042"]  # mass, origin xyz, the nan rpy: each at its place
    # a bad value is reported every time it is read, never cached as good
    again = urdf_reader.read_urdf_text(A, "a.urdf")[1]
    assert sorted(f.code for f in again) == ["READ010", "READ042"]


def test_the_caches_are_bounded(monkeypatch: pytest.MonkeyPatch) -> None:
    _fresh(monkeypatch)
    want = urdf_reader.read_urdf_text(A, "a.urdf")
    kept = (set(urdf_reader._PARSED), set(urdf_reader._NUMBERS), set(urdf_reader._POSES))
    monkeypatch.setattr(urdf_reader, "_KEPT", 0)  # emptied before every file
    urdf_reader.read_urdf_text(B, "b.urdf")
    assert urdf_reader.read_urdf_text(A, "a.urdf") == want
    # B's entries went before A was read: what is kept is what A alone leaves
    assert (set(urdf_reader._PARSED), set(urdf_reader._NUMBERS), set(urdf_reader._POSES)) == kept


def test_a_long_number_is_read_but_not_kept(monkeypatch: pytest.MonkeyPatch) -> None:
    # a valid number can be a megabyte of digits: kept, 200,000 such texts would hold 200 GB
    _fresh(monkeypatch)
    long = "0." + "0" * 100_000 + "1"
    xyz = f"{long} 0 0"
    text = _urdf(
        f'<link name="b"><inertial><mass value="{long}"/><origin xyz="{xyz}"/>'
        f'<inertia ixx="{long}" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
        '<joint name="k" type="fixed"><parent link="base"/><child link="b"/></joint>'
    )
    robot, findings = urdf_reader.read_urdf_text(text, "long.urdf")
    assert findings == []
    b = robot.link("b")
    assert b is not None and b.inertial is not None and b.inertial.inertia is not None
    assert (b.inertial.mass, b.inertial.inertia.ixx) == (float(long), float(long))
    assert b.inertial.origin.xyz == (float(long), 0.0, 0.0)
    kept = [*urdf_reader._PARSED, *urdf_reader._NUMBERS, *(t for pair in urdf_reader._POSES for t in pair if t)]
    assert kept and max(len(t) for t in kept) <= urdf_reader._KEPT_TEXT  # the short ones are kept


@settings(max_examples=60, deadline=None)
@given(st.lists(st.booleans(), min_size=7, max_size=7), st.sampled_from(["", "<!-- <!d -->", "<?xml version='1.0'?>"]))
def test_a_doctype_in_any_case_is_refused(upper: list[bool], before: str) -> None:
    word = "".join(c.upper() if u else c for c, u in zip("doctype", upper, strict=True))
    data = f'{before}<!{word} robot [<!ENTITY e "x">]><robot name="r"><link name="a"/></robot>'.encode()
    with pytest.raises(InputError) as caught:
        urdf_reader.parse_xml(data, "x.urdf")
    assert caught.value.findings[0].code == "READ002"


def test_a_comment_that_looks_like_a_doctype_start_is_read() -> None:
    data = b'<!-- <!d <!D --><robot name="r"><link name="a"/></robot>'
    root = urdf_reader.parse_xml(data, "x.urdf")
    assert root.tag == "robot" and len(root) == 1
