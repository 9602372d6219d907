"""The model against an independent measurement of one frame: residuals, when they changed, and
which calibration parameters explain them (``descgen drift``; docs/calibration.md).

Parameters are those of descgen/physics/calibration.py: ``joint:<name>:offset`` for each moving
joint between the base and the frame, ``joint:<name>:origin.<x|y|z|roll|pitch|yaw>`` for every
joint on that chain. The model with parameters θ places the frame at FK(q; θ); the measured
position is p. Identification is Gauss-Newton on the positions (the identification Jacobian by
central differences of the batched forward kinematics), with the rank decided from the singular
values of the column-scaled Jacobian: a parameter with a component in the Jacobian's null space
cannot be told apart from others by this motion, and is reported unidentifiable (with the
parameters it is confounded with) instead of given a value. The identified values are those
every least-squares solution shares; their standard errors come from the residual variance.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from descgen.core.model import ONE_DOF, ROTATING, Joint, Robot
from descgen.physics.calibration import ORIGIN_COMPONENTS, parameter, split_parameter
from descgen.physics.transforms import rpy_matrix

RANK_TOL = 1e-7  # relative singular value below which a direction is not excited
NULL_SHARE = 1e-3  # a parameter with this much of its direction in the null space is unidentifiable
STEP_H = 1e-6  # central-difference step, m or rad
CHANGE_F = 20.0  # F statistic a split must pass to be reported as a change


def chain(robot: Robot, base: str, frame: str) -> list[Joint] | None:
    """The joints from ``base`` down to ``frame``; None when ``frame`` is not below ``base``."""
    out: list[Joint] = []
    link, seen = frame, {frame}
    while link != base:
        j = robot.parent_joint(link)
        if j is None or j.parent is None or j.parent in seen:
            return None
        out.append(j)
        link = j.parent
        seen.add(link)
    return out[::-1]


def parameters(joints: Sequence[Joint]) -> list[str]:
    out: list[str] = []
    for j in joints:
        if j.type in ONE_DOF:
            out.append(parameter(j.name, "offset"))
        out += [parameter(j.name, c) for c in ORIGIN_COMPONENTS]
    return out


def _rot_batch(axis: np.ndarray, q: np.ndarray) -> np.ndarray:
    x, y, z = axis
    c, s = np.cos(q), np.sin(q)
    k = 1 - c
    r = np.empty((len(q), 3, 3))
    r[:, 0, 0], r[:, 0, 1], r[:, 0, 2] = c + x * x * k, x * y * k - z * s, x * z * k + y * s
    r[:, 1, 0], r[:, 1, 1], r[:, 1, 2] = y * x * k + z * s, c + y * y * k, y * z * k - x * s
    r[:, 2, 0], r[:, 2, 1], r[:, 2, 2] = z * x * k - y * s, z * y * k + x * s, c + z * z * k
    return r


@dataclass
class Model:
    """The chain with its parameters: forward kinematics of many samples at once."""

    joints: list[Joint]
    names: list[str]
    index: dict[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.index = {n: i for i, n in enumerate(self.names)}

    def _origin(self, j: Joint, theta: np.ndarray) -> tuple[np.ndarray, list[float]]:
        d = [theta[i] if (i := self.index.get(parameter(j.name, c))) is not None else 0.0 for c in ORIGIN_COMPONENTS]
        return np.asarray(j.origin.xyz) + d[:3], [j.origin.rpy[i] + d[3 + i] for i in range(3)]

    def _sweep(
        self, q: dict[str, np.ndarray], theta: np.ndarray, n: int, keep: bool = True
    ) -> tuple[np.ndarray, np.ndarray, list[tuple[Joint, np.ndarray, np.ndarray, np.ndarray, list[float]]]]:
        """Forward kinematics of the frame in the base, keeping for each joint the frame of its
        parent link (rotation, position), its origin's xyz and rpy (corrections applied)."""
        rot = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        pos = np.zeros((n, 3))
        kept = []
        for j in self.joints:
            xyz, rpy = self._origin(j, theta)
            if keep:  # (n, 3, 3) and (n, 3) per joint: only the Jacobian's chunks need them
                kept.append((j, rot, pos, xyz, rpy))
            pos = pos + rot @ xyz
            rot = rot @ rpy_matrix(rpy)
            if j.type in ONE_DOF and j.axis is not None and any(j.axis):
                off = self.index.get(parameter(j.name, "offset"))
                qj = q[j.name] + (theta[off] if off is not None else 0.0)
                axis = np.asarray(j.axis, dtype=float) / float(np.linalg.norm(j.axis))
                if j.type in ROTATING:
                    rot = rot @ _rot_batch(axis, qj)
                else:
                    pos = pos + np.einsum("nij,j,n->ni", rot, axis, qj)
        return pos, rot, kept

    def forward(self, q: dict[str, np.ndarray], theta: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """(positions (n, 3), rotations (n, 3, 3)) of the frame in the base."""
        pos, rot, _kept = self._sweep(q, theta, n, keep=False)
        return pos, rot

    def jacobian(
        self, q: dict[str, np.ndarray], theta: np.ndarray, n: int, only: Sequence[int] | None = None
    ) -> np.ndarray:
        """d position / d theta, (n*3, P) (or the columns ``only``), in closed form. A translation
        of joint J's origin moves the frame along the parent link's axis; a turn of the origin (URDF
        rpy R = Rz Ry Rx: roll about the origin's own x, pitch about Rz(yaw) y, yaw about the
        parent's z) or a zero offset of a revolute joint (about its axis) moves it by ω x (frame -
        joint origin); a prismatic offset moves it along the axis. Checked against central
        differences and pinocchio in tests/test_calibration.py."""
        return self.linearised(q, theta, n, only)[0]

    def linearised(
        self, q: dict[str, np.ndarray], theta: np.ndarray, n: int, only: Sequence[int] | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(:meth:`jacobian`, the frame's positions): both from one pass of the kinematics."""
        pos, _rot, kept = self._sweep(q, theta, n)
        want = list(range(len(theta))) if only is None else list(only)
        out = np.zeros((n, 3, len(want)))
        by_joint: dict[str, list[tuple[int, str]]] = {}
        for col, i in enumerate(want):
            split = split_parameter(self.names[i])
            if split is not None:
                by_joint.setdefault(split[0], []).append((col, split[1]))
        for j, r_parent, p_parent, xyz, rpy in kept:
            asked = by_joint.get(j.name)
            if not asked:
                continue
            p_origin = p_parent + r_parent @ xyz
            lever = pos - p_origin
            r_joint = r_parent @ rpy_matrix(rpy)
            for col, what in asked:
                if what in ("x", "y", "z"):
                    out[:, :, col] = r_parent[:, :, "xyz".index(what)]
                    continue
                if what == "offset":
                    if j.axis is None or not any(j.axis) or j.type not in ONE_DOF:
                        continue
                    axis = np.asarray(j.axis, dtype=float) / float(np.linalg.norm(j.axis))
                    w = r_joint @ axis
                    if j.type == "prismatic":
                        out[:, :, col] = w
                        continue
                elif what == "roll":
                    w = r_joint[:, :, 0]
                elif what == "pitch":
                    w = r_parent @ np.array([-math.sin(rpy[2]), math.cos(rpy[2]), 0.0])
                else:  # yaw
                    w = r_parent[:, :, 2]
                out[:, :, col] = np.cross(w, lever)
        return out.reshape(3 * n, len(want)), pos

    def jacobian_numeric(self, q: dict[str, np.ndarray], theta: np.ndarray, n: int) -> np.ndarray:
        """Central differences of :meth:`forward`: the check of :meth:`jacobian` in the tests."""
        cols = []
        for i in range(len(theta)):
            up, down = theta.copy(), theta.copy()
            up[i] += STEP_H
            down[i] -= STEP_H
            cols.append(((self.forward(q, up, n)[0] - self.forward(q, down, n)[0]) / (2 * STEP_H)).reshape(-1))
        return np.stack(cols, axis=1) if cols else np.zeros((3 * n, 0))


# -- least squares in bounded memory -------------------------------------------------------
#
# The identification Jacobian has 3 rows per sample. It is never held whole: each chunk of
# CHUNK samples gives its rows [J | r], and a QR factorisation folds them into one
# (k+1) x (k+1) triangle (``_fold``), whose R has the singular values and column inner products
# of J (RᵀR = JᵀJ, without squaring the condition number as normal equations would) and whose
# last column gives the residual: ||Jθ - r||² = ||Rθ - z||² + ρ² for every θ.

CHUNK = 4096


def _rows(
    model: Model,
    q: dict[str, np.ndarray],
    measured: np.ndarray,
    theta: np.ndarray,
    cols: Sequence[int],
    lo: int,
    hi: int,
) -> np.ndarray:
    """[J | r] of samples lo:hi (3 rows each) for the parameters ``cols``."""
    part = {k: v[lo:hi] for k, v in q.items()}
    jac, pos = model.linearised(part, theta, hi - lo, cols)
    return np.column_stack([jac, (measured[lo:hi] - pos).reshape(-1)])


def _fold(tri: np.ndarray | None, rows: np.ndarray) -> np.ndarray:
    """The triangle of ``tri`` stacked on ``rows`` (square, zero-padded when rows are few)."""
    stacked = rows if tri is None else np.vstack([tri, rows])
    r: np.ndarray = np.linalg.qr(stacked, mode="r")  # type: ignore[assignment]
    m = rows.shape[1]
    if r.shape[0] < m:
        r = np.vstack([r, np.zeros((m - r.shape[0], m))])
    return np.asarray(r[:m])


def _triangle(
    model: Model,
    q: dict[str, np.ndarray],
    measured: np.ndarray,
    theta: np.ndarray,
    cols: Sequence[int],
    lo: int,
    hi: int,
) -> np.ndarray:
    tri = None
    for start in range(lo, hi, CHUNK):
        tri = _fold(tri, _rows(model, q, measured, theta, cols, start, min(hi, start + CHUNK)))
    return tri if tri is not None else np.zeros((len(cols) + 1, len(cols) + 1))


def _scaled(r: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(R with unit columns, the column norms of J, which columns move anything)."""
    norms = np.linalg.norm(r, axis=0)
    top = float(norms.max()) if norms.size else 0.0
    excited = norms > RANK_TOL * max(top, 1e-300)
    return np.where(excited, r / np.where(excited, norms, 1.0), 0.0), norms, excited


def _rss(tri: np.ndarray) -> tuple[float, int]:
    """The least-squares residual of a folded [J | r], and the rank used (singular values of
    the column-scaled J above RANK_TOL of the largest)."""
    k = tri.shape[1] - 1
    rs, _norms, _excited = _scaled(tri[:k, :k])
    z, rho = tri[:k, k], float(tri[k, k])
    if k == 0:
        return rho**2, 0
    u, s, _vt = np.linalg.svd(rs)
    keep = s > RANK_TOL * (s[0] if s[0] > 0 else 1.0)
    uk = u[:, keep]
    left = z - uk @ (uk.T @ z)
    return float(left @ left) + rho**2, int(keep.sum())


@dataclass
class Fit:
    theta: np.ndarray
    stderr: np.ndarray  # nan for a parameter not fitted
    fitted: list[bool]  # chosen to carry its combination (see fit)
    confounded: dict[str, list[str]]  # parameter -> those it cannot be told apart from
    rank: int
    sigma: float


def _priority(names: Sequence[str]) -> list[int]:
    """Offsets first, then origin translations, then rotations: the parameter that carries a
    combination is the one a calibration usually corrects (a joint's zero before its casting)."""

    def rank(i: int) -> int:
        n = names[i]
        return 0 if n.endswith(":offset") else 1 if n[-2:] in (".x", ".y", ".z") else 2

    return sorted(range(len(names)), key=lambda i: (rank(i), i))


def fit(model: Model, q: dict[str, np.ndarray], measured: np.ndarray, iterations: int = 6) -> Fit:
    """Least squares over the parameters the motion can tell apart. Each group of parameters
    that only their combination moves (a joint's offset and its origin's turn about the same
    axis) is fitted through one of them, chosen by :func:`_priority`; the others are reported
    with the parameters they are confounded with, and the value of the one fitted is the
    combination's (its standard error too)."""
    n = len(measured)
    p = len(model.names)
    theta = np.zeros(p)
    every = list(range(p))
    tri = _triangle(model, q, measured, theta, every, 0, n)
    rs, _norms, excited = _scaled(tri[:p, :p])
    _u, s, vt = np.linalg.svd(rs)
    rank = int(np.sum(s > RANK_TOL * (s[0] if len(s) and s[0] > 0 else 1.0)))
    null = vt[rank:].T
    # the projector onto the null space does not depend on which basis the SVD chose: two
    # parameters are confounded when a change of one can be undone by the other
    proj = null @ null.T if null.size else np.zeros((p, p))
    chosen: list[int] = []
    basis = np.zeros((p, 0))  # Gram-Schmidt on R's columns: the inner products are J's
    for i in _priority(model.names):
        if not excited[i]:
            continue
        col = rs[:, i] - basis @ (basis.T @ rs[:, i])
        left = float(np.linalg.norm(col))
        if left > 1e-6:
            basis = np.column_stack([basis, col / left])
            chosen.append(i)
    chosen.sort()
    confounded: dict[str, list[str]] = {}
    for i, name in enumerate(model.names):
        if not excited[i]:
            confounded[name] = []
        elif proj[i, i] > NULL_SHARE**2:
            confounded[name] = sorted(
                model.names[k] for k in range(p) if k != i and excited[k] and abs(proj[i, k]) > NULL_SHARE
            )
    for _ in range(iterations):
        tri = _triangle(model, q, measured, theta, chosen, 0, n)
        k = len(chosen)
        step, *_ = np.linalg.lstsq(tri[:k, :k], tri[:k, k], rcond=None)
        theta[chosen] += step
        if not k or np.max(np.abs(step)) < 1e-13:
            break
    tri = _triangle(model, q, measured, theta, chosen, 0, n)
    k = len(chosen)
    rss = _rss(tri)[0]
    sigma = math.sqrt(rss / max(1, 3 * n - k))
    stderr = np.full(p, math.nan)
    if chosen:
        cov = np.linalg.pinv(tri[:k, :k].T @ tri[:k, :k]) * sigma**2
        stderr[chosen] = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    fitted = [i in chosen for i in range(p)]
    return Fit(theta, stderr, fitted, confounded, len(chosen), sigma)


@dataclass
class Change:
    index: int  # first sample after the change
    f: float


def change_point(model: Model, q: dict[str, np.ndarray], measured: np.ndarray, min_share: float = 0.1) -> Change | None:
    """The split of the samples (in time order) after which a calibration fitted on each side
    explains the residuals far better than one over all (a Chow F test on the linearised model,
    at 48 candidate splits); None when no split passes CHANGE_F. Each stretch between candidates
    is folded once; a side is the fold of its stretches."""
    n = len(measured)
    if n < 40:
        return None
    p = len(model.names)
    theta = np.zeros(p)
    every = list(range(p))
    cuts = [int(c) for c in np.unique(np.linspace(int(n * min_share), int(n * (1 - min_share)), 48).astype(int))]
    bounds = [0, *cuts, n]
    parts = [_triangle(model, q, measured, theta, every, a, b) for a, b in itertools.pairwise(bounds)]
    prefix, suffix = [parts[0]], [parts[-1]]
    for t in parts[1:]:
        prefix.append(_fold(prefix[-1], t))
    for t in parts[-2::-1]:
        suffix.append(_fold(suffix[-1], t))
    suffix.reverse()
    whole, rank = _rss(prefix[-1])
    best: tuple[float, int] | None = None
    for i, k in enumerate(cuts):  # the split before parts[i + 1]
        split = _rss(prefix[i])[0] + _rss(suffix[i + 1])[0]
        if best is None or split < best[0]:
            best = (split, k)
    if best is None:
        return None
    split, k = best
    dof = max(1, 3 * n - 2 * rank)
    f = ((whole - split) / max(1, rank)) / max(split / dof, 1e-300)
    return Change(k, f) if f > CHANGE_F else None


__all__ = ["Change", "Fit", "Model", "chain", "change_point", "fit", "parameters"]
