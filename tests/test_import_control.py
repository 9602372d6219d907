"""``descgen import`` of ``<ros2_control>`` blocks and the controllers YAML (issue 12).

Expected values are the hand-written inputs below, read back from the generated files with
lxml and yaml.safe_load (never through descgen's own readers)."""

from __future__ import annotations

from pathlib import Path

import yaml
from lxml import etree

from descgen.audit.spec import load_spec_text
from descgen.commands.importer import control
from descgen.commands.importer.run import ImportOptions, Outcome, import_description
from descgen.read.description import Options
from descgen.render import render_package

URDF = """<?xml version="1.0"?>
<robot name="bot">
  <link name="base"/>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <link name="finger"><inertial><mass value="0.1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="2"/></joint>
  <joint name="slide" type="prismatic"><parent link="arm"/><child link="finger"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.04" effort="20" velocity="0.1"/><mimic joint="j1" multiplier="0.01"/></joint>
  {block}
</robot>
"""

BLOCK = """<ros2_control name="Bot" type="system">
    <hardware>
      <plugin>my_driver/BotSystem</plugin>
      <param name="port">/dev/ttyUSB0</param>
      <param name="rate">0.5</param>
    </hardware>
    <joint name="j1">
      <command_interface name="position"><param name="min">-1</param><param name="max">1</param></command_interface>
      <command_interface name="velocity"/>
      <state_interface name="position"><param name="initial_value">0.25</param></state_interface>
      <state_interface name="velocity"/>
    </joint>
    <joint name="slide" mimic="false">
      <command_interface name="position"><param name="max">0.03</param></command_interface>
      <state_interface name="position"/>
    </joint>
    <sensor name="ft">
      <state_interface name="force.z"/>
      <param name="frame_id">arm</param>
    </sensor>
    <gpio name="io">
      <command_interface name="out" data_type="bool"/>
      <state_interface name="temp"><param name="initial_value">20.5</param></state_interface>
    </gpio>
  </ros2_control>"""


def _write(tmp_path: Path, block: str = BLOCK) -> Path:
    p = tmp_path / "bot.urdf"
    p.write_text(URDF.replace("{block}", block))
    return p


def _import(path: Path, controllers: Path | None = None) -> Outcome:
    outcome = import_description(path, ImportOptions(Options(controllers=controllers)))
    assert outcome.proven, (outcome.invalid, outcome.imported.differences)
    return outcome


def _generated(spec_text: str) -> dict[str, str]:
    robot = load_spec_text(spec_text, "bot.yaml", rules=False).robot
    return render_package(robot, "bot.yaml")


def _params(e: etree._Element) -> dict[str, str]:
    return {p.get("name"): (p.text or "").strip() for p in e.findall("param")}


def test_a_block_imports_into_the_spec_and_comes_back(tmp_path: Path) -> None:
    outcome = _import(_write(tmp_path))
    spec = yaml.safe_load(outcome.imported.spec_text)
    rc = spec["ros2_control"]
    assert "passthrough" not in spec  # nothing left behind
    assert rc["hardware"] == {"plugin": "my_driver/BotSystem", "params": {"port": "/dev/ttyUSB0", "rate": "0.5"}}
    j1, slide = rc["joints"]
    assert j1["command"][1] == "velocity" and j1["state"][1] == "velocity"
    assert slide["mimic"] is False and slide["command"][0]["max"] == "30 mm"  # the prismatic joint's unit
    assert rc["sensors"][0]["params"] == {"frame_id": "arm"}
    assert rc["gpios"][0]["command"] == [{"name": "out", "data_type": "bool"}]
    assert rc["update_rate"] == "100 Hz"
    codes = {f.code for f in outcome.imported.report}
    assert {"IMP020", "IMP022", "IMP023"} <= codes and "IMP003" not in codes
    # read the generated block back with lxml: the hand-written values
    root = etree.fromstring(_generated(outcome.imported.spec_text)["urdf/bot.urdf"].encode())
    (block,) = root.findall("ros2_control")
    assert _params(block.find("hardware")) == {"port": "/dev/ttyUSB0", "rate": "0.5"}
    cmd = block.find("joint[@name='j1']/command_interface[@name='position']")
    assert {k: float(v) for k, v in _params(cmd).items()} == {"min": -1.0, "max": 1.0}
    st = block.find("joint[@name='j1']/state_interface[@name='position']")
    assert float(_params(st)["initial_value"]) == 0.25
    slide_cmd = block.find("joint[@name='slide']/command_interface")
    # max as written; min added from the URDF lower limit (IMP022), which Jazzy takes anyway
    assert float(_params(slide_cmd)["max"]) == 0.03 and float(_params(slide_cmd)["min"]) == 0.0
    assert block.find("joint[@name='slide']").get("mimic") == "false"
    gpio_state = block.find("gpio/state_interface[@name='temp']")
    assert float(_params(gpio_state)["initial_value"]) == 20.5


def test_a_block_the_spec_cannot_say_stays_pass_through(tmp_path: Path) -> None:
    block = BLOCK.replace('<command_interface name="velocity"/>', '<command_interface name="velocity" size="2"/>')
    outcome = _import(_write(tmp_path, block))
    spec = yaml.safe_load(outcome.imported.spec_text)
    assert "ros2_control" not in spec
    assert [etree.fromstring(p["xml"].encode()).tag for p in spec["passthrough"]] == ["ros2_control"]
    found = [f for f in outcome.imported.report if f.code == "IMP021"]
    assert len(found) == 1 and "size" in found[0].message


def test_controllers_without_an_imported_block_are_still_said(tmp_path: Path) -> None:
    # <properties> has no spec field: the block is kept in pass-through, its controllers still said
    block = BLOCK.replace("</hardware>", '</hardware><properties><async print_warnings="false"/></properties>')
    ctl = tmp_path / "c.yaml"
    ctl.write_text("controller_manager:\n  ros__parameters:\n    update_rate: 50\n")
    outcome = _import(_write(tmp_path, block), ctl)
    assert "IMP005" in {f.code for f in outcome.imported.report}


CONTROLLERS = """\
controller_manager:
  ros__parameters:
    update_rate: 250
    use_sim_time: true
    jsb:
      type: joint_state_broadcaster/JointStateBroadcaster
fwd:
  ros__parameters:
    type: forward_command_controller/ForwardCommandController
    joints: [j1]
    interface_name: position
    gains: {p: 10, d: 0.10}
/**:
  ros__parameters:
    robot_description: x
"""


def test_controllers_import_and_their_file_comes_back(tmp_path: Path) -> None:
    ctl = tmp_path / "ctl.yaml"
    ctl.write_text(CONTROLLERS)
    outcome = _import(_write(tmp_path), ctl)
    spec = yaml.safe_load(outcome.imported.spec_text)
    rc = spec["ros2_control"]
    assert rc["update_rate"] == "250 Hz"
    assert [c["name"] for c in rc["controllers"]] == ["jsb", "fwd"]
    assert rc["controllers"][1]["source"] == "ctl.yaml:7"  # the line of 'fwd:'
    not_imported = sorted(f.subject for f in outcome.imported.report if f.code == "IMP024")
    assert not_imported == ["controller:/**", "controllers"]  # the wildcard entry and use_sim_time
    written = yaml.safe_load(_generated(outcome.imported.spec_text)["config/ros2_controllers.yaml"])
    original = yaml.safe_load(CONTROLLERS)
    assert written["controller_manager"]["ros__parameters"]["update_rate"] == 250
    fwd = {k: v for k, v in original["fwd"]["ros__parameters"].items() if k != "type"}
    assert written["fwd"]["ros__parameters"] == fwd


def test_the_block_compare_sees_a_changed_value(tmp_path: Path) -> None:
    """block_differences must fail on a lost or changed param, and on an addition that is
    not what generate derives from the URDF limits."""
    outcome = _import(_write(tmp_path))
    robot = outcome.imported.robot
    original = [etree.fromstring(x.encode()) for x in outcome.imported.control.blocks]
    generated = etree.fromstring(_generated(outcome.imported.spec_text)["urdf/bot.urdf"].encode())
    assert control.block_differences(original, generated.findall("ros2_control"), robot) == []

    def changed(xpath: str, text: str) -> list[str]:
        g = etree.fromstring(etree.tostring(generated))
        g.find(xpath).text = text
        return control.block_differences(original, g.findall("ros2_control"), robot)

    assert changed("ros2_control/hardware/param[@name='port']", "/dev/ttyUSB1")
    assert changed("ros2_control/joint[@name='j1']/state_interface[@name='position']/param", "0")
    # slide's min was added from the URDF lower limit 0; any other value is not a derived default
    assert changed("ros2_control/joint[@name='slide']/command_interface/param[@name='min']", "-0.01")
    assert changed("ros2_control/gpio/state_interface/param", "20")


def test_the_controllers_compare_sees_a_changed_value(tmp_path: Path) -> None:
    ctl = tmp_path / "ctl.yaml"
    ctl.write_text(CONTROLLERS)
    outcome = _import(_write(tmp_path), ctl)
    c = outcome.imported.control.controllers
    assert c is not None
    written = _generated(outcome.imported.spec_text)["config/ros2_controllers.yaml"]
    assert control.controllers_differences(c.text, written, c, set()) == []
    assert control.controllers_differences(c.text, written.replace("d: 0.1", "d: 0.2"), c, set())
    assert control.controllers_differences(c.text, written.replace("update_rate: 250", "update_rate: 100"), c, set())
