"""The example robot encodes the measurement sheet, in SI."""

from __future__ import annotations

import math

import pytest

from descgen.audit.spec import load_spec
from descgen.core.model import Box, Cylinder, Sphere

from .conftest import EXAMPLE


@pytest.fixture(scope="module")
def robot():  # type: ignore[no-untyped-def]
    return load_spec(EXAMPLE).robot


def test_names_and_tree_match_the_sheet(robot) -> None:  # type: ignore[no-untyped-def]
    # the sheet's "Names" table: link -> (parent joint, type, parent link)
    table = {
        "base_link": ("base_joint", "fixed", "base_footprint"),
        "left_wheel_link": ("left_wheel_joint", "continuous", "base_link"),
        "right_wheel_link": ("right_wheel_joint", "continuous", "base_link"),
        "caster_link": ("caster_joint", "fixed", "base_link"),
        "lidar_link": ("lidar_joint", "fixed", "base_link"),
        "arm_base_link": ("arm_mount_joint", "fixed", "base_link"),
        "lift_link": ("lift_joint", "prismatic", "arm_base_link"),
        "shoulder_link": ("shoulder_pan_joint", "revolute", "lift_link"),
        "upper_link": ("shoulder_lift_joint", "revolute", "shoulder_link"),
        "forearm_link": ("elbow_joint", "revolute", "upper_link"),
        "tool_link": ("tool_joint", "fixed", "forearm_link"),
        "camera_link": ("camera_joint", "fixed", "tool_link"),
        "camera_optical_frame": ("camera_optical_joint", "fixed", "camera_link"),
    }
    assert {lk.name for lk in robot.links} == {"base_footprint", *table}
    assert robot.roots() == ["base_footprint"]
    for link, (jname, jtype, parent) in table.items():
        j = robot.parent_joint(link)
        assert (j.name, j.type, j.parent) == (jname, jtype, parent), link


def test_axes_match_the_sheet(robot) -> None:  # type: ignore[no-untyped-def]
    axes = {
        "left_wheel_joint": (0, 1, 0),
        "right_wheel_joint": (0, 1, 0),
        "lift_joint": (0, 0, 1),
        "shoulder_pan_joint": (0, 0, 1),
        "shoulder_lift_joint": (0, 1, 0),
        "elbow_joint": (0, 1, 0),
    }
    for name, axis in axes.items():
        assert robot.joint(name).axis == axis


def test_measured_values_in_si(robot) -> None:  # type: ignore[no-untyped-def]
    wheel = robot.link("left_wheel_link")
    cyl = wheel.collisions[0].geometry
    assert isinstance(cyl, Cylinder)
    assert cyl.radius == pytest.approx(0.085) and cyl.length == pytest.approx(0.040)  # M01, M02
    assert wheel.inertial.mass == pytest.approx(1.2)  # M03: 1200 g
    # M04: 19.1 in track width, wheel centre to wheel centre
    ly = robot.joint("left_wheel_joint").origin.xyz[1]
    ry = robot.joint("right_wheel_joint").origin.xyz[1]
    assert ly - ry == pytest.approx(19.1 * 0.0254, abs=1e-12)
    chassis = robot.link("base_link")
    box = chassis.collisions[0].geometry
    assert isinstance(box, Box) and box.size == pytest.approx((0.6, 0.45, 0.2))  # M05
    assert chassis.inertial.mass == 28.0  # M06
    assert chassis.inertial.origin.xyz == pytest.approx((-0.040, 0.0, 0.075 - 0.030))  # M07 + M08
    assert robot.joint("base_joint").origin.xyz == pytest.approx((0, 0, 0.085))  # M09
    assert robot.joint("caster_joint").origin.xyz == pytest.approx((-0.24, 0, -0.055))  # M10
    ball = robot.link("caster_link").collisions[0].geometry
    assert isinstance(ball, Sphere) and ball.radius == pytest.approx(0.03)
    assert robot.joint("lidar_joint").origin.xyz == pytest.approx((0.18, 0, 0.24))  # M11
    lift = robot.joint("lift_joint").limit
    assert (lift.lower, lift.upper, lift.velocity, lift.effort) == pytest.approx((0, 0.3, 0.1, 500))  # M15
    pan = robot.joint("shoulder_pan_joint").limit
    assert (pan.lower, pan.upper) == pytest.approx((-math.radians(170), math.radians(170)))  # M17
    assert pan.velocity == pytest.approx(math.pi) and pan.effort == 40  # 30 rpm, 40 N*m
    assert robot.joint("shoulder_lift_joint").limit.velocity == pytest.approx(math.pi / 2)  # 90 deg/s
    assert robot.joint("elbow_joint").limit.velocity == pytest.approx(math.radians(120))  # M21
    assert robot.joint("left_wheel_joint").limit.velocity == pytest.approx(112 * math.pi / 30)  # C03
    cam_col = robot.link("camera_link").collisions[0].geometry
    assert cam_col.size == pytest.approx((0.035, 0.100, 0.035))  # M25 + 2 x M26


def test_camera_optical_frame_rep103(robot) -> None:  # type: ignore[no-untyped-def]
    from descgen.physics.transforms import rpy_matrix

    j = robot.joint("camera_optical_joint")
    r = rpy_matrix(j.origin.rpy)
    # columns: optical x = body -y (right), optical y = body -z (down), optical z = body +x (forward)
    assert r[:, 0] == pytest.approx((0, -1, 0), abs=1e-12)
    assert r[:, 1] == pytest.approx((0, 0, -1), abs=1e-12)
    assert r[:, 2] == pytest.approx((1, 0, 0), abs=1e-12)


def test_inertia_from_primitives_hand_computed(robot) -> None:  # type: ignore[no-untyped-def]
    # chassis: box 0.6 x 0.45 x 0.2 m, 28 kg: ixx = m (y^2 + z^2) / 12
    t = robot.link("base_link").inertial.inertia
    assert t.ixx == pytest.approx(28 * (0.45**2 + 0.2**2) / 12)
    assert t.iyy == pytest.approx(28 * (0.6**2 + 0.2**2) / 12)
    assert t.izz == pytest.approx(28 * (0.6**2 + 0.45**2) / 12)
    # wheel: cylinder r 0.085, h 0.04, 1.2 kg, turned so its axis is y: iyy = m r^2 / 2
    w = robot.link("left_wheel_link").inertial.inertia
    assert w.iyy == pytest.approx(1.2 * 0.085**2 / 2)
    assert w.ixx == pytest.approx(1.2 * (3 * 0.085**2 + 0.04**2) / 12)
    assert w.izz == pytest.approx(w.ixx)
    assert (w.ixy, w.ixz, w.iyz) == (0, 0, 0)
    # caster ball: 2/5 m r^2
    assert robot.link("caster_link").inertial.inertia.ixx == pytest.approx(0.4 * 0.3 * 0.03**2)


def test_repeated_part_and_sources(robot) -> None:  # type: ignore[no-untyped-def]
    assert robot.link("left_wheel_link").part == robot.link("right_wheel_link").part == "drive_wheel"
    assert "M04" in robot.joint("left_wheel_joint").source
    assert "M17" in robot.joint("shoulder_pan_joint").source


def test_control_semantics_and_poses(robot) -> None:  # type: ignore[no-untyped-def]
    rc = robot.ros2_control
    assert rc.plugin == "mock_components/GenericSystem" and rc.update_rate == 100
    assert [c.name for c in rc.controllers] == ["joint_state_broadcaster", "diff_drive_controller", "arm_controller"]
    wheel = next(cj for cj in rc.joints if cj.name == "left_wheel_joint")
    assert [i.name for i in wheel.command] == ["velocity"]
    assert [i.name for i in wheel.state] == ["position", "velocity"]
    ready = next(s for s in robot.semantic.states if s.name == "ready")
    assert dict(ready.values) == pytest.approx(
        {"lift_joint": 0.15, "shoulder_pan_joint": 0, "shoulder_lift_joint": 0, "elbow_joint": -math.pi / 2}
    )
    assert [p.name for p in robot.known_poses] == ["zero", "ready", "side_reach", "shoulder_up_30"]
    k5 = robot.known_poses[2]
    assert dict(k5.joints) == pytest.approx({"lift_joint": 0.3, "shoulder_pan_joint": math.pi / 2})
    assert k5.frames[0].xyz == pytest.approx((-0.049, 0.552, 0.758)) and k5.frames[0].tolerance == 0.002
