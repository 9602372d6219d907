"""Plain-float principal moments with a proven bound (issue 17, goal 2): INER003, INER004 and
INER011's screen decide and print without numpy, and exactly as numpy's answers would.

Oracles: numpy.linalg.eigvalsh / eigh, the rules' own tests applied to numpy's eigenvalues
(the code before this change), and a fresh interpreter's sys.modules. Nothing is timed.
"""

from __future__ import annotations

import itertools
import math
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from descgen import extent, principal
from descgen.audit.rules import inertia as rules
from descgen.model import Inertia, Link
from tests.test_audit_plain_floats import inertial_links

ROOT = Path(__file__).resolve().parents[1]


@contextmanager
def numpy_not_loaded() -> Iterator[None]:
    """principal.bounded answers only while numpy is not loaded; here it always is."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(principal, "sys", SimpleNamespace(modules={}))
        yield


def _numpy(t: Inertia) -> list[float]:
    return [float(v) for v in np.linalg.eigvalsh(np.array(t.matrix()))]


magnitude = st.integers(-40, 40)
unit = st.floats(-1.0, 1.0, allow_nan=False)


@st.composite
def tensors(draw: st.DrawFn) -> Inertia:
    """Full symmetric tensors, including repeated, near-singular, rank-deficient, indefinite
    and huge or tiny ones (their eigenvalues placed by a random rotation)."""
    scale = 10.0 ** draw(magnitude)
    kind = draw(st.sampled_from(["entries", "spectrum", "near_diagonal"]))
    if kind == "entries":
        v = [draw(unit) * scale for _ in range(6)]
        return Inertia(*v)
    if kind == "near_diagonal":
        d = [draw(st.floats(0.1, 1.0)) * scale for _ in range(3)]
        tiny = [draw(unit) * scale * 10.0 ** draw(st.integers(-18, -6)) for _ in range(3)]
        return Inertia(d[0], tiny[0], tiny[1], d[1], tiny[2], d[2])
    choices = st.sampled_from([0.0, 1.0, -1.0, 1.0 + 1e-13, 1e-15, 1e-9, 0.5, 2.0])
    lam = np.array([draw(choices) for _ in range(3)]) * scale
    q, _ = np.linalg.qr(np.array([[draw(unit) + (i == j) for j in range(3)] for i in range(3)]))
    m = q @ np.diag(lam) @ q.T
    return Inertia(m[0, 0], m[0, 1], m[0, 2], m[1, 1], m[1, 2], m[2, 2])


@settings(max_examples=1500, deadline=None)
@given(tensors())
def test_numpys_eigenvalues_lie_within_the_bound(t: Inertia) -> None:
    # the property every use relies on: numpy's k-th value is within err of ours
    b = principal._bounded(principal._key(t))
    want = _numpy(t)
    if b is None:
        assert not all(math.isfinite(v) for v in want)  # only what cannot be computed at all
        return
    assert b.err > 0 or list(b.values) == want
    for k in range(3):
        assert b.low(k) <= want[k] <= b.high(k), (k, b, want)
    # and the bound is tight enough to settle ordinary tensors: a few ulps of the largest entry
    top = max(abs(v) for v in t.matrix()[0] + t.matrix()[1] + t.matrix()[2])
    assert b.err <= 1e-12 * top or top < 1e-290  # (subnormal entries: a few units of the last place)


@pytest.mark.parametrize("signs", list(itertools.product((0.0, -0.0), repeat=6)))
def test_a_zero_tensor_is_numpys_for_every_sign_pattern(signs: tuple[float, ...]) -> None:
    a, b, c, d, e, f = signs
    t = Inertia(a, b, c, d, e, f)
    want = np.linalg.eigvalsh(np.array(t.matrix()))
    w, v = np.linalg.eigh(np.array(t.matrix()))
    principal._moments.cache_clear()
    principal._axes.cache_clear()
    got = principal.moments(t)
    values, vectors = principal.axes(t)

    def signed(xs: object) -> list[tuple[float, float]]:
        return [(float(x), math.copysign(1.0, x)) for x in xs]  # type: ignore[attr-defined]

    assert signed(got) == signed(want) and signed(values) == signed(w)
    assert [list(x) for x in zip(*vectors, strict=True)] == v.tolist()


def _old_rule(t: Inertia, test: object) -> str | None:
    """The rules before this change: numpy's eigenvalues, tested and printed."""
    eig = tuple(_numpy(t))
    return rules._fmt(eig) if test(eig) else None  # type: ignore[operator]


edge = st.sampled_from(
    [
        Inertia(0.001, 0.001, 0.001, 0.001, 0.001, 0.001),  # rank one: its zeros are LAPACK's noise
        Inertia(0.0, 0.0, 2.40741e-35, 0.0, 0.0, 0.0),
        Inertia(-5.42101e-20, 0.0, 0.0, -5.42101e-20, 0.0, 0.0),
        Inertia(0.00012, 0.0, 0.0, 0.00012, 0.0, 0.0),
        Inertia(1.0, 0.0, 0.0, 1.0, 0.0, 2.0 - 1e-9),  # on INER004's edge
        Inertia(1e-3, 1e-4, 0.0, 1e-3, 0.0, 2.2e-3),  # breaks the triangle inequality
        Inertia(2e-15, 1e-16, 0.0, 1.0, 0.0, 1.0),  # on INER003's edge
    ]
)


@settings(max_examples=800, deadline=None)
@given(st.one_of(tensors(), edge))
def test_iner003_and_iner004_decide_and_print_as_with_numpy(t: Inertia) -> None:
    with numpy_not_loaded():
        got3 = rules._verdict(t, rules._not_positive_definite, rules._settled_not_pd)
        got4 = rules._verdict(t, rules._breaks_triangle, rules._settled_triangle)
    assert got3 == _old_rule(t, rules._not_positive_definite)
    assert got4 == _old_rule(t, rules._breaks_triangle)


def test_a_finding_is_printed_from_plain_floats_only_when_they_print_alike(monkeypatch: pytest.MonkeyPatch) -> None:
    b = principal.Bounded((1.0, 2.0, 2.00049999), 1e-6)  # the last straddles 2 / 2.001 at 4 digits
    assert principal.text(b, lambda v: f"{v:.4g}") is None
    assert principal.text(principal.Bounded((1.0, 2.0, 3.0), 1e-9), lambda v: f"{v:.4g}") == ["1", "2", "3"]
    # a settled verdict whose print is not settled goes to numpy, which prints it
    asked = []
    monkeypatch.setattr(principal, "bounded", lambda t: b)
    monkeypatch.setattr(principal, "moments", lambda t: asked.append(t) or (1.0, 2.0, 2.0005))
    t = Inertia(1.0, 0.0, 0.0, 2.0, 0.0, 2.0)
    assert rules._verdict(t, lambda e: True, lambda b: True) == "[1, 2, 2.001]"  # numpy's, not ours
    assert asked == [t]


@settings(max_examples=400, deadline=None)
@given(inertial_links())
def test_the_screen_without_eigenvectors_never_hides_a_finding(link: Link) -> None:
    hulls = extent.bounding_hulls(link)
    found = extent.moment_by_shapes(link)  # numpy's eigh: the full computation the rule falls back to
    if hulls is None or found is None:
        return
    for margin in (0.5, 1.0, 2.0, 20.0):
        with numpy_not_loaded():
            passed = extent._within_for_every_axis(link, hulls, margin)
        if passed:
            assert found.ratio <= margin


def test_the_screen_settles_a_plain_full_tensor() -> None:
    # a 1 kg box 0.2 x 0.1 x 0.1 m with its own (rotated) tensor: far inside the bound
    from descgen.model import Box, Collision, Inertial, Pose

    t = Inertia(1.108502e-03, 9.9077e-05, -2.3811e-05, 1.092725e-03, 2.3137e-05, 1.898772e-03)
    link = Link("l", collisions=(Collision(Box((0.2, 0.1, 0.1)), Pose()),), inertial=Inertial(1.0, Pose(), t))
    hulls = extent.bounding_hulls(link)
    assert hulls is not None
    with numpy_not_loaded():
        assert extent._within_for_every_axis(link, hulls, 2.0)
        assert not extent._within_for_every_axis(link, hulls, 0.01)  # a bound it cannot prove is not claimed


def test_auditing_a_urdf_with_full_tensors_does_not_import_numpy(tmp_path: Path) -> None:
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><inertial><mass value="1"/>'
        '<inertia ixx="1.1e-3" ixy="1e-4" ixz="-2e-5" iyy="1.09e-3" iyz="2e-5" izz="1.9e-3"/></inertial>'
        '<collision><geometry><box size="0.2 0.1 0.1"/></geometry></collision></link>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
        '<link name="b"><inertial><mass value="0.5"/>'
        '<inertia ixx="1e-3" ixy="1e-4" ixz="0" iyy="1e-3" iyz="0" izz="2.5e-3"/></inertial>'
        '<visual><geometry><cylinder radius="0.05" length="0.1"/></geometry></visual></link></robot>'
    )
    code = (
        "import sys; from pathlib import Path; from descgen.audit.inputs import audit; "
        f"found = audit(Path({str(urdf)!r})); "
        "print('numpy' in sys.modules); print(sorted(f.code for f in found if f.code.startswith('INER')))"
    )
    env = {"PATH": "/usr/bin:/bin", "DESCGEN_CACHE_DIR": ""}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True, env=env)
    loaded, codes = done.stdout.split("\n")[:2]
    assert loaded == "False"
    # link b's moments [0.0009, 0.0011, 0.0025] break the triangle inequality: found without numpy
    assert "INER004" in codes


near = st.sampled_from([0.0, 1e-15, 1e-12, 1.0, 2.0, 2.0 / (1 - 1e-9), 3.0, -1e-15, 5e-16])


@settings(max_examples=1500, deadline=None)
@given(st.tuples(near, near, near).map(sorted), st.sampled_from([0.0, 1e-17, 1e-15, 1e-9, 1e-6, 0.5]), st.data())
def test_a_settled_verdict_holds_for_every_value_in_the_intervals(values, err, data) -> None:  # type: ignore[no-untyped-def]
    b = principal.Bounded(tuple(values), err)  # type: ignore[arg-type]
    corners = [
        tuple(v + s * err for v, s in zip(values, signs, strict=True)) for signs in itertools.product((-1, 1), repeat=3)
    ]
    inside = [tuple(v + data.draw(st.floats(-1, 1)) * err for v in values) for _ in range(4)]
    points = [p for p in corners + inside if list(p) == sorted(p)]  # numpy's values come sorted
    for test, settled in (
        (rules._not_positive_definite, rules._settled_not_pd),
        (rules._breaks_triangle, rules._settled_triangle),
    ):
        verdict = settled(b)
        if verdict is not None:
            assert all(test(p) == verdict for p in points), (test.__name__, b)
