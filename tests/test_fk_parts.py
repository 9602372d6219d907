"""Forward kinematics reuses each joint's origin matrix and axis per robot (descgen/physics/kinematics.py
_parts): the poses must be the ones the joint-by-joint chain of ``joint_transform`` gives, to the
last bit (committed tables are rounded from them), and a robot with a changed joint must never
be given the parts of another."""

from __future__ import annotations

import dataclasses
import math
import random

import numpy as np

from descgen.audit.spec import load_spec
from descgen.core.model import Pose, Robot
from descgen.physics import kinematics, mimic
from tests.helpers import ROOT


def _chain(robot: Robot, q: dict[str, float]) -> dict[str, np.ndarray]:
    """The reference: the walk forward did before, ``joint_transform`` per joint."""
    values = mimic.resolve(robot, q)
    root = robot.root()
    assert root is not None
    poses = {root: np.eye(4)}
    todo = [root]
    while todo:
        parent = todo.pop()
        for j in robot.child_joints(parent):
            if j.child is None or j.child in poses:
                continue
            poses[j.child] = poses[parent] @ kinematics.joint_transform(j, values.get(j.name, 0.0))
            todo.append(j.child)
    return poses


def test_poses_are_the_chains_to_the_last_bit() -> None:
    rng = random.Random(17)
    for spec in (ROOT / "specs" / "warehouse_arm.yaml", ROOT / "tests" / "data" / "mimic" / "gripper.yaml"):
        robot = load_spec(spec).robot
        assert any(j.type == "prismatic" for j in robot.joints) or spec.name == "gripper.yaml"
        for _ in range(20):
            q = {j.name: rng.uniform(-math.pi, math.pi) for j in robot.joints}
            got, want = kinematics.forward(robot, q), _chain(robot, q)
            assert got.keys() == want.keys()
            for link, pose in want.items():
                assert np.array_equal(got[link], pose), (spec.name, link)


def test_another_robot_object_gets_its_own_origins() -> None:
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    before = kinematics.forward(robot)
    j = next(j for j in robot.joints if j.name == "elbow_joint")
    moved = dataclasses.replace(j, origin=Pose((j.origin.xyz[0] + 0.5, *j.origin.xyz[1:]), j.origin.rpy))
    other = dataclasses.replace(robot, joints=tuple(moved if x is j else x for x in robot.joints))
    after = kinematics.forward(other)
    assert after[j.child][0, 3] != before[j.child][0, 3]  # type: ignore[index]
    for link, pose in _chain(other, {}).items():
        assert np.array_equal(after[link], pose)
    assert np.array_equal(kinematics.forward(robot)[j.child], before[j.child])  # type: ignore[index]
