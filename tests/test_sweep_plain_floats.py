"""The sweep's motion analysis in plain floats (descgen/physics/sweep/motion.py, so that a ``check``
computing the sweep does not import numpy) against pinocchio, joint by joint, over every robot of
the example-robot-data corpus and the example. Nothing is timed; that a ``check`` computing the
sweep imports no numpy is tests/test_check_plain_floats.py's and tests/test_cold_start.py's.

The oracle reads the URDF itself: pinocchio places every link at every grid value (mimic
followers set from the URDF's ``<mimic>`` tags, which pinocchio's model leaves free) and gives
the joint axis in the root frame (its world Jacobian). What the sweep reports is then stated
from those placements, as motion.py's docstring defines it, in numpy:

- a link moves when some entry of its 3x4 pose differs from the first step's by more than
  ``MOVES`` (a nan entry, inf - inf, is no motion: ``np.max`` of it is nan);
- its displacement is its origin's change between the two ends of the span: the limits; a
  quarter turn from the state for a continuous joint, and for a revolute one whose range is
  more than half a turn (kept inside the limits);
- a pair of links with geometry (not disabled) changes when their relative pose ``A^-1 B``
  differs from the first step's by more than ``MOVES``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.core.model import Joint, Robot
from descgen.physics.sweep import DEFAULT_STEPS, disabled_pairs, grid, state_values, sweepable
from descgen.physics.sweep.motion import MOVES, analyse
from descgen.read.urdf import read_urdf
from descgen.render import render_package
from tests.corpus import descriptions
from tests.helpers import ROOT, cli

CORPUS = descriptions()


class Oracle:
    """pinocchio's placements of every link of the URDF at ``path``."""

    def __init__(self, path: Path) -> None:
        import pinocchio as pin

        self.pin = pin
        self.model = pin.buildModelFromUrdf(str(path))
        self.data = self.model.createData()
        self.links = {f.name: i for i, f in enumerate(self.model.frames) if f.type == pin.FrameType.BODY}
        # follower -> (leader, multiplier, offset), from the file (pinocchio's model leaves them free);
        # a follower whose chain of leaders ends at no joint of the file, or goes round, has no
        # driver: it keeps its own value, as a joint of its own
        joints = etree.parse(str(path)).getroot().findall("joint")
        named = {j.get("name") for j in joints}
        tags = {
            j.get("name"): (m.get("joint"), float(m.get("multiplier", "1")), float(m.get("offset", "0")))
            for j in joints
            if (m := j.find("mimic")) is not None
        }

        def driven(name: str) -> bool:
            seen = {name}
            while name in tags:
                name = tags[name][0]
                if name in seen or name not in named:
                    return False
                seen.add(name)
            return True

        self.mimics = {f: t for f, t in tags.items() if driven(f)}

    def q(self, values: Mapping[str, float]) -> np.ndarray:
        values = dict(values)
        for _ in self.mimics:  # a follower of a follower: as many passes as followers
            for f, (lead, k, off) in self.mimics.items():
                values[f] = k * values.get(lead, 0.0) + off
        q = self.pin.neutral(self.model)
        for name, value in values.items():
            if not self.model.existJointName(name):
                continue
            j = self.model.joints[self.model.getJointId(name)]
            if j.nq == 2:  # a continuous joint: (cos, sin)
                q[j.idx_q : j.idx_q + 2] = [math.cos(value), math.sin(value)]
            elif j.nq == 1:
                q[j.idx_q] = value
        return q

    def poses(self, values: Mapping[str, float]) -> dict[str, np.ndarray]:
        """Every link's 3x4 pose in the root frame."""
        self.pin.framesForwardKinematics(self.model, self.data, self.q(values))
        return {n: self.data.oMf[i].homogeneous[:3].copy() for n, i in self.links.items()}

    def axis(self, joint: Joint, values: Mapping[str, float]) -> np.ndarray:
        """The joint's axis in the root frame: its column of the world Jacobian."""
        pin = self.pin
        jid = self.model.getJointId(joint.name)
        pin.computeJointJacobians(self.model, self.data, self.q(values))
        jacobian = pin.getJointJacobian(self.model, self.data, jid, pin.ReferenceFrame.WORLD)
        column = np.reshape(jacobian, (6, -1))[:, self.model.joints[jid].idx_v]  # (6,) when the model has one joint
        a = column[:3] if joint.type == "prismatic" else column[3:]
        return a / np.linalg.norm(a)


def _span(j: Joint, values: Sequence[float], continuous: bool, q0: float) -> tuple[float, float]:
    if continuous:
        return q0, q0 + math.pi / 2
    if j.type in ("revolute", "continuous") and values[-1] - values[0] > math.pi:
        start = min(max(q0, values[0]), values[-1] - math.pi / 2)
        return start, start + math.pi / 2
    return values[0], values[-1]


def _largest_change(stack: np.ndarray) -> np.ndarray:
    """For (steps, *items, 3, 4) poses: each item's largest entry change from the first step,
    nan when one is nan (``np.max`` of a nan)."""
    return np.max(np.abs(stack[1:] - stack[:1]), axis=(0, -2, -1))


def _relative(first: np.ndarray, second: np.ndarray) -> np.ndarray:
    """``A^-1 B`` for every A of the (steps, m, 3, 4) poses ``first`` and B of the (steps, n, 3, 4)
    poses ``second``, as (steps, m, n, 3, 4): the rotation ``R_a^T R_b`` and the translation
    ``R_a^T t_b - R_a^T t_a``, matrix products per step of every ``R_a^T`` against every ``R_b``."""
    k, m, n = first.shape[0], first.shape[1], second.shape[1]
    if m == 0 or n == 0:
        return np.zeros((k, m, n, 3, 4))
    rt = np.swapaxes(first[..., :3], -1, -2).reshape(k, 3 * m, 3)  # rows (a, i): R_a^T
    rot = (rt @ np.swapaxes(second[..., :3], 1, 2).reshape(k, 3, 3 * n)).reshape(k, m, 3, n, 3)  # [a, i, b, l]
    to_b = (rt @ np.swapaxes(second[..., 3], 1, 2)).reshape(k, m, 3, n)  # [a, i, b]: R_a^T t_b
    to_a = np.einsum("kaji,kaj->kai", first[..., :3], first[..., 3])  # R_a^T t_a
    shift = to_b - to_a[..., None]
    return np.concatenate([rot.transpose(0, 1, 3, 2, 4), shift.transpose(0, 1, 3, 2)[..., None]], axis=-1)


def _expected(
    oracle: Oracle,
    robot: Robot,
    j: Joint,
    values: Sequence[float],
    continuous: bool,
    state: Mapping[str, float],
    geometry: list[str],
    disabled: set[frozenset[str]],
) -> tuple[set[str], dict[str, np.ndarray], tuple[float, float], np.ndarray | None, set[tuple[str, str]]]:
    at = [oracle.poses({**state, j.name: v}) for v in values]
    names = list(at[0])
    with np.errstate(invalid="ignore"):
        moves = _largest_change(np.stack([[p[n] for n in names] for p in at])) > MOVES
    moving = {n for n, m in zip(names, moves, strict=True) if m}
    span = _span(j, values, continuous, state.get(j.name, 0.0))
    ends = [oracle.poses({**state, j.name: v}) for v in span]
    shift = {n: ends[1][n][:, 3] - ends[0][n][:, 3] for n in moving}
    axis = oracle.axis(j, state) if j.type in ("revolute", "continuous", "prismatic") else None
    shaped = [n for n in geometry if n in at[0]]
    stack = np.stack([[p[n] for n in shaped] for p in at]).reshape(len(at), -1, 3, 4)
    # a pair of links whose poses are the very same floats at every step has the same relative
    # pose at every step (the same products of the same numbers, to rounding): only pairs with a link whose
    # pose changes at all (or is nan) need the products
    with np.errstate(invalid="ignore", over="ignore"):
        own = _largest_change(stack)
        changing = [i for i, c in enumerate(own) if c != 0.0]
        change = _largest_change(_relative(stack[:, changing], stack))  # (changing, shaped)
    pairs = set()
    for row, i in enumerate(changing):
        for k, b in enumerate(shaped):
            if k != i and change[row, k] > MOVES and frozenset((shaped[i], b)) not in disabled:
                pairs.add((shaped[min(i, k)], shaped[max(i, k)]))
    return moving, shift, span, axis, pairs


def _same_as_pinocchio(robot: Robot, urdf: Path, steps: int = DEFAULT_STEPS) -> int:
    oracle: Oracle | None = None  # built for a robot with a joint to sweep (pinocchio refuses a file without links)
    _, values = state_values(robot, None)
    geometry = [lk.name for lk in robot.links if lk.collisions]
    disabled = disabled_pairs(robot)[0]
    checked = 0
    for j in sweepable(robot):
        g = grid(j, steps)
        if isinstance(g, str):
            continue
        got = analyse(robot, j, g[0], g[1], values, geometry, disabled)
        oracle = oracle or Oracle(urdf)
        moving, shift, span, axis, pairs = _expected(oracle, robot, j, g[0], g[1], values, geometry, disabled)
        assert set(got.moving) == moving, j.name
        assert got.span == span, j.name
        for m in got.moved:
            assert m.displacement == pytest.approx(tuple(shift[m.link]), abs=1e-12), (j.name, m.link)
        assert (got.axis is None) == (axis is None), j.name
        if axis is not None:
            assert got.axis == pytest.approx(tuple(axis), abs=1e-12), j.name
        assert set(got.pairs) == pairs, j.name
        checked += 1
    return checked


# corpus robots with no joint to sweep (read by hand in their files): for them the comparison
# below checks nothing, so it must be these and no others
NOTHING_TO_SWEEP = {
    "double_pendulum_description/urdf/double_pendulum.urdf": "revolute joints with lower = upper = 0",
    "double_pendulum_description/urdf/double_pendulum_simple.urdf": "revolute joints with lower = upper = 0",
    "hector_description/robots/quadrotor_base.urdf": "one link, no joint",
    "iris_description/robots/iris_simple.urdf": "fixed joints only",
    "ur_description/urdf/ur3.urdf": "no link at all",
}


@pytest.mark.skipif(not CORPUS, reason="example-robot-data is not installed")
@pytest.mark.parametrize(("ident", "urdf"), [(i, u) for i, u, _ in CORPUS], ids=[i for i, _, _ in CORPUS])
def test_the_corpus_sweeps_as_pinocchio_places_it(ident: str, urdf: Path, pin: Any) -> None:
    robot, _ = read_urdf(urdf)
    checked = _same_as_pinocchio(
        robot, urdf, steps=12
    )  # fewer steps than check's 36: the same code, a third of the time
    assert (checked == 0) == (ident in NOTHING_TO_SWEEP), checked


def test_the_example_sweeps_as_pinocchio_places_it(tmp_path: Path, pin: Any) -> None:
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    assert disabled_pairs(robot)[0]  # the example has an SRDF matrix: its pairs are filtered
    urdf = tmp_path / "warehouse_arm.urdf"
    urdf.write_text(render_package(robot, "warehouse_arm.yaml")["urdf/warehouse_arm.urdf"])
    assert _same_as_pinocchio(robot, urdf) >= 4  # lift, shoulder pan and lift, elbow


def test_a_pose_past_the_float_range_moves_nothing_as_pinocchio_says(tmp_path: Path, pin: Any) -> None:
    # two 1e308 offsets put the arm at x = inf: its pose entries inf - inf = nan compare as no
    # motion, and the sweep command says so instead of failing on round(nan)
    far = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    urdf = tmp_path / "overflow.urdf"
    urdf.write_text(
        f'<robot name="r"><link name="base">{far}</link>'
        '<joint name="off1" type="fixed"><parent link="base"/><child link="far1"/><origin xyz="1e308 0 0"/></joint>'
        f'<link name="far1">{far}</link>'
        '<joint name="off2" type="fixed"><parent link="far1"/><child link="far2"/><origin xyz="1e308 0 0"/></joint>'
        f'<link name="far2">{far}</link>'
        '<joint name="turn" type="revolute"><parent link="far2"/><child link="arm"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        f'<link name="arm">{far}</link>'
        '<joint name="tip" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="0.5 0 0"/></joint>'
        f'<link name="tool">{far}</link></robot>'
    )
    robot, _ = read_urdf(urdf)
    assert _same_as_pinocchio(robot, urdf, steps=4) == 1
    (j,) = sweepable(robot)
    g = grid(j, 4)
    assert not isinstance(g, str)
    got = analyse(robot, j, g[0], g[1], {}, [lk.name for lk in robot.links], disabled_pairs(robot)[0])
    assert got.moving == () and got.pairs == ()  # by hand: every pose past far2 holds inf - inf
    done = cli("sweep", str(urdf))
    assert done.returncode == 0, done.stderr
    assert "positive turn moves no link" in done.stdout


def test_the_oracle_sees_a_wrong_analysis(pin: Any) -> None:
    """The comparison can fail: a sweep that reports the displacement of the panda's hand from
    the lower limit to the middle of panda_joint4's range (less than half a turn), instead of to
    the upper limit."""
    ((_, urdf, _),) = [d for d in CORPUS if d[0] == "panda_description/urdf/panda.urdf"]
    robot, _ = read_urdf(urdf)
    j = next(x for x in sweepable(robot) if x.name == "panda_joint4")
    g = grid(j, 12)
    assert not isinstance(g, str)
    geometry = [lk.name for lk in robot.links if lk.collisions]
    disabled = disabled_pairs(robot)[0]
    half = analyse(robot, j, g[0][:7], g[1], {}, geometry, disabled)  # lower limit to the middle
    moving, shift, _, _, pairs = _expected(Oracle(urdf), robot, j, g[0], g[1], {}, geometry, disabled)
    assert set(half.moving) == moving and set(half.pairs) <= pairs
    assert any(m.displacement != pytest.approx(tuple(shift[m.link]), abs=1e-12) for m in half.moved)


def test_a_range_too_large_to_sweep_is_said_not_a_traceback(tmp_path: Path) -> None:
    # upper 1e308: lower + (upper - lower) * k overflows to inf, and cos(inf) raises
    urdf = tmp_path / "huge.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1e308" effort="1" velocity="1"/></joint><link name="b"/></robot>'
    )
    done = cli("sweep", str(urdf))
    assert "Traceback" not in done.stderr
    assert "info[SWEEP003]: j is not swept: its range is too large to sweep (lower -1, upper 1e+308)" in done.stderr
