"""Forward kinematics and known poses, against pinocchio and hand-computed values."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from descgen.audit.spec import load_spec, load_spec_text
from descgen.commands.generate import generate
from descgen.physics import kinematics
from descgen.physics.poses import evaluate, findings
from descgen.render import render_package

from .conftest import EXAMPLE, ROOT
from .helpers import EXAMPLE_TEXT, cli, plant


def pin_frames(pin, urdf_text: str, values: dict[str, float]) -> dict[str, np.ndarray]:  # type: ignore[no-untyped-def]
    """Every link frame in the root frame, computed by pinocchio from the URDF."""
    model = pin.buildModelFromXML(urdf_text)
    data = model.createData()
    q = pin.neutral(model)
    for jid in range(1, model.njoints):
        name = model.names[jid]
        if name not in values:
            continue
        j = model.joints[jid]
        if j.nq == 1:
            q[j.idx_q] = values[name]
        elif j.nq == 2:  # continuous: (cos, sin)
            q[j.idx_q] = math.cos(values[name])
            q[j.idx_q + 1] = math.sin(values[name])
    pin.framesForwardKinematics(model, data, q)
    out = {}
    for fid, frame in enumerate(model.frames):
        if frame.type == pin.FrameType.BODY:
            out[frame.name] = data.oMf[fid].homogeneous
    return out


def assert_same_frames(pin, robot, values: dict[str, float]) -> None:  # type: ignore[no-untyped-def]
    urdf = render_package(robot, "specs/x.yaml")[f"urdf/{robot.name}.urdf"]
    ours = kinematics.forward(robot, values)
    theirs = pin_frames(pin, urdf, values)
    root = robot.root()
    for link in robot.links:
        if link.name == root:
            continue
        assert link.name in theirs, link.name
        np.testing.assert_allclose(ours[link.name], theirs[link.name], atol=1e-9, rtol=0, err_msg=link.name)


def test_zero_pose_by_hand() -> None:
    robot = load_spec(EXAMPLE).robot
    poses = kinematics.forward(robot)
    # the sheet's hand check: x = -50 + 300 + 250 mm, z = 85 + 175 + 100 + 50 + 50 mm
    np.testing.assert_allclose(poses["tool_link"][:3, 3], (0.500, 0.0, 0.460), atol=1e-12)
    # camera 25 mm forward and 40 mm above the tool flange (M24)
    np.testing.assert_allclose(poses["camera_link"][:3, 3], (0.525, 0.0, 0.500), atol=1e-12)


def test_ready_pose_by_hand() -> None:
    robot = load_spec(EXAMPLE).robot
    poses = kinematics.forward(robot, {"lift_joint": 0.15, "elbow_joint": -math.pi / 2})
    # lift raises the shoulder to z = 0.61; the elbow at x = 0.25 turns the forearm straight up
    np.testing.assert_allclose(poses["tool_link"][:3, 3], (0.250, 0.0, 0.860), atol=1e-12)
    # the camera's forward (+x of the tool) now points up; its "above" (+z) points back
    np.testing.assert_allclose(poses["camera_link"][:3, 3], (0.210, 0.0, 0.885), atol=1e-12)


def test_example_agrees_with_pinocchio_at_random_configurations(pin) -> None:  # type: ignore[no-untyped-def]
    robot = load_spec(EXAMPLE).robot
    rng = np.random.default_rng(7)
    for _ in range(20):
        values = {}
        for j in robot.joints:
            if j.type == "continuous":
                values[j.name] = float(rng.uniform(-10, 10))
            elif j.type in ("revolute", "prismatic"):
                values[j.name] = float(rng.uniform(j.limit.lower, j.limit.upper))
        assert_same_frames(pin, robot, values)


JOINT_TYPES = ("fixed", "revolute", "continuous", "prismatic", "floating", "planar")


@st.composite
def random_robot(draw: st.DrawFn) -> tuple[str, dict[str, float]]:
    """A random tree: every link hangs from an earlier one, by any joint type, with any
    origin, any rpy and any unit axis; plus a configuration for its 1-DOF joints."""
    n = draw(st.integers(min_value=2, max_value=8))
    coord = st.floats(min_value=-0.5, max_value=0.5, allow_nan=False)
    angle = st.floats(min_value=-math.pi, max_value=math.pi, allow_nan=False)
    lines = ["name: random", "links:"] + [f"  - name: l{i}" for i in range(n)] + ["joints:"]
    values: dict[str, float] = {}
    for i in range(1, n):
        parent = draw(st.integers(min_value=0, max_value=i - 1))
        jtype = draw(st.sampled_from(JOINT_TYPES))
        xyz = [draw(coord) for _ in range(3)]
        rpy = [draw(angle) for _ in range(3)]
        lines += [
            f"  - name: j{i}",
            f"    type: {jtype}",
            f"    parent: l{parent}",
            f"    child: l{i}",
            "    origin: {xyz: ["
            + ", ".join(f"{v!r} m" for v in xyz)
            + "], rpy: ["
            + ", ".join(f"{v!r} rad" for v in rpy)
            + "]}",
        ]
        if jtype in ("revolute", "continuous", "prismatic", "planar"):
            raw = np.array([draw(st.floats(min_value=-1, max_value=1, allow_nan=False)) for _ in range(3)])
            if np.linalg.norm(raw) < 0.1:
                raw = np.array([0.0, 0.0, 1.0])
            axis = raw / np.linalg.norm(raw)
            lines.append("    axis: [" + ", ".join(repr(float(c)) for c in axis) + "]")
        if jtype == "revolute":
            lines.append("    limit: {lower: -3 rad, upper: 3 rad, effort: 10 N*m, velocity: 1 rad/s}")
            values[f"j{i}"] = draw(st.floats(min_value=-3, max_value=3, allow_nan=False))
        elif jtype == "prismatic":
            lines.append("    limit: {lower: -1 m, upper: 1 m, effort: 10 N, velocity: 1 m/s}")
            values[f"j{i}"] = draw(st.floats(min_value=-1, max_value=1, allow_nan=False))
        elif jtype == "continuous":
            values[f"j{i}"] = draw(st.floats(min_value=-20, max_value=20, allow_nan=False))
    return "\n".join(lines) + "\n", values


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(random_robot())
def test_random_trees_agree_with_pinocchio(pin, case: tuple[str, dict[str, float]]) -> None:  # type: ignore[no-untyped-def]
    text, values = case
    robot = load_spec_text(text, "random.yaml", rules=False).robot  # kinematics only: FRAME003 would object
    assert_same_frames(pin, robot, values)


def test_measured_poses_pass() -> None:
    robot = load_spec(EXAMPLE).robot
    rows = evaluate(robot)
    assert [(r.pose.name, r.measurement.frame) for r in rows] == [
        ("zero", "tool_link"),
        ("zero", "camera_link"),
        ("ready", "tool_link"),
        ("ready", "camera_link"),
        ("side_reach", "tool_link"),
        ("shoulder_up_30", "tool_link"),
    ]
    assert all(r.ok for r in rows)
    assert findings(robot, rows) == []
    # K6 by hand: the arm tipped up 30 deg: 550 mm * (cos 30, sin 30) from the shoulder-lift axis
    k6 = rows[-1]
    assert k6.model == pytest.approx((-0.05 + 0.55 * math.cos(math.radians(30)), 0.0, 0.46 + 0.55 * 0.5), abs=1e-12)


def test_poses_cli() -> None:
    r = cli("poses", "specs/warehouse_arm.yaml", "--format", "json")
    assert r.returncode == 0, r.stderr
    import json

    doc = json.loads(r.stdout)
    assert len(doc["poses"]) == 6 and all(p["ok"] for p in doc["poses"])
    assert doc["summary"]["error"] == 0


def _project(tmp: Path, text: str) -> Path:
    (tmp / "specs").mkdir()
    spec = tmp / "specs" / "warehouse_arm.yaml"
    spec.write_text(text)
    return spec


def pose_failures(tmp: Path, text: str) -> list:  # type: ignore[type-arg]
    spec = _project(tmp, text)
    outcome = generate(spec)
    assert outcome.failed and not (tmp / "generated").exists(), "generate wrote files despite a failed pose"
    return [f for f in outcome.findings if f.code == "POSE010"]


def test_camera_25_m_caught_by_range(tmp_path: Path) -> None:
    from descgen.core.findings import InputError

    with pytest.raises(InputError) as exc:
        load_spec_text(plant("xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]"), "spec.yaml")
    [f] = [f for f in exc.value.findings if f.blocks]  # the refusal carries the spec's infos too
    assert f.code == "UNIT004" and '"25 m"' in f.message


def test_camera_25_m_caught_by_the_known_poses() -> None:
    text = plant("xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]")
    text = plant("require_sources: true\n", "require_sources: true\nplausibility: {offset: {max: 100 m}}\n", text)
    robot = load_spec_text(text, "spec.yaml", rules=False).robot  # other rules object too; look at the poses
    found = findings(robot)
    # K2 (zero) and K4 (ready) measure camera_link; the tool poses still pass
    assert [(f.subject, "camera_link" in f.message) for f in found] == [("pose:zero", True), ("pose:ready", True)]
    assert all("camera_joint" in f.message for f in found)
    assert "measured at (524.0, 1.0, 501.0) mm but the model puts it at (25500.0, 0.0, 500.0) mm" in found[0].message


def test_elbow_axis_z_caught_by_ready_pose(tmp_path: Path) -> None:
    text = plant(
        "    child: forearm_link\n    origin: {xyz: [300 mm, 0, 0], source: M20}\n    axis: +y",
        "    child: forearm_link\n    origin: {xyz: [300 mm, 0, 0], source: M20}\n    axis: +z",
    )
    found = pose_failures(tmp_path, text)
    assert {f.subject for f in found} == {"pose:ready"}
    assert len(found) == 2  # K3 tool_link and K4 camera_link
    assert all("elbow_joint (revolute, origin (300.0, 0.0, 0.0) mm, axis (0.0, 0.0, 1.0))" in f.message for f in found)


def test_swapped_parent_caught(tmp_path: Path) -> None:
    text = plant("    parent: tool_link\n", "    parent: forearm_link\n")
    found = pose_failures(tmp_path, text)
    assert {f.subject for f in found} == {"pose:zero", "pose:ready"}
    assert all("camera_link" in f.message and "tool_joint" not in f.message for f in found)


def test_evidence_table_committed() -> None:
    table = (ROOT / "generated" / "warehouse_arm_description" / "evidence" / "known_poses.md").read_text()
    assert "| `tool_link` | `base_footprint` | 501.0, 0.0, 459.0 | 500.0, 0.0, 460.0 | -1.0, 0.0, 1.0 |" in table
    assert "FAIL" not in table
    assert table.count("| pass |") == 6


def test_tolerance_is_per_axis() -> None:
    # K5 is 1, 2 and 2 mm off on the three axes (3 mm in distance) and passes: "each ±2 mm"
    rows = evaluate(load_spec(EXAMPLE).robot)
    k5 = next(r for r in rows if r.pose.name == "side_reach")
    assert k5.ok and k5.distance > 0.002


def test_measurement_just_outside_fails() -> None:
    text = plant("{frame: tool_link, xyz: [428 mm, 0 mm, 733 mm]", "{frame: tool_link, xyz: [428 mm, 0 mm, 732.9 mm]")
    robot = load_spec_text(text, "spec.yaml").robot
    [f] = findings(robot)
    assert f.code == "POSE010" and "shoulder_up_30" in f.message
    assert text != EXAMPLE_TEXT
