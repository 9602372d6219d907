"""GEOM040-043 beyond the per-rule fixtures: lumping decides whether a massless link survives
(sdformat parser_urdf.cc: ReduceFixedJoints runs before CreateSDF), and the rules see a
generated description. Expected findings are worked out by hand from each URDF."""

from __future__ import annotations

from descgen.audit import run
from descgen.read.urdf import read_urdf_text

INER = '<inertial><mass value="{m}"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'


def _robot(body: str) -> str:
    return f'<?xml version="1.0"?>\n<robot name="r">\n{body}\n</robot>\n'


def _codes(text: str, code: str) -> list[tuple[str, str]]:
    robot, _ = read_urdf_text(text.encode(), "r.urdf")
    return [(f.subject, f.message) for f in run(robot, codes=[code])]


# hand: a massless link "hub" on a revolute joint, with a fixed child "weight" of 2 kg
HUB = _robot(
    f"""<link name="base">{INER.format(m=1)}</link>
<link name="hub"/>
<link name="weight">{INER.format(m=2)}</link>
<joint name="spin" type="continuous"><parent link="base"/><child link="hub"/><axis xyz="0 0 1"/></joint>
<joint name="glue" type="fixed"><parent link="hub"/><child link="weight"/></joint>"""
)


def test_a_fixed_child_with_mass_lumped_into_a_massless_link_keeps_it() -> None:
    assert _codes(HUB, "GEOM040") == []


def test_preserving_that_fixed_joint_leaves_the_link_massless_and_dropped() -> None:
    preserved = HUB.replace(
        "</robot>", '<gazebo reference="glue"><preserveFixedJoint>true</preserveFixedJoint></gazebo>\n</robot>'
    )
    found = _codes(preserved, "GEOM040")
    assert [s for s, _ in found] == ["link:hub"]
    assert "parent joint 'spin' and the 1 link(s) and 1 joint(s) below it" in found[0][1]


def test_a_chain_of_lumped_fixed_joints_carries_mass_up_two_levels() -> None:
    # base(1 kg) -rev-> a(massless) -fixed-> b(massless) -fixed-> c(0.5 kg): a gets c's mass
    text = _robot(
        f"""<link name="base">{INER.format(m=1)}</link><link name="a"/><link name="b"/>
<link name="c">{INER.format(m=0.5)}</link>
<joint name="j1" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
<joint name="j2" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="j3" type="fixed"><parent link="b"/><child link="c"/></joint>"""
    )
    assert _codes(text, "GEOM040") == []
    assert _codes(text.replace('<mass value="0.5"/>', '<mass value="0"/>'), "GEOM040")[0][0] == "link:a"


def test_a_planar_joint_under_ros2_control_says_control_is_lost() -> None:
    text = _robot(
        f"""<link name="odom"/><link name="base">{INER.format(m=1)}</link>
<joint name="slide" type="planar"><parent link="odom"/><child link="base"/><axis xyz="0 0 1"/></joint>
<ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
<joint name="slide"><command_interface name="position"/><state_interface name="position"/></joint></ros2_control>"""
    )
    found = _codes(text, "GEOM042")
    assert [s for s, _ in found] == ["joint:slide"]
    assert found[0][1].endswith("its ros2_control joint loses control in Gazebo")


def test_the_example_loses_nothing_in_gazebo_and_reports_its_merges() -> None:
    from tests.helpers import ROOT

    urdf = (ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf").read_bytes()
    robot, _ = read_urdf_text(urdf, "warehouse_arm.urdf")
    assert run(robot, codes=["GEOM040", "GEOM042", "GEOM043"]) == []
    merged = run(robot, codes=["GEOM041"])
    # the spec's fixed joints: base, caster, arm base, tool, lidar, camera and its optical frame
    assert len(merged) == 1 and merged[0].message.startswith("Gazebo merges 7 fixed joint(s)")
