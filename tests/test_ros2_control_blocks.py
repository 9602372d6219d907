"""Issue 14: several ``<ros2_control>`` blocks (one per hardware component), per-interface
params on joint interfaces, the round trip of sensors/gpios/blocks, gz_ros2_control in
package.xml, and ``descgen control`` with a GenericSystem per block.

Expected values are written by hand from tests/data/two_blocks/robot.yaml (angles converted
by hand: 90 deg = pi/2 rad, 30 deg = pi/6 rad); the oracles are lxml, xacro's own evaluator
(trusted, as ROS runs it) and the Jazzy sources each validation cites."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.commands.control.load import load_system
from descgen.commands.control.system import Plant
from descgen.prove.semantic_roundtrip import ros2_control_roundtrip
from descgen.prove.xacro_expand import xacro_variants_match
from descgen.read.xacro_file import expand
from descgen.render import render_package
from tests.helpers import ROOT, cli, errors_of, line_of, plant

DATA = ROOT / "tests" / "data" / "two_blocks"
SPEC_TEXT = (DATA / "robot.yaml").read_text()
ROBOT = load_spec(DATA / "robot.yaml").robot
FILES = render_package(ROBOT, "robot.yaml")
URDF = "urdf/two_blocks.urdf"
IMU = [
    *(f"orientation.{a}" for a in "xyzw"),
    *(f"angular_velocity.{a}" for a in "xyz"),
    *(f"linear_acceleration.{a}" for a in "xyz"),
]


def _iface(e: etree._Element) -> tuple[str | None, str | None, dict[str | None, str | None]]:
    return e.get("name"), e.get("data_type"), {p.get("name"): p.text for p in e.findall("param")}


def test_two_blocks_are_written_each_with_its_own_components_and_interface_params() -> None:
    root = etree.fromstring(FILES[URDF].encode())
    blocks = root.findall("ros2_control")
    assert [(b.get("name"), b.get("type")) for b in blocks] == [("WristSystem", "system"), ("GripperSystem", "system")]
    wrist, gripper = blocks
    assert [j.get("name") for j in wrist.findall("joint")] == ["wrist_joint"]
    assert [s.get("name") for s in wrist.findall("sensor")] == ["imu_sensor"]
    assert wrist.find("gpio") is None
    assert [j.get("name") for j in gripper.findall("joint")] == ["finger_joint"]
    assert gripper.find("sensor") is None
    assert [g.get("name") for g in gripper.findall("gpio")] == ["tool_io"]
    # the default (mock) hardware of each block, with the gripper's own params
    assert [
        (b.findtext("hardware/plugin"), {p.get("name"): p.text for p in b.findall("hardware/param")}) for b in blocks
    ] == [
        ("mock_components/GenericSystem", {}),
        ("mock_components/GenericSystem", {"mock_gpio_commands": "false"}),
    ]
    # wrist: the spec's -90..90 deg replace the joint's -180..180 deg; 30 deg initial position
    (cmd,) = wrist.findall("joint/command_interface")
    name, data_type, params = _iface(cmd)
    assert (name, data_type) == ("position", "double")
    assert float(params["min"] or "") == pytest.approx(-math.pi / 2, abs=1e-12)
    assert float(params["max"] or "") == pytest.approx(math.pi / 2, abs=1e-12)
    states = [_iface(s) for s in wrist.findall("joint/state_interface")]
    assert [(n, t) for n, t, _ in states] == [("position", None), ("velocity", None)]
    assert float(states[0][2]["initial_value"] or "") == pytest.approx(math.pi / 6, abs=1e-12)
    # finger: max 35 mm from the spec, min 0 still from the joint limit (0 mm)
    (fcmd,) = gripper.findall("joint/command_interface")
    assert {k: float(v or "") for k, v in _iface(fcmd)[2].items()} == {"min": 0.0, "max": pytest.approx(0.035)}
    assert [_iface(i)[0] for i in wrist.findall("sensor/state_interface")] == IMU
    gpio = gripper.find("gpio")
    assert gpio is not None
    assert [_iface(i) for i in gpio] == [
        ("vacuum", "bool", {"initial_value": "0"}),
        ("vacuum", "bool", {}),
    ]


def _expanded(tmp_path: Path, hardware: str) -> etree._Element:
    """The generated Xacro expanded by xacro's own evaluator, as ``ros2 launch`` would."""
    assert cli("generate", DATA / "robot.yaml", "--out", tmp_path).returncode == 0
    pkg = tmp_path / "two_blocks_description"
    xacro = pkg / "urdf" / "two_blocks.urdf.xacro"
    return etree.fromstring(expand(xacro, str(xacro), {"hardware": hardware}, package_paths=[tmp_path], trusted=True))


def _hardware(doc: etree._Element) -> list[tuple[str | None, str, dict[str | None, str | None]]]:
    return [
        (
            b.get("name"),
            (b.findtext("hardware/plugin") or "").strip(),
            {p.get("name"): p.text for p in b.findall("hardware/param")},
        )
        for b in doc.findall("ros2_control")
    ]


def test_one_hardware_argument_selects_every_blocks_own_variant(tmp_path: Path) -> None:
    real = _expanded(tmp_path, "real")
    assert _hardware(real) == [
        ("WristSystem", "wrist_driver/WristSystem", {"device": "/dev/ttyUSB0"}),
        ("GripperSystem", "gripper_driver/GripperSystem", {"device": "/dev/ttyUSB1", "baud_rate": "57600"}),
    ]
    assert real.find("gazebo") is None
    gazebo = _expanded(tmp_path / "gz", "gazebo")
    assert _hardware(gazebo) == [
        ("WristSystem", "gz_ros2_control/GazeboSimSystem", {}),
        ("GripperSystem", "gz_ros2_control/GazeboSimSystem", {}),
    ]
    assert len(gazebo.findall("gazebo/plugin")) == 1  # one sim plugin for the whole robot


def test_the_variant_proof_checks_each_block_separately(tmp_path: Path) -> None:
    assert xacro_variants_match(FILES, ROBOT, tmp_path) == []
    rel = "urdf/two_blocks.ros2_control.xacro"
    # only the second block's real param is wrong: a proof that gives every block the first
    # block's variant, or skips the second block, misses it
    wrong = dict(FILES, **{rel: FILES[rel].replace('<param name="baud_rate">57600', '<param name="baud_rate">9600')})
    found = xacro_variants_match(wrong, ROBOT, tmp_path)
    assert [f.code for f in found] == ["GEN001"] and "hardware:=real" in found[0].message


def test_generate_and_check_pass_for_two_blocks(tmp_path: Path) -> None:
    assert ros2_control_roundtrip(FILES, ROBOT, tmp_path) == []
    assert cli("generate", DATA / "robot.yaml", "--out", tmp_path).returncode == 0
    # check re-runs every proof (both blocks read back, every variant expanded) on the files
    ran = cli("check", DATA / "robot.yaml", "--out", tmp_path)
    assert ran.returncode == 0, ran.stdout + ran.stderr


def _block_fields() -> list[tuple[int, str | None]]:
    """(element index, attribute or None for text) of every field inside a <ros2_control>."""
    root = etree.fromstring(FILES[URDF].encode())
    out: list[tuple[int, str | None]] = []
    for i, e in enumerate(root.iter()):
        inside = e.tag == "ros2_control" or any(a.tag == "ros2_control" for a in e.iterancestors())
        if not isinstance(e.tag, str) or not inside:
            continue
        out += [(i, a) for a in e.attrib]
        if e.text and e.text.strip():
            out.append((i, None))
    return out


FIELDS = _block_fields()


def _edit(index: int, attr: str | None) -> str:
    root = etree.fromstring(FILES[URDF].encode())
    e = list(root.iter())[index]
    old = e.text.strip() if attr is None and e.text else e.get(attr or "", "")
    try:
        new = repr(float(old) + 0.001)
    except ValueError:
        new = {"system": "actuator", "double": "float32", "bool": "int8"}.get(old, old + "_x")
    if attr is None:
        e.text = new
    else:
        e.set(attr, new)
    return etree.tostring(root, encoding="unicode")


def test_there_are_fields_of_sensors_gpios_and_both_blocks() -> None:
    tags = {list(etree.fromstring(FILES[URDF].encode()).iter())[i].tag for i, _ in FIELDS}
    assert {"ros2_control", "plugin", "param", "joint", "sensor", "gpio", "command_interface"} <= tags
    assert len(FIELDS) > 40


@pytest.mark.parametrize(("index", "attr"), FIELDS)
def test_every_edit_inside_a_block_is_reported(index: int, attr: str | None) -> None:
    files = dict(FILES, **{URDF: _edit(index, attr)})
    found = ros2_control_roundtrip(files, ROBOT, Path("/pkg"))
    assert found, f"edit of element {index} {attr} went unnoticed"
    assert {f.code for f in found} == {"GEN032"}


@pytest.mark.parametrize(
    "removed",
    ['<state_interface name="orientation.w"/>', '<param name="frame_id">imu_link</param>', "</gpio>"],
)
def test_a_removed_sensor_interface_param_or_gpio_is_reported(removed: str) -> None:
    text = FILES[URDF]
    if removed == "</gpio>":  # drop the whole gpio element
        start = text.index("    <gpio ")
        text = text[:start] + text[text.index("</gpio>") + len("</gpio>\n") :]
    else:
        text = text.replace(removed, "", 1)
    found = ros2_control_roundtrip(dict(FILES, **{URDF: text}), ROBOT, Path("/pkg"))
    assert [f.code for f in found][:1] == ["GEN032"]


def test_an_extra_element_in_a_block_is_reported() -> None:
    text = FILES[URDF].replace("    <gpio ", '    <sensor name="ghost"/>\n    <gpio ', 1)
    found = ros2_control_roundtrip(dict(FILES, **{URDF: text}), ROBOT, Path("/pkg"))
    assert found and {f.code for f in found} == {"GEN032"}


def test_control_runs_a_generic_system_per_block(tmp_path: Path) -> None:
    assert cli("generate", DATA / "robot.yaml", "--out", tmp_path).returncode == 0
    cm = load_system(tmp_path / "two_blocks_description", ROBOT, Plant("mock"))
    # both components went through their own lifecycle
    activated = [
        e["name"] for e in cm.trace.events if e.get("kind") == "hardware" and e.get("transition") == "activate"
    ]
    assert activated == ["WristSystem", "GripperSystem"]
    # the spec's initial_value (30 deg) reached the wrist's position state
    assert cm.state("wrist_joint", "position") == pytest.approx(math.pi / 6, abs=1e-12)
    # the spec's 35 mm command max is the gripper's limit
    assert cm.by_name["finger_joint"].limits["position"] == (0.0, pytest.approx(0.035))
    out = tmp_path / "run"
    ran = cli(
        "control",
        DATA / "robot.yaml",
        "--trajectory",
        DATA / "open_close.yaml",
        "--package",
        tmp_path,
        "--plant",
        "sim",
        "--out",
        out,
    )
    assert ran.returncode == 0, ran.stderr
    verdict = json.loads((out / "verdict.json").read_text())
    assert verdict["ok"] and verdict["controllers_not_active"] == [] and verdict["rejected"] == []
    # beyond the spec's 35 mm (inside the joint's 40 mm) the command is rejected
    beyond = tmp_path / "beyond.yaml"
    beyond.write_text((DATA / "open_close.yaml").read_text().replace("[35 mm]", "[38 mm]"))
    ran = cli("control", DATA / "robot.yaml", "--trajectory", beyond, "--package", tmp_path, "--out", tmp_path / "b")
    assert ran.returncode == 1
    assert json.loads((tmp_path / "b" / "verdict.json").read_text())["rejected"]


def test_package_xml_depends_on_gz_ros2_control_only_with_a_gazebo_variant(tmp_path: Path) -> None:
    def depends(files: dict[str, str]) -> list[str | None]:
        return [
            e.text for e in etree.fromstring(files["package.xml"].split("\n", 3)[3].encode()).findall("exec_depend")
        ]

    assert "gz_ros2_control" in depends(FILES)
    assert "hardware_interface" in depends(FILES)  # mock_components lives there
    # without gazebo variants (real only) no gz_ros2_control; the vendor driver is no dependency
    text = SPEC_TEXT.replace("      gazebo: {}\n", "").replace("          gazebo: {}\n", "")
    path = tmp_path / "robot.yaml"
    path.write_text(text)
    robot = load_spec(path).robot
    deps = depends(render_package(robot, "robot.yaml"))
    assert "gz_ros2_control" not in deps and "wrist_driver" not in deps and "gripper_driver" not in deps


SECOND = "    - name: GripperSystem\n"


@pytest.mark.parametrize(
    ("old", "new", "code", "needle"),
    [
        # the finger in both blocks (resource_manager.cpp: "already existing key")
        (
            "initial_value: 0}]\n",
            "initial_value: 0}]\n    - {name: finger_joint, command: [position], state: [position]}\n",
            "SPEC085",
            "- {name: finger_joint, command: [{name: position, max: 35 mm}]",
        ),
        # two blocks with one name (resource_manager.cpp: "Hardware name %s is duplicated")
        (SECOND, "    - name: WristSystem\n", "SPEC086", "    - name: WristSystem"),
        # a sensor block with a command interface
        (SECOND, SECOND + "      type: sensor\n", "SPEC087", "command: [{name: position, max: 35 mm}]"),
        # mock_components/GenericSystem is a SystemInterface plugin only
        (SECOND, SECOND + "      type: actuator\n", "SPEC088", "      hardware:\n        plugin: mock"),
        # the second block without the variants the first declares
        (
            "        variants:\n          gazebo: {}\n          real: {plugin: gripper_driver/GripperSystem, "
            "params: {device: /dev/ttyUSB1, baud_rate: 57600}}\n",
            "",
            "SPEC089",
            "params: {mock_gpio_commands: false}",
        ),
        # the initial position twice
        ("    - name: wrist_joint\n", "    - name: wrist_joint\n      initial_position: 10 deg\n", "CTRL080", "30 deg"),
        # a spec min beyond the joint limit (-180 deg)
        ("min: -90 deg", "min: -200 deg", "CTRL008", "min: -200 deg"),
        # a length for a revolute joint's limit
        ("min: -90 deg", "min: -90 mm", "UNIT", "min: -90 mm"),
    ],
)
def test_a_block_or_interface_mistake_is_an_error_at_its_line(
    tmp_path: Path, old: str, new: str, code: str, needle: str
) -> None:
    text = plant(old, new, SPEC_TEXT)
    found = [f for f in errors_of(text, tmp_path) if f.severity == "error"]
    hits = [f for f in found if f.code.startswith(code)]
    assert hits, [f"{f.code} {f.message}" for f in found]
    target = line_of(text, needle)
    # at the line of the mistake, or of the element holding it (a block, a joint)
    assert any(target - 3 <= f.where.line <= target + 1 for f in hits), [(f.code, f.where.line, target) for f in hits]
