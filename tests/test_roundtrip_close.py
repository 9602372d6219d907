"""Proof 2 compares model and read-back values in plain floats (urdf_roundtrip._close); the
oracle is what it replaced, numpy's ``allclose(rtol=0, atol=1e-9)`` on equal shapes."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from descgen.prove.urdf_roundtrip import TOL, _close


def _numpy(a: Any, b: Any) -> bool:
    if a is None or b is None:
        return a is None and b is None
    try:
        x, y = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return bool(a == b)
    return x.shape == y.shape and bool(np.allclose(x, y, rtol=0, atol=TOL))


EYE = np.eye(4)
NEAR = tuple(tuple(float(v) for v in row) for row in EYE)
PAIRS: list[tuple[Any, Any]] = [
    (1.0, 1.0),
    (1.0, 1.0 + 0.9e-9),
    (1.0, 1.0 + 1.1e-9),  # just outside the tolerance
    (0.0, -0.0),
    (1, 1.0),
    (True, 1.0),
    (math.inf, math.inf),
    (math.inf, -math.inf),
    (math.inf, 1e308),
    (math.nan, math.nan),
    (math.nan, 0.0),
    (1e300, 1e300 * (1 + 1e-15)),  # a huge value: an absolute tolerance, numpy says no
    ((0.1, 0.2, 0.3), (0.1, 0.2, 0.3 + 2e-9)),
    ((0.1, 0.2, 0.3), (0.1, 0.2, 0.3)),
    ((0.1, 0.2, 0.3), (0.1, 0.2)),  # shapes differ
    ((0.1, 0.2), [0.1, 0.2]),
    ((), ()),
    ((), (0.0,)),
    (EYE, NEAR),
    (EYE, tuple(tuple(v + (2e-9 if i == j == 0 else 0) for j, v in enumerate(row)) for i, row in enumerate(NEAR))),
    (EYE, NEAR[:3]),
    (EYE, EYE.ravel()),  # same numbers, other shape
    (((1.0, 2.0), (3.0,)), ((1.0, 2.0), (3.0,))),  # ragged: numpy decides
    ("box", "box"),
    ("box", "cylinder"),
    ("1.0", 1.0),  # text that numpy reads as a number
    (None, None),
    (None, 0.0),
    (np.float64(0.5), 0.5),
    (np.array([1, 2, 3]), (1.0, 2.0, 3.0 + 5e-10)),
]


@pytest.mark.parametrize(("a", "b"), PAIRS)
def test_close_is_numpys_allclose(a: Any, b: Any) -> None:
    assert _close(a, b) == _numpy(a, b)
    assert _close(b, a) == _numpy(b, a)
