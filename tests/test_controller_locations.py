"""Findings about a controllers YAML point at the key or value they are about (not at the
controller's ``ros__parameters:`` line), and one wrong diff-drive base_frame_id is one FRAME004.

Every line:col below is counted by hand in the YAML the test writes."""

from __future__ import annotations

from pathlib import Path

import pytest

from descgen.core.findings import Finding
from descgen.read.description import Options, audit

from .conftest import ROOT
from .helpers import cli

ROVER = ROOT / "tests" / "rules" / "FRAME004" / "good.urdf"  # base_link, two wheels (r 0.1 m, 0.4 m apart)

FAULTY = """\
controller_manager:
  ros__parameters:
    update_rate: 99.5
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    diff_drive_controller:
      type: diff_drive_controller/DiffDriveController
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
    gripper:
      type: position_controllers/GripperActionController
    mystery:
      type: my_pkg/Mystery

joint_state_broadcaster:
  ros__parameters:
    frame_id: imu_frame
    interfaces: [position, velocity]

diff_drive_controller:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
    wheel_radius: 100
    wheel_separation: 0.4
    odom_frame_id: odom
    base_frame_id: base_foot

arm_controller:
  ros__parameters:
    joints:
      - left_wheel_joint
      - elbow_joint
    command_interfaces: [position]
    state_interfaces: [position]

gripper:
  ros__parameters:
    action_monitor_rate: 20.0

gripper2:
  ros__parameters:
    type: position_controllers/GripperActionController
    joint: finger_joint
"""

# (code, a piece of its message, line, col): each finding the file's faults must give, where
EXPECTED = [
    ("CTRL007", "update_rate 99.5", 3, 18),  # the value, not the URDF's <ros2_control>
    ("CTRL049", "my_pkg/Mystery", 13, 13),  # the type value under controller_manager
    ("FRAME004", "frame_id 'imu_frame'", 17, 15),
    ("CTRL010", "publishes 'velocity'", 18, 28),  # the list item, second of two
    ("CTRL006", "wheel_radius is 100 m", 24, 19),
    ("FRAME004", "base_frame_id 'base_foot'", 27, 20),
    ("CTRL002", "claims 'left_wheel_joint/position'", 32, 9),
    ("CTRL002", "claims 'elbow_joint/position'", 33, 9),
    ("CTRL002", "reads state 'elbow_joint/position'", 33, 9),
    ("CTRL009", "joints names 'elbow_joint'", 33, 9),
    ("CTRL050", "'gripper' (position_controllers/GripperActionController): 'joint'", 37, 1),  # missing: its key
    ("CTRL009", "joint names 'finger_joint'", 44, 12),  # a scalar joint parameter
    ("CTRL002", "claims 'finger_joint/position'", 44, 12),
]


def _audit(tmp_path: Path, text: str, **launch_args: str) -> list[Finding]:
    yaml_file = tmp_path / "controllers.yaml"
    yaml_file.write_text(text)
    return audit(ROVER, Options(controllers=yaml_file, launch_args=launch_args))


@pytest.mark.parametrize(("code", "piece", "line", "col"), EXPECTED, ids=[f"{c}:{ln}" for c, _, ln, _ in EXPECTED])
def test_finding_points_at_its_key_or_value(tmp_path: Path, code: str, piece: str, line: int, col: int) -> None:
    found = [f for f in _audit(tmp_path, FAULTY) if f.code == code and piece in f.message]
    assert len(found) == 1, [str(f.where) + " " + f.message for f in found]
    [f] = found
    assert f.where.file.endswith("controllers.yaml")
    assert (f.where.line, f.where.col) == (line, col), f.message


def test_no_controller_finding_sits_on_a_ros_parameters_line(tmp_path: Path) -> None:
    lines = FAULTY.splitlines()
    in_file = [f for f in _audit(tmp_path, FAULTY) if f.where.file.endswith("controllers.yaml")]
    assert in_file
    for f in in_file:
        assert "ros__parameters" not in lines[f.where.line - 1], f"{f.code} at {f.where}: {f.message}"


BASE_WRONG = """\
controller_manager:
  ros__parameters:
    update_rate: 100
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    diff_drive_controller:
      type: diff_drive_controller/DiffDriveController

diff_drive_controller:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
    odom_frame_id: odom
    base_frame_id: {base}
"""


def test_wrong_base_frame_is_one_frame004(tmp_path: Path) -> None:
    # the diff-drive odom -> base edge and the base_frame_id check both saw this one name
    found = [f for f in _audit(tmp_path, BASE_WRONG.format(base="base_foot")) if f.code == "FRAME004"]
    assert [(f.subject, f.where.line, f.where.col) for f in found] == [("controller:diff_drive_controller", 14, 20)]


def test_unresolved_base_frame_is_no_frame004(tmp_path: Path) -> None:
    # a $(var ...) left as written is CTRL052/053's, not a frame that connects to nothing
    found = _audit(tmp_path, BASE_WRONG.format(base='"$(var base)"'))
    assert [f.code for f in found if f.code == "FRAME004"] == []
    assert any(f.code in ("CTRL052", "CTRL053") for f in found)


def test_spec_wrong_base_frame_is_one_frame004(tmp_path: Path) -> None:
    text = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    assert text.count("base_frame_id: base_footprint") == 1
    spec = tmp_path / "warehouse_arm.yaml"
    spec.write_text(text.replace("base_frame_id: base_footprint", "base_frame_id: base_foot"))
    r = cli("validate", spec)
    assert r.returncode == 2
    lines = [ln for ln in r.stdout.splitlines() + r.stderr.splitlines() if "FRAME004" in ln]
    assert len(lines) == 1, lines
    assert "base_frame_id 'base_foot'" in lines[0]


def test_an_entry_without_a_type_is_said_to_be_unchecked_not_dropped() -> None:
    """CTRL056: a top-level entry with ros__parameters and no type anywhere is reported once,
    at its key (line 8, column 1 of the text below), as info; typed controllers are still read."""
    from descgen.read.controllers import read_controllers_text

    text = """\
controller_manager:
  ros__parameters:
    arm:
      type: joint_trajectory_controller/JointTrajectoryController
arm:
  ros__parameters:
    joints: [a]
untyped:
  ros__parameters:
    joints: [b]
own_type:
  ros__parameters:
    type: forward_command_controller/ForwardCommandController
"""
    controllers, _, found = read_controllers_text(text, "c.yaml")
    assert sorted(c.name for c in controllers) == ["arm", "own_type"]
    ctrl056 = [f for f in found if f.code == "CTRL056"]
    assert [(f.severity, f.subject, f.where.line, f.where.col) for f in ctrl056] == [
        ("info", "controller:untyped", 8, 1)
    ]
    _, _, typed_only = read_controllers_text(text.split("untyped:")[0], "c.yaml")
    assert not [f for f in typed_only if f.code == "CTRL056"]
