"""The audit's plain-float and once-per-value paths (issue 17, goal 2) give numpy's answers.

Oracles: numpy (``transforms.rpy_matrix``, ``eigvalsh``/``eigh``, corner matrices), pinocchio's
rpy, the eigen equation itself, and a fresh interpreter's ``sys.modules``. Nothing is timed.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from descgen.core.model import Inertia
from descgen.meshes import cache as mesh_cache
from descgen.meshes.facts import MeshFacts
from descgen.meshes.load import box_in_metres
from descgen.physics import extent, principal, rigid, transforms

ROOT = Path(__file__).resolve().parents[1]

angle = st.floats(-7.0, 7.0, allow_nan=False)
coord = st.floats(-50.0, 50.0, allow_nan=False)
vec = st.tuples(coord, coord, coord)
rpy = st.tuples(angle, angle, angle)


@settings(max_examples=300, deadline=None)
@given(rpy)
def test_rpy_rot_is_the_numpy_matrix_float_for_float(r: tuple[float, float, float]) -> None:
    assert np.array(rigid.rpy_rot(r)).tolist() == transforms.rpy_matrix(r).tolist()


def test_rpy_rot_agrees_with_pinocchio() -> None:
    pin = pytest.importorskip("pinocchio")
    for r in [(0.3, -1.2, 2.0), (math.pi / 2, 0.0, -math.pi / 2), (-2.5, 0.7, 0.1)]:
        assert np.allclose(np.array(rigid.rpy_rot(r)), pin.rpy.rpyToMatrix(*r), atol=1e-12)


@settings(max_examples=200, deadline=None)
@given(vec, angle)
def test_axis_angle_matches_numpy_rodrigues(axis: tuple[float, float, float], a: float) -> None:
    assert np.allclose(np.array(rigid.axis_angle_rot(axis, a)), transforms.axis_angle_matrix(axis, a), atol=1e-12)


@settings(max_examples=200, deadline=None)
@given(vec, rpy, vec, rpy, vec)
def test_compose_and_apply_match_4x4_products(t1, r1, t2, r2, p) -> None:  # type: ignore[no-untyped-def]
    want = transforms.pose_matrix(t1, r1) @ transforms.pose_matrix(t2, r2)
    got = rigid.compose(rigid.frame(t1, r1), rigid.frame(t2, r2))
    assert np.allclose(np.array(got[0]), want[:3, :3], atol=1e-12)
    assert np.allclose(np.array(got[1]), want[:3, 3], atol=1e-9)
    assert np.allclose(rigid.apply(got, p), want[:3, :3] @ np.array(p) + want[:3, 3], atol=1e-8)


@settings(max_examples=300, deadline=None)
@given(vec, vec, vec, rpy)
def test_placed_box_is_the_box_around_the_eight_placed_corners(low, high, t, r) -> None:  # type: ignore[no-untyped-def]
    # the numpy way the rule used before: every corner through R, then min/max (a "low" may exceed "high")
    corners = np.array([[(high if bit else low)[k] for k, bit in enumerate(b)] for b in np.ndindex(2, 2, 2)])
    placed = corners @ transforms.rpy_matrix(r).T + np.array(t)
    lo, hi = rigid.placed_box(low, high, rigid.frame(t, r))
    assert np.allclose(lo, placed.min(axis=0), rtol=0, atol=1e-9)
    assert np.allclose(hi, placed.max(axis=0), rtol=0, atol=1e-9)


def test_box_in_metres_applies_unit_and_signed_scale() -> None:
    facts = MeshFacts(lower=(-1.0, 0.0, 2.0), upper=(3.0, 5.0, 4.0), unit_meter=0.001)
    lo, hi = box_in_metres(facts, (1.0, -2.0, 0.5)) or ((), ())
    assert lo == pytest.approx((-0.001, 0.0, 0.001)) and hi == pytest.approx((0.003, -0.01, 0.002))
    assert box_in_metres(MeshFacts(problem="unreadable"), (1.0, 1.0, 1.0)) is None


moment = st.floats(1e-9, 1e3, allow_nan=False)
product = st.floats(-1e2, 1e2, allow_nan=False)


@settings(max_examples=400, deadline=None)
@given(moment, moment, moment, product, product, product, st.booleans())
def test_principal_moments_are_numpys_eigvalsh_exactly(a, b, c, xy, xz, yz, diagonal) -> None:  # type: ignore[no-untyped-def]
    t = Inertia(a, 0.0, 0.0, b, 0.0, c) if diagonal else Inertia(a, xy, xz, b, yz, c)
    want = np.linalg.eigvalsh(np.array(t.matrix())).tolist()
    assert list(principal.moments(t)) == want  # the diagonal fast path too: same floats, same order


@settings(max_examples=300, deadline=None)
@given(moment, moment, moment, product, product, product, st.booleans(), st.booleans())
def test_principal_axes_solve_the_eigen_equation(a, b, c, xy, xz, yz, diagonal, tie) -> None:  # type: ignore[no-untyped-def]
    if tie:
        b = a  # equal moments: any order of their axes spans the same plane
    t = Inertia(a, 0.0, 0.0, b, 0.0, c) if diagonal else Inertia(a, xy, xz, b, yz, c)
    values, vectors = principal.axes(t)
    e, _ = np.linalg.eigh(np.array(t.matrix()))
    assert list(values) == e.tolist()
    m = np.array(t.matrix())
    scale = max(1.0, float(np.abs(m).max()))
    for lam, v in zip(values, vectors, strict=True):
        assert np.allclose(m @ np.array(v), lam * np.array(v), atol=1e-9 * scale)
        assert math.isclose(float(np.linalg.norm(v)), 1.0, rel_tol=1e-12)


def test_a_negative_zero_does_not_share_a_cache_entry_with_zero() -> None:
    plus, minus = Inertia(0.0, 0.0, 0.0, 1.0, 0.0, 2.0), Inertia(-0.0, 0.0, 0.0, 1.0, 0.0, 2.0)
    for t in (plus, minus):  # either order: each gets what numpy gives for it, sign of zero included
        got = principal.moments(t)
        want = np.linalg.eigvalsh(np.array(t.matrix()))
        assert [math.copysign(1, v) for v in got] == [math.copysign(1, float(v)) for v in want]


def test_the_span_is_computed_once_per_robot(monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.read.description import load_description
    from tests.corpus import descriptions

    corpus = descriptions()
    if not corpus:
        pytest.skip("example-robot-data is not installed")
    robot, _ = load_description(corpus[0][1])
    want = extent._span(robot)  # the computation itself, uncached
    calls = []
    real = extent._span
    monkeypatch.setattr(extent, "_span", lambda r: calls.append(r) or real(r))
    extent._SPANS.clear()
    assert extent.robot_span(robot) == want and extent.robot_span(robot) == want
    assert len(calls) == 1


def test_the_mesh_cache_folder_follows_the_variable(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(tmp_path))
    first = mesh_cache.folder()
    assert first is not None and first.parent == tmp_path
    monkeypatch.setenv("DESCGEN_CACHE_DIR", "")
    assert mesh_cache.folder() is None  # switched off at once, not remembered from before
    monkeypatch.setenv("DESCGEN_CACHE_DIR", str(tmp_path / "other"))
    assert mesh_cache.folder() == tmp_path / "other" / first.name


def test_auditing_a_plain_urdf_imports_neither_yaml_nor_the_xacro_reader(tmp_path: Path) -> None:
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>'
        '<child link="b"/></joint><link name="b"/></robot>'
    )
    code = (
        "import sys; from pathlib import Path; from descgen.read.description import audit; "
        f"audit(Path({str(urdf)!r})); "
        "print(sorted(m for m in ('yaml', 'descgen.read.xacro_file', 'xacro') if m in sys.modules))"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=True,
        env={"PATH": "/usr/bin:/bin", "DESCGEN_CACHE_DIR": ""},
    )
    assert done.stdout.strip() == "[]"
