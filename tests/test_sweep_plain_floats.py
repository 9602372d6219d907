"""The sweep's motion analysis in plain floats (descgen/physics/sweep/motion.py, so that a ``check``
computing the sweep does not import numpy) against the same analysis done on the numpy 4x4
matrices of descgen.physics.kinematics (held to pinocchio by tests/test_kinematics.py), joint by joint,
over every robot of the example-robot-data corpus and the example. Nothing is timed; that a
``check`` computing the sweep imports no numpy is tests/test_check_plain_floats.py's and
tests/test_cold_start.py's."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import pytest

from descgen.audit.spec import load_spec
from descgen.core.model import Robot
from descgen.physics import kinematics
from descgen.physics.sweep import DEFAULT_STEPS, disabled_pairs, grid, state_values, sweepable
from descgen.physics.sweep.motion import MOVES, analyse, joint_values, quarter_turn
from descgen.read.urdf import read_urdf
from tests.corpus import descriptions
from tests.helpers import ROOT, cli

CORPUS = descriptions()


def _numpy_motion(
    robot: Robot,
    name: str,
    values: Sequence[float],
    continuous: bool,
    state: Mapping[str, float],
    geometry: list[str],
    disabled: set[frozenset[str]],
) -> tuple[set[str], dict[str, np.ndarray], tuple[float, ...] | None, set[tuple[str, str]]]:
    """Moving links, their displacement, the axis at the state and the changing pairs, from
    numpy matrices (the sweep as it was computed before)."""
    j = next(x for x in robot.joints if x.name == name)
    poses = [kinematics.forward(robot, joint_values(robot, state, name, v)) for v in values]
    first = poses[0]
    moving = {n for p in poses[1:] for n, m in p.items() if n in first and np.max(np.abs(m - first[n])) > MOVES}
    q0 = state.get(name, 0.0)
    if continuous:
        span = (q0, q0 + math.pi / 2)
    elif quarter_turn(j, values, continuous):
        start = min(max(q0, values[0]), values[-1] - math.pi / 2)
        span = (start, start + math.pi / 2)
    else:
        span = (values[0], values[-1])
    at = [kinematics.forward(robot, joint_values(robot, state, name, v)) for v in span]
    shift = {n: at[1][n][:3, 3] - at[0][n][:3, 3] for n in moving}
    axis = None
    if j.axis is not None and j.parent is not None and j.type in ("revolute", "continuous", "prismatic"):
        here = kinematics.forward(robot, joint_values(robot, state, name, q0))
        if j.parent in here:
            # the rotation blocks alone: a 4x4 product would mix an inf translation into them (inf * 0)
            turn = here[j.parent][:3, :3] @ kinematics.joint_transform(j)[:3, :3]
            a = turn @ np.asarray(j.axis, dtype=float)
            axis = tuple(a / np.linalg.norm(a)) if np.linalg.norm(a) > 0 else None
    names = [n for n in geometry if n in first]
    inv0 = {n: np.linalg.inv(first[n]) for n in names}
    deltas = {n: np.stack([p[n] @ inv0[n] for p in poses]) for n in names}
    pairs = {
        (a, b)
        for i, a in enumerate(names)
        for b in names[i + 1 :]
        if frozenset((a, b)) not in disabled and np.max(np.abs(deltas[a] - deltas[b])) > MOVES
    }
    return moving, shift, axis, pairs


def _same_as_numpy(robot: Robot, steps: int = DEFAULT_STEPS) -> int:
    _, values = state_values(robot, None)
    geometry = [lk.name for lk in robot.links if lk.collisions]
    disabled = disabled_pairs(robot)[0]
    checked = 0
    for j in sweepable(robot):
        g = grid(j, steps)
        if isinstance(g, str):
            continue
        got = analyse(robot, j, g[0], g[1], values, geometry, disabled)
        moving, shift, axis, pairs = _numpy_motion(robot, j.name, g[0], g[1], values, geometry, disabled)
        assert set(got.moving) == moving, j.name
        for m in got.moved:
            assert m.displacement == pytest.approx(tuple(shift[m.link]), abs=1e-12), (j.name, m.link)
        assert (got.axis is None) == (axis is None), j.name
        if axis is not None:
            assert got.axis == pytest.approx(axis, abs=1e-12), j.name
        assert set(got.pairs) == pairs, j.name
        checked += 1
    return checked


@pytest.mark.skipif(not CORPUS, reason="example-robot-data is not installed")
@pytest.mark.parametrize("urdf", [u for _, u, _ in CORPUS], ids=[i for i, _, _ in CORPUS])
def test_the_corpus_sweeps_as_with_numpy(urdf: object) -> None:
    robot, _ = read_urdf(urdf)  # type: ignore[arg-type]
    _same_as_numpy(robot, steps=12)  # fewer steps than check's 36: the same code, a third of the time


def test_the_example_sweeps_as_with_numpy() -> None:
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    assert disabled_pairs(robot)[0]  # the example has an SRDF matrix: its pairs are filtered
    assert _same_as_numpy(robot) >= 4  # lift, shoulder pan and lift, elbow


def test_a_pose_past_the_float_range_moves_nothing_as_with_numpy(tmp_path: Path) -> None:
    # two 1e308 offsets put the arm at x = inf: its pose entries inf - inf = nan compare as no
    # motion (numpy's max is nan), and the sweep command says so instead of failing on round(nan)
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
    with np.errstate(all="ignore"):  # the oracle's 4x4 products overflow, as intended
        assert _same_as_numpy(robot, steps=4) == 1
    done = cli("sweep", str(urdf))
    assert done.returncode == 0, done.stderr
    assert "positive turn moves no link" in done.stdout


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
