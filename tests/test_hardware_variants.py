"""Issue 14: ros2_control sensors, gpios and hardware variants (mock|gazebo|real selected by the
Xacro argument ``hardware``), proven for every variant; a gripper and IMU spec that validates,
generates and runs in ``control``. Expected values are written by hand from the specs; the
oracles are xacro's own evaluator (trusted, as ROS runs it) and lxml."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.core.findings import InputError
from descgen.prove.xacro_expand import xacro_variants_match
from descgen.read.xacro_file import expand
from descgen.render import render_package
from tests.helpers import EXAMPLE_TEXT, JAZZY_IMU_INTERFACES, ROOT, cli, errors_of, line_of, plant

PKG = ROOT / "generated" / "warehouse_arm_description"
XACRO = PKG / "urdf" / "warehouse_arm.urdf.xacro"
GRIPPER = ROOT / "tests" / "data" / "gripper_imu"
GZ_SIM = ("gz_ros2_control-system", "gz_ros2_control::GazeboSimROS2ControlPlugin")


def _xacro(hardware: str | None) -> etree._Element:
    """The committed Xacro expanded by xacro's own evaluator, as `ros2 launch` would."""
    args = {} if hardware is None else {"hardware": hardware}
    text = expand(XACRO, str(XACRO), args, package_paths=[PKG.parent], trusted=True)
    return etree.fromstring(text)


def _hardware(doc: etree._Element) -> tuple[str, dict[str, str]]:
    hw = doc.find("ros2_control/hardware")
    assert hw is not None
    return (hw.findtext("plugin") or "").strip(), {p.get("name"): (p.text or "").strip() for p in hw.findall("param")}


def test_example_default_is_mock_and_equals_the_committed_urdf() -> None:
    default, mock = _xacro(None), _xacro("mock")
    assert _hardware(default) == ("mock_components/GenericSystem", {})
    assert etree.tostring(default) == etree.tostring(mock)
    urdf = etree.parse(str(PKG / "urdf" / "warehouse_arm.urdf")).getroot()
    assert _hardware(urdf) == ("mock_components/GenericSystem", {})
    assert urdf.find("gazebo") is None and default.find("gazebo") is None  # no sim plugin outside gazebo


def test_example_gazebo_variant_loads_gz_ros2_control_with_the_controllers_file() -> None:
    doc = _xacro("gazebo")
    assert _hardware(doc) == ("gz_ros2_control/GazeboSimSystem", {})
    plugins = doc.findall("gazebo/plugin")
    assert [(p.get("filename"), p.get("name")) for p in plugins] == [GZ_SIM]
    params = Path((plugins[0].findtext("parameters") or "").strip())
    assert params == PKG / "config" / "ros2_controllers.yaml" and params.is_file()


def test_example_real_variant_loads_the_vendor_plugin_with_its_params() -> None:
    doc = _xacro("real")
    assert _hardware(doc) == (
        "warehouse_arm_driver/WarehouseArmSystem",
        {"device": "/dev/ttyACM0", "baud_rate": "115200"},
    )
    assert doc.find("gazebo") is None
    # everything but the hardware is the default description
    for hw in (doc.find("ros2_control/hardware"), (mock := _xacro("mock")).find("ros2_control/hardware")):
        assert hw is not None
        for child in list(hw):
            hw.remove(child)
    assert etree.tostring(doc) == etree.tostring(mock)


def test_an_unknown_hardware_value_fails_expansion_with_the_allowed_values() -> None:
    with pytest.raises(InputError) as exc:
        _xacro("sim")
    assert "hardware:=sim is not one of mock, gazebo, real" in exc.value.findings[0].message


def _example_files() -> tuple[dict[str, str], object]:
    loaded = load_spec(ROOT / "specs" / "warehouse_arm.yaml")
    return render_package(loaded.robot, "specs/warehouse_arm.yaml"), loaded.robot


def test_the_variant_proof_passes_and_catches_a_variant_the_template_got_wrong(tmp_path: Path) -> None:
    files, robot = _example_files()
    assert xacro_variants_match(files, robot, tmp_path) == []  # type: ignore[arg-type]
    rel = "urdf/warehouse_arm.ros2_control.xacro"
    wrong_real = dict(files, **{rel: files[rel].replace("warehouse_arm_driver/WarehouseArmSystem", "x/Y")})
    found = xacro_variants_match(wrong_real, robot, tmp_path)  # type: ignore[arg-type]
    assert [f.code for f in found] == ["GEN001"] and "hardware:=real" in found[0].message
    no_sim = dict(files, **{rel: files[rel].replace('filename="gz_ros2_control-system"', 'filename="other"')})
    found = xacro_variants_match(no_sim, robot, tmp_path)  # type: ignore[arg-type]
    assert [f.code for f in found] == ["GEN001"] and "hardware:=gazebo" in found[0].message


VARIANTS = """    plugin: mock_components/GenericSystem
    variants:
"""


@pytest.mark.parametrize(
    ("old", "new", "code", "needle"),
    [
        (VARIANTS, VARIANTS.replace("mock_components/GenericSystem", "acme/Arm"), "SPEC080", "plugin: acme/Arm"),
        (
            "gazebo: {plugin: gz_ros2_control/GazeboSimSystem}",
            "gazebo: {plugin: gazebo_ros2_control/GazeboSystem}",
            "SPEC081",
            "gazebo: {plugin: gazebo_ros2_control",
        ),
        (
            "plugin: warehouse_arm_driver/WarehouseArmSystem",
            "plugin: mock_components/GenericSystem",
            "SPEC082",
            "real:",
        ),
    ],
)
def test_a_wrong_variant_plugin_is_an_input_error(tmp_path: Path, old: str, new: str, code: str, needle: str) -> None:
    text = plant(old, new, EXAMPLE_TEXT)
    found = errors_of(text, tmp_path)
    assert [f.code for f in found] == [code]
    # the error points into the hardware block it is about
    assert line_of(text, "hardware:") <= found[0].where.line <= line_of(text, needle) + 1


GRIPPER_TEXT = (GRIPPER / "robot.yaml").read_text()
IMU = JAZZY_IMU_INTERFACES


def test_gripper_imu_spec_generates_sensor_gpio_and_runs_the_gripper(tmp_path: Path) -> None:
    gen = cli("generate", GRIPPER / "robot.yaml", "--out", tmp_path)
    assert gen.returncode == 0, gen.stderr
    pkg = tmp_path / "gripper_imu_description"
    urdf = etree.parse(str(pkg / "urdf" / "gripper_imu.urdf")).getroot()
    sensor = urdf.find("ros2_control/sensor[@name='imu_sensor']")
    assert sensor is not None
    assert [s.get("name") for s in sensor.findall("state_interface")] == IMU
    assert {p.get("name"): p.text for p in sensor.findall("param")} == {"frame_id": "imu_link"}
    gpio = urdf.find("ros2_control/gpio[@name='tool_io']")
    assert gpio is not None
    cmd = gpio.find("command_interface")
    assert cmd is not None and (
        cmd.get("name"),
        cmd.get("data_type"),
        cmd.findtext("param[@name='initial_value']"),
    ) == (
        "vacuum",
        "bool",
        "0",
    )
    out = tmp_path / "run"
    ran = cli(
        "control",
        GRIPPER / "robot.yaml",
        "--trajectory",
        GRIPPER / "open_close.yaml",
        "--package",
        tmp_path,
        "--plant",
        "sim",
        "--out",
        out,
    )
    assert ran.returncode == 0, ran.stderr
    verdict = json.loads((out / "verdict.json").read_text())
    assert verdict["ok"] and verdict["controllers_not_active"] == []
    rows = [line.split(",") for line in (out / "desired_vs_measured.csv").read_text().splitlines()[1:]]
    finger = {round(float(r[0]), 6): float(r[4]) for r in rows if r[1] == "finger_joint"}
    # open_close.yaml: 40 mm due at 1 s, then 20 mm due at 2 s
    assert finger[1.0] == pytest.approx(0.040, abs=1e-6)
    assert finger[2.0] == pytest.approx(0.020, abs=1e-6)
    assert max(finger.values()) <= 0.040 + 1e-9  # never beyond the goal (nor the 40 mm limit)


@pytest.mark.parametrize(
    ("old", "new", "code"),
    [
        ("params: {joint: finger_joint}", "params: {joint: fingr_joint}", "CTRL002"),
        ("sensor_name: imu_sensor,", "sensor_name: imu_sensr,", "CTRL002"),
        ("joints: [wrist_joint]", "joints: [wrist_jiont]", "CTRL002"),
        ("command_interfaces: [position]", "command_interfaces: [postion]", "CTRL002"),
        ("frame: imu_link}", "frame: imu_lnk}", "SPEC083"),
        ("state: [{name: vacuum, data_type: bool}]", "state: [{name: vacuum, data_type: bool}, vacuum]", "SPEC084"),
        ("name: tool_io", "name: finger_joint", "SPEC084"),
    ],
)
def test_a_typo_in_a_controller_or_component_is_an_error(tmp_path: Path, old: str, new: str, code: str) -> None:
    text = plant(old, new, GRIPPER_TEXT)
    found = [f for f in errors_of(text, tmp_path) if f.severity == "error"]
    assert code in {f.code for f in found}
    changed = line_of(GRIPPER_TEXT, old)  # the one line the typo is on (replacements stay on it)
    # each error is on that line or on the element holding it (a controller, a sensor)
    assert any(f.where.line in range(changed - 5, changed + 1) for f in found if f.code == code)
