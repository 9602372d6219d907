"""Principal moments and axes of inertia tensors, computed once per tensor value.

Three audit rules (INER003, INER004, INER011) and the fault catalogue ask for the same
eigen-decompositions; this keeps one per distinct tensor. A diagonal tensor (about half of
the example-robot-data corpus) is answered without LAPACK: its eigenvalues are its diagonal,
sorted, which is exactly what ``numpy.linalg.eigvalsh`` returns for it (the tests hold the
two equal), and its principal axes are the coordinate axes.

Answers are the same floats numpy gives (numpy computes every non-diagonal case): the key
keeps the sign of each zero, since ``-0.0 == 0.0`` would otherwise share an entry.

Most questions do not need numpy's exact floats, only a decision and a 4-digit print:
:func:`bounded` gives plain-float eigenvalues from a few Jacobi sweeps with a bound ``err``
such that each value numpy would give lies within ``err`` of ours, and a rule uses them
only when every value in those intervals gives the same decision and the same printed text
(:func:`text`); otherwise it asks :func:`moments` (numpy). The bound is a posteriori, not
trusted from the iteration: with V the accumulated rotations and B = V^T A V computed from
the tensor again, the eigenvalues of A are within ``off(B)`` of B's sorted diagonal (Weyl),
V's departure from orthogonality moves them by at most ``delta * |A|`` (Ostrowski), the
rounding of forming B by a few ulps of |A|, and numpy's own answer is within LAPACK's
backward-error bound ``p(n) * eps * |A|`` of the true ones (LAPACK Users' Guide, 4.7; we
allow p(3) = 256, far above what dsyevd needs for a 3x3); the sum is doubled.
"""

from __future__ import annotations

import functools
import math
import sys
from collections.abc import Callable

from descgen.core.model import Inertia
from descgen.core.record import record

Moments = tuple[float, float, float]
_AXES = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def _key(t: Inertia) -> tuple[float, ...]:
    values = (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz)
    return values + tuple(math.copysign(1.0, v) for v in values)


def _diagonal(t: Inertia) -> bool:
    # a zero on the diagonal goes to numpy: it decides the sign of that zero eigenvalue
    return t.ixy == 0 and t.ixz == 0 and t.iyz == 0 and t.ixx != 0 and t.iyy != 0 and t.izz != 0


def _zero(t: Inertia) -> bool:
    """Every entry zero (of either sign): numpy gives the diagonal as written, signs and
    order kept, and the coordinate axes (the tests hold this for all 64 sign patterns)."""
    return not (t.ixx or t.ixy or t.ixz or t.iyy or t.iyz or t.izz)


def moments(t: Inertia) -> Moments:
    """Eigenvalues in ascending order, as ``numpy.linalg.eigvalsh`` gives them."""
    return _moments(_key(t))


def _finite(t: Inertia) -> bool:
    return all(math.isfinite(v) for v in (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz))


_NAN3 = (math.nan, math.nan, math.nan)


@functools.lru_cache(maxsize=16384)
def _moments(key: tuple[float, ...]) -> Moments:
    t = Inertia(*key[:6])
    if _diagonal(t):
        a, b, c = sorted((t.ixx, t.iyy, t.izz))
        return a, b, c
    if _zero(t):
        return t.ixx, t.iyy, t.izz
    if not _finite(t):  # an overflowing full tensor (inf, nan): LAPACK raises LinAlgError
        return _NAN3
    import numpy as np  # only for full tensors

    e = np.linalg.eigvalsh(np.array(t.matrix()))
    return float(e[0]), float(e[1]), float(e[2])


def axes_without_numpy(t: Inertia) -> bool:
    """True when :func:`axes` answers without numpy (a diagonal or zero tensor)."""
    return _diagonal(t) or _zero(t)


def axes(t: Inertia) -> tuple[Moments, tuple[tuple[float, float, float], ...]]:
    """Eigenvalues (ascending) and unit eigenvectors, as ``numpy.linalg.eigh`` gives them
    (vector k belongs to value k). For a diagonal tensor the vectors are coordinate axes;
    among equal eigenvalues their order may differ from LAPACK's, which changes no pairing
    of a value with the plane it spans."""
    return _axes(_key(t))


@functools.lru_cache(maxsize=16384)
def _axes(key: tuple[float, ...]) -> tuple[Moments, tuple[tuple[float, float, float], ...]]:
    t = Inertia(*key[:6])
    if _diagonal(t):
        diag = (t.ixx, t.iyy, t.izz)
        order = sorted(range(3), key=lambda k: diag[k])
        return (diag[order[0]], diag[order[1]], diag[order[2]]), tuple(_AXES[k] for k in order)
    if _zero(t):
        return (t.ixx, t.iyy, t.izz), _AXES
    if not _finite(t):
        return _NAN3, _AXES
    import numpy as np

    e, v = np.linalg.eigh(np.array(t.matrix()))
    vectors = tuple((float(v[0, k]), float(v[1, k]), float(v[2, k])) for k in range(3))
    return (float(e[0]), float(e[1]), float(e[2])), vectors


# --- plain-float eigenvalues with a proven bound ---------------------------------------------------

_EPS = 2.0**-52
_PAIRS = ((0, 1), (0, 2), (1, 2))


@record
class Bounded:
    """Eigenvalues in ascending order and ``err``: numpy's k-th value is within ``err`` of
    ``values[k]``. ``err`` is 0 only for exact answers (a diagonal tensor)."""

    values: Moments
    err: float

    def low(self, k: int) -> float:
        return self.values[k] - self.err

    def high(self, k: int) -> float:
        return self.values[k] + self.err


def bounded(t: Inertia) -> Bounded | None:
    """Plain-float eigenvalues of ``t`` with their bound; None when they cannot be given
    (not finite, or the iteration did not settle), or when numpy is loaded already (its
    exact answer is then ~5x cheaper than ours): then ask :func:`moments`. Either way a rule
    decides and prints the same, except for a tensor with an entry whose square is subnormal
    (|v| < 1.5e-154) beside normal ones: there LAPACK misses by far more than its error bound
    (4e-6 relative, tests/test_principal_bounded.py), and ours is the right answer."""
    if "numpy" in sys.modules and not (_diagonal(t) or _zero(t)):
        return None
    return _bounded(_key(t))


def bounded_matrix(m: tuple[tuple[float, ...], ...]) -> Bounded | None:
    """:func:`bounded` for any symmetric 3x3 matrix (only its upper triangle is read)."""
    return _bounded(_key(Inertia(m[0][0], m[0][1], m[0][2], m[1][1], m[1][2], m[2][2])))


@functools.lru_cache(maxsize=16384)
def _bounded(key: tuple[float, ...]) -> Bounded | None:
    t = Inertia(*key[:6])
    if _diagonal(t) or _zero(t):
        return Bounded(_moments(key), 0.0)  # exact, and what numpy gives (see moments)
    values = key[:6]
    if not all(math.isfinite(v) for v in values):
        return None
    top = max(abs(v) for v in values)
    # scale by a power of two (exact) so squares neither overflow nor vanish
    shift = -math.frexp(top)[1]
    a = [[math.ldexp(t.ixx, shift), math.ldexp(t.ixy, shift), math.ldexp(t.ixz, shift)]]
    a.append([a[0][1], math.ldexp(t.iyy, shift), math.ldexp(t.iyz, shift)])
    a.append([a[0][2], a[1][2], math.ldexp(t.izz, shift)])
    found = _jacobi(a)
    if found is None:
        return None
    diag, err = found
    if not (math.isfinite(err) and err < 0.5):
        return None
    try:
        # 2**-1074 per entry: what scaling may have lost of a subnormal; never a zero bound
        err = math.ldexp(err + 1e-300, -shift) or 5e-324
        d = sorted(math.ldexp(v, -shift) for v in diag)
    except OverflowError:  # a moment past the floats (entries near 1e308): not ours to give
        return None
    return Bounded((d[0], d[1], d[2]), err)


def _jacobi(a: list[list[float]]) -> tuple[tuple[float, float, float], float] | None:
    """Diagonal of V^T A V after cyclic Jacobi sweeps and the bound described above, for a
    symmetric A scaled to |a_ij| <= 1."""
    m = [row[:] for row in a]
    v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    for _ in range(12):
        off = m[0][1] ** 2 + m[0][2] ** 2 + m[1][2] ** 2
        if off <= 1e-36:  # |a_ij| <= 1: far below what the bound below counts anyway
            break
        for p, q in _PAIRS:
            apq = m[p][q]
            if apq == 0.0:
                continue
            theta = (m[q][q] - m[p][p]) / (2.0 * apq)
            tan = (
                math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
                if abs(theta) < 1e150
                else 0.5 / theta
            )
            c = 1.0 / math.sqrt(tan * tan + 1.0)
            s = tan * c
            for k in range(3):  # M J
                mkp, mkq = m[k][p], m[k][q]
                m[k][p], m[k][q] = c * mkp - s * mkq, s * mkp + c * mkq
            for k in range(3):  # J^T (M J)
                mpk, mqk = m[p][k], m[q][k]
                m[p][k], m[q][k] = c * mpk - s * mqk, s * mpk + c * mqk
            for k in range(3):  # V J
                vkp, vkq = v[k][p], v[k][q]
                v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    # a posteriori: B = V^T A V from A itself, and how far V is from orthogonal (written out:
    # this runs once per distinct tensor of every audited robot)
    (a00, a01, a02), (_, a11, a12), (_, _, a22) = a
    cols = [(v[0][j], v[1][j], v[2][j]) for j in range(3)]
    avs = [(a00 * x + a01 * y + a02 * z, a01 * x + a11 * y + a12 * z, a02 * x + a12 * y + a22 * z) for x, y, z in cols]
    diag = []
    off2 = 0.0
    gram2 = 0.0
    for i, (x, y, z) in enumerate(cols):
        for j, (ax, ay, az) in enumerate(avs):
            bij = x * ax + y * ay + z * az
            if i == j:
                diag.append(bij)
            else:
                off2 += bij * bij
            u, w, t = cols[j]
            g = x * u + y * w + z * t - (i == j)
            gram2 += g * g
    off_b = math.sqrt(off2)
    delta = math.sqrt(gram2) + 16 * _EPS
    if delta >= 0.1:
        return None
    size = math.sqrt(a00 * a00 + a11 * a11 + a22 * a22 + 2 * (a01 * a01 + a02 * a02 + a12 * a12))
    # Weyl (off-diagonal of B, and B's rounding twice), Ostrowski (V not orthogonal), numpy's own error
    err = off_b + 2 * 64 * _EPS * size + 2 * delta * size + 256 * _EPS * size
    return (diag[0], diag[1], diag[2]), 2 * err


def text(b: Bounded, fmt: Callable[[float], str]) -> list[str] | None:
    """How ``fmt`` prints each value, when it prints every value numpy may give the same
    way (rounding to a fixed number of digits is monotone, so both ends of an interval
    printing alike means all of it does); None otherwise."""
    out = []
    for k in range(3):
        shown = fmt(b.low(k))
        if fmt(b.high(k)) != shown:
            return None
        out.append(shown)
    return out
