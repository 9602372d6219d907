"""Frame ownership: who publishes each transform, the evidence files, and FRAME findings."""

from __future__ import annotations

import dataclasses
import subprocess
from pathlib import Path

import pytest

from descgen.audit import run
from descgen.audit.spec import load_spec
from descgen.core.model import ExternalFrame, Joint, JointStateSource
from descgen.physics.frames import edges

from .conftest import EXAMPLE, ROOT, require_tool
from .helpers import cli

ROBOT = load_spec(EXAMPLE).robot
EVIDENCE = ROOT / "generated" / "warehouse_arm_description" / "evidence"


def test_example_owners_match_the_sheet() -> None:
    by_child = {e.child: e for e in edges(ROBOT)}
    # every URDF link but the root has exactly one publisher, plus odom -> base_footprint (C05)
    assert set(by_child) == {lk.name for lk in ROBOT.links} - {"base_footprint"} | {"base_footprint"}
    assert len(edges(ROBOT)) == len(by_child)
    for j in ROBOT.joints:
        e = by_child[j.child]
        assert e.owner == "robot_state_publisher" and e.parent == j.parent and e.joint == j.name
        assert e.static == (j.type == "fixed")
        assert e.topic == ("/tf_static" if j.type == "fixed" else "/tf")
    for name in ("lift_link", "left_wheel_link", "forearm_link"):
        assert "joint_state_broadcaster" in by_child[name].via
    odom = by_child["base_footprint"]
    assert (odom.parent, odom.owner, odom.topic, odom.static) == ("odom", "diff_drive_controller", "/tf", False)


def test_evidence_committed_and_drawable(tmp_path: Path) -> None:
    md = (EVIDENCE / "frames.md").read_text()
    assert "```mermaid" in md and "graph TD" in md
    assert "| `base_footprint` | `odom` | diff\\_drive\\_controller | `/tf` | dynamic | — |" in md
    dot_text = (EVIDENCE / "frames.dot").read_text()
    assert '"odom" -> "base_footprint"' in dot_text
    dot = require_tool("dot")
    out = tmp_path / "frames.svg"
    r = subprocess.run(
        [dot, "-Tsvg", str(EVIDENCE / "frames.dot"), "-o", str(out)], capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 0, r.stderr
    svg = out.read_text()
    assert "<svg" in svg and "camera_optical_frame" in svg


def _codes(robot) -> set[str]:  # type: ignore[no-untyped-def]
    return {f.code for f in run(robot)}


def test_clean_example_has_no_frame_findings() -> None:
    assert not {c for c in _codes(ROBOT) if c.startswith("FRAME")}


def test_declared_odometry_node_collides_with_diff_drive() -> None:
    ekf = ExternalFrame("odom", "base_footprint", "ekf_filter_node")
    robot = dataclasses.replace(ROBOT, external_frames=(ekf,))
    [f] = [f for f in run(robot) if f.code == "FRAME001"]
    assert "base_footprint" in f.message and "diff_drive_controller" in f.message and "ekf_filter_node" in f.message


def test_localisation_map_to_odom_is_fine() -> None:
    amcl = ExternalFrame("map", "odom", "amcl")
    robot = dataclasses.replace(ROBOT, external_frames=(amcl,))
    assert not {c for c in _codes(robot) if c.startswith("FRAME")}
    assert any(e.child == "odom" and e.owner == "amcl" for e in edges(robot))


def test_joint_without_position_state() -> None:
    rc = ROBOT.ros2_control
    assert rc is not None
    joints = tuple(dataclasses.replace(cj, state=cj.state[1:]) if cj.name == "elbow_joint" else cj for cj in rc.joints)
    robot = dataclasses.replace(ROBOT, ros2_control=dataclasses.replace(rc, joints=joints))
    [f] = [f for f in run(robot) if f.code == "FRAME002"]
    assert "elbow_joint" in f.message and "forearm_link" in f.message


def test_no_joint_state_broadcaster_means_no_moving_frames() -> None:
    rc = ROBOT.ros2_control
    assert rc is not None
    robot = dataclasses.replace(ROBOT, ros2_control=dataclasses.replace(rc, controllers=rc.controllers[1:]))
    found = [f for f in run(robot) if f.code == "FRAME002"]
    assert len(found) == 6  # lift, pan, lift, elbow and both wheels


def test_floating_and_planar_joints() -> None:
    extra = (Joint("float_joint", "floating", "tool_link", "camera_link", axis=None),)
    robot = dataclasses.replace(ROBOT, joints=tuple(j for j in ROBOT.joints if j.name != "camera_joint") + extra)
    [f] = [f for f in run(robot) if f.code == "FRAME003"]
    assert f.severity == "error" and "float_joint" in f.message
    declared = dataclasses.replace(robot, external_frames=(ExternalFrame("tool_link", "camera_link", "hand_eye_node"),))
    assert "FRAME003" not in _codes(declared)
    planar = dataclasses.replace(
        ROBOT,
        joints=tuple(
            dataclasses.replace(j, type="planar", axis=(0.0, 0.0, 1.0)) if j.name == "caster_joint" else j
            for j in ROBOT.joints
        ),
    )
    [f] = [f for f in run(planar) if f.code == "FRAME003"]
    assert f.severity == "warning" and "frozen at zero" in f.message


def test_diff_drive_base_frame_must_be_a_link() -> None:
    rc = ROBOT.ros2_control
    assert rc is not None
    cs = tuple(
        dataclasses.replace(c, params=tuple((k, "base_foot") if k == "base_frame_id" else (k, v) for k, v in c.params))
        for c in rc.controllers
    )
    robot = dataclasses.replace(ROBOT, ros2_control=dataclasses.replace(rc, controllers=cs))
    assert any(f.code == "FRAME004" and "base_foot" in f.message for f in run(robot))


@pytest.mark.parametrize("kind", ["desired", "measured"])
def test_second_joint_states_publisher(kind: str) -> None:
    robot = dataclasses.replace(ROBOT, joint_state_sources=(JointStateSource("preview_node", kind),))
    found = [f for f in run(robot) if f.code == "FRAME005"]
    assert found  # desired: commands shown as motion; measured: two publishers per joint
    if kind == "desired":
        assert any("desired commands" in f.message for f in found)


def test_frames_cli() -> None:
    import json

    r = cli("frames", "specs/warehouse_arm.yaml", "--format", "json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert len(doc["frames"]) == 14 and doc["summary"]["error"] == 0
