"""Mimic followers in the self-collision matrix (descgen/physics/collision.py): a follower takes
``multiplier * leader + offset`` in every sample and in the default state, as MoveIt's
RobotModel::getVariableRandomPositions / getVariableDefaultPositions do (updateMimicJoints,
moveit2 jazzy robot_model.cpp), never a value of its own. Oracles: the box geometry by hand
and pinocchio's computeCollisions at hand-set configurations."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from descgen.audit.spec import load_spec
from descgen.core.model import MatrixSettings
from descgen.physics import collision
from descgen.read.urdf import read_urdf_text
from tests.helpers import ROOT

pin = pytest.importorskip("pinocchio")

SETTINGS = MatrixSettings(seed=3, samples=2000, fraction=0.95)
BOX = '<collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision>'


def _urdf(joints: str, links: tuple[str, ...], mimic: bool = True) -> str:
    """A base with a box 1 m below everything (so the sliders are not adjacent to each other
    through a link without geometry) and 2 cm cube ``links`` on ``joints``."""
    if not mimic:
        joints = re.sub(r"<mimic [^>]*/>", "", joints)
    body = "\n".join(f'<link name="{n}">{BOX}</link>' for n in links)
    return f"""<robot name="hand">
<link name="base_link"><collision><origin xyz="0 0 -1"/>
<geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
{body}
{joints}
</robot>"""


def _slider(name: str, xyz: str, axis: str, lower: float, upper: float, mimic: str = "") -> str:
    return f"""<joint name="{name}" type="prismatic"><parent link="base_link"/><child link="{name[:-6]}_link"/>
<origin xyz="{xyz}"/><axis xyz="{axis}"/><limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>
{mimic}
</joint>"""


# Two carriages on one belt: the follower sits 8 cm behind the leader whatever the belt does
# (multiplier 1, offset -8 cm), so the 2 cm cubes stay 6 cm apart. Sampled on its own the
# follower (limits -14..2 cm) meets the leader (-6..6 cm) whenever |qL - qR| < 2 cm, and at
# the zero state both cubes sit on the origin.
CARRIAGES = (
    _slider("left_joint", "0 0 0", "0 1 0", -0.06, 0.06)
    + "\n"
    + _slider("right_joint", "0 0 0", "0 1 0", -0.14, 0.02, '<mimic joint="left_joint" multiplier="1" offset="-0.08"/>')
)

# Jaws closing onto each other: the leader's stroke is 41..50 mm towards the centre, the
# follower moves 2 * q - 40 mm from the other side. Left cube centre y = 0.05 - qL, right
# centre y = -0.05 + 2 qL - 0.04, so the centres are 0.14 - 3 qL apart: -10..+17 mm, always
# under the 20 mm that separates touching cubes. At the zero state (qL = 0, qR = -40 mm) they
# are 140 mm apart. Sampled on its own (0..60 mm) the follower overlaps only when
# 80 mm < qL + qR < 120 mm: some samples, far from 95 %.
JAW_MIMIC = '<mimic joint="left_joint" multiplier="2" offset="-0.04"/>'
JAWS = (
    _slider("left_joint", "0 0.05 0", "0 -1 0", 0.041, 0.05)
    + "\n"
    + _slider(
        "right_joint", "0 -0.05 0", "0 1 0", 0.0, 0.06, '<mimic joint="left_joint" multiplier="2" offset="-0.04"/>'
    )
)
FINGERS = ("left_link", "right_link")
PAIR = frozenset(FINGERS)


def _pin_collides(urdf: str, q_by_name: dict[str, float]) -> bool:
    """pinocchio alone: are the two cubes in collision with the joints at these values?"""
    model = pin.buildModelFromXML(urdf)
    geom = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.COLLISION)
    names = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    geom.addCollisionPair(pin.CollisionPair(names.index("left_link"), names.index("right_link")))
    q = pin.neutral(model)
    for name, v in q_by_name.items():
        q[model.joints[model.getJointId(name)].idx_q] = v
    return bool(pin.computeCollisions(model, model.createData(), geom, pin.GeometryData(geom), q, True))


def _reason(urdf: str) -> str | None:
    robot, findings = read_urdf_text(urdf.encode(), "hand.urdf")
    assert not [f for f in findings if f.severity == "error"]
    matrix = collision.compute(robot, urdf, {}, "hand", SETTINGS)
    return {frozenset((d.link1, d.link2)): d.reason for d in matrix.pairs}.get(PAIR)


def test_follower_that_keeps_its_distance_is_never() -> None:
    urdf = _urdf(CARRIAGES, FINGERS)
    # the oracle: coupled, the cubes never touch over the leader's whole stroke ...
    for ql in np.linspace(-0.06, 0.06, 25):
        assert not _pin_collides(urdf, {"left_joint": ql, "right_joint": ql - 0.08})
    # ... but the follower's own limits allow overlapping (the zero state is one such)
    assert _pin_collides(urdf, {"left_joint": 0.0, "right_joint": 0.0})
    assert _pin_collides(urdf, {"left_joint": 0.03, "right_joint": 0.02})
    # a follower sampled on its own (or left at zero for the default state) is Default, not Never
    assert _reason(urdf) == "Never"
    assert _reason(_urdf(CARRIAGES, FINGERS, mimic=False)) == "Default"


def test_follower_that_always_meets_its_leader_is_default_then_always() -> None:
    """The leader's stroke (41..50 mm) excludes zero, so MoveIt's default state puts it in the
    middle (45.5 mm; moveit_core's getVariableDefaultPositions), where the jaws touch: the Setup
    Assistant marks such a pair Default, before it samples. Over every sample they touch too."""
    urdf = _urdf(JAWS, FINGERS)
    for ql in np.linspace(0.041, 0.05, 10):
        assert _pin_collides(urdf, {"left_joint": ql, "right_joint": 2 * ql - 0.04})
    assert _pin_collides(urdf, {"left_joint": 0.0455, "right_joint": 0.051})  # the default state
    assert not _pin_collides(urdf, {"left_joint": 0.041, "right_joint": 0.0})  # allowed on its own
    assert _reason(urdf) == "Default"
    # sampled on its own the pair collides sometimes: no reason at all (MoveIt keeps checking it)
    assert _reason(_urdf(JAWS, FINGERS, mimic=False)) is None


# A chain and a continuous follower: f1 = 2 lead + 1 cm, whose own limits (0..1 mm) the coupled
# value leaves (MoveIt does not clamp a follower); f2 = -3 f1 + 0.5 rad, continuous.
CHAIN = """
<joint name="lead_joint" type="prismatic"><parent link="base_link"/><child link="lead_link"/>
<axis xyz="1 0 0"/><limit lower="-0.1" upper="0.1" effort="1" velocity="1"/></joint>
<joint name="f1_joint" type="prismatic"><parent link="base_link"/><child link="f1_link"/>
<origin xyz="0 0.5 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.001" effort="1" velocity="1"/>
<mimic joint="lead_joint" multiplier="2" offset="0.01"/></joint>
<joint name="f2_joint" type="continuous"><parent link="base_link"/><child link="f2_link"/>
<origin xyz="0 -0.5 0"/><axis xyz="0 0 1"/>
<mimic joint="f1_joint" multiplier="-3" offset="0.5"/></joint>
<joint name="tail_joint" type="prismatic"><parent link="base_link"/><child link="tail_link"/>
<origin xyz="0 0 0.5"/><axis xyz="1 0 0"/><limit lower="-0.1" upper="0.1" effort="1" velocity="1"/></joint>
"""
CHAIN_LINKS = ("lead_link", "f1_link", "f2_link", "tail_link")


def _chain_scene(mimic: bool = True) -> tuple[collision._Scene, dict[str, slice]]:
    urdf = _urdf(CHAIN, CHAIN_LINKS, mimic=mimic)
    robot, _ = read_urdf_text(urdf.encode(), "chain.urdf")
    scene = collision.load_scene(robot, urdf, {}, "hand", 0.0)
    cols = {}
    for name in ("lead_joint", "f1_joint", "f2_joint", "tail_joint"):
        jm = scene.model.joints[scene.model.getJointId(name)]
        cols[name] = slice(jm.idx_q, jm.idx_q + jm.nq)
    return scene, cols


def test_samples_set_followers_from_the_driving_joint() -> None:
    scene, cols = _chain_scene()
    qs = collision.random_configurations(scene, 500, 7)
    lead = qs[:, cols["lead_joint"]][:, 0]
    f1 = qs[:, cols["f1_joint"]][:, 0]
    f2 = qs[:, cols["f2_joint"]]
    assert lead.min() >= -0.1 and lead.max() <= 0.1 and lead.max() - lead.min() > 0.15
    np.testing.assert_allclose(f1, 2 * lead + 0.01, rtol=0, atol=1e-15)
    assert f1.max() > 0.1  # not clamped to its own upper limit (1 mm)
    angle = -3 * (2 * lead + 0.01) + 0.5  # through the chain, by hand
    np.testing.assert_allclose(f2, np.column_stack([np.cos(angle), np.sin(angle)]), rtol=0, atol=1e-12)
    # every joint still draws its numbers, so the driving joints (the one after the followers
    # too) get the same values as without mimic
    free, free_cols = _chain_scene(mimic=False)
    assert [free.model.names[j] for j in range(1, free.model.njoints)][-1] == "tail_joint"
    alone = collision.random_configurations(free, 500, 7)
    for name in ("lead_joint", "tail_joint"):
        assert np.array_equal(alone[:, free_cols[name]], qs[:, cols[name]])
    assert not np.allclose(alone[:, free_cols["f1_joint"]][:, 0], f1)


def test_named_state_sets_followers_from_their_leader() -> None:
    scene, cols = _chain_scene()
    q = collision.configuration(scene, {"lead_joint": 0.05, "f1_joint": 123.0})  # f1's own entry loses
    assert q[cols["f1_joint"]][0] == pytest.approx(0.11, abs=1e-15)
    assert list(q[cols["f2_joint"]]) == pytest.approx([math.cos(0.17), math.sin(0.17)], abs=1e-12)
    q0 = collision.configuration(scene, {})  # the leader unlisted counts as zero
    assert q0[cols["f1_joint"]][0] == pytest.approx(0.01, abs=1e-15)


def test_robot_without_mimic_keeps_the_pairs_sampled_before_followers_were_handled() -> None:
    """tests/data/collision/warehouse_arm_pairs_v1.txt was written from the SRDF that
    descgen-collision-1 computed; only the algorithm name (so the input hash) changed since."""
    fixture = ROOT / "tests" / "data" / "collision" / "warehouse_arm_pairs_v1.txt"
    expected = [tuple(line.split()) for line in fixture.read_text().splitlines() if line and line[0] != "#"]
    assert len(expected) == 38
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    urdf = (ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf").read_text()
    assert robot.semantic is not None and robot.semantic.collision_matrix is not None
    assert not [j for j in robot.joints if j.mimic is not None]
    m = collision.compute(robot, urdf, {}, "warehouse_arm_description", robot.semantic.collision_matrix)
    assert [(d.link1, d.link2, d.reason) for d in m.pairs] == expected


def test_gripper_fixture_fingers_are_never_with_the_right_finger_following() -> None:
    """tests/data/mimic/gripper.yaml (no matrix of its own): left jaw y in [qL, qL + 10 mm],
    right jaw y in [qR - 10 mm, qR] with qR = -qL - 10 mm, so 2 qL + 10 mm apart over
    qL in 0..40 mm. A right finger left at zero (outside its own -50..-10 mm) touches the left
    one at y = 0, which made the pair Default."""
    from descgen.physics.sweep.contacts import pinocchio_urdf

    robot = load_spec(ROOT / "tests" / "data" / "mimic" / "gripper.yaml").robot
    urdf = pinocchio_urdf(robot)
    model = pin.buildModelFromXML(urdf)
    geom = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.COLLISION)
    names = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    geom.addCollisionPair(pin.CollisionPair(names.index("finger_left_link"), names.index("finger_right_link")))
    gdata = pin.GeometryData(geom)
    left = model.joints[model.getJointId("finger_left_joint")].idx_q
    right = model.joints[model.getJointId("finger_right_joint")].idx_q
    for ql in np.linspace(0.0, 0.04, 9):
        q = pin.neutral(model)
        q[left], q[right] = ql, -ql - 0.01
        assert not pin.computeCollisions(model, model.createData(), geom, gdata, q, True)
        pin.computeDistances(model, model.createData(), geom, gdata, q)
        assert gdata.distanceResults[0].min_distance == pytest.approx(2 * ql + 0.01, abs=1e-9)
    m = collision.compute(robot, urdf, {}, "mimic_gripper_description", SETTINGS)
    reasons = {frozenset((d.link1, d.link2)): d.reason for d in m.pairs}
    assert reasons[frozenset(("finger_left_link", "finger_right_link"))] == "Never"
