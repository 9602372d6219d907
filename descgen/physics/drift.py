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

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from descgen.core.model import ONE_DOF, ROTATING, Joint, Robot
from descgen.physics.calibration import ORIGIN_COMPONENTS, parameter
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

    def forward(self, q: dict[str, np.ndarray], theta: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """(positions (n, 3), rotations (n, 3, 3)) of the frame in the base."""
        rot = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        pos = np.zeros((n, 3))
        for j in self.joints:
            d = [
                theta[i] if (i := self.index.get(parameter(j.name, c))) is not None else 0.0 for c in ORIGIN_COMPONENTS
            ]
            xyz = np.asarray(j.origin.xyz) + d[:3]
            r0 = rpy_matrix([j.origin.rpy[i] + d[3 + i] for i in range(3)])
            pos = pos + rot @ xyz
            rot = rot @ r0
            if j.type in ONE_DOF and j.axis is not None and any(j.axis):
                off_name = parameter(j.name, "offset")
                qj = q[j.name] + (theta[self.index[off_name]] if off_name in self.index else 0.0)
                axis = np.asarray(j.axis, dtype=float) / float(np.linalg.norm(j.axis))
                if j.type in ROTATING:
                    rot = rot @ _rot_batch(axis, qj)
                else:
                    pos = pos + np.einsum("nij,j,n->ni", rot, axis, qj)
        return pos, rot

    def jacobian(
        self, q: dict[str, np.ndarray], theta: np.ndarray, n: int, only: Sequence[int] | None = None
    ) -> np.ndarray:
        """d position / d theta, (n*3, P) (or the columns ``only``), by central differences."""
        cols = []
        for i in range(len(theta)) if only is None else only:
            up, down = theta.copy(), theta.copy()
            up[i] += STEP_H
            down[i] -= STEP_H
            cols.append(((self.forward(q, up, n)[0] - self.forward(q, down, n)[0]) / (2 * STEP_H)).reshape(-1))
        return np.stack(cols, axis=1) if cols else np.zeros((3 * n, 0))


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
    jac = model.jacobian(q, theta, n)
    norms = np.linalg.norm(jac, axis=0)
    top = float(norms.max()) if p else 0.0
    excited = norms > RANK_TOL * max(top, 1e-300)
    js = np.where(excited, jac / np.where(excited, norms, 1.0), 0.0)
    _u, s, vt = np.linalg.svd(js, full_matrices=False)
    rank = int(np.sum(s > RANK_TOL * (s[0] if len(s) and s[0] > 0 else 1.0)))
    null = vt[rank:].T
    # the projector onto the null space does not depend on which basis the SVD chose: two
    # parameters are confounded when a change of one can be undone by the other
    proj = null @ null.T if null.size else np.zeros((p, p))
    confounded: dict[str, list[str]] = {}
    for i, name in enumerate(model.names):
        if not excited[i]:
            confounded[name] = []
            continue
        if proj[i, i] > NULL_SHARE**2:
            confounded[name] = sorted(
                model.names[k] for k in range(p) if k != i and excited[k] and abs(proj[i, k]) > NULL_SHARE
            )
    chosen: list[int] = []
    basis = np.zeros((js.shape[0], 0))
    for i in _priority(model.names):
        if not excited[i]:
            continue
        col = js[:, i] - basis @ (basis.T @ js[:, i])
        left = float(np.linalg.norm(col))
        if left > 1e-6:
            basis = np.column_stack([basis, col / left])
            chosen.append(i)
    chosen.sort()
    for _ in range(iterations):
        pos, _r = model.forward(q, theta, n)
        r = (measured - pos).reshape(-1)
        jc = model.jacobian(q, theta, n, chosen)
        step, *_ = np.linalg.lstsq(jc, r, rcond=None)
        theta[chosen] += step
        if not len(step) or np.max(np.abs(step)) < 1e-13:
            break
    pos, _r = model.forward(q, theta, n)
    rss = float(np.sum((measured - pos) ** 2))
    sigma = math.sqrt(rss / max(1, 3 * n - len(chosen)))
    stderr = np.full(p, math.nan)
    if chosen:
        jc = model.jacobian(q, theta, n, chosen)
        cov = np.linalg.pinv(jc.T @ jc) * sigma**2
        stderr[chosen] = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    fitted = [i in chosen for i in range(p)]
    return Fit(theta, stderr, fitted, confounded, len(chosen), sigma)


def linear_rss(jac: np.ndarray, r: np.ndarray) -> tuple[float, int]:
    """Residual sum of squares of r after the least-squares fit of jac, and the rank used."""
    norms = np.linalg.norm(jac, axis=0)
    js = jac / np.where(norms > 0, norms, 1.0)
    u, s, _vt = np.linalg.svd(js, full_matrices=False)
    keep = s > RANK_TOL * (s[0] if len(s) else 0.0)
    uk = u[:, keep]
    res = r - uk @ (uk.T @ r)
    return float(res @ res), int(keep.sum())


@dataclass
class Change:
    index: int  # first sample after the change
    f: float


def change_point(model: Model, q: dict[str, np.ndarray], measured: np.ndarray, min_share: float = 0.1) -> Change | None:
    """The split of the samples (in time order) after which a calibration fitted on each side
    explains the residuals far better than one over all (an F test on the linearised model);
    None when no split passes CHANGE_F."""
    n = len(measured)
    if n < 40:
        return None
    theta = np.zeros(len(model.names))
    pos, _r = model.forward(q, theta, n)
    r = (measured - pos).reshape(-1)
    jac = model.jacobian(q, theta, n)
    whole, rank = linear_rss(jac, r)
    best: tuple[float, int] | None = None
    for k in np.unique(np.linspace(int(n * min_share), int(n * (1 - min_share)), 48).astype(int)):
        a, _ra = linear_rss(jac[: 3 * k], r[: 3 * k])
        b, _rb = linear_rss(jac[3 * k :], r[3 * k :])
        if best is None or a + b < best[0]:
            best = (a + b, int(k))
    if best is None:
        return None
    split, k = best
    dof = max(1, 3 * n - 2 * rank)
    f = ((whole - split) / max(1, rank)) / max(split / dof, 1e-300)
    return Change(k, f) if f > CHANGE_F else None


__all__ = ["Change", "Fit", "Model", "chain", "change_point", "fit", "parameters"]
