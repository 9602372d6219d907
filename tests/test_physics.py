"""The shared physics, names and display helpers below the rules, against hand computations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from descgen.core import display
from descgen.core.model import Box, Collision, Inertial, Joint, Limit, Link, Pose, Robot
from descgen.core.naming import mirror_name
from descgen.physics import bodies as physics
from descgen.physics.zero_pose import forward  # the frames the audit rules pose robots with

G = 9.80665


def _arm(joint_type: str, axis: tuple[float, float, float], lower: float, upper: float) -> Robot:
    """base_link -j-> arm (2 kg at 0.5 m along x) -fixed-> tip (1 kg at 0.2 m further along x)."""
    arm = Link("arm", inertial=Inertial(2.0, Pose((0.5, 0.0, 0.0))))
    tip = Link("tip", inertial=Inertial(1.0, Pose((0.2, 0.0, 0.0))))
    j = Joint("j", joint_type, "base_link", "arm", axis=axis, limit=Limit(lower, upper, 100.0, 1.0))
    weld = Joint("weld", "fixed", "arm", "tip", origin=Pose((0.5, 0.0, 0.0)))
    return Robot("r", links=(Link("base_link"), arm, tip), joints=(j, weld))


def _load(robot: Robot) -> float:
    poses = forward(robot)
    mass, moment = physics.subtree_loads(robot, poses)["arm"]
    return physics.static_load(robot.joints[0], poses["arm"], mass, moment)


def test_subtree_loads_sum_masses_and_moments() -> None:
    robot = _arm("revolute", (0.0, 1.0, 0.0), -1.0, 1.0)
    mass, moment = physics.subtree_loads(robot, forward(robot))["arm"]
    assert mass == pytest.approx(3.0)
    # 2 kg at x = 0.5 and 1 kg at x = 0.5 + 0.2: sum m*x = 1.0 + 0.7
    np.testing.assert_allclose(moment, [1.7, 0.0, 0.0], atol=1e-12)


def test_gravity_torque_of_a_horizontal_arm_by_hand() -> None:
    # torque(q) = g * sum(m x) * cos q about a horizontal axis; largest at q = 0 inside [-1, 1]
    assert _load(_arm("revolute", (0.0, 1.0, 0.0), -1.0, 1.0)) == pytest.approx(G * 1.7)
    # a range that keeps the arm raised: largest at the end nearest horizontal, q = 0.5
    assert _load(_arm("revolute", (0.0, 1.0, 0.0), 0.5, 1.0)) == pytest.approx(G * 1.7 * math.cos(0.5))
    # about the vertical axis gravity gives no torque
    assert _load(_arm("revolute", (0.0, 0.0, 1.0), -1.0, 1.0)) == pytest.approx(0.0, abs=1e-9)


def test_gravity_force_on_a_prismatic_joint_by_hand() -> None:
    assert _load(_arm("prismatic", (0.0, 0.0, 1.0), 0.0, 0.3)) == pytest.approx(3.0 * G)
    assert _load(_arm("prismatic", (1.0, 0.0, 0.0), 0.0, 0.3)) == pytest.approx(0.0, abs=1e-9)
    # 45 degrees off vertical: the weight's component along the axis
    assert _load(_arm("prismatic", (1.0, 0.0, 1.0), 0.0, 0.3)) == pytest.approx(3.0 * G / math.sqrt(2))


@pytest.mark.parametrize(
    ("a", "b", "lo", "hi", "expected"),
    [
        (1.0, 0.0, -0.5, 0.5, 1.0),  # the maximum of cos q at q = 0, inside
        (1.0, 0.0, 0.5, 1.0, math.cos(0.5)),  # at an end
        (0.0, 2.0, 2.0, 2.5, 2 * math.sin(2.0)),  # 2 sin q falls over [2, 2.5]: the lower end
        (3.0, 4.0, -10.0, 10.0, 5.0),  # a full turn: the amplitude hypot(3, 4)
        (1.0, 1.0, 3.0, 4.5, math.sqrt(2)),  # |cos q + sin q| peaks at q = 5pi/4 = 3.93
    ],
)
def test_max_abs_harmonic_by_hand(a: float, b: float, lo: float, hi: float, expected: float) -> None:
    assert physics.max_abs_harmonic(a, b, lo, hi) == pytest.approx(expected)


def test_moving_links_and_own_bodies() -> None:
    robot = _arm("revolute", (0.0, 1.0, 0.0), -1.0, 1.0)
    assert physics.moving_links(robot) == {"arm", "tip"}  # tip is welded to a moving link
    assert physics.own_bodies(robot) == {"arm"}  # tip is merged into arm


def test_welded_count_counts_per_rigid_body() -> None:
    robot = _arm("revolute", (0.0, 1.0, 0.0), -1.0, 1.0)
    tip = robot.links[2]
    with_box = Link("tip", collisions=(Collision(Box((0.1, 0.1, 0.1))),), inertial=tip.inertial)
    robot = Robot(robot.name, links=(*robot.links[:2], with_box), joints=robot.joints)
    assert physics.welded_count(robot, lambda lk: lk.collisions) == {"base_link": 0, "arm": 1, "tip": 1}


def test_dims_of_primitives() -> None:
    from descgen.core.model import Cylinder, Mesh, Sphere

    assert physics.dims(Box((0.1, 0.2, 0.3))) == [0.1, 0.2, 0.3]
    assert physics.dims(Cylinder(0.05, 0.4)) == [0.1, 0.4]
    assert physics.dims(Sphere(0.25)) == [0.5]
    assert physics.dims(Mesh("m.stl")) == []


@pytest.mark.parametrize(
    ("name", "mirror"),
    [
        ("l_elbow", "r_elbow"),
        ("right_wheel_joint", "left_wheel_joint"),
        ("FL_hip", "FR_hip"),
        ("Left_arm", "Right_arm"),
        ("base_link", None),
    ],
)
def test_mirror_name(name: str, mirror: str | None) -> None:
    assert mirror_name(name) == mirror


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (1200.0, 1000.0),  # 1.2 inside [0.5, 5] after dividing by 1000
        (0.0012, 0.001),  # 1.2 inside after multiplying by 1000
        (1.2, None),  # inside already
        (50.0, None),  # off, but not by a thousand
        (6_000_000.0, None),  # still outside after dividing
    ],
)
def test_thousand_off(value: float, expected: float | None) -> None:
    assert display.thousand_off(value, 0.5, 5.0) == expected


def test_mm_shows_metres_in_millimetres() -> None:
    assert display.mm((0.1, 0.0, -0.25)) == "100.0, 0.0, -250.0"
    # FK's rounding residue (-1e-17 m) and anything under -0.05 mm show as 0.0, not -0.0;
    # -0.06 mm rounds to -0.1 and keeps its sign
    assert display.mm((-1e-17, -4.9e-5, -0.00006)) == "0.0, 0.0, -0.1"


@pytest.mark.parametrize(
    "offsets",
    [[], [0.0], [0.3], [0.3, 0.1], [0.5, 0.00005, 0.2, 0.1], [0.1, 0.4, 0.2, 0.0, 0.7], [0.2] * 4],
    ids=["none", "only-zero", "one", "two", "even", "odd", "equal"],
)
def test_robot_scale_is_the_median_joint_offset(offsets: list[float]) -> None:
    import statistics  # the oracle: robot_scale writes the median out to spare the audit its import

    links = [Link(f"l{i}") for i in range(len(offsets) + 1)]
    joints = [
        Joint(f"j{i}", "fixed", f"l{i}", f"l{i + 1}", Pose((0.0, d, 0.0), (0.0, 0.0, 0.0)))
        for i, d in enumerate(offsets)
    ]
    robot = Robot("r", tuple(links), tuple(joints))
    kept = [d for d in offsets if d > 1e-4]
    assert physics.robot_scale(robot) == (statistics.median(kept) if kept else 0.1)
