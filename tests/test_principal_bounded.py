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
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from descgen.audit.rules import inertia as rules
from descgen.core.model import Inertia, Link
from descgen.physics import extent, principal
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


def _lapack_within_its_bound(t: Inertia) -> bool:
    """False for a tensor with a nonzero entry whose square is subnormal (|v| < 1.5e-154) beside
    entries that are not: LAPACK's dsyevd (OpenBLAS, numpy 2) then misses by far more than its
    backward-error bound (test below); no inertia is written with such entries."""
    values = [abs(v) for v in (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz)]
    return all(v == 0 or v * v >= sys.float_info.min for v in values) or max(values) ** 2 < sys.float_info.min


@settings(max_examples=1500, deadline=None)
@given(tensors())
def test_numpys_eigenvalues_lie_within_the_bound(t: Inertia) -> None:
    # the property every use relies on: numpy's k-th value is within err of ours
    assume(_lapack_within_its_bound(t))
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
    """The rules computed from numpy's eigenvalues: tested, and printed as the message
    promises (4 significant digits; 0 for a moment within 1e-10 of the largest entry)."""
    eig = tuple(_numpy(t))
    zero = 1e-10 * max(abs(v) for row in t.matrix() for v in row)
    shown = ["0" if abs(v) <= zero else f"{v:.4g}" for v in eig]
    return "[" + ", ".join(shown) + "]" if test(eig, zero) else None  # type: ignore[operator]


edge = st.sampled_from(
    [
        Inertia(0.001, 0.001, 0.001, 0.001, 0.001, 0.001),  # rank one: its zeros are LAPACK's noise
        Inertia(0.0, 0.0, 2.40741e-35, 0.0, 0.0, 0.0),
        Inertia(-5.42101e-20, 0.0, 0.0, -5.42101e-20, 0.0, 0.0),
        Inertia(0.00012, 0.0, 0.0, 0.00012, 0.0, 0.0),
        Inertia(1.0, 0.0, 0.0, 1.0, 0.0, 2.0 - 1e-9),  # on INER004's edge
        Inertia(1e-3, 1e-4, 0.0, 1e-3, 0.0, 2.2e-3),  # breaks the triangle inequality
        Inertia(2e-15, 1e-16, 0.0, 1.0, 0.0, 1.0),  # on INER003's edge
        Inertia(1e-4, 0.0, 1e-4, 5e-4, 0.0, 1e-4),  # moments 0, 2e-4, 5e-4: numpy's 0 is +2.7e-20 here
        Inertia(1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6),  # hyq's feet: rank one
    ]
)


def test_where_lapack_misses_the_plain_floats_do_not() -> None:
    # [[e, 0, a], [0, 0, e], [a, e, 0]] has eigenvalues -a + O(e), O(e^2 / a), a + O(e) (by
    # hand: e = 0 gives -a, 0, a, and each moves by at most |E| = 2e, Weyl); with e = 1e-160,
    # e^2 is subnormal and LAPACK answers +-0.37499855, off by 4e-6 relative
    e, a = 1e-160, 0.375
    t = Inertia(e, 0.0, a, 0.0, e, 0.0)
    b = principal._bounded(principal._key(t))
    assert b is not None
    for k, exact in enumerate((-a, 0.0, a)):
        assert b.low(k) - 2 * e <= exact <= b.high(k) + 2 * e
    assert not _lapack_within_its_bound(t)


@settings(max_examples=800, deadline=None)
@given(st.one_of(tensors(), edge))
def test_iner003_and_iner004_decide_and_print_as_with_numpy(t: Inertia) -> None:
    assume(_lapack_within_its_bound(t))
    with numpy_not_loaded():
        got3 = rules._verdict(t, rules._not_positive_definite, rules._settled_not_pd)
        got4 = rules._verdict(t, rules._breaks_triangle, rules._settled_triangle)
    assert got3 == _old_rule(t, rules._not_positive_definite)
    assert got4 == _old_rule(t, rules._breaks_triangle)


@pytest.mark.parametrize("plain", [True, False], ids=["plain floats", "numpy"])
def test_a_moment_that_is_zero_in_truth_prints_as_0_and_decides_one_finding(plain: bool) -> None:
    # [[a, 0, a], [0, 5a, 0], [a, 0, a]] has principal moments 0, 2a, 5a (by hand: x - z is in
    # the kernel, x + z gives 2a, y gives 5a). LAPACK's 0 is noise whose sign depends on the
    # build (+2.7e-20 with this OpenBLAS): printed as such, and deciding INER004 by that sign,
    # the rules reported "[2.711e-20, 0.0002, 0.0005]" twice, as not positive definite and as
    # breaking the triangle inequality.
    t = Inertia(1e-4, 0.0, 1e-4, 5e-4, 0.0, 1e-4)
    principal._moments.cache_clear()
    if plain:
        with numpy_not_loaded():
            got3 = rules._verdict(t, rules._not_positive_definite, rules._settled_not_pd)
            got4 = rules._verdict(t, rules._breaks_triangle, rules._settled_triangle)
    else:
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(principal, "bounded", lambda t: None)  # numpy decides and prints
            got3 = rules._verdict(t, rules._not_positive_definite, rules._settled_not_pd)
            got4 = rules._verdict(t, rules._breaks_triangle, rules._settled_triangle)
    assert got3 == "[0, 0.0002, 0.0005]"
    assert got4 is None


@pytest.mark.parametrize(
    ("ixx", "iner003", "iner004"),
    [
        (1e-11, "[0, 0.5, 1]", None),  # printed as 0, so it is a zero moment: INER003's, not INER004's
        (1e-10, "[0, 0.5, 1]", None),  # on the threshold (1e-10 of the largest entry, 1): zero
        (1e-9, None, "[1e-09, 0.5, 1]"),  # a thin body, but a body: 1e-9 + 0.5 < 1 breaks the triangle
    ],
)
def test_one_threshold_prints_a_moment_as_0_and_makes_it_iner003s(
    ixx: float, iner003: str | None, iner004: str | None
) -> None:
    t = Inertia(ixx, 0.0, 0.0, 0.5, 0.0, 1.0)  # diagonal: its moments are its entries, by hand
    assert rules._verdict(t, rules._not_positive_definite, rules._settled_not_pd) == iner003
    assert rules._verdict(t, rules._breaks_triangle, rules._settled_triangle) == iner004


def test_a_small_moment_that_is_not_zero_still_prints() -> None:
    # a thin rod: 1e-9 of the largest entry is a moment, printed; 1e-11 of it is rounding
    with numpy_not_loaded():
        rod = Inertia(1e-9, 0.0, 0.0, 1.0, 0.0, 1.0)
        assert rules._verdict(rod, lambda e, z: True, lambda b, z: True) == "[1e-09, 1, 1]"
        flat = Inertia(1e-11, 0.0, 0.0, 1.0, 0.0, 1.0)
        assert rules._verdict(flat, lambda e, z: True, lambda b, z: True) == "[0, 1, 1]"


def test_a_finding_is_printed_from_plain_floats_only_when_they_print_alike(monkeypatch: pytest.MonkeyPatch) -> None:
    b = principal.Bounded((1.0, 2.0, 2.00049999), 1e-6)  # the last straddles 2 / 2.001 at 4 digits
    assert principal.text(b, lambda v: f"{v:.4g}") is None
    assert principal.text(principal.Bounded((1.0, 2.0, 3.0), 1e-9), lambda v: f"{v:.4g}") == ["1", "2", "3"]
    # a settled verdict whose print is not settled goes to numpy, which prints it
    asked = []
    monkeypatch.setattr(principal, "bounded", lambda t: b)
    monkeypatch.setattr(principal, "moments", lambda t: asked.append(t) or (1.0, 2.0, 2.0005))
    t = Inertia(1.0, 0.0, 0.0, 2.0, 0.0, 2.0)
    assert rules._verdict(t, lambda e, z: True, lambda b, z: True) == "[1, 2, 2.001]"  # numpy's, not ours
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
    from descgen.core.model import Box, Collision, Inertial, Pose

    t = Inertia(1.108502e-03, 9.9077e-05, -2.3811e-05, 1.092725e-03, 2.3137e-05, 1.898772e-03)
    link = Link("l", collisions=(Collision(Box((0.2, 0.1, 0.1)), Pose()),), inertial=Inertial(1.0, Pose(), t))
    hulls = extent.bounding_hulls(link)
    assert hulls is not None
    with numpy_not_loaded():
        assert extent._within_for_every_axis(link, hulls, 2.0)
        assert not extent._within_for_every_axis(link, hulls, 0.01)  # a bound it cannot prove is not claimed


def test_the_screen_settles_a_sphere_about_its_centre() -> None:
    # a sphere's hull is its centre grown by its radius: no sampled point is off the axis, so
    # only the radius bounds the reach. 0.1 kg within 0.02 m: at most m r^2 = 4e-5 about any
    # axis; the rank-one tensor's largest moment is 3e-6 (by hand: the trace)
    from descgen.core.model import Collision, Inertial, Pose, Sphere

    t = Inertia(1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6)
    link = Link("l", collisions=(Collision(Sphere(0.02), Pose()),), inertial=Inertial(0.1, Pose(), t))
    hulls = extent.bounding_hulls(link)
    assert hulls is not None
    with numpy_not_loaded():
        assert extent._within_for_every_axis(link, hulls, 1.0)  # 3e-6 <= 4e-5
        assert not extent._within_for_every_axis(link, hulls, 0.07)  # 0.07 * 4e-5 = 2.8e-6 < 3e-6


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
        '<visual><geometry><cylinder radius="0.05" length="0.1"/></geometry></visual></link>'
        '<joint name="k" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 1 0"/>'
        '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'  # c: hyq's feet, rank one
        '<link name="c"><inertial><mass value="0.1"/>'
        '<inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"/></inertial>'
        '<collision><geometry><sphere radius="0.02"/></geometry></collision></link></robot>'
    )
    code = (
        "import sys; from pathlib import Path; from descgen.read.description import audit; "
        f"found = audit(Path({str(urdf)!r})); "
        "print('numpy' in sys.modules); print(sorted(f.code for f in found if f.code.startswith('INER'))); "
        "print([f.message for f in found if f.code == 'INER003'])"
    )
    env = {"PATH": "/usr/bin:/bin", "DESCGEN_CACHE_DIR": ""}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True, env=env)
    loaded, codes, messages = done.stdout.split("\n")[:3]
    assert loaded == "False"
    # link b's moments [0.0009, 0.0011, 0.0025] break the triangle inequality: found without numpy
    assert "INER004" in codes
    # c's moments are 0, 0, 3e-6 (by hand: rank one, trace 3e-6): not positive definite, and
    # printed without numpy though LAPACK's zeros would be noise of either sign
    assert messages == str(["link 'c' inertia has principal moments [0, 0, 3e-06]: not positive definite"])


near = st.sampled_from([0.0, 1e-15, 1e-12, 1.0, 2.0, 2.0 / (1 - 1e-9), 3.0, -1e-15, 5e-16])


@settings(max_examples=1500, deadline=None)
@given(
    st.tuples(near, near, near).map(sorted),
    st.sampled_from([0.0, 1e-17, 1e-15, 1e-9, 1e-6, 0.5]),
    st.sampled_from([0.0, 1e-15, 1e-12, 1e-10, 3e-10]),  # the tensor's zero: 1e-10 of its largest entry
    st.data(),
)
def test_a_settled_verdict_holds_for_every_value_in_the_intervals(values, err, zero, data) -> None:  # type: ignore[no-untyped-def]
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
        verdict = settled(b, zero)
        if verdict is not None:
            assert all(test(p, zero) == verdict for p in points), (test.__name__, b)
