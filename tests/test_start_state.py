"""The state sweep, simulate and the collision matrix start a robot in when none is named
(descgen/physics/start_state.py): inside every joint's limits at MoveIt's default position (zero,
or the middle of limits that exclude it: moveit_core's getVariableDefaultPositions), the SRDF's
first state where there is one; and the floor under a wheeled base. Hand values on small robots,
and real arms whose zero is outside their limits."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from descgen.commands.simulate import pose_values
from descgen.core.model import Controller, GroupState, Joint, Limit, Link, Robot, Ros2Control, Semantic
from descgen.physics import start_state
from descgen.physics.start_state import default_base
from descgen.physics.sweep import state_values
from descgen.read.description import Options, load_description
from tests.corpus import share

DEG = math.pi / 180


def _robot(**more: object) -> Robot:
    """A base, a wrist whose range is 10 to 350 degrees, a gripper finger that opens from 5 mm,
    a joint whose range holds zero, and a continuous wheel."""
    joints = (
        Joint("wrist", "revolute", "base", "a", limit=Limit(10 * DEG, 350 * DEG, 10, 1)),
        Joint("finger", "prismatic", "a", "b", limit=Limit(0.005, 0.04, 10, 0.1)),
        Joint("elbow", "revolute", "b", "c", limit=Limit(-1.0, 2.0, 10, 1)),
        Joint("below", "revolute", "c", "d", limit=Limit(-2.0, -0.5, 10, 1)),
        Joint("wheel", "continuous", "base", "w"),
    )
    links = tuple(Link(n) for n in ("base", "a", "b", "c", "d", "w"))
    return Robot("r", links, joints, **more)  # type: ignore[arg-type]


# MoveIt's default: zero where the limits hold it (elbow), else their middle
CLAMPED = {"wrist": 180 * DEG, "finger": 0.0225, "elbow": 0.0, "below": -1.25}


def test_every_joint_starts_at_moveits_default_position() -> None:
    assert start_state.inside_limits(_robot()) == pytest.approx(CLAMPED)
    assert start_state.default_state(_robot()) == ("", pytest.approx(CLAMPED))


def test_the_srdf_first_state_is_taken_and_the_rest_at_their_default() -> None:
    states = (GroupState("ready", "arm", (("elbow", 1.5),)), GroupState("home", "arm", (("elbow", 0.2),)))
    name, values = start_state.default_state(_robot(semantic=Semantic(states=states)))
    assert name == "ready" and values == pytest.approx({**CLAMPED, "elbow": 1.5})


def test_sweep_starts_inside_the_limits_and_a_named_state_keeps_the_others_there() -> None:
    assert state_values(_robot(), None) == ("", pytest.approx(CLAMPED))
    states = (GroupState("tucked", "arm", (("wrist", 3.0),)),)
    robot = _robot(semantic=Semantic(states=states))
    assert state_values(robot, None) == ("tucked", pytest.approx({**CLAMPED, "wrist": 3.0}))
    assert state_values(robot, "tucked") == ("tucked", pytest.approx({**CLAMPED, "wrist": 3.0}))


def test_simulate_holds_the_same_default_state() -> None:
    values = pose_values(_robot(), None)
    assert {k: values[k] for k in CLAMPED} == pytest.approx(CLAMPED)


def test_a_wheeled_base_stands_on_the_floor() -> None:
    drive = Controller("diff_drive_controller", "diff_drive_controller/DiffDriveController")
    arm = Controller("arm_controller", "joint_trajectory_controller/JointTrajectoryController")
    assert default_base(_robot(ros2_control=Ros2Control("hw", controllers=(arm,)))) == "fixed"
    assert default_base(_robot(ros2_control=Ros2Control("hw", controllers=(arm, drive)))) == "floor"
    assert default_base(_robot()) == "fixed"


@pytest.mark.parametrize(
    ("urdf", "joints"),
    [
        ("kinova_description/robots/kinova.urdf", ["j2s6s200_joint_2", "j2s6s200_joint_3", "j2s6s200_joint_5"]),
        ("panda_description/urdf/panda_collision.urdf", ["panda_joint4"]),
    ],
)
def test_real_arms_whose_zero_is_outside_their_limits_start_in_the_middle(urdf: str, joints: list[str]) -> None:
    root = share()
    if root is None:
        pytest.fail("example-robot-data is not installed (the test extra installs it)")
    robot, _ = load_description(Path(root / "example-robot-data" / "robots" / urdf), Options(package_paths=(root,)))
    _, values = state_values(robot, None)
    for name in joints:
        (j,) = [j for j in robot.joints if j.name == name]
        assert j.limit is not None and j.limit.lower is not None and j.limit.upper is not None
        assert not j.limit.lower <= 0 <= j.limit.upper  # the case: zero is outside
        assert values[name] == pytest.approx((j.limit.lower + j.limit.upper) / 2)
