"""What real Jazzy ``<ros2_control>`` blocks hold, kept by import and written by generate
(issue 28): ``is_async`` (open_manipulator), a joint's own ``<param>`` (franka), interfaces the
hardware exports beyond the standard four (a legged robot's ``kp``/``kd``), a gpio whose name
starts with a digit (franka) and whose registers and params have spaces (Dynamixel's
``Goal Position``). Before, any of them left every block in pass-through and dropped the
controllers file (IMP005). The oracle is the block as written here, read back with lxml."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from lxml import etree

from .helpers import cli

URDF = """<?xml version="1.0"?>
<robot name="leg">
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="hip" type="revolute">
    <parent link="base_link"/><child link="thigh"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="20" velocity="5"/>
  </joint>
  <link name="thigh">
    <inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <ros2_control name="LegSystem" type="system" is_async="true">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="hip">
      <command_interface name="position"/>
      <command_interface name="kp"/>
      <command_interface name="kd"/>
      <state_interface name="position"/>
      <state_interface name="velocity"/>
      <param name="motor id">7</param>
    </joint>
    <gpio name="0">
      <command_interface name="Goal Position"/>
      <state_interface name="Present Position"/>
      <param name="Baud Rate (Bus)">57600</param>
    </gpio>
  </ros2_control>
</robot>
"""

CONTROLLERS = """controller_manager:
  ros__parameters:
    update_rate: 500
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    leg_controller:
      type: forward_command_controller/ForwardCommandController
leg_controller:
  ros__parameters:
    joints: [hip]
    interface_name: kp
"""


def _block(path: Path) -> etree._Element:
    root = etree.parse(str(path)).getroot()
    (block,) = root.findall("ros2_control")
    return block


def test_the_jazzy_forms_are_imported_and_generated(tmp_path: Path) -> None:
    src = tmp_path / "leg.urdf"
    src.write_text(URDF)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    spec = tmp_path / "specs" / "leg.yaml"
    ran = cli("import", src, "--controllers", tmp_path / "controllers.yaml", "-o", spec)
    assert ran.returncode == 0, ran.stderr
    assert "IMP021" not in ran.stderr and "IMP005" not in ran.stderr  # nothing left in pass-through
    rc = yaml.safe_load(spec.read_text())["ros2_control"]
    assert rc["is_async"] is True
    (joint,) = rc["joints"]
    assert joint["command"][1:] == ["kp", "kd"] and joint["params"] == {"motor id": "7"}
    (gpio,) = rc["gpios"]
    assert gpio["name"] == "0" and gpio["params"] == {"Baud Rate (Bus)": "57600"}
    assert [c["name"] for c in rc["controllers"]] == ["joint_state_broadcaster", "leg_controller"]

    assert cli("generate", spec).returncode == 0
    urdf = tmp_path / "generated" / "leg_description" / "urdf" / "leg.urdf"
    block = _block(urdf)
    assert block.get("is_async") == "true"
    (j,) = block.findall("joint")
    assert [c.get("name") for c in j.findall("command_interface")] == ["position", "kp", "kd"]
    assert {p.get("name"): p.text for p in j.findall("param")} == {"motor id": "7"}
    (g,) = block.findall("gpio")
    assert g.get("name") == "0"
    assert [c.get("name") for c in g.findall("command_interface")] == ["Goal Position"]
    assert [c.get("name") for c in g.findall("state_interface")] == ["Present Position"]
    assert {p.get("name"): p.text for p in g.findall("param")} == {"Baud Rate (Bus)": "57600"}
    assert cli("check", spec).returncode == 0


@pytest.mark.parametrize(
    ("path", "value"),
    [
        (("joints", 0, "params"), {'id" onload="x': "1"}),  # a quote would end the attribute
        (("joints", 0, "params"), {"<b>": "1"}),
        (("joints", 0, "params"), {"${x}": "1"}),  # xacro would evaluate it
        (("joints", 0, "command"), ["position", {"name": "kp", "min": "1"}]),  # units unknown for kp
        (("gpios", 0, "command"), ["Goal$Position"]),
    ],
)
def test_what_the_forms_do_not_take(tmp_path: Path, path: tuple[object, ...], value: object) -> None:
    src = tmp_path / "leg.urdf"
    src.write_text(URDF)
    spec = tmp_path / "specs" / "leg.yaml"
    assert cli("import", src, "-o", spec).returncode == 0
    data = yaml.safe_load(spec.read_text())
    node = data["ros2_control"]
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    spec.write_text(yaml.safe_dump(data, sort_keys=False))
    ran = cli("validate", spec)
    assert ran.returncode == 2, ran.stdout
    assert "Traceback" not in ran.stderr


@pytest.mark.parametrize(
    "old,new",
    [
        ('<param name="motor id">', '<param name="motor id&#10;">'),
        ('<gpio name="0">', '<gpio name="0&#10;">'),
        ('<command_interface name="Goal Position"/>', '<command_interface name="Goal Position&#10;"/>'),
    ],
)
def test_a_name_with_a_line_break_stays_in_pass_through(tmp_path: Path, old: str, new: str) -> None:
    """A name the spec cannot hold (a line break: Python's ``$`` would match before it, the
    spec's schema does not) keeps the block verbatim in pass-through, and the import is proven."""
    src = tmp_path / "leg.urdf"
    assert old in URDF
    src.write_text(URDF.replace(old, new))
    spec = tmp_path / "specs" / "leg.yaml"
    ran = cli("import", src, "-o", spec)
    assert ran.returncode == 0 and "IMP021" in ran.stderr and "round trip proven" in ran.stderr, ran.stderr
    assert "ros2_control" not in yaml.safe_load(spec.read_text())
    assert cli("validate", spec).returncode == 0
