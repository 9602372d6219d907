"""Jazzy's ros2_control rules, per-controller claims, calibrated wheel values and mimic joints
in the control model. Expected outcomes come from the Jazzy sources quoted at each test
(ros-controls/ros2_control and ros2_controllers, jazzy branch; docs/ros2_control_jazzy.md),
or from a hand computation on the fixture; never from descgen's own output."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen.audit import run as run_rules
from descgen.cli import main
from descgen.commands.control.load import load_system
from descgen.commands.control.system import Plant
from descgen.core.findings import Finding, InputError
from descgen.read.controllers import read_controllers_text
from descgen.read.urdf import read_urdf_text

from .helpers import JAZZY_IMU_INTERFACES, ROOT, errors_of, plant

# A two-finger gripper: the left finger mimics the right one, q_left = -1 * q_right + 0.01
# (multiplier != 1, offset != 0), the arm joint is an ordinary revolute joint.
LINKS = "".join(f'<link name="{n}"/>' for n in ("base_link", "arm_link", "finger_r", "finger_l", "imu_link"))
JOINTS = """
<joint name="arm_joint" type="revolute"><parent link="base_link"/><child link="arm_link"/>
  <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
<joint name="finger_right_joint" type="prismatic"><parent link="arm_link"/><child link="finger_r"/>
  <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="5" velocity="0.1"/></joint>
<joint name="finger_left_joint" type="prismatic"><parent link="arm_link"/><child link="finger_l"/>
  <axis xyz="0 1 0"/><limit lower="-0.04" upper="0.01" effort="5" velocity="0.1"/>
  <mimic joint="finger_right_joint" multiplier="-1" offset="0.01"/></joint>
<joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>
"""
RIGHT = """<joint name="finger_right_joint"><command_interface name="position"/>
  <state_interface name="position"/><state_interface name="velocity"/></joint>"""
LEFT_OK = """<joint name="finger_left_joint"><state_interface name="position"/>
  <state_interface name="velocity"/></joint>"""
ARM = """<joint name="arm_joint"><command_interface name="position"/>
  <state_interface name="position"/><state_interface name="velocity"/></joint>"""
IMU_NAMES = JAZZY_IMU_INTERFACES
IMU = '<sensor name="imu">' + "".join(f'<state_interface name="{i}"/>' for i in IMU_NAMES) + "</sensor>"


def urdf(*blocks: str, plugin: str = "mock_components/GenericSystem", extra: str = "", hw: str = "") -> str:
    body = "".join(
        f'<ros2_control name="hw{i}" type="system"><hardware><plugin>{plugin}</plugin>{hw}</hardware>{b}</ros2_control>'
        for i, b in enumerate(blocks)
    )
    return f'<?xml version="1.0"?><robot name="gripper">{LINKS}{JOINTS}{body}{extra}</robot>'


def audit(text: str, codes: list[str], controllers: str | None = None) -> list[Finding]:
    robot, _ = read_urdf_text(text.encode(), "gripper.urdf")
    if controllers is not None:
        import dataclasses

        ctrls, _, _ = read_controllers_text(controllers, "gripper.controllers.yaml")
        assert robot.ros2_control is not None
        robot = dataclasses.replace(robot, ros2_control=dataclasses.replace(robot.ros2_control, controllers=ctrls))
    return run_rules(robot, codes=codes)


def codes(found: list[Finding]) -> list[str]:
    return sorted(f.code for f in found)


# -- mimic joints under ros2_control ------------------------------------------------------
# component_parser.cpp (jazzy), parse_control_resources_from_urdf:
#   if (urdf_joint->mimic && joint.is_mimic != MimicAttribute::FALSE) {
#     if (joint.command_interfaces.size() > 0) throw "... Activated mimic joints cannot have command interfaces."
#     find_joint(mimic->joint_name) -> throw "Mimic joint '{}' not found in <ros2_control> tag" }
#   if (!urdf_joint->mimic && joint.is_mimic == MimicAttribute::TRUE) throw "... no mimic information in the URDF"
# and parse_bool() accepts only "true"/"false" in any case, throwing std::invalid_argument otherwise.
LEFT_CMD = LEFT_OK.replace("<state_interface", '<command_interface name="position"/><state_interface', 1)
MIMIC_CASES = [
    # (ros2_control joints, Jazzy refuses with)
    (RIGHT + LEFT_CMD, ["CTRL040"]),  # attribute absent = NOT_SET: active mimic with a command
    (RIGHT + LEFT_CMD.replace('"finger_left_joint"', '"finger_left_joint" mimic="true"'), ["CTRL040"]),
    (RIGHT + LEFT_CMD.replace('"finger_left_joint"', '"finger_left_joint" mimic="false"'), []),  # ordinary joint
    (RIGHT + LEFT_OK, []),  # the documented Jazzy form
    (RIGHT + LEFT_OK.replace('"finger_left_joint"', '"finger_left_joint" mimic="TRUE"'), []),  # parse_bool lowercases
    (RIGHT + LEFT_OK.replace('"finger_left_joint"', '"finger_left_joint" mimic="1"'), ["CTRL043"]),
    (ARM.replace('"arm_joint"', '"arm_joint" mimic="true"') + RIGHT, ["CTRL041"]),
    (ARM.replace('"arm_joint"', '"arm_joint" mimic="false"') + RIGHT, []),
    (LEFT_OK, ["CTRL042"]),  # the leader is not under ros2_control at all
]


@pytest.mark.parametrize(("joints", "expected"), MIMIC_CASES)
def test_mimic_rules_follow_the_jazzy_parser(joints: str, expected: list[str]) -> None:
    found = audit(urdf(joints), ["CTRL040", "CTRL041", "CTRL042", "CTRL043"])
    assert codes(found) == expected
    for f in found:
        assert f.severity == "error" and f.where.line > 0 and f.hint


def test_mimic_leader_in_another_block_is_refused() -> None:
    # hw_info is per <ros2_control> element; find_joint looks only in that block's joints
    assert codes(audit(urdf(RIGHT, LEFT_OK), ["CTRL042"])) == ["CTRL042"]
    assert codes(audit(urdf(RIGHT + LEFT_OK, ARM), ["CTRL042"])) == []


def test_audited_mimic_hint_names_the_xml_not_the_spec() -> None:
    (f,) = audit(urdf(RIGHT + LEFT_CMD), ["CTRL040"])
    assert 'mimic="false"' in f.hint and "spec" not in f.hint
    assert f.where.line == text_line(urdf(RIGHT + LEFT_CMD), '<joint name="finger_left_joint"><command')


def text_line(text: str, needle: str) -> int:
    return text[: text.index(needle)].count("\n") + 1


# -- removed before Jazzy ------------------------------------------------------------------
PRE_JAZZY_MIMIC = """<joint name="finger_left_joint"><param name="mimic">finger_right_joint</param>
  <param name="multiplier">-1</param><state_interface name="position"/></joint>"""


def test_pre_jazzy_mimic_params_are_an_error() -> None:
    # doc/migration.rst (jazzy): "The parameters within the ros2_control tag are not supported any more"
    (f,) = audit(urdf(RIGHT + PRE_JAZZY_MIMIC), ["CTRL044"])
    assert f.severity == "error" and '<mimic joint="finger_right_joint"' in f.hint
    assert audit(urdf(RIGHT + LEFT_OK), ["CTRL044"]) == []


@pytest.mark.parametrize(
    ("plugin", "replacement"),
    [
        ("fake_components/GenericSystem", "mock_components/GenericSystem"),  # removed in 4.0.0 (#1150)
        ("gazebo_ros2_control/GazeboSystem", "gz_ros2_control/GazeboSimSystem"),  # not released for Jazzy
    ],
)
def test_hardware_plugins_jazzy_lacks(plugin: str, replacement: str) -> None:
    (f,) = audit(urdf(RIGHT + LEFT_OK, plugin=plugin), ["CTRL045"])
    assert f.severity == "error" and replacement in f.hint
    assert audit(urdf(RIGHT + LEFT_OK, plugin=replacement), ["CTRL045"]) == []


def test_renamed_generic_system_params_warn() -> None:
    old = urdf(RIGHT + LEFT_OK, hw='<param name="fake_sensor_commands">true</param>')
    (f,) = audit(old, ["CTRL046"])
    assert f.severity == "warning" and "mock_sensor_commands" in f.hint
    new = urdf(RIGHT + LEFT_OK, hw='<param name="mock_sensor_commands">true</param>')
    assert audit(new, ["CTRL046"]) == []
    initial = RIGHT.replace("<command_interface", '<param name="initial_position">0.02</param><command_interface')
    (g,) = audit(urdf(initial + LEFT_OK), ["CTRL046"])
    assert "initial_value" in g.hint


def test_gazebo_classic_plugin_warns() -> None:
    classic = '<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/></gazebo>'
    harmonic = (
        '<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>'
        "</gazebo>"
    )
    (f,) = audit(urdf(RIGHT + LEFT_OK, extra=classic), ["CTRL047"])
    assert f.severity == "warning" and "gz_ros2_control-system" in f.hint
    assert audit(urdf(RIGHT + LEFT_OK, extra=harmonic), ["CTRL047"]) == []


# -- what each controller type claims (ros2_controllers, jazzy) ----------------------------
def ctrl_yaml(name: str, type_: str, params: dict[str, object]) -> str:
    doc = {
        "controller_manager": {"ros__parameters": {"update_rate": 100, name: {"type": type_}}},
        name: {"ros__parameters": params},
    }
    return yaml.safe_dump(doc)


CLAIM_CHECKS = ["CTRL002", "CTRL009", "CTRL049", "CTRL050"]
CLAIM_CASES = [
    # (type, good params, bad params, codes of the bad one)
    # gripper_action_controller_impl.hpp: command {joint + "/" + HardwareInterface},
    # state {joint/position, joint/velocity}
    (
        "position_controllers/GripperActionController",
        {"joint": "finger_right_joint"},
        {"joint": "finger_rigth_joint"},
        ["CTRL002", "CTRL002", "CTRL002", "CTRL009"],
    ),
    # effort: command joint/effort, which the fixture does not export
    ("effort_controllers/GripperActionController", None, {"joint": "finger_right_joint"}, ["CTRL002"]),
    # gripper_action_controller_impl.hpp on_configure: "Joint name cannot be empty" -> ERROR
    ("position_controllers/GripperActionController", None, {}, ["CTRL050"]),
    # parallel_gripper_action_controller_impl.hpp: command joint/position (+ max_*_interface),
    # state joint/<state_interfaces> (default [position, velocity])
    (
        "parallel_gripper_action_controller/GripperActionController",
        {"joint": "finger_right_joint"},
        {"joint": "finger_right_joint", "state_interfaces": ["position", "effort"]},
        ["CTRL002"],
    ),
    (
        "parallel_gripper_action_controller/GripperActionController",
        None,
        {"joint": "finger_right_joint", "max_effort_interface": "finger_right_joint/max_effort"},
        ["CTRL002"],
    ),
    # forward_command_controller: joints x interface_name
    (
        "forward_command_controller/ForwardCommandController",
        {"joints": ["arm_joint"], "interface_name": "position"},
        {"joints": ["arm_joint"], "interface_name": "velocity"},
        ["CTRL002"],
    ),
    (
        "forward_command_controller/MultiInterfaceForwardCommandController",
        {"joint": "arm_joint", "interface_names": ["position"]},
        {"joint": "arm_joint", "interface_names": ["position", "effort"]},
        ["CTRL002"],
    ),
    ("position_controllers/JointGroupPositionController", {"joints": ["arm_joint"]}, {"joints": []}, ["CTRL050"]),
    ("velocity_controllers/JointGroupVelocityController", None, {"joints": ["arm_joint"]}, ["CTRL002"]),
    # JTC parameters: joints, command_interfaces, state_interfaces all size_gt<>: [0]
    (
        "joint_trajectory_controller/JointTrajectoryController",
        {"joints": ["arm_joint"], "command_interfaces": ["position"], "state_interfaces": ["position", "velocity"]},
        {"joints": ["arm_joint"], "command_interfaces": ["position"], "state_interfaces": ["acceleration"]},
        ["CTRL002"],
    ),
    (
        "joint_trajectory_controller/JointTrajectoryController",
        None,
        {"joints": ["arm_joint"], "state_interfaces": ["position"]},
        ["CTRL050"],
    ),
    # JSB: joints x interfaces when set
    (
        "joint_state_broadcaster/JointStateBroadcaster",
        {"joints": ["arm_joint"], "interfaces": ["position"]},
        {"joints": ["arm_joint"], "interfaces": ["effort"]},
        ["CTRL002"],
    ),
    # imu_sensor.hpp: the ten <sensor_name>/... interfaces; sensor_name and frame_id not_empty
    (
        "imu_sensor_broadcaster/IMUSensorBroadcaster",
        {"sensor_name": "imu", "frame_id": "imu_link"},
        {"sensor_name": "imu_sensr", "frame_id": "imu_link"},
        ["CTRL002"],
    ),
    ("imu_sensor_broadcaster/IMUSensorBroadcaster", None, {"sensor_name": "imu"}, ["CTRL050"]),
    # force_torque_sensor_broadcaster.cpp: sensor_name xor interface_names; six force/torque interfaces
    (
        "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster",
        None,
        {"sensor_name": "imu", "frame_id": "imu_link", "interface_names": {"force": {"x": "imu/orientation.x"}}},
        ["CTRL002", "CTRL002", "CTRL002", "CTRL002", "CTRL002", "CTRL002", "CTRL050"],
    ),
    (
        "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster",
        {"frame_id": "imu_link", "interface_names": {"force": {"x": "imu/linear_acceleration.x"}}},
        {"frame_id": "imu_link", "interface_names": {"force": {"x": "imu/force.x"}}},
        ["CTRL002"],
    ),
    ("my_controllers/WristController", None, {"joints": ["arm_joint"]}, ["CTRL049"]),
]


@pytest.mark.parametrize(("type_", "good", "bad", "expected"), CLAIM_CASES)
def test_controller_claims_per_type(
    type_: str, good: dict[str, object] | None, bad: dict[str, object], expected: list[str]
) -> None:
    text = urdf(RIGHT + LEFT_OK + ARM + IMU)
    if good is not None:
        assert audit(text, CLAIM_CHECKS, ctrl_yaml("c", type_, good)) == []
    assert codes(audit(text, CLAIM_CHECKS, ctrl_yaml("c", type_, bad))) == expected


# -- specs: validate refuses what Jazzy refuses; generate never writes it ------------------
_ELBOW_LIMIT = (
    "    axis: +y\n    limit: {lower: -150 deg, upper: 150 deg, velocity: 120 deg/s, effort: 20 N*m, source: M21,\n"
    '            acceleration: {value: 240 deg/s^2, source: "A1: chosen limit, max speed (M21) reached in 0.5 s"}}\n'
)
MIMIC_ELBOW = plant(
    _ELBOW_LIMIT,
    _ELBOW_LIMIT + "    mimic: {joint: shoulder_lift_joint, multiplier: -1, offset: {value: 10 deg, source: M21}}\n",
)
ELBOW_CTRL = (
    '    - {name: elbow_joint, command: [position], state: [position, velocity], on_limit: reject, source: "C04, C06"}'
)


def test_spec_mimic_joint_with_command_is_refused(tmp_path: Path) -> None:
    found = errors_of(MIMIC_ELBOW, tmp_path)
    assert "CTRL040" in codes(found)
    (f,) = [f for f in found if f.code == "CTRL040"]
    assert f.where.line == MIMIC_ELBOW[: MIMIC_ELBOW.index(ELBOW_CTRL)].count("\n") + 1
    assert "mimic: false" in f.hint
    out = tmp_path / "out"
    spec = tmp_path / "robot.yaml"
    assert main(["generate", str(spec), "--out", str(out)]) == 2
    assert not out.exists() or not any(out.rglob("*.xacro"))


def test_spec_mimic_false_writes_the_attribute(tmp_path: Path) -> None:
    text = plant(ELBOW_CTRL, ELBOW_CTRL.replace("on_limit: reject,", "on_limit: reject, mimic: false,"), MIMIC_ELBOW)
    # (the example's known poses set elbow_joint against its new leader: other rules, not these)
    assert [f for f in errors_of(text, tmp_path) if f.code.startswith("CTRL04")] == []
    from descgen.audit.spec import load_spec_text
    from descgen.render.context import build

    ctx = build(load_spec_text(text, rules=False).robot, xacro=True)
    assert ctx["control_mimic"] == {"elbow_joint": "false"}


def test_spec_gripper_controller_typo_does_not_validate(tmp_path: Path) -> None:
    gripper = (
        "    - name: gripper_controller\n      type: position_controllers/GripperActionController\n"
        "      source: C05\n      params: {joint: elbow_jiont}\n"
    )
    text = plant("\nsemantic:\n", gripper + "\nsemantic:\n")
    found = errors_of(text, tmp_path)
    assert {"CTRL002", "CTRL009"} <= set(codes(found))
    good = plant("\nsemantic:\n", gripper.replace("elbow_jiont", "elbow_joint") + "\nsemantic:\n")
    assert errors_of(good, tmp_path, "good.yaml") == []


# -- calibrated wheel values (CTRL006 / CTRL051) -----------------------------------------
GENERATED_URDF = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"


def urdf_wheels() -> tuple[float, float]:
    """Oracle by hand from the URDF with lxml: the wheel joints' y distance (axis +y) and
    the wheel link's collision cylinder radius."""
    root = etree.parse(str(GENERATED_URDF)).getroot()
    y = {
        j.get("name"): float(j.find("origin").get("xyz").split()[1])
        for j in root.findall("joint")
        if j.get("name") in ("left_wheel_joint", "right_wheel_joint")
    }
    assert all(j.find("axis").get("xyz") == "0 1 0" for j in root.findall("joint") if j.get("name") in y)
    child = next(j.find("child").get("link") for j in root.findall("joint") if j.get("name") == "left_wheel_joint")
    link = next(lk for lk in root.findall("link") if lk.get("name") == child)
    radius = float(link.find("collision/geometry/cylinder").get("radius"))
    return abs(y["left_wheel_joint"] - y["right_wheel_joint"]), radius


def dd_yaml(**params: float) -> str:
    base = {"left_wheel_names": ["left_wheel_joint"], "right_wheel_names": ["right_wheel_joint"], **params}
    return ctrl_yaml("diff_drive_controller", "diff_drive_controller/DiffDriveController", base)


def audit_generated(controllers: str) -> list[Finding]:
    robot, _ = read_urdf_text(GENERATED_URDF.read_bytes(), str(GENERATED_URDF))
    import dataclasses

    ctrls, _, _ = read_controllers_text(controllers, "robot.controllers.yaml")
    assert robot.ros2_control is not None
    robot = dataclasses.replace(robot, ros2_control=dataclasses.replace(robot.ros2_control, controllers=ctrls))
    return run_rules(robot, codes=["CTRL006", "CTRL051"])


def test_audited_wheel_values_tolerance_and_unit_slip() -> None:
    sep, radius = urdf_wheels()
    assert audit_generated(dd_yaml(wheel_separation=sep + 0.003, wheel_radius=radius - 0.002)) == []
    (warn,) = audit_generated(dd_yaml(wheel_separation=sep + 0.03, wheel_radius=radius))
    assert (warn.code, warn.severity) == ("CTRL051", "warning")
    (slip,) = audit_generated(dd_yaml(wheel_separation=sep, wheel_radius=radius * 1000))  # mm typed as m
    assert (slip.code, slip.severity) == ("CTRL006", "error")
    assert "robot.controllers.yaml" in slip.hint and "spec" not in slip.hint
    (tenth,) = audit_generated(dd_yaml(wheel_separation=sep / 10, wheel_radius=radius))
    assert tenth.code == "CTRL006"


def calibrated(value: str, key: str = "wheel_separation", extra: str = "") -> str:
    return plant(
        "        enable_odom_tf: true\n",
        "        enable_odom_tf: true\n      calibrated:\n"
        f"        {key}: {{value: {value}, source: odometry run 7{extra}}}\n",
    )


def test_spec_calibrated_wheel_value(tmp_path: Path) -> None:
    sep, _ = urdf_wheels()
    mm = round(sep * 1000 + 2.0, 3)  # 2 mm off: within the default 5 mm
    ok = calibrated(f'"{mm} mm"')
    assert errors_of(ok, tmp_path) == []
    from descgen.audit.spec import load_spec_text
    from descgen.render.context import controllers_doc

    loaded = load_spec_text(ok)
    written = controllers_doc(loaded.robot)["diff_drive_controller"]["ros__parameters"]
    assert math.isclose(written["wheel_separation"], mm / 1000, rel_tol=1e-12)  # the calibrated value is used
    off = calibrated(f'"{sep * 1000 + 30:.1f} mm"')
    assert errors_of(off, tmp_path, "off.yaml") == []
    assert [f.code for f in load_spec_text(off).findings if f.code == "CTRL051"] == ["CTRL051"]
    assert errors_of(calibrated(f'"{sep * 1000 + 30:.1f} mm"', extra=", tolerance: 5 cm"), tmp_path, "t.yaml") == []
    slip = calibrated(f'"{sep * 10:.4f} m"')  # 10x: a unit slip (dm or a misplaced point)
    (f,) = [f for f in errors_of(slip, tmp_path, "slip.yaml") if f.code == "CTRL006"]
    assert "calibrated.wheel_separation" in f.hint
    wrong = plant(
        "        state_interfaces: [position, velocity]\n",
        "        state_interfaces: [position, velocity]\n      calibrated:\n"
        '        wheel_radius: {value: "0.1 m", source: x}\n',
    )
    assert "CTRL048" in codes(errors_of(wrong, tmp_path, "wrong.yaml"))


# -- the control model: mimic states as GenericSystem fills them ---------------------------
def package(tmp_path: Path, left: str) -> tuple[Path, object]:
    text = urdf(ARM + RIGHT + left)
    robot, _ = read_urdf_text(text.encode(), "gripper.urdf")
    pkg = tmp_path / "gripper_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "config").mkdir()
    start, end = text.index("<ros2_control"), text.rindex("</ros2_control>") + len("</ros2_control>")
    (pkg / "urdf" / "gripper.ros2_control.xacro").write_text(f'<robot name="gripper">{text[start:end]}</robot>')
    (pkg / "config" / "ros2_controllers.yaml").write_text(
        ctrl_yaml(
            "gripper_controller",
            "forward_command_controller/ForwardCommandController",
            {"joints": ["finger_right_joint"], "interface_name": "position"},
        )
    )
    return pkg, robot


def test_control_model_fills_mimic_states_like_generic_system(tmp_path: Path) -> None:
    pkg, robot = package(tmp_path, LEFT_OK)
    cm = load_system(pkg, robot, Plant())  # type: ignore[arg-type]
    cm.by_name["finger_right_joint"].commands["position"] = 0.03
    cm.step(0.01)
    # generic_system.cpp read(): pos = offset + multiplier * pos(leader); vel = multiplier * vel(leader)
    assert cm.state("finger_right_joint", "position") == pytest.approx(0.03)
    assert cm.state("finger_left_joint", "position") == pytest.approx(0.01 + -1 * 0.03)
    assert cm.state("finger_left_joint", "velocity") == pytest.approx(-1 * cm.state("finger_right_joint", "velocity"))


def test_control_model_refuses_a_commanded_mimic_joint(tmp_path: Path) -> None:
    pkg, robot = package(tmp_path, LEFT_CMD)
    with pytest.raises(InputError) as exc:
        load_system(pkg, robot, Plant())  # type: ignore[arg-type]
    assert [f.code for f in exc.value.findings] == ["CTRL040"]


# -- control finds the package where generate --out wrote it -----------------------------
def test_control_package_option(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text((ROOT / "specs" / "warehouse_arm.yaml").read_text())
    ready = str(ROOT / "specs" / "trajectories" / "ready.yaml")
    assert main(["control", str(spec), "--trajectory", ready, "--out", str(tmp_path / "ev")]) == 2
    err = capsys.readouterr().err
    assert "CTRL021" in err and "Traceback" not in err and "--package" in err
    out = tmp_path / "somewhere"
    assert main(["generate", str(spec), "--out", str(out)]) == 0
    for given in (out, out / "warehouse_arm_description"):  # the --out root or the package itself
        assert (
            main(["control", str(spec), "--trajectory", ready, "--package", str(given), "--out", str(tmp_path / "ev")])
            == 0
        )
    assert (tmp_path / "ev" / "verdict.json").is_file()
    assert main(["control", str(spec), "--trajectory", ready, "--package", str(tmp_path / "nope")]) == 2
    assert "CTRL021" in capsys.readouterr().err
