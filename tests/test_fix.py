"""``descgen fix`` (descgen/commands/fix.py): only the fixes that cannot change the robot, written
in place with comments and formatting kept, printed as a diff. The oracle for "the robot did not
change" is the URDF generate writes, before and after, with the renamed plugin put back."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from descgen.commands import fix
from descgen.render import render_package

from .helpers import cli

SPEC = """\
name: fx
links:
  - name: base_link
  - name: arm_link
    inertial:
      mass: 1 kg
      origin: {xyz: [0, 0, 50 mm]}
      inertia: {ixx: 0.001 kg*m^2, iyy: 0.001 kg*m^2, izz: 0.001 kg*m^2}
joints:
  - name: j1
    type: revolute
    parent: base_link
    child: arm_link
    axis: +z
    limit: {lower: -90 deg, upper: 90 deg, effort: 10 N*m, velocity: 1 rad/s}
ros2_control:
  name: hw
  update_rate: 100 Hz
  hardware:
    plugin: fake_components/GenericSystem   # was fake_components/GenericSystem on Humble
    params:
      fake_sensor_commands: "true"
  joints:
    - {name: j1, command: [position], state: [position]}
  controllers:
    - name: joint_state_broadcaster
      type: joint_state_broadcaster/JointStateBroadcaster
    - name: arm_controller
      type: joint_trajectory_controller/JointTrajectoryController
      params:
        joints: [j1]
        command_interfaces: [position]
        state_interfaces: [position]
        state_publish_rate: 50.0   # removed in Jazzy
        start_with_holding: true
"""
# as import writes them (block style, after the rest)
WAIVERS = """
waivers:
- code: CTRL045
  subject: ros2_control:hw
  reason: imported as is
- code: GEOM040
  subject: link:base_link
  reason: imported as is
"""


def _urdf(text: str, name: str = "fx.yaml") -> str:
    from descgen.audit.spec import load_spec_text

    robot = load_spec_text(text, name, rules=False).robot
    urdf = render_package(robot, name, only={"urdf/fx.urdf"})["urdf/fx.urdf"]
    return "\n".join(line for line in urdf.splitlines() if "descgen spec-sha256" not in line)


def _codes(path: Path) -> list[str]:
    ran = cli("validate", path)
    return re.findall(r"(?:error|warning|info)\[(\w+)\]", ran.stderr)


def test_fix_renames_what_jazzy_renamed_and_drops_what_it_removed(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    spec.write_text(SPEC + WAIVERS)
    before = _codes(spec)
    assert {"CTRL045", "CTRL046", "CTRL063"} <= set(before)
    ran = cli("fix", spec)
    assert ran.returncode == 0, ran.stderr
    after_text = spec.read_text()
    after = _codes(spec)
    assert not {"CTRL045", "CTRL046", "CTRL063", "SPEC130"} & set(after)
    assert after.count("GEOM040") == 1  # not fixable (it would add a mass), and its waiver stays
    # the comment naming the old plugin is a comment: kept as written, like the layout
    assert "mock_components/GenericSystem   # was fake_components/GenericSystem on Humble" in after_text
    assert 'mock_sensor_commands: "true"' in after_text and "state_publish_rate" not in after_text
    assert yaml.safe_load(after_text)["waivers"] == [
        {"code": "GEOM040", "subject": "link:base_link", "reason": "imported as is"}
    ]
    # the robot is the one it was: the same URDF, the new names of the plugin and its parameter aside
    renamed = _urdf(SPEC).replace("fake_components/GenericSystem", "mock_components/GenericSystem")
    assert _urdf(after_text) == renamed.replace('"fake_sensor_commands"', '"mock_sensor_commands"')
    # the diff printed is the change made
    assert "-    plugin: fake_components/GenericSystem" in ran.stdout
    assert "+    plugin: mock_components/GenericSystem" in ran.stdout
    assert "-- code: CTRL045" in ran.stdout and "-        start_with_holding: true" in ran.stdout


def test_dry_run_writes_nothing(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    spec.write_text(SPEC)
    ran = cli("fix", "--dry-run", spec)
    assert ran.returncode == 0 and "+    plugin: mock_components/GenericSystem" in ran.stdout
    assert spec.read_text() == SPEC and "nothing written" in ran.stderr


def test_nothing_to_fix_leaves_the_file_alone(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    clean = SPEC.replace("fake_components/GenericSystem   # was", "mock_components/GenericSystem   # was")
    clean = clean.replace("fake_sensor_commands", "mock_sensor_commands").replace(
        "        start_with_holding: true\n", ""
    )
    clean = clean.replace("        state_publish_rate: 50.0   # removed in Jazzy\n", "")
    spec.write_text(clean)
    stat = spec.stat()
    ran = cli("fix", spec)
    assert ran.returncode == 0 and ran.stdout == "" and "nothing to fix safely" in ran.stderr
    assert spec.stat().st_mtime_ns == stat.st_mtime_ns


def test_a_value_that_would_change_the_robot_is_never_changed(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    spec.write_text(SPEC.replace("effort: 10 N*m", "effort: 0 N*m"))
    assert cli("fix", spec).returncode == 0
    text = spec.read_text()
    assert "effort: 0 N*m" in text and "mock_components/GenericSystem" in text
    assert "JOINT005" in _codes(spec)


def test_a_parameter_in_a_flow_mapping_is_left_for_the_user(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    block = (
        "      params:\n        joints: [j1]\n        command_interfaces: [position]\n"
        "        state_interfaces: [position]\n        state_publish_rate: 50.0   # removed in Jazzy\n"
        "        start_with_holding: true\n"
    )
    flow = "      params: {joints: [j1], command_interfaces: [position], state_interfaces: [position], "
    flow += "state_publish_rate: 50.0}\n"
    assert block in SPEC
    spec.write_text(SPEC.replace(block, flow))
    assert cli("fix", spec).returncode == 0
    assert "state_publish_rate: 50.0" in spec.read_text() and "CTRL063" in _codes(spec)


def _buggy(old: str, new: str) -> fix.Fixer:
    """A fixer with a bug: it edits ``old`` into ``new`` wherever it stands."""

    def edit(f: object, doc: object, lines: list[str], deleted: set[int]) -> str:
        for i, line in enumerate(lines):
            lines[i] = line.replace(old, new)
        return "a bug"

    return edit


@pytest.mark.parametrize(
    ("code", "old", "new"),
    [("CTRL045", "mass: 1 kg", "mass: 2 kg"), ("CTRL046", "update_rate: 100 Hz", "update_rate: 200 Hz")],
    ids=["a mass", "the ros2_control model"],
)
def test_a_fix_that_would_change_the_robot_is_refused_and_nothing_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, code: str, old: str, new: str
) -> None:
    """The proof behind every fix: a fixer that (by a bug) changed the robot is caught."""
    monkeypatch.setitem(fix._FIXERS, code, (_buggy(old, new),))
    spec = tmp_path / "fx.yaml"
    spec.write_text(SPEC)
    ran = cli("fix", spec)
    assert ran.returncode == 2 and "error[FIX001]" in ran.stderr and "Traceback" not in ran.stderr
    assert spec.read_text() == SPEC


def test_a_spec_that_does_not_read_is_an_input_error(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    spec.write_text("name: fx\nlinks: [\n")
    ran = cli("fix", spec)
    assert ran.returncode == 2 and "error[YAML001]" in ran.stderr
    assert spec.read_text() == "name: fx\nlinks: [\n"


def test_a_vendor_variant_parameter_of_the_same_name_is_not_renamed(tmp_path: Path) -> None:
    """fake_sensor_commands is GenericSystem's; under the real variant it is the vendor driver's."""
    spec = tmp_path / "fx.yaml"
    variant = (
        '      fake_sensor_commands: "true"\n'
        "    variants:\n"
        "      real:\n"
        "        plugin: vendor_driver/VendorSystem\n"
        '        params: {fake_sensor_commands: "yes"}\n'
    )
    text = SPEC.replace("fake_components/GenericSystem   #", "mock_components/GenericSystem   #")
    text = text.replace('      fake_sensor_commands: "true"\n', variant)
    spec.write_text(text)
    assert cli("fix", spec).returncode == 0
    fixed = spec.read_text()
    assert 'mock_sensor_commands: "true"' in fixed and 'params: {fake_sensor_commands: "yes"}' in fixed


def test_a_fixed_spec_keeps_its_file_mode(tmp_path: Path) -> None:
    spec = tmp_path / "fx.yaml"
    spec.write_text(SPEC)
    spec.chmod(0o600)
    assert cli("fix", spec).returncode == 0
    assert "mock_components" in spec.read_text() and spec.stat().st_mode & 0o777 == 0o600
