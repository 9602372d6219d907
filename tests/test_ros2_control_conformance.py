"""Conformance of descgen's model of Jazzy's ``<ros2_control>`` parser with the parser itself,
case by case over ros2_control's own test corpus (issue 33).

Upstream: ros-controls/ros2_control, branch ``jazzy`` at 9ffbf97fd6798085db22797fed44da59089dc10a
(hardware_interface 4.46.0). Short names in the citations below, all at that commit:

- ``C``  = ros2_control_test_assets/include/ros2_control_test_assets/components_urdfs.hpp
- ``D``  = ros2_control_test_assets/include/ros2_control_test_assets/descriptions.hpp
- ``T``  = hardware_interface/test/test_component_parser.cpp
- ``TI`` = hardware_interface/test/test_component_interfaces.cpp
- ``P``  = hardware_interface/src/component_parser.cpp
- ``L``/``LH`` = hardware_interface/src/lexical_casts.cpp / include/hardware_interface/lexical_casts.hpp
- ``CM`` = controller_manager/test/controller_manager_test_common.hpp

"Row" is a row of the throw table in docs/ros2_control_parser_jazzy.md, section 3; the cases
are that file's section 4 table. Every snippet here is written for this test from what the
upstream case exercises (the same element structure, other names and values); none is a copy.
The parser's verdict is the upstream test's (ASSERT_THROW / EXPECT_NO_THROW, or a parse whose
result the test then reads), or for an asset no test uses, the one P gives it.

descgen's verdict: "throw" when ``component_parser.refusals()`` (CTRL066's model of the XML
stage, P:697-800) refuses some ``<ros2_control>`` block of the document, or when one of the
rules that model the parser's URDF stage (P:1034-1089: CTRL001 for rows 19/23, CTRL040-042
for rows 21/20/22, and CTRL043 for a bad ``mimic``) reports the document; "accept" otherwise.

Left out, because they are about the document around the tag, not about the tag:
- T:41 (``""``, row 1), T:46 (a ``<robot>`` with no ``<ros2_control>``, row 4: descgen audits
  URDFs without ros2_control) and T:54 (junk before ``<?xml``, row 2): the XML document itself;
- T:1329 (``urdf_head_revolute_missing_limits`` D:150 / ``urdf_head_prismatic_missing_limits``
  D:455 with C:21) and T:1727 (``gripper_urdf_head_invalid_two_root_links`` D:1946): row 18,
  urdfdom refusing the URDF (descgen's own URDF rules, e.g. JOINT003, cover that); the
  ``<ros2_control>`` part of T:1329 is C:21, which is a case below;
- T:847 (locale), T:1749/1768/1791/1815/1840 (interface descriptions): the same assets as
  T:786/705/753/871, no new verdict.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import pytest
from lxml import etree

from descgen.audit import run as run_rules
from descgen.physics.component_parser import refusals
from descgen.read.urdf import read_urdf_text

from .helpers import cli

ACCEPT, THROW = "accept", "throw"
# the rules that model the parser's URDF stage (P:1034-1089) and its mimic parse_bool (P:454-467)
URDF_STAGE = ("CTRL001", "CTRL040", "CTRL041", "CTRL042", "CTRL043")


@dataclass(frozen=True)
class Case:
    name: str  # the upstream asset or test (a suffix tells variants apart)
    source: str  # where upstream fixes the verdict (file:line at 9ffbf97)
    parser: str  # the jazzy parser's verdict: ACCEPT or THROW
    document: str  # our own URDF (SDF for one case) for what the case tests
    rule: str = ""  # for a THROW: the descgen rule that reports it (CTRL066 = refusals())
    message: str | None = None  # for a CTRL066 throw: the parser's what(), our names filled in


# -- our own robots --------------------------------------------------------------------------
# In place of urdf_head (D:23): a fixed joint to the world, three revolute joints (the middle
# one with a <safety_controller>) and a fixed sensor mount (tool_joint's role). pan/lift/tilt
# stand for joint1/joint2/joint3, sensor_fix for tool_joint.
def _arm_head(kind: str = "revolute") -> str:
    """``revolute`` (D:23), ``continuous`` (pan and lift continuous without <limit>, D:240) or
    ``continuous_limited`` (with effort and velocity only, D:364)."""
    limit = {
        "revolute": '<limit lower="-2.5" upper="2.5" effort="40" velocity="1.5"/>',
        "continuous": "",
        "continuous_limited": '<limit effort="40" velocity="1.5"/>',
    }[kind]
    kind_of = "revolute" if kind == "revolute" else "continuous"
    return f"""
  <link name="ground"/>
  <joint name="ground_fix" type="fixed"><parent link="ground"/><child link="pedestal"/></joint>
  <link name="pedestal"/>
  <joint name="pan" type="{kind_of}"><parent link="pedestal"/><child link="turret"/>
    <axis xyz="0 0 1"/>{limit}</joint>
  <link name="turret"/>
  <joint name="lift" type="{kind_of}"><parent link="turret"/><child link="boom"/>
    <axis xyz="0 1 0"/>{limit}
    <safety_controller soft_lower_limit="-2.0" soft_upper_limit="1.0" k_position="15" k_velocity="5"/></joint>
  <link name="boom"/>
  <joint name="tilt" type="revolute"><parent link="boom"/><child link="head"/>
    <axis xyz="0 1 0"/><limit lower="-1.2" upper="1.2" effort="10" velocity="2"/></joint>
  <link name="head"/>
  <joint name="sensor_fix" type="fixed"><parent link="boom"/><child link="sensor_plate"/></joint>
  <link name="sensor_plate"/>
"""


ARM = _arm_head()


def arm(*blocks: str, head: str = ARM, extra: str = "") -> str:
    return f'<?xml version="1.0"?>\n<robot name="bench_arm">{head}{"".join(blocks)}{extra}\n</robot>\n'


# In place of gripper_urdf_head (D:1686): jaw_b_joint mimics jaw_a_joint. The variants: no
# <mimic> (D:1757), a <mimic> of a joint the URDF does not have (D:1827), and jaw_b_joint left
# out of the URDF (D:1898).
def _gripper_head(mimic: str = "jaw_a_joint", with_b: bool = True) -> str:
    m = f'<mimic joint="{mimic}" multiplier="-1" offset="0.01"/>' if mimic else ""
    b = f"""
  <joint name="jaw_b_joint" type="prismatic">{m}<parent link="palm"/><child link="jaw_b"/>
    <axis xyz="-1 0 0"/><limit lower="0" upper="0.05" effort="80" velocity="0.2"/></joint>
  <link name="jaw_b"/>"""
    return f"""
  <link name="table"/>
  <joint name="table_fix" type="fixed"><parent link="table"/><child link="palm"/></joint>
  <link name="palm"/>
  <joint name="jaw_a_joint" type="prismatic"><parent link="palm"/><child link="jaw_a"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.05" effort="80" velocity="0.2"/></joint>
  <link name="jaw_a"/>{b if with_b else ""}
"""


def gripper(*blocks: str, head: str | None = None) -> str:
    head = _gripper_head() if head is None else head
    return f'<?xml version="1.0"?>\n<robot name="bench_gripper">{head}{"".join(blocks)}\n</robot>\n'


def _cmd(name: str, lo: str = "", hi: str = "", *more: str) -> str:
    """A command interface with optional min/max params and more params (name, value)."""
    params = ([f'<param name="min">{lo}</param>'] if lo else []) + ([f'<param name="max">{hi}</param>'] if hi else [])
    return f'<command_interface name="{name}">{"".join(params)}{"".join(more)}</command_interface>'


def _hw(plugin: str, *params: tuple[str, str], group: str = "") -> str:
    g = f"<group>{group}</group>" if group else ""
    p = "".join(f'<param name="{k}">{v}</param>' for k, v in params)
    return f"<hardware><plugin>{plugin}</plugin>{g}{p}</hardware>"


BUS = (("bus", "can0"), ("timeout_ms", "40"))
POSITION_PAN_LIFT = f"""
    <joint name="pan">{_cmd("position", "-2", "2")}<state_interface name="position"/></joint>
    <joint name="lift">{_cmd("position", "-2", "2")}<state_interface name="position"/></joint>"""
WRIST_FT = """
    <sensor name="wrist_ft">
      <state_interface name="force.x"/><state_interface name="force.y"/><state_interface name="force.z"/>
      <state_interface name="torque.x"/><state_interface name="torque.y"/><state_interface name="torque.z"/>
      <param name="frame_id">ft_frame</param><param name="range_min">-250</param><param name="range_max">250</param>
    </sensor>"""
# a gpio with an array, a bool and a type the parser does not know (C:464-468)
FLANGE_IO = """
    <gpio name="tool_io">
      <command_interface name="relay" size="2" data_type="bool"/>
      <state_interface name="adc" size="4"/>
      <state_interface name="snapshot" data_type="cv::Mat"/>
    </gpio>"""
# the three blocks of hardware_resources (D:649), reused by D:762/818/873 with changes
THREE = {
    "actuator": """
    <joint name="pan">
      <command_interface name="position"/><state_interface name="position"/>
      <state_interface name="velocity"/><command_interface name="speed_cap"/>
    </joint>""",
    "sensor": '<sensor name="imu_yaw"><state_interface name="velocity"/></sensor>',
    "system": """
    <joint name="lift">
      <command_interface name="velocity"/><state_interface name="position"/><state_interface name="velocity"/>
      <state_interface name="acceleration"/><command_interface name="accel_cap"/>
    </joint>
    <joint name="tilt">
      <command_interface name="velocity"/><state_interface name="position"/><state_interface name="velocity"/>
      <state_interface name="acceleration"/>
    </joint>
    <gpio name="tuning"><command_interface name="jerk_cap"/><state_interface name="jerk_cap"/></gpio>""",
}
# jazzy's full set of joint command interfaces, with min/max on some (C:599-628)
ALL_INTERFACES = f"""
    <joint name="pan">
      {_cmd("position", "-2", "2")}{_cmd("velocity", "-0.1", "0.3")}{_cmd("effort", "-5", "5")}
      {_cmd("acceleration", "-0.8", "0.8")}{_cmd("jerk", "", "9")}<state_interface name="position"/>
    </joint>
    <joint name="lift">
      <command_interface name="position"/><command_interface name="velocity"/><command_interface name="effort"/>
      <command_interface name="acceleration"/><command_interface name="jerk"/><state_interface name="position"/>
    </joint>"""


def _gripper_block(b_joint: str) -> str:
    """gripper_hardware_resources_* (D:2009-2073): no <hardware> at all, jaw_a_joint driven."""
    return f"""
  <ros2_control name="BenchGripper" type="system">
    <joint name="jaw_a_joint">
      <command_interface name="effort"/><state_interface name="position"/>
      <state_interface name="velocity"/><state_interface name="effort"/>
    </joint>
    {b_joint}
  </ros2_control>"""


B_STATE = '<joint name="jaw_b_joint"><state_interface name="position"/><state_interface name="velocity"/></joint>'
B_MIMIC_STATE = B_STATE.replace('"jaw_b_joint"', '"jaw_b_joint" mimic="true"')
B_MIMIC_COMMAND = B_MIMIC_STATE.replace("<state_interface", '<command_interface name="effort"/><state_interface', 1)
B_NOT_MIMIC_COMMAND = B_MIMIC_COMMAND.replace('mimic="true"', 'mimic="false"')

CART_SDF = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="cart">
    <link name="chassis"/>
    <joint name="wheel_l_joint" type="revolute"><parent>chassis</parent><child>wheel_l</child>
      <axis><xyz>0 1 0</xyz><limit><lower>-inf</lower><upper>inf</upper></limit></axis></joint>
    <link name="wheel_l"/>
    <joint name="wheel_r_joint" type="revolute"><parent>chassis</parent><child>wheel_r</child>
      <axis><xyz>0 1 0</xyz><limit><lower>-inf</lower><upper>inf</upper></limit></axis></joint>
    <link name="wheel_r"/>
    <ros2_control name="CartSim" type="system">
      <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
      <joint name="wheel_l_joint"><command_interface name="velocity"><param name="min">-6</param>
        <param name="max">6</param></command_interface>
        <state_interface name="velocity"/><state_interface name="position"/></joint>
      <joint name="wheel_r_joint"><command_interface name="velocity"><param name="min">-6</param>
        <param name="max">6</param></command_interface>
        <state_interface name="velocity"/><state_interface name="position"/></joint>
    </ros2_control>
    <plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
      <parameters>cart_controllers.yaml</parameters>
    </plugin>
  </model>
</sdf>
"""

MODBUS_10 = '<param name="address">10</param><param name="width">2</param>'

# -- the cases of ros2_control's own corpus (docs/ros2_control_parser_jazzy.md, section 4) ----
UPSTREAM = [
    # C:21 two joints, position command with min/max, hardware params; T:104 parses it
    Case(
        "valid_urdf_ros2_control_system_one_interface",
        "C:21, T:104",
        ACCEPT,
        arm(
            f'<ros2_control name="PanLiftPosition" type="system">{_hw("bench_hw/PanLift", *BUS)}'
            f"{POSITION_PAN_LIFT}</ros2_control>"
        ),
    ),
    # C:48 initial_value params; an effort max with a stray quote (kept as text, stderr only, P:832)
    Case(
        "valid_urdf_ros2_control_system_multi_interface",
        "C:48, T:168",
        ACCEPT,
        arm(f"""<ros2_control name="PanLiftMulti" type="system">{_hw("bench_hw/PanLiftMulti", *BUS)}
    <joint name="pan">
      {_cmd("position", "-2", "2", '<param name="initial_value">0.4</param>')}
      {_cmd("velocity", "-1", "1", '<param name="initial_value">-0.2</param>')}
      {_cmd("effort", "-0.8", '0.8"')}
      <state_interface name="position"/><state_interface name="velocity"/><state_interface name="effort"/>
    </joint>
    <joint name="lift">{_cmd("position", "-2", "2")}
      <state_interface name="position"/><state_interface name="velocity"/><state_interface name="effort"/>
    </joint></ros2_control>"""),
    ),
    # C:89 arbitrary interface params (a data_type *param* too), joint params, blanks in texts
    Case(
        "valid_urdf_ros2_control_system_multi_interface_and_custom_interface_parameters",
        "C:89, T:300",
        ACCEPT,
        arm(f"""<ros2_control name="PanLiftModbus" type="system">{_hw("bench_hw/PanLiftModbus", *BUS)}
    <joint name="pan">
      {_cmd("position", "-2", "2", '<param name="initial_value">0.1</param>', MODBUS_10)}
      {_cmd("velocity", "-1.5", "1.5", '<param name="address">12</param>')}
      {_cmd("effort", "-3", "3")}
      <state_interface name="position"><param name="address">30</param><param name="width">2</param></state_interface>
      <state_interface name="velocity"><param name="address">32</param></state_interface>
      <state_interface name="effort"/>
      <param name="host"> 10.0.0.7</param>
      <param name="port">502
      </param>
      <param name="keep_alive"> false</param>
    </joint>
    <joint name="lift">
      {_cmd("position", "-2", "2", '<param name="address">40</param><param name="data_type">uint16_t</param>')}
      <state_interface name="position"><param name="address">41</param><param name="data_type">uint16_t </param>
      </state_interface>
      <state_interface name="velocity"/>
      <state_interface name="effort"><param name="data_type"> uint16_t </param></state_interface>
      <param name="host">10.0.0.8</param>
    </joint></ros2_control>"""),
    ),
    # C:153 a sensor with six state interfaces and params in the system block
    Case(
        "valid_urdf_ros2_control_system_robot_with_sensor",
        "C:153, T:231",
        ACCEPT,
        arm(
            f'<ros2_control name="PanLiftFt" type="system">{_hw("bench_hw/PanLiftFt", *BUS)}'
            f"{POSITION_PAN_LIFT}{WRIST_FT}</ros2_control>"
        ),
    ),
    # C:190 two blocks: the system, and a sensor block for the same sensor
    Case(
        "valid_urdf_ros2_control_system_robot_with_external_sensor",
        "C:190, T:402",
        ACCEPT,
        arm(
            f'<ros2_control name="PanLiftPosition" type="system">{_hw("bench_hw/PanLift", *BUS)}'
            f"{POSITION_PAN_LIFT}</ros2_control>",
            f'<ros2_control name="WristFt" type="sensor">{_hw("bench_hw/Ft", ("period", "0.01"))}'
            f"{WRIST_FT}</ros2_control>",
        ),
    ),
    # C:233 one actuator block per joint, with <group>
    Case(
        "valid_urdf_ros2_control_actuator_modular_robot",
        "C:233, T:470",
        ACCEPT,
        arm(
            *(
                f'<ros2_control name="Module_{j}" type="actuator">'
                f"{_hw('bench_hw/Module', ('slot', str(i)), group='bench modules')}"
                f'<joint name="{j}">{_cmd("position", "-2", "2")}<state_interface name="position"/></joint>'
                "</ros2_control>"
                for i, j in enumerate(("pan", "lift"))
            )
        ),
    ),
    # C:269 actuators (one with a simple transmission and mechanical_reduction), and sensor
    # blocks holding state-only joints
    Case(
        "valid_urdf_ros2_control_actuator_modular_robot_sensors",
        "C:269, T:545",
        ACCEPT,
        arm(
            f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive", group="bus a")}
    <joint name="pan">{_cmd("velocity", "-1", "1")}<state_interface name="velocity"/></joint>
    <transmission name="pan_belt">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="pan" role="joint1"><mechanical_reduction>48.5</mechanical_reduction></joint>
    </transmission></ros2_control>""",
            f'<ros2_control name="LiftDrive" type="actuator">{_hw("bench_hw/Drive", group="bus b")}'
            f'<joint name="lift">{_cmd("velocity", "-1", "1")}<state_interface name="velocity"/></joint>'
            "</ros2_control>",
            f'<ros2_control name="PanEncoder" type="sensor">{_hw("bench_hw/Encoder", group="bus a")}'
            '<joint name="pan"><state_interface name="position"/></joint></ros2_control>',
            f'<ros2_control name="LiftEncoder" type="sensor">{_hw("bench_hw/Encoder", group="bus b")}'
            '<joint name="lift"><state_interface name="position"/></joint></ros2_control>',
        ),
    ),
    # C:331 a differential transmission: two actuators (one read_only), joints with
    # mechanical_reduction, offset and read_only
    Case(
        "valid_urdf_ros2_control_system_multi_joints_transmission",
        "C:331, T:705",
        ACCEPT,
        arm(f"""<ros2_control name="Wrist" type="system">{_hw("bench_hw/Wrist")}{POSITION_PAN_LIFT}
    <transmission name="bevel">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="motor_left" role="actuator1" read_only="true"/>
      <actuator name="motor_right" role="actuator2"/>
      <joint name="pan" role="joint1"><mechanical_reduction>12</mechanical_reduction><offset>0.25</offset></joint>
      <joint name="lift" role="joint2" read_only="false"><mechanical_reduction>30</mechanical_reduction></joint>
    </transmission></ros2_control>"""),
    ),
    # C:369 a sensor block with two sensors
    Case(
        "valid_urdf_ros2_control_sensor_only",
        "C:369, T:753",
        ACCEPT,
        arm(f"""<ros2_control name="Head" type="sensor">{_hw("bench_hw/Head", ("period", "0.05"))}
    <sensor name="attitude"><state_interface name="roll"/><state_interface name="pitch"/>
      <state_interface name="yaw"/></sensor>
    <sensor name="camera"><state_interface name="frame"/></sensor></ros2_control>"""),
    ),
    # C:388 an actuator block with a transmission <param>
    Case(
        "valid_urdf_ros2_control_actuator_only",
        "C:388, T:786",
        ACCEPT,
        arm(f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive", ("slot", "3"))}
    <joint name="pan">{_cmd("velocity", "-1", "1")}<state_interface name="velocity"/></joint>
    <transmission name="pan_screw">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="pan" role="joint1"><mechanical_reduction>101.5</mechanical_reduction></joint>
      <param name="backlash">0.002</param>
    </transmission></ros2_control>"""),
    ),
    # C:414 two gpios, one with an initial_value on a state interface
    Case(
        "valid_urdf_ros2_control_system_robot_with_gpio",
        "C:414, T:871",
        ACCEPT,
        arm(f"""<ros2_control name="PanLiftIo" type="system">{_hw("bench_hw/PanLiftIo", *BUS)}{POSITION_PAN_LIFT}
    <gpio name="tool_analog">
      <command_interface name="aout0"/><state_interface name="aout0"/>
      <state_interface name="ain0"/><state_interface name="ain1"/>
    </gpio>
    <gpio name="suction">
      <command_interface name="pump"/>
      <state_interface name="pump"><param name="initial_value">0.0</param></state_interface>
    </gpio></ros2_control>"""),
    ),
    # C:452 size and data_type on gpio interfaces (cv::Mat accepted: the parser does not check it)
    Case(
        "valid_urdf_ros2_control_system_robot_with_size_and_data_type",
        "C:452, T:940",
        ACCEPT,
        arm(f"""<ros2_control name="PanIo" type="system">{_hw("bench_hw/PanIo", *BUS)}
    <joint name="pan"><command_interface name="position"/><state_interface name="position"/></joint>
    {FLANGE_IO}</ros2_control>"""),
    ),
    # C:473 <limits enable="false"> on an interface and on a joint; acceleration/jerk min/max
    Case(
        "valid_urdf_ros2_control_system_robot_with_gpio_and_disabled_interface_limits",
        "C:473, T:1064",
        ACCEPT,
        arm(f"""<ros2_control name="PanLiftTiltIo" type="system">{_hw("bench_hw/PanLiftTilt", *BUS)}
    <joint name="pan">
      <command_interface name="position"><limits enable="false"/><param name="min">-2</param>
        <param name="max">2</param></command_interface>
      {_cmd("velocity", "-0.1", "0.3")}{_cmd("effort", "-5", "5")}{_cmd("acceleration", "-0.8", "0.8")}
      {_cmd("jerk", "", "9")}<state_interface name="position"/>
    </joint>
    <joint name="lift">
      <limits enable="false"/>
      {_cmd("position", "-2", "2")}<command_interface name="velocity"/><command_interface name="effort"/>
      {_cmd("acceleration", "-0.4", "0.4")}{_cmd("jerk", "-3", "3")}<state_interface name="position"/>
    </joint>
    <joint name="tilt">{_cmd("acceleration", "", "2")}</joint>
    {FLANGE_IO}</ros2_control>"""),
    ),
    # C:534 min on acceleration only; min/max on an interface that is no joint limit (stderr only, P:896)
    Case(
        "valid_urdf_ros2_control_system_robot_with_unavailable_interfaces",
        "C:534, T:1206",
        ACCEPT,
        arm(f"""<ros2_control name="PanLiftTilt" type="system">{_hw("bench_hw/PanLiftTilt", *BUS)}
    <joint name="pan">
      <command_interface name="position"><limits enable="false"/><param name="min">-2</param>
        <param name="max">2</param></command_interface>
      {_cmd("velocity", "-0.1", "0.3")}{_cmd("jerk", "", "9")}<state_interface name="position"/>
    </joint>
    <joint name="lift"><limits enable="false"/>{_cmd("position", "-2", "2")}
      {_cmd("acceleration", "-0.4", "0.4")}<command_interface name="jerk"/><state_interface name="position"/></joint>
    <joint name="tilt">{_cmd("acceleration", "0.5")}{_cmd("torque_ripple", "-0.4", "0.4")}</joint>
    </ros2_control>"""),
    ),
    # C:591 every joint command interface; the URDF's pan/lift continuous without <limit>
    Case(
        "valid_urdf_ros2_control_system_robot_with_all_interfaces+urdf_head_continuous_missing_limits",
        "C:591, D:240, T:1352-1358 (EXPECT_NO_THROW)",
        ACCEPT,
        arm(
            f'<ros2_control name="PanLiftAll" type="system">{_hw("bench_hw/PanLift", *BUS)}{ALL_INTERFACES}'
            "</ros2_control>",
            head=_arm_head("continuous"),
        ),
    ),
    # ... and continuous with effort/velocity <limit>
    Case(
        "valid_urdf_ros2_control_system_robot_with_all_interfaces+urdf_head_continuous_with_limits",
        "C:591, D:364, T:1390-1396 (EXPECT_NO_THROW)",
        ACCEPT,
        arm(
            f'<ros2_control name="PanLiftAll" type="system">{_hw("bench_hw/PanLift", *BUS)}{ALL_INTERFACES}'
            "</ros2_control>",
            head=_arm_head("continuous_limited"),
        ),
    ),
    # C:633 initial_value as an *attribute* of an interface: ignored (unknown attributes are)
    Case(
        "valid_urdf_ros2_control_voltage_sensor_only",
        "C:633, TI:1054-1058",
        ACCEPT,
        arm(
            f'<ros2_control name="Battery" type="sensor">{_hw("bench_hw/Battery", ("period", "1"))}'
            '<sensor name="cell"><state_interface name="volts" initial_value="12.0"/></sensor></ros2_control>'
        ),
    ),
    # C:647 a sensor block with a state-only joint and a sensor
    Case(
        "valid_urdf_ros2_control_joint_voltage_sensor",
        "C:647, TI:1102-1106",
        ACCEPT,
        arm(
            f'<ros2_control name="Battery" type="sensor">{_hw("bench_hw/Battery", ("period", "1"))}'
            '<joint name="pan"><state_interface name="position"/></joint>'
            '<sensor name="cell"><state_interface name="volts" initial_value="12.0"/></sensor></ros2_control>'
        ),
    ),
    # C:663 an actuator with a transmission and its <param>
    Case(
        "valid_urdf_ros2_control_dummy_actuator_only",
        "C:663, TI:888-892",
        ACCEPT,
        arm(f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive", ("slot", "1"))}
    <joint name="pan">{_cmd("velocity", "-1", "1")}<state_interface name="position"/>
      <state_interface name="velocity"/></joint>
    <transmission name="pan_gear">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="pan" role="joint1"><mechanical_reduction>20</mechanical_reduction></joint>
      <param name="lash">0.01</param>
    </transmission></ros2_control>"""),
    ),
    # C:689 three joints with a velocity command each
    Case(
        "valid_urdf_ros2_control_dummy_system_robot",
        "C:689, TI:1293-1297",
        ACCEPT,
        arm(
            f'<ros2_control name="PanLiftTilt" type="system">{_hw("bench_hw/PanLiftTilt", *BUS)}'
            + "".join(
                f'<joint name="{j}">{_cmd("velocity", "-1", "1")}<state_interface name="position"/>'
                '<state_interface name="velocity"/></joint>'
                for j in ("pan", "lift", "tilt")
            )
            + "</ros2_control>"
        ),
    ),
    # C:724 an empty <param></param> (text "", stderr only, P:97-100); an empty interface body
    Case(
        "valid_urdf_ros2_control_parameter_empty",
        "C:724, T:1501",
        ACCEPT,
        arm("""<ros2_control name="PanOnly" type="system">
    <hardware><plugin>bench_hw/PanOnly</plugin><param name="bus"></param><param name="timeout_ms">40</param></hardware>
    <joint name="pan"><command_interface name="position">
    </command_interface></joint></ros2_control>"""),
    ),
    # C:739 bool interfaces on a joint, a *command* interface on a sensor, a gpio
    Case(
        "valid_urdf_ros2_control_system_robot_with_size_and_data_type_on_joint_sensor_and_gpio",
        "C:739, T:988",
        ACCEPT,
        arm(f"""<ros2_control name="PanTyped" type="system">{_hw("bench_hw/PanTyped", *BUS)}
    <joint name="pan">
      <command_interface name="position"/><state_interface name="position"/>
      <state_interface name="brake_engaged" data_type="bool"/><command_interface name="brake" data_type="bool"/>
    </joint>
    <sensor name="light_curtain">
      <command_interface name="mute" data_type="bool"/><state_interface name="mute" data_type="bool"/>
    </sensor>
    {FLANGE_IO}</ros2_control>"""),
    ),
    # C:766 a child of <ros2_control> the parser does not know (a misspelt <hardware>): row 17
    Case(
        "invalid_urdf_ros2_control_invalid_child",
        "C:766, T:64-71 (ASSERT_THROW)",
        THROW,
        arm("""<ros2_control name="PanOnly" type="system">
    <hardware_if><plugin>bench_hw/PanOnly</plugin><param name="bus">can0</param></hardware_if>
    </ros2_control>"""),
        "CTRL066",
        "invalid tag name 'hardware_if'",
    ),
    # C:777 <ros2_control> without a name: row 5
    Case(
        "invalid_urdf_ros2_control_missing_attribute",
        "C:777, T:74-81 (ASSERT_THROW)",
        THROW,
        arm(f'<ros2_control type="system">{_hw("bench_hw/PanOnly", *BUS)}</ros2_control>'),
        "CTRL066",
        "no attribute 'name' in 'ros2_control' tag",
    ),
    # C:788 (no test uses it) a joint with params and no interface: nothing in P:446-506 throws
    Case(
        "invalid_urdf_ros2_control_component_missing_plugin_name",
        "C:788 (unused upstream; P:446-506 reads it without a throw)",
        ACCEPT,
        arm(f"""<ros2_control name="PanOnly" type="system">{_hw("bench_hw/PanOnly", *BUS)}
    <joint name="pan"><param name="soft_min">-1.5</param><param name="soft_max">1.5</param></joint>
    </ros2_control>"""),
    ),
    # C:803 a hardware <param> without a name: row 6 (the joint-level <plugin> is never reached)
    Case(
        "invalid_urdf_ros2_control_parameter_missing_name",
        "C:803, T:84-91 (ASSERT_THROW)",
        THROW,
        arm("""<ros2_control name="PanOnly" type="system">
    <hardware><plugin>bench_hw/PanOnly</plugin><param>5</param><param name="timeout_ms">40</param></hardware>
    <joint name="pan"><plugin>bench_components/Axis</plugin><param name="soft_min">-1.5</param></joint>
    </ros2_control>"""),
        "CTRL066",
        "no parameter name attribute set in param tag for 'PanOnly'",
    ),
    # C:819 (no test uses it) an empty <plugin> inside a joint: unknown joint children are ignored
    Case(
        "invalid_urdf_ros2_control_component_plugin_name_empty",
        "C:819 (unused upstream; P:446-506 ignores a joint's <plugin>)",
        ACCEPT,
        arm(f"""<ros2_control name="PanOnly" type="system">{_hw("bench_hw/PanOnly", *BUS)}
    <joint name="pan"><plugin></plugin><param name="soft_min">-1.5</param><param name="soft_max">1.5</param></joint>
    </ros2_control>"""),
    ),
    # C:835 a <state_interface> without a name: row 5
    Case(
        "invalid_urdf_ros2_control_component_interface_type_empty",
        "C:835, T:94-101 (ASSERT_THROW)",
        THROW,
        arm(f"""<ros2_control name="PanOnly" type="system">{_hw("bench_hw/PanOnly", *BUS)}
    <joint name="pan"><plugin>bench_components/Axis</plugin><state_interface></state_interface>
      <param name="soft_min">-1.5</param></joint>
    </ros2_control>"""),
        "CTRL066",
        "no attribute 'name' in 'state_interface' tag",
    ),
    # C:852 a negative size: row 7
    Case(
        "invalid_urdf2_ros2_control_illegal_size",
        "C:852, T:1553-1558 (ASSERT_THROW)",
        THROW,
        arm(f"""<ros2_control name="IoBoard" type="system">{_hw("bench_hw/IoBoard")}
    <gpio name="tool_io"><command_interface name="relay" data_type="bool" size="-3"/></gpio></ros2_control>"""),
        "CTRL066",
        'Could not parse size tag in "command_interface". Got "-3", but expected a non-zero positive integer.',
    ),
    # C:864 a size that is not a number: row 7
    Case(
        "invalid_urdf2_ros2_control_illegal_size2",
        "C:864, T:1561-1566 (ASSERT_THROW)",
        THROW,
        arm(f"""<ros2_control name="IoBoard" type="system">{_hw("bench_hw/IoBoard")}
    <gpio name="tool_io"><command_interface name="relay" data_type="bool" size="several"/></gpio></ros2_control>"""),
        "CTRL066",
        'Could not parse size tag in "command_interface". Got "several", but expected a non-zero positive integer.',
    ),
    # C:876 a transmission joint that is not a joint of the block: row 13
    Case(
        "invalid_urdf2_hw_transmission_joint_mismatch",
        "C:876, T:1569-1575 (ASSERT_THROW)",
        THROW,
        arm(f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive")}
    <joint name="pan">{_cmd("velocity", "-1", "1")}<state_interface name="velocity"/></joint>
    <transmission name="pan_belt"><plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="pan_axis" role="joint1"/></transmission></ros2_control>"""),
        "CTRL066",
        "Error while parsing 'PanDrive'. Transmission 'pan_belt' declared joint 'pan_axis' is not available in "
        "component 'PanDrive'.",
    ),
    # C:896 two transmission joints in an actuator block, the second not in the block: row 13
    # fires before row 14 (P:645-655 runs before P:670-679)
    Case(
        "invalid_urdf2_transmission_given_too_many_joints",
        "C:896, T:1578-1584 (ASSERT_THROW)",
        THROW,
        arm(f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive")}
    <joint name="pan">{_cmd("velocity", "-1", "1")}<state_interface name="velocity"/></joint>
    <transmission name="pan_belt"><plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="pan" role="joint1"/><joint name="lift" role="joint2"/></transmission></ros2_control>"""),
        "CTRL066",
        "Error while parsing 'PanDrive'. Transmission 'pan_belt' declared joint 'lift' is not available in "
        "component 'PanDrive'.",
    ),
    # C:917 a ros2_control joint that is a fixed URDF joint: row 23 (URDF stage)
    Case(
        "invalid_urdf_ros2_control_system_with_command_fixed_joint",
        "C:917, T:1343-1349 (EXPECT_THROW)",
        THROW,
        arm(f"""<ros2_control name="PanOnly" type="system">{_hw("bench_hw/PanOnly", *BUS)}
    <joint name="sensor_fix"><command_interface name="position">
    </command_interface></joint></ros2_control>"""),
        "CTRL001",
    ),
    # D:649 + D:738 hardware_resources: three blocks, a simple and two differential/four-bar
    # transmissions, a gpio; plus an old top-level <transmission> outside <ros2_control>, which
    # this parser ignores. It is minimal_robot_urdf (D:2342), the controller_manager tests' robot.
    Case(
        "hardware_resources+minimal_robot_transmissions",
        "D:649, D:738, D:2342; CM:59 (the default robot_description the controller_manager loads)",
        ACCEPT,
        arm(
            f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive")}{THREE["actuator"]}
    <transmission name="pan_gear"><plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="pan" role="joint1"><mechanical_reduction>64</mechanical_reduction></joint></transmission>
    </ros2_control>""",
            f'<ros2_control name="Yaw" type="sensor">{_hw("bench_hw/Yaw", ("period", "0.02"))}{THREE["sensor"]}'
            "</ros2_control>",
            f"""<ros2_control name="LiftTilt" type="system">{_hw("bench_hw/LiftTilt", *BUS)}{THREE["system"]}
    <transmission name="bevel"><plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="motor_l" role="actuator1"><mechanical_reduction>40</mechanical_reduction></actuator>
      <actuator name="motor_r" role="actuator2"><mechanical_reduction>-40</mechanical_reduction></actuator>
      <joint name="lift" role="joint1"><offset>0.2</offset><mechanical_reduction>1.5</mechanical_reduction></joint>
      <joint name="tilt" role="joint2"><offset>-0.2</offset><mechanical_reduction>-1.5</mechanical_reduction></joint>
    </transmission>
    <transmission name="linkage"><plugin>transmission_interface/FourBarLinkageTransmission</plugin>
      <actuator name="motor_l" role="actuator1"/><actuator name="motor_r" role="actuator2"/>
      <joint name="lift" role="joint1"/><joint name="tilt" role="joint2"/>
    </transmission></ros2_control>""",
            extra="""
  <transmission name="legacy_pan"><type>transmission_interface/SimpleTransmission</type>
    <joint name="pan"><hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="legacy_motor"><mechanicalReduction>64</mechanicalReduction></actuator>
  </transmission>""",
        ),
    ),
    # D:762 joint-level and interface-level <limits enable="false"> across three blocks
    Case(
        "hardware_resources_with_disabled_limits",
        "D:762, T:1859-1867 (ASSERT_NO_THROW)",
        ACCEPT,
        arm(
            f"""<ros2_control name="PanDrive" type="actuator">{_hw("bench_hw/Drive")}
    <joint name="pan"><limits enable="false"/><command_interface name="position"/>
      <command_interface name="velocity"/><command_interface name="effort"/><state_interface name="position"/>
      <state_interface name="velocity"/><command_interface name="speed_cap"/></joint></ros2_control>""",
            f'<ros2_control name="Yaw" type="sensor">{_hw("bench_hw/Yaw")}{THREE["sensor"]}</ros2_control>',
            f"""<ros2_control name="LiftTilt" type="system">{_hw("bench_hw/LiftTilt", *BUS)}
    <joint name="lift"><limits enable="false"/><command_interface name="velocity"/>
      <state_interface name="position"/><command_interface name="accel_cap"/></joint>
    <joint name="tilt"><command_interface name="position"><limits enable="false"/></command_interface>
      <command_interface name="velocity"/><state_interface name="position"/></joint>
    <gpio name="tuning"><command_interface name="jerk_cap"/><state_interface name="jerk_cap"/></gpio>
    </ros2_control>""",
        ),
    ),
    # D:818 (minimal_async_robot_urdf D:2346) is_async, thread_priority, <properties><async>
    # with affinity (blanks inside the array), scheduling_policy, print_warnings; a default
    # priority; <async thread_priority> overriding
    Case(
        "async_hardware_resources",
        "D:818, D:2346, T:1432-1499",
        ACCEPT,
        arm(
            f"""<ros2_control name="PanDrive" type="actuator" is_async="true" thread_priority="40">
    <properties><async affinity="[1, 3,5]" scheduling_policy="detached" print_warnings="false"/></properties>
    {_hw("bench_hw/Drive")}{THREE["actuator"]}</ros2_control>""",
            f'<ros2_control name="Yaw" type="sensor" is_async="true">{_hw("bench_hw/Yaw")}{THREE["sensor"]}'
            "</ros2_control>",
            f"""<ros2_control name="LiftTilt" type="system" is_async="true">
    <properties><async thread_priority="60" affinity="[0]" scheduling_policy="synchronized"/></properties>
    {_hw("bench_hw/LiftTilt", *BUS)}{THREE["system"]}</ros2_control>""",
        ),
    ),
    # T:1543 an async block whose thread_priority is negative: row 11
    Case(
        "successfully_parse_valid_urdf_async_invalid_thread_priority (inline)",
        "T:1543-1550 (ASSERT_THROW)",
        THROW,
        arm('<ros2_control name="PanDrive" type="actuator" is_async="true" thread_priority="-5"/>'),
        "CTRL066",
        'Could not parse thread_priority tag in "ros2_control". Got "-5", but expected a non-zero positive integer.',
    ),
    # D:873 (minimal_robot_urdf_with_different_hw_rw_rate D:2348) rw_rate on each block
    Case(
        "hardware_resources_with_different_rw_rates",
        "D:873, D:2348, T:1653-1683 (ASSERT_NO_THROW)",
        ACCEPT,
        arm(
            f'<ros2_control name="PanDrive" type="actuator" rw_rate="100">{_hw("bench_hw/Drive")}'
            f"{THREE['actuator']}</ros2_control>",
            f'<ros2_control name="Yaw" type="sensor" rw_rate="10">{_hw("bench_hw/Yaw")}{THREE["sensor"]}'
            "</ros2_control>",
            f'<ros2_control name="LiftTilt" type="system" rw_rate="40">{_hw("bench_hw/LiftTilt", *BUS)}'
            f"{THREE['system']}</ros2_control>",
        ),
    ),
    # D:971 a negative rw_rate: row 8 (on the gripper head, as upstream)
    Case(
        "hardware_resources_with_negative_rw_rates",
        "D:971, T:1623-1630 (ASSERT_THROW)",
        THROW,
        gripper(f"""<ros2_control name="JawDrive" type="actuator" rw_rate="-10">{_hw("bench_hw/Jaw")}
    <joint name="jaw_a_joint"><command_interface name="position"/><state_interface name="position"/></joint>
    </ros2_control>"""),
        "CTRL066",
        'Could not parse rw_rate tag in "ros2_control". Got "-10", but expected a positive integer.',
    ),
    # D:986 an rw_rate with no leading integer: row 9
    Case(
        "hardware_resources_invalid_with_text_in_rw_rates",
        "D:986, T:1633-1640 (ASSERT_THROW)",
        THROW,
        gripper(f"""<ros2_control name="JawDrive" type="actuator" rw_rate="x 10">{_hw("bench_hw/Jaw")}
    <joint name="jaw_a_joint"><command_interface name="position"/><state_interface name="position"/></joint>
    </ros2_control>"""),
        "CTRL066",
        'Could not parse rw_rate tag in "ros2_control". Invalid value: "x 10", expected a positive integer.',
    ),
    # D:1001 an rw_rate beyond INT_MAX: row 10
    Case(
        "hardware_resources_invalid_out_of_range_in_rw_rates",
        "D:1001, T:1643-1650 (ASSERT_THROW)",
        THROW,
        gripper(f"""<ros2_control name="JawDrive" type="actuator" rw_rate="98765432109">{_hw("bench_hw/Jaw")}
    <joint name="jaw_a_joint"><command_interface name="position"/><state_interface name="position"/></joint>
    </ros2_control>"""),
        "CTRL066",
        'Could not parse rw_rate tag in "ros2_control". Out of range value: "98765432109", expected a positive '
        "valid integer.",
    ),
    # D:1686 + D:2009 the URDF mimic joint under ros2_control, no attribute, state only
    # (and no <hardware> at all: the plugin is "", no throw)
    Case(
        "gripper_urdf_head+gripper_hardware_resources_no_command_if",
        "D:1686, D:2009, T:1605-1612 (ASSERT_NO_THROW)",
        ACCEPT,
        gripper(_gripper_block(B_STATE)),
    ),
    # D:2025 mimic="true", state only
    Case(
        "gripper_urdf_head+gripper_hardware_resources_mimic_true_no_command_if",
        "D:1686, D:2025, T:1587-1594 (ASSERT_NO_THROW)",
        ACCEPT,
        gripper(_gripper_block(B_MIMIC_STATE)),
    ),
    # D:1827 the URDF <mimic> names a joint nobody has: row 22 (urdfdom accepts it)
    Case(
        "gripper_urdf_head_unknown_joint+gripper_hardware_resources_mimic_true_no_command_if",
        "D:1827, D:2025, T:1685-1691 (ASSERT_THROW)",
        THROW,
        gripper(_gripper_block(B_MIMIC_STATE), head=_gripper_head(mimic="jaw_c_joint")),
        "CTRL042",
    ),
    # D:1757 mimic="true" and no URDF <mimic>: row 20
    Case(
        "gripper_urdf_head_no_mimic+gripper_hardware_resources_mimic_true_no_command_if",
        "D:1757, D:2025, T:1694-1700 (ASSERT_THROW)",
        THROW,
        gripper(_gripper_block(B_MIMIC_STATE), head=_gripper_head(mimic="")),
        "CTRL041",
    ),
    # D:2041 mimic="true" with a command interface: row 21
    Case(
        "gripper_urdf_head+gripper_hardware_resources_mimic_true_command_if",
        "D:1686, D:2041, T:1703-1709 (ASSERT_THROW)",
        THROW,
        gripper(_gripper_block(B_MIMIC_COMMAND)),
        "CTRL040",
    ),
    # D:2058 mimic="false" with a command interface: an ordinary joint
    Case(
        "gripper_urdf_head+gripper_hardware_resources_mimic_false_command_if",
        "D:1686, D:2058, T:1712-1719 (ASSERT_NO_THROW)",
        ACCEPT,
        gripper(_gripper_block(B_NOT_MIMIC_COMMAND)),
    ),
    # D:1898 a ros2_control joint the URDF does not have: row 19
    Case(
        "gripper_urdf_head_incomplete+gripper_hardware_resources_mimic_true_no_command_if",
        "D:1898, D:2025, T:1740-1746 (ASSERT_THROW)",
        THROW,
        gripper(_gripper_block(B_MIMIC_STATE), head=_gripper_head(with_b=False)),
        "CTRL001",
    ),
    # D:2075 an SDF root: the blocks are the first <model>'s children (P:1003-1007). descgen
    # reads URDF only, so only the XML stage (refusals) judges it
    Case(
        "diff_drive_robot_sdf",
        "D:2075, T:2005-2038",
        ACCEPT,
        CART_SDF,
    ),
    # T:2040 a <hardware> without <plugin>: row 15, the message names the block
    Case(
        "missing_hardware_plugin_tag_includes_component_name (inline)",
        "T:2040-2066 (throw, HasSubstr name, <plugin>, <hardware>)",
        THROW,
        arm("""<ros2_control name="ShopCart" type="system">
    <hardware><!-- no plugin --><param name="gain">0.5</param></hardware></ros2_control>"""),
        "CTRL066",
        "Missing <plugin> tag of <hardware> element for 'ShopCart' in your URDF.",
    ),
    # T:2068 a <command_interface> without a name (with a <param> inside): row 5
    Case(
        "missing_joint_attribute_includes_joint_name (inline)",
        "T:2068-2103 (throw, HasSubstr name, command_interface)",
        THROW,
        arm(f"""<ros2_control name="PanLift" type="system">{_hw("bench_hw/PanLift")}
    <joint name="pan"><command_interface name="position"/></joint>
    <joint name="lift"><command_interface><param name="min">-2</param></command_interface></joint>
    </ros2_control>"""),
        "CTRL066",
        "no attribute 'name' in 'command_interface' tag",
    ),
    # T:2105 an interface <param> without a name: row 6, context = the joint's name
    Case(
        "parameter_missing_name_includes_parent_context (inline)",
        "T:2105-2133 (throw, HasSubstr joint name, parameter name)",
        THROW,
        arm(f"""<ros2_control name="PanLift" type="system">{_hw("bench_hw/PanLift")}
    <joint name="pan"><command_interface name="position"><param>0.5</param></command_interface></joint>
    </ros2_control>"""),
        "CTRL066",
        "no parameter name attribute set in param tag for 'pan'",
    ),
]


# -- throws (and accepts) no upstream asset covers, from P itself (doc section 4, "No asset
#    covers"; section 1 for the reading conventions) ---------------------------------------
def _pan_block(attrs: str = "", inner: str = "", joint: str = "") -> str:
    """One system block driving pan: ``attrs`` on <ros2_control>, ``inner`` before <hardware>."""
    joint = joint or f'<joint name="pan">{_cmd("position", "-2", "2")}<state_interface name="position"/></joint>'
    block = f'<ros2_control name="PanOnly" type="system"{attrs}>{inner}{_hw("bench_hw/PanOnly")}{joint}'
    return arm(block + "</ros2_control>")


def _async(attrs: str) -> str:
    return _pan_block(' is_async="true"', f"<properties><async {attrs}/></properties>")


def _pan_transmission(body: str, kind: str = "system") -> str:
    joints = "".join(f'<joint name="{j}"><command_interface name="velocity"/></joint>' for j in ("pan", "lift"))
    return arm(f"""<ros2_control name="PanLiftDrive" type="{kind}">{_hw("bench_hw/Drive")}{joints}
    <transmission name="pan_belt">{body}</transmission></ros2_control>""")


SIMPLE = "<plugin>transmission_interface/SimpleTransmission</plugin>"
NOT_BOOL = "is not a valid boolean value. Expected 'true' or 'false'."
ASYNC = "Error parsing async tag: "
EXTRA = [
    Case(
        "row 12: transmission without <plugin>",
        "P:595-601",
        THROW,
        _pan_transmission('<joint name="pan" role="joint1"/>'),
        "CTRL066",
        "Missing <plugin> tag of <transmission> element for 'pan_belt' in your URDF.",
    ),
    Case(
        "row 14: actuator block, transmission with two of its joints",
        "P:670-679",
        THROW,
        _pan_transmission(f'{SIMPLE}<joint name="pan" role="joint1"/><joint name="lift" role="joint2"/>', "actuator"),
        "CTRL066",
        "Error while parsing 'PanLiftDrive'. There should be exactly one joint defined in this component but found 2.",
    ),
    Case(
        "row 14: actuator block, transmission with no joint",
        "P:670-679",
        THROW,
        _pan_transmission(f'{SIMPLE}<actuator name="motor" role="actuator1"/>', "actuator"),
        "CTRL066",
        "Error while parsing 'PanLiftDrive'. There should be exactly one joint defined in this component but found 0.",
    ),
    Case(
        "row 14 not: system block, transmission with two joints",
        "P:670 (only an actuator block is checked)",
        ACCEPT,
        _pan_transmission(f'{SIMPLE}<joint name="pan" role="joint1"/><joint name="lift" role="joint2"/>'),
    ),
    Case(
        "row 16: affinity with a nested array",
        "P:745-749, 766-769; LH:118-123",
        THROW,
        _async('affinity="[[0],1]"'),
        "CTRL066",
        ASYNC + "String must be a flat array: starts with '[' and ends with ']', no nested arrays",
    ),
    Case(
        "row 16: affinity without brackets",
        "P:745-749, 766-769; LH:118-123",
        THROW,
        _async('affinity="0,1"'),
        "CTRL066",
        ASYNC + "String must be a flat array: starts with '[' and ends with ']', no nested arrays",
    ),
    Case(
        "row 16: affinity with an empty item",
        "P:745-749, 766-769; LH:134-139",
        THROW,
        _async('affinity="[0,,1]"'),
        "CTRL066",
        ASYNC + "String must be a flat array with comma-separated values and no spaces between them",
    ),
    Case(
        "row 16: affinity with an item that is no number",
        "P:745-749, 766-769; LH:164-175",
        THROW,
        _async('affinity="[0, one]"'),
        "CTRL066",
        ASYNC + "Failed converting string to floating point or integer: one",
    ),
    Case(
        "row 16: print_warnings not a boolean",
        "P:760-769; L:148-150",
        THROW,
        _async('print_warnings="sometimes"'),
        "CTRL066",
        ASYNC + f"Input string : 'sometimes' {NOT_BOOL}",
    ),
    Case(
        "row 16: async thread_priority zero",
        "P:755-769, 319-341",
        THROW,
        _async('thread_priority="0"'),
        "CTRL066",
        ASYNC + 'Could not parse thread_priority tag in "async". Got "0", but expected a non-zero positive integer.',
    ),
    Case(
        "row 16 not: empty affinity, free scheduling_policy",
        "P:745-754 (scheduling_policy is not validated here); LH:126-130",
        ACCEPT,
        _async('affinity="[ ]" scheduling_policy="Round-Robin"'),
    ),
    Case(
        "row 16 not: blanks around the array, a fractional core",
        "P:745-749 (get_attribute_value strips, P:133); LH:164-169 (stod, then cast to int)",
        ACCEPT,
        _async('affinity=" [1.9,2] "'),
    ),
    Case(
        "row 5: joint <limits> without enable",
        "P:469-476, 125-131",
        THROW,
        _pan_block(joint='<joint name="pan"><limits/><command_interface name="position"/></joint>'),
        "CTRL066",
        "no attribute 'enable' in 'limits' tag",
    ),
    Case(
        "row 5: interface <limits> without enable",
        "P:406-413, 125-131",
        THROW,
        _pan_block(joint='<joint name="pan"><command_interface name="position"><limits/></command_interface></joint>'),
        "CTRL066",
        "no attribute 'enable' in 'limits' tag",
    ),
    Case(
        "row 5: transmission joint without role",
        "P:553-557, 125-131",
        THROW,
        _pan_transmission(f'{SIMPLE}<joint name="pan"/>'),
        "CTRL066",
        "no attribute 'role' in 'joint' tag with name 'pan'",
    ),
    Case(
        "row 5: transmission actuator without name",
        "P:568-572, 125-131",
        THROW,
        _pan_transmission(f'{SIMPLE}<joint name="pan" role="joint1"/><actuator role="actuator1"/>'),
        "CTRL066",
        "no attribute 'name' in 'actuator' tag",
    ),
    Case(
        "E1: is_async not a boolean",
        "P:305-309; L:148-150",
        THROW,
        _pan_block(' is_async="yes"'),
        "CTRL066",
        f"Input string : 'yes' {NOT_BOOL}",
    ),
    Case(
        "E1: joint <limits enable> not a boolean",
        "P:469-476; L:148-150",
        THROW,
        _pan_block(joint='<joint name="pan"><limits enable="off"/><command_interface name="position"/></joint>'),
        "CTRL066",
        f"Input string : 'off' {NOT_BOOL}",
    ),
    Case(
        "E1: transmission actuator read_only not a boolean",
        "P:573-575; L:148-150",
        THROW,
        _pan_transmission(f'{SIMPLE}<joint name="pan" role="joint1"/><actuator name="m" role="a1" read_only="1"/>'),
        "CTRL066",
        f"Input string : '1' {NOT_BOOL}",
    ),
    Case(
        "E1: joint mimic not a boolean",
        "P:454-467 (the catch takes runtime_error only); L:148-150",
        THROW,
        gripper(_gripper_block(B_STATE.replace('"jaw_b_joint"', '"jaw_b_joint" mimic="yes"'))),
        "CTRL043",
    ),
    # E2: the regex matches, std::stoi overflows: std::out_of_range, whose what() is libstdc++'s
    # "stoi" (no message to compare)
    Case(
        "E2: size beyond INT_MAX",
        "P:211-215",
        THROW,
        _pan_block(joint='<joint name="pan"><state_interface name="position" size="4294967296"/></joint>'),
        "CTRL066",
    ),
    Case(
        "E2: thread_priority beyond INT_MAX",
        "P:705-707, 327-331",
        THROW,
        _pan_block(' is_async="true" thread_priority="3000000000"'),
        "CTRL066",
    ),
    Case(
        "not a throw: thread_priority of a block that is not async",
        "P:705-707 (read only when is_async)",
        ACCEPT,
        _pan_block(' thread_priority="-5"'),
    ),
    Case(
        "not a throw: blanks and case in is_async, thread_priority and size",
        "P:133, 212, 308, 328 (stripped, hardware_interface >= 4.43.0); L:137 (lower-cased)",
        ACCEPT,
        _pan_block(
            ' is_async=" True " thread_priority=" 20 "',
            joint='<joint name="pan"><state_interface name="position" size=" 2 "/></joint>',
        ),
    ),
    Case(
        "not a throw: rw_rate with trailing text",
        "P:264 (std::stoi reads the leading integer)",
        ACCEPT,
        _pan_block(' rw_rate="30hz"'),
    ),
    Case(
        "not a throw: a comment among the children of <ros2_control>",
        "P:710, 794 (FirstChildElement/NextSiblingElement skip comments)",
        ACCEPT,
        _pan_block(inner="<!-- the bench arm's pan axis -->"),
    ),
    Case(
        "not a throw: mimic with blanks and capitals",
        "P:458 (get_attribute_value strips, P:133; parse_bool lower-cases, L:137)",
        ACCEPT,
        gripper(_gripper_block(B_STATE.replace('"jaw_b_joint"', '"jaw_b_joint" mimic=" TRUE "'))),
    ),
    Case(
        "not a throw: a joint name with blanks around it",
        "P:452 (the name is stripped, P:133) and P:1039 (then looked up in the URDF)",
        ACCEPT,
        _pan_block(
            joint=f'<joint name=" pan ">{_cmd("position", "-2", "2")}<state_interface name="position"/></joint>'
        ),
    ),
]


# -- descgen's verdict --------------------------------------------------------------------------
def blocks(root: etree._Element) -> list[etree._Element]:
    """The <ros2_control> elements parse_control_resources_from_urdf reads (P:999-1026)."""
    if root.tag == "sdf":
        model = root.find("model")
        return [] if model is None else model.findall("ros2_control")
    return root.findall("ros2_control")


def refused(document: str) -> list[str]:
    """CTRL066's model of the XML stage: every message refusals() gives, blocks in order."""
    root = etree.fromstring(document.encode())
    return [message for block in blocks(root) for message, _ in refusals(block)]


def urdf_stage(document: str) -> list[str]:
    """The codes of the rules that model the URDF stage (and mimic's parse_bool) that report
    the document; an SDF is not a URDF descgen reads."""
    if etree.fromstring(document.encode()).tag != "robot":
        return []
    robot, _ = read_urdf_text(document.encode(), "conformance.urdf")
    return sorted({f.code for f in run_rules(robot, codes=URDF_STAGE)})


def verdict(document: str) -> str:
    return THROW if refused(document) or urdf_stage(document) else ACCEPT


def _ids(cases: list[Case]) -> list[object]:
    return [pytest.param(c, id=c.name) for c in cases]


ALL = UPSTREAM + EXTRA


def test_the_cases_are_well_formed() -> None:
    names = [c.name for c in ALL]
    assert len(names) == len(set(names))
    for c in ALL:
        assert blocks(etree.fromstring(c.document.encode())), c.name  # well-formed, with a block to judge
        assert c.parser in (ACCEPT, THROW)
        assert (c.parser == THROW) == bool(c.rule), c.name
        assert c.message is None or c.rule == "CTRL066", c.name


@pytest.mark.parametrize("case", _ids(UPSTREAM))
def test_upstream_case_gets_the_parsers_verdict(case: Case) -> None:
    assert verdict(case.document) == case.parser, (
        f"{case.name} ({case.source}): the parser says {case.parser}; "
        f"refusals: {refused(case.document)}, URDF-stage rules: {urdf_stage(case.document)}"
    )


@pytest.mark.parametrize("case", _ids(EXTRA))
def test_uncovered_case_gets_the_parsers_verdict(case: Case) -> None:
    assert verdict(case.document) == case.parser, (
        f"{case.name} ({case.source}): the parser says {case.parser}; "
        f"refusals: {refused(case.document)}, URDF-stage rules: {urdf_stage(case.document)}"
    )


@pytest.mark.parametrize("case", _ids([c for c in ALL if c.parser == THROW]))
def test_the_throw_is_reported_where_descgen_models_it(case: Case) -> None:
    """An XML-stage throw is refusals()' (and its first message is the parser's what());
    a URDF-stage one is its rule's, and then the XML stage has passed (refusals() is empty)."""
    found = refused(case.document)
    if case.rule == "CTRL066":
        assert found, f"{case.name}: refusals() finds nothing"
        if case.message is not None:
            assert found[0] == case.message
    else:
        assert found == []
        assert case.rule in urdf_stage(case.document)


# -- the command line agrees (CTRL066 in `descgen audit --format json`) -------------------------
CLI_CASES = [
    "invalid_urdf_ros2_control_invalid_child",
    "invalid_urdf2_hw_transmission_joint_mismatch",
    "hardware_resources_invalid_with_text_in_rw_rates",
    "valid_urdf_ros2_control_system_multi_joints_transmission",
    "async_hardware_resources",
    "row 16: affinity with a nested array",
]


@pytest.mark.parametrize("name", CLI_CASES)
def test_the_audit_command_reports_the_same(name: str, tmp_path: Path) -> None:
    (case,) = [c for c in ALL if c.name == name]
    path = tmp_path / "robot.urdf"
    path.write_text(case.document)
    ran = cli("audit", path, "--format", "json")
    findings = json.loads(ran.stdout)["findings"]
    ctrl066 = [f["message"] for f in findings if f["code"] == "CTRL066"]
    assert ctrl066 == [f"Jazzy's ros2_control parser throws: {m}" for m in refused(case.document)]
    assert bool(ctrl066) == (case.parser == THROW)
