"""The audit's numpy-free paths (issue 17, goal 2) give what the numpy code they replaced gave.

Oracles: descgen.physics.kinematics.forward (numpy 4x4 matrices), the numpy hull formulas the
extent module used before (every corner of every 64-gon, written out again here),
numpy.allclose, importlib.metadata, and a fresh interpreter's sys.modules. Nothing is timed.
"""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from descgen.audit.rules import conventions
from descgen.core.model import (
    Box,
    Collision,
    Cylinder,
    Inertia,
    Inertial,
    Joint,
    Link,
    Mimic,
    Pose,
    Robot,
    Sphere,
    Visual,
)
from descgen.infra import keys
from descgen.meshes import cache as mesh_cache
from descgen.physics import extent, kinematics, rigid, transforms, zero_pose

ROOT = Path(__file__).resolve().parents[1]

angle = st.floats(-7.0, 7.0, allow_nan=False)
coord = st.floats(-2.0, 2.0, allow_nan=False)
size = st.floats(0.001, 1.0, allow_nan=False)
vec = st.tuples(coord, coord, coord)
rpy = st.tuples(angle, angle, angle)
axis = st.tuples(coord, coord, coord).filter(lambda a: math.hypot(*a) > 1e-3)
pose = st.builds(Pose, vec, rpy)
geometry = st.one_of(
    st.builds(Box, st.tuples(size, size, size)),
    st.builds(Cylinder, size, size),
    st.builds(Sphere, size),
)
shape = st.one_of(st.builds(Visual, geometry, pose), st.builds(Collision, geometry, pose))


# -- forward kinematics in plain floats against the numpy 4x4 path --------------------------------


@st.composite
def chains(draw: st.DrawFn) -> Robot:
    n = draw(st.integers(1, 6))
    joints = []
    for k in range(n):
        kind = draw(st.sampled_from(["revolute", "prismatic", "continuous", "fixed"]))
        mimic = Mimic("j0", draw(coord), draw(coord)) if k > 0 and kind != "fixed" and draw(st.booleans()) else None
        joints.append(Joint(f"j{k}", kind, f"l{k}", f"l{k + 1}", draw(pose), draw(axis), mimic=mimic))
    links = tuple(Link(f"l{k}") for k in range(n + 1))
    return Robot("r", links=links, joints=tuple(joints))


@settings(max_examples=150, deadline=None)
@given(chains(), st.floats(-3.0, 3.0, allow_nan=False))
def test_plain_forward_kinematics_equals_the_numpy_matrices(robot: Robot, q: float) -> None:
    values = {"j0": q}  # the mimic followers move with j0, by their offsets too
    want = kinematics.forward(robot, values)
    got = zero_pose.forward(robot, values)
    assert set(got) == set(want)
    for name, (r, t) in got.items():
        np.testing.assert_allclose(np.array(r), want[name][:3, :3], atol=1e-12)
        np.testing.assert_allclose(np.array(t), want[name][:3, 3], atol=1e-9)


def test_zero_pose_is_computed_once_per_robot() -> None:
    robot = Robot("r", links=(Link("a"), Link("b")), joints=(Joint("j", "fixed", "a", "b", Pose((0.0, 0.0, 0.1))),))
    first = zero_pose.at_zero(robot)
    assert zero_pose.at_zero(robot) is first
    other = Robot("r", links=robot.links, joints=(Joint("j", "fixed", "a", "b", Pose((0.0, 0.0, 0.2))),))
    assert zero_pose.at_zero(other)["b"][1] == (0.0, 0.0, 0.2)  # not the first robot's answer (same name)


def test_a_negative_zero_rpy_gives_the_formula_s_signed_zeros() -> None:
    # the rotation memo must not hand (0, 0, 0)'s matrix to (-0.0, 0, 0): numpy's would differ in signs
    for r in [(0.0, 0.0, 0.0), (-0.0, 0.0, 0.0), (0.0, -0.0, -0.0), (-0.0, 0.0, 0.0)]:
        got = np.array(transforms.rpy_matrix(r).tolist())
        mine = np.array(rigid.rpy_rot(r))
        assert [math.copysign(1, v) for v in mine.ravel()] == [math.copysign(1, v) for v in got.ravel()]


# -- hulls: the closed form and the sampled bound against every corner ------------------------------

_ANGLES = np.linspace(0.0, 2 * math.pi, 64, endpoint=False)


def _numpy_points(s: Visual | Collision) -> tuple[np.ndarray, float] | None:
    """The hull points as extent.py built them with numpy before (the oracle)."""
    g = s.geometry
    if isinstance(g, Box):
        cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        local, pad = cube * (np.array(g.size) / 2), 0.0
    elif isinstance(g, Cylinder):
        r = g.radius / math.cos(math.pi / 64)
        ring = np.stack([r * np.cos(_ANGLES), r * np.sin(_ANGLES)], axis=1)
        local = np.vstack([np.column_stack([ring, np.full(64, z)]) for z in (-g.length / 2, g.length / 2)])
        pad = 0.0
    elif isinstance(g, Sphere):
        local, pad = np.zeros((1, 3)), g.radius
    else:
        return None
    t = transforms.pose_matrix(s.origin.xyz, s.origin.rpy)
    return local @ t[:3, :3].T + t[:3, 3], pad


@settings(max_examples=300, deadline=None)
@given(shape, vec, rpy)
def test_the_extent_of_a_hull_is_that_of_all_its_corners(s: Visual | Collision, t: tuple, r: tuple) -> None:
    h = extent.shape_hull(s)
    pts, _ = _numpy_points(s) or (None, 0.0)
    assert h is not None and pts is not None
    for placed in (None, rigid.frame(t, r)):
        moved = pts if placed is None else pts @ transforms.rpy_matrix(r).T + np.array(t)
        lo, hi = extent.extent(h, placed)
        np.testing.assert_allclose(lo, moved.min(axis=0), atol=1e-9)
        np.testing.assert_allclose(hi, moved.max(axis=0), atol=1e-9)
    np.testing.assert_allclose(np.array(extent.corners(h)), pts, atol=1e-12)  # the same 128 / 8 / 1 points


@st.composite
def inertial_links(draw: st.DrawFn) -> Link:
    shapes = draw(st.lists(shape, min_size=1, max_size=3))
    a, b, c = draw(size), draw(size), draw(size)
    scale = draw(st.sampled_from([1e-4, 1e-2, 1.0, 10.0]))  # from plausible to far too large
    products = draw(st.tuples(coord, coord, coord)) if draw(st.booleans()) else (0.0, 0.0, 0.0)
    tensor = Inertia(a * scale, products[0] * 1e-3, products[1] * 1e-3, b * scale, products[2] * 1e-3, c * scale)
    inertial = Inertial(draw(size) * 10, draw(pose), tensor)
    return Link(
        "l",
        visuals=tuple(x for x in shapes if isinstance(x, Visual)),
        collisions=tuple(x for x in shapes if isinstance(x, Collision)),
        inertial=inertial,
    )


def _numpy_moment_by_shapes(link: Link) -> extent.MomentBound | None:
    """moment_by_shapes as it was, with numpy hulls and numpy's eigh (the oracle)."""
    i = link.inertial
    hulls = [_numpy_points(s) for s in link.shapes()]
    if i is None or i.inertia is None or not i.mass or any(h is None for h in hulls) or not hulls:
        return None
    pts = [h for h in hulls if h is not None]
    ptp = float(np.ptp(np.vstack([p for p, _ in pts]), axis=0).max())
    if max(ptp, 2 * max(pad for _, pad in pts)) < extent.MARKER:
        return None
    eig, vecs = np.linalg.eigh(np.array(i.inertia.matrix()))
    turn, com = transforms.rpy_matrix(i.origin.rpy), np.array(i.origin.xyz)
    worst = None
    for k in range(3):
        a = turn @ vecs[:, k]
        reach = 0.0
        for p, pad in pts:
            d = p - com
            perp = d - np.outer(d @ a, a)
            reach = max(reach, float(np.max(np.linalg.norm(perp, axis=1))) + pad)
        found = extent.MomentBound(float(eig[k]), i.mass * reach**2, reach)
        if found.bound > 0 and (worst is None or found.ratio > worst.ratio):
            worst = found
    return worst


@settings(max_examples=300, deadline=None)
@given(inertial_links())
def test_moment_by_shapes_equals_the_numpy_hulls_and_the_quick_test_never_hides_a_finding(link: Link) -> None:
    want = _numpy_moment_by_shapes(link)
    got = extent.moment_by_shapes(link)
    if want is None:
        assert got is None
        return
    assert got is not None
    assert got.moment == pytest.approx(want.moment, rel=1e-9, abs=1e-15)
    assert got.reach == pytest.approx(want.reach, rel=1e-9, abs=1e-12)
    hulls = extent.bounding_hulls(link)
    assert hulls is not None
    for margin in (0.5, 1.0, 2.0):
        if extent.within_shapes(link, hulls, margin):  # the rule then skips the link: rightly
            assert want.ratio <= margin


def test_the_span_of_a_corpus_robot_equals_the_numpy_span() -> None:
    from descgen.read.description import load_description
    from tests.corpus import descriptions

    corpus = descriptions()
    if not corpus:
        pytest.skip("example-robot-data is not installed")
    for ident, urdf, _ in corpus[::7]:
        robot, _ = load_description(urdf)
        poses = kinematics.forward(robot)
        lows, highs = [], []
        for name, p in poses.items():
            lows.append(p[:3, 3])
            highs.append(p[:3, 3])
            lk = robot.link(name)
            for s in lk.shapes() if lk is not None else ():
                found = _numpy_points(s)
                if found is not None:
                    pts = found[0] @ p[:3, :3].T + p[:3, 3]
                    lows.append(pts.min(axis=0) - found[1])
                    highs.append(pts.max(axis=0) + found[1])
        want = float(np.linalg.norm(np.max(highs, axis=0) - np.min(lows, axis=0))) if poses else 0.0
        assert extent._span(robot) == pytest.approx(want, rel=1e-12, abs=1e-12), ident


# -- NAME013's rotation test, the cache folder's versions, and what a plain URDF audit imports --------


@settings(max_examples=300, deadline=None)
@given(st.tuples(*[st.floats(-1.6, 1.6, allow_nan=False) | st.sampled_from([-math.pi / 2, 0.0])] * 3))
def test_name013_closeness_is_numpy_allclose(r: tuple[float, float, float]) -> None:
    rot = rigid.rpy_rot(r)
    rep = np.array(conventions.REP103)
    assert conventions._allclose(rot, conventions.REP103, 1e-3) == bool(np.allclose(np.array(rot), rep, atol=1e-3))
    assert conventions._allclose(rot, rigid.IDENTITY, 1e-6) == bool(np.allclose(np.array(rot), np.eye(3), atol=1e-6))


@pytest.mark.parametrize("dist", mesh_cache.LIBRARIES)
def test_the_cache_folder_versions_are_importlib_metadata_s(dist: str) -> None:
    # the mesh cache's folder is named by a key (descgen/infra/keys.py) holding these versions
    assert keys.libraries([dist]) == {dist: metadata.version(dist)}


def test_a_plain_urdf_audit_imports_neither_numpy_nor_importlib_metadata(tmp_path: Path) -> None:
    mesh = tmp_path / "m.stl"
    mesh.write_bytes(b"solid x\nendsolid x\n")  # parsed (trimesh, numpy) by the first run only
    urdf = tmp_path / "r.urdf"
    tensor = '<inertia ixx="0.1" iyy="0.1" izz="0.05" ixy="0" ixz="0" iyz="0"/>'
    inertial = f'<inertial><origin xyz="0 0 0.1"/><mass value="2"/>{tensor}</inertial>'
    urdf.write_text(
        f'<robot name="r"><link name="base_link">{inertial}<collision><geometry><cylinder radius="0.1" length="0.3"/>'
        "</geometry></collision></link>"
        f'<link name="arm">{inertial}<visual><geometry><mesh filename="m.stl"/></geometry></visual>'
        '<collision><origin rpy="0 1.57 0"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>'
        '<link name="slide"/><link name="camera_optical_frame"/>'
        '<joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/><origin xyz="0 0 0.3"/>'
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        '<joint name="left_j" type="prismatic"><parent link="base_link"/><child link="slide"/>'
        '<origin xyz="0 0.2 0"/><limit lower="0" upper="300" effort="10" velocity="1"/></joint>'
        '<joint name="cam" type="fixed"><parent link="arm"/><child link="camera_optical_frame"/>'
        '<origin rpy="0 0 0.5"/></joint></robot>'
    )
    code = (
        "import sys; from pathlib import Path; from descgen.read.description import audit; "
        f"found = audit(Path({str(urdf)!r})); "
        "print(sorted({f.code for f in found}), sorted(m for m in ('numpy', 'importlib.metadata') if m in sys.modules))"
    )
    env = {"PATH": "/usr/bin:/bin", "DESCGEN_CACHE_DIR": str(tmp_path / "cache")}
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True, env=env)]
    runs.append(
        subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True, env=env)
    )
    cold, warm = (r.stdout.strip().rsplit("] ", 1) for r in runs)
    assert "numpy" in cold[1]  # the oracle that the mesh needed numpy to measure at all
    assert warm[1] == "[]", runs[1].stdout  # its facts come from the cache: no numpy, no metadata
    assert warm[0] == cold[0]
    # the rules that used numpy ran and answered: gravity (JOINT008), travel (JOINT020), optical (NAME013)
    for code in ("JOINT008", "JOINT020", "NAME013"):
        assert code in warm[0], runs[1].stdout


_angles = st.floats(-math.pi, math.pi, allow_nan=False)
_coords = st.floats(-2.0, 2.0, allow_nan=False)


@settings(max_examples=300, deadline=None)
@given(
    st.tuples(_coords, _coords, _coords),
    st.tuples(_coords, _coords, _coords),
    st.tuples(_angles, _angles, _angles),
    st.sampled_from([(0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.3, 0.4, 0.0)]),
)
def test_wheel_separation_in_plain_floats_is_the_numpy_projection(
    left: tuple[float, float, float],
    right: tuple[float, float, float],
    rpy: tuple[float, float, float],
    axis: tuple[float, float, float],
) -> None:
    """derive.diff_drive_geometry (plain floats) against the projection written with numpy:
    |(t_left - t_right) . R(rpy) a / |R a||. A transposed rotation or a dropped
    normalisation fails."""
    from descgen.core.model import Controller
    from descgen.physics import derive

    wheel = Link("wheel", collisions=(Collision(Cylinder(0.05, 0.02)),))
    joints = tuple(
        Joint(name, "continuous", "base", child, Pose(xyz, rpy), axis)
        for name, child, xyz in (("l", "wl", left), ("r", "wr", right))
    )
    robot = Robot(
        "r",
        (Link("base"), dataclasses.replace(wheel, name="wl"), dataclasses.replace(wheel, name="wr")),
        joints,
    )
    c = Controller(
        "dd",
        "diff_drive_controller/DiffDriveController",
        params=(("left_wheel_names", ["l"]), ("right_wheel_names", ["r"])),
    )
    got = derive.diff_drive_geometry(robot, c)
    r = transforms.rpy_matrix(rpy)
    a = r @ np.asarray(axis)
    want = abs(float(np.dot(np.asarray(left) - np.asarray(right), a / np.linalg.norm(a))))
    assert got.wheel_separation == pytest.approx(want, rel=1e-12, abs=1e-15)
    assert got.wheel_radius == 0.05
