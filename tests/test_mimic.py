"""Mimic joints are joints: forward kinematics, known poses, frames and the tf scenario
follow ``q = multiplier * q_leader + offset``, checked against pinocchio (built with its own
mimic support, or expanded by hand from the leader) and yourdfpy's mimic handling."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yourdfpy
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from descgen.audit.spec import load_spec, load_spec_text
from descgen.cli import main
from descgen.physics import kinematics, mimic
from descgen.physics.frames import edges
from descgen.physics.poses import evaluate
from descgen.read.urdf import read_urdf_text
from descgen.render import render_package

from .helpers import ROOT, line_of, plant

FIXTURE = ROOT / "tests" / "data" / "mimic" / "gripper.yaml"
TEXT = FIXTURE.read_text()
LEADER, FOLLOWER = "finger_left_joint", "finger_right_joint"


def urdf_of(text: str, tmp: Path, name: str = "robot.urdf") -> Path:
    robot = load_spec_text(text, "x.yaml", rules=False).robot
    path = tmp / name
    path.write_text(render_package(robot, "specs/x.yaml")[f"urdf/{robot.name}.urdf"])
    return path


def pin_positions(
    pin, urdf: Path, values: dict[str, float], frames: list[str], use_mimic: bool
) -> dict[str, np.ndarray]:
    """Frame origins in the root frame by pinocchio; ``values`` by joint name (1-DOF joints;
    continuous joints as an angle). With ``use_mimic`` pinocchio computes the followers."""
    model = pin.buildModelFromUrdf(str(urdf), mimic=use_mimic)
    data = model.createData()
    q = pin.neutral(model)
    for jid in range(1, model.njoints):
        name, j = model.names[jid], model.joints[jid]
        if name not in values or j.nq == 0:
            continue
        if j.nq == 1:
            q[j.idx_q] = values[name]
        elif j.nq == 2:  # continuous: (cos, sin)
            q[j.idx_q], q[j.idx_q + 1] = math.cos(values[name]), math.sin(values[name])
    pin.framesForwardKinematics(model, data, q)
    return {f: data.oMf[model.getFrameId(f)].homogeneous for f in frames}


def ydf_positions(urdf: Path, leaders: dict[str, float], frames: list[str], root: str) -> dict[str, np.ndarray]:
    """yourdfpy sets the mimic joints itself from the actuated joints."""
    u = yourdfpy.URDF.load(str(urdf), load_meshes=False, build_collision_scene_graph=False)
    u.update_cfg({n: leaders.get(n, 0.0) for n in u.actuated_joint_names})
    return {f: u.get_transform(f, root) for f in frames}


# --- the gripper fixture --------------------------------------------------------------


def test_fixture_poses_are_what_pinocchio_and_yourdfpy_measure(pin, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    loaded = load_spec(FIXTURE)
    urdf = urdf_of(TEXT, tmp_path)
    for kp in loaded.robot.known_poses:
        leaders = dict(kp.joints)
        frames = [fm.frame for fm in kp.frames]
        theirs = pin_positions(pin, urdf, leaders, frames, use_mimic=True)
        ydf = ydf_positions(urdf, leaders, frames, "base_link")
        for fm in kp.frames:
            # the fixture's numbers are the oracles' numbers (so the poses test below is fair)
            np.testing.assert_allclose(theirs[fm.frame][:3, 3], fm.xyz, atol=1e-12, err_msg=kp.name)
            np.testing.assert_allclose(ydf[fm.frame], theirs[fm.frame], atol=1e-12, err_msg=kp.name)


def test_fixture_known_poses_pass_with_the_follower_moved() -> None:
    rows = evaluate(load_spec(FIXTURE).robot)
    assert len(rows) == 4 and all(r.ok for r in rows)
    # exact, not merely within the 0.5 mm tolerance: a follower left at zero is 10 mm off
    assert max(r.worst for r in rows) < 1e-12


def test_poses_and_validate_cli_pass(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", str(FIXTURE)]) == 0
    capsys.readouterr()
    assert main(["poses", str(FIXTURE), "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert len(doc["poses"]) == 4 and all(p["ok"] for p in doc["poses"])


def _open_pose_with(value: str) -> str:
    return plant(
        "joints: {finger_left_joint: 40 mm}", f"joints: {{finger_left_joint: 40 mm, {FOLLOWER}: {value}}}", TEXT
    )


def test_pose_contradicting_the_mimic_is_an_input_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = _open_pose_with("40 mm")  # the leader puts it at -1 * 40 mm - 10 mm = -50 mm
    spec = tmp_path / "gripper.yaml"
    spec.write_text(text)
    assert main(["validate", str(spec)]) == 2
    err = capsys.readouterr().err
    lines = [x for x in err.splitlines() if "POSE020" in x]
    assert len(lines) == 1, err
    assert lines[0].startswith(f"{spec}:{line_of(text, '- name: open')}:")
    assert "'finger_right_joint' to 0.04 m" in lines[0] and "at -0.05 m" in lines[0]
    assert "hint:" in err and "Traceback" not in err


def test_pose_setting_the_follower_where_the_leader_puts_it_is_info(capsys: pytest.CaptureFixture[str]) -> None:
    loaded = load_spec_text(_open_pose_with("-50 mm"), "gripper.yaml")
    [info] = [f for f in loaded.findings if f.code.startswith("POSE02")]
    assert (info.code, info.severity, info.subject) == ("POSE021", "info", "pose:open")
    assert all(r.ok for r in evaluate(loaded.robot))


def test_pose_contradiction_by_an_unset_leader() -> None:
    # 'closed' does not set the leader: it is at zero, so the follower is at the offset, -10 mm
    text = plant("  - name: closed\n    joints: {}", "  - name: closed\n    joints: {finger_right_joint: 0 mm}", TEXT)
    with pytest.raises(Exception) as exc:
        load_spec_text(text, "gripper.yaml")
    [f] = [f for f in exc.value.findings if f.code == "POSE020"]  # type: ignore[attr-defined]
    assert "not set by the pose" in f.message and "-0.01 m" in f.message


def test_leader_driving_the_follower_outside_its_limits() -> None:
    text = plant("limit: {lower: -50 mm, upper: -10 mm", "limit: {lower: -45 mm, upper: -10 mm", TEXT)
    with pytest.raises(Exception) as exc:
        load_spec_text(text, "gripper.yaml")
    found = [(f.code, f.subject) for f in exc.value.findings if f.blocks]  # type: ignore[attr-defined]
    assert found == [("POSE022", "pose:open")]  # 40 mm open puts the follower at -50 mm


def test_validate_on_unchanged_main_would_have_failed_the_measured_gripper() -> None:
    # the measured pose that is right must not be explained away by the tolerance:
    # with the follower at zero, 'closed' is 10 mm off (the offset) and 'open' 50 mm
    robot = load_spec(FIXTURE).robot
    frozen = kinematics.forward(robot, {})
    assert np.allclose(frozen["finger_right_tip"][:3, 3], (0.05, -0.015, 0.1), atol=1e-12)
    naive = np.eye(4)
    for j in robot.path_to_root("finger_right_tip"):
        naive = naive @ kinematics.joint_transform(j, 0.0)
    assert abs(naive[1, 3] - frozen["finger_right_tip"][1, 3]) == pytest.approx(0.010, abs=1e-12)


# --- cycles and dangling leaders ------------------------------------------------------


def test_mimic_of_a_missing_joint_is_an_input_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = plant("mimic: {joint: finger_left_joint", "mimic: {joint: finger_middle_joint", TEXT)
    spec = tmp_path / "gripper.yaml"
    spec.write_text(text)
    assert main(["validate", str(spec)]) == 2
    err = capsys.readouterr().err
    assert f"{spec}:{line_of(text, '- name: finger_right_joint')}:" in err and "JOINT007" in err
    assert "finger_middle_joint" in err and "Traceback" not in err


def _cycle_urdf() -> str:
    joints = "".join(
        f'<joint name="{n}" type="prismatic"><parent link="base"/><child link="{c}"/><axis xyz="0 1 0"/>'
        f'<limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="{m}" offset="0.5"/></joint>'
        for n, c, m in (("a", "la", "b"), ("b", "lb", "a"), ("c", "lc", "a"))
    )
    return f'<robot name="r"><link name="base"/><link name="la"/><link name="lb"/><link name="lc"/>{joints}</robot>'


def test_a_mimic_cycle_drives_nothing_and_is_reported(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    robot, _ = read_urdf_text(_cycle_urdf().encode(), "cycle.urdf")
    found = mimic.problems(robot)
    assert [p.joint.name for p in found] == ["a", "b", "c"]  # c hangs from the cycle
    assert "cycle" in found[0].message
    assert mimic.resolve(robot, {"a": 0.25}) == {"a": 0.25}  # no relation: nothing invented, no loop
    assert kinematics.forward(robot)["la"][1, 3] == 0.0
    path = tmp_path / "cycle.urdf"
    path.write_text(_cycle_urdf())
    assert main(["audit", str(path)]) == 1
    out = capsys.readouterr()
    assert "JOINT007" in out.out + out.err and "cycle" in out.out + out.err and "Traceback" not in out.err


# --- frames and the tf scenario ---------------------------------------------------------


def test_frames_says_the_follower_is_driven_by_its_leader(capsys: pytest.CaptureFixture[str]) -> None:
    robot = load_spec(FIXTURE).robot
    by_child = {e.child: e for e in edges(robot)}
    follower, leader = by_child["finger_right_link"], by_child["finger_left_link"]
    # robot_state_publisher publishes a mimic joint on /tf from its leader's /joint_states
    assert (follower.topic, follower.static, follower.joint) == ("/tf", False, FOLLOWER)
    assert follower.via.startswith(f"mimics {LEADER} (q = -1 * q({LEADER}) - 0.01 m)")
    assert follower.via.endswith(leader.via)
    assert main(["frames", str(FIXTURE), "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    [row] = [r for r in doc["frames"] if r["child"] == "finger_right_link"]
    assert "mimics finger_left_joint" in row["fed_by"]


def test_tf_scenario_moves_the_follower_as_the_oracle_does(tmp_path: Path) -> None:
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    from descgen.commands.tf import scenario

    robot = load_spec(FIXTURE).robot
    bag = tmp_path / "rec"
    scenario.write(robot, bag, (), duration=1.0)
    urdf = urdf_of(TEXT, tmp_path)
    u = yourdfpy.URDF.load(str(urdf), load_meshes=False, build_collision_scene_graph=False)
    states: dict[int, dict[str, float]] = {}
    tfs: dict[int, np.ndarray] = {}
    with AnyReader([bag], default_typestore=get_typestore(Stores.ROS2_JAZZY)) as reader:
        for conn, _, raw in reader.messages([c for c in reader.connections if c.topic in ("/joint_states", "/tf")]):
            msg = reader.deserialize(raw, conn.msgtype)
            if conn.topic == "/joint_states":
                ns = msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec
                states[ns] = dict(zip(msg.name, (float(p) for p in msg.position), strict=True))
                continue
            for t in msg.transforms:
                if t.child_frame_id == "finger_right_link":
                    ns = t.header.stamp.sec * 10**9 + t.header.stamp.nanosec
                    tr, r = t.transform.translation, t.transform.rotation
                    m = np.eye(4)
                    m[:3, :3] = _rot(r.x, r.y, r.z, r.w)
                    m[:3, 3] = (tr.x, tr.y, tr.z)
                    tfs[ns] = m
    assert len(tfs) == 100
    stamps = sorted(tfs)
    leader_values = {states[ns][LEADER] for ns in stamps}
    assert len(leader_values) > 50  # the leader really moves, so the check below means something
    for ns in stamps[::20]:
        lead = states[ns][LEADER]
        assert states[ns][FOLLOWER] == pytest.approx(-lead - 0.010, abs=1e-12)  # what GenericSystem publishes
        u.update_cfg({n: (lead if n == LEADER else states[ns].get(n, 0.0)) for n in u.actuated_joint_names})
        np.testing.assert_allclose(tfs[ns], u.get_transform("finger_right_link", "palm_link"), atol=1e-9)


def _rot(x: float, y: float, z: float, w: float) -> np.ndarray:
    """Quaternion to rotation matrix (the textbook formula)."""
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


# --- random trees with mimic chains -----------------------------------------------------

TYPES = ("revolute", "prismatic", "continuous", "fixed")


@st.composite
def mimic_tree(draw: st.DrawFn) -> tuple[str, dict[str, float], dict[str, tuple[str, float, float]]]:
    """A random tree whose revolute/prismatic joints may mimic any earlier-listed or later
    1-DOF joint (acyclic by a random driving order): multipliers of either sign, offsets,
    chains of up to three followers. Returns the spec, the drivers' values and the mimics."""
    n = draw(st.integers(min_value=3, max_value=9))
    coord = st.floats(min_value=-0.5, max_value=0.5, allow_nan=False)
    angle = st.floats(min_value=-math.pi, max_value=math.pi, allow_nan=False)
    types = [draw(st.sampled_from(TYPES)) for _ in range(1, n)]
    one_dof = [i for i, t in enumerate(types, start=1) if t != "fixed"]
    rank = {i: r for r, i in enumerate(draw(st.permutations(one_dof)))}  # mimic only lower ranks: acyclic
    mimics: dict[str, tuple[str, float, float]] = {}
    values: dict[str, float] = {}
    lines = ["name: random", "links:"] + [f"  - name: l{i}" for i in range(n)] + ["joints:"]
    for i, jtype in enumerate(types, start=1):
        parent = draw(st.integers(min_value=0, max_value=i - 1))
        xyz = [draw(coord) for _ in range(3)]
        rpy = [draw(angle) for _ in range(3)]
        lines += [f"  - name: j{i}", f"    type: {jtype}", f"    parent: l{parent}", f"    child: l{i}"]
        lines.append(
            "    origin: {xyz: ["
            + ", ".join(f"{v!r} m" for v in xyz)
            + "], rpy: ["
            + ", ".join(f"{v!r} rad" for v in rpy)
            + "]}"
        )
        if jtype == "fixed":
            continue
        raw = np.array([draw(st.floats(min_value=-1, max_value=1, allow_nan=False)) for _ in range(3)])
        axis = raw / np.linalg.norm(raw) if np.linalg.norm(raw) >= 0.1 else np.array([0.0, 0.0, 1.0])
        lines.append("    axis: [" + ", ".join(repr(float(c)) for c in axis) + "]")
        unit = "m" if jtype == "prismatic" else "rad"
        if jtype == "prismatic":
            lines.append("    limit: {lower: -5 m, upper: 5 m, effort: 10 N, velocity: 1 m/s}")
        elif jtype == "revolute":
            lines.append("    limit: {lower: -12 rad, upper: 12 rad, effort: 10 N*m, velocity: 1 rad/s}")
        leaders = [k for k in one_dof if rank[k] < rank[i]]
        if jtype != "continuous" and leaders and draw(st.sampled_from((True, True, False))):  # mostly followers
            lead = draw(st.sampled_from(leaders))
            mult = draw(st.sampled_from([-2.5, -1.0, -0.5, 0.5, 1.0, 1.7]))
            off = draw(st.floats(min_value=-0.3, max_value=0.3, allow_nan=False))
            mimics[f"j{i}"] = (f"j{lead}", mult, off)
            lines.append(f"    mimic: {{joint: j{lead}, multiplier: {mult!r}, offset: {off!r} {unit}}}")
        else:
            values[f"j{i}"] = draw(st.floats(min_value=-2, max_value=2, allow_nan=False))
    return "\n".join(lines) + "\n", values, mimics


def expand(values: dict[str, float], mimics: dict[str, tuple[str, float, float]]) -> dict[str, float]:
    """The definition, by hand: q_f = m * q_leader + o, leaders first (recursively)."""
    out = dict(values)

    def q(name: str) -> float:
        if name not in out:
            lead, m, o = mimics[name]
            out[name] = m * q(lead) + o
        return out[name]

    for name in mimics:
        q(name)
    return out


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mimic_tree())
def test_random_mimic_trees_agree_with_pinocchio_and_yourdfpy(  # type: ignore[no-untyped-def]
    pin,
    tmp_path_factory: pytest.TempPathFactory,
    case: tuple[str, dict[str, float], dict[str, tuple[str, float, float]]],
) -> None:
    text, values, mimics = case
    robot = load_spec_text(text, "random.yaml", rules=False).robot  # JOINT007 objects to chains
    ours = kinematics.forward(robot, values)
    urdf = urdf_of(text, tmp_path_factory.mktemp("tree"))
    links = [lk.name for lk in robot.links if lk.name != "l0"]
    # pinocchio without mimic, every follower expanded by hand from its leader
    theirs = pin_positions(pin, urdf, expand(values, mimics), links, use_mimic=False)
    for name in links:
        np.testing.assert_allclose(ours[name], theirs[name], atol=1e-9, rtol=0, err_msg=name)
    chains = any(lead in mimics for lead, _, _ in mimics.values())
    event(f"followers: {len(mimics)}, chains: {chains}")
    if chains:
        return  # pinocchio and yourdfpy do not follow a mimic of a mimic (JOINT007 says so)
    # yourdfpy (trimesh's scene graph) keeps the old transform for a change under ~1e-8: a joint
    # at 4.6e-9 rad stays at zero there (pinocchio above moves it), so such cases skip that oracle
    if all(v == 0 or abs(v) >= 1e-7 for v in values.values()):
        ydf = ydf_positions(urdf, values, links, "l0")
        for name in links:
            np.testing.assert_allclose(ours[name], ydf[name], atol=1e-9, rtol=0, err_msg=name)
    if all(robot.joint(lead).type != "continuous" for lead, _, _ in mimics.values()):  # type: ignore[union-attr]
        try:
            native = pin_positions(pin, urdf, values, links, use_mimic=True)  # pinocchio's own mimic joints
        except ValueError as exc:  # pinocchio needs each leader before its follower in its tree walk
            assert "not in the kinematic tree" in str(exc)
            event("pinocchio's own mimic: leader after follower")
            return
        event("pinocchio's own mimic compared")
        for name in links:
            np.testing.assert_allclose(ours[name], native[name], atol=1e-9, rtol=0, err_msg=name)


def test_chains_resolve_leader_first() -> None:
    # c mimics b mimics a, listed follower first: by hand c = 2 * (-0.5 * a + 0.1) - 0.3
    urdf = "".join(
        f'<joint name="{n}" type="revolute"><parent link="base"/><child link="l{n}"/><axis xyz="0 0 1"/>'
        f'<limit lower="-9" upper="9" effort="1" velocity="1"/>{m}</joint>'
        for n, m in (
            ("c", '<mimic joint="b" multiplier="2" offset="-0.3"/>'),
            ("b", '<mimic joint="a" multiplier="-0.5" offset="0.1"/>'),
            ("a", ""),
        )
    )
    text = f'<robot name="r"><link name="base"/><link name="la"/><link name="lb"/><link name="lc"/>{urdf}</robot>'
    robot, _ = read_urdf_text(text.encode(), "chain.urdf")
    assert mimic.resolve(robot, {"a": 0.8}) == pytest.approx({"a": 0.8, "b": -0.3, "c": -0.9})
    rel = mimic.relation(robot, "c")
    assert rel is not None and (rel.leader, rel.direct) == ("a", "b")


def test_a_mimic_cycle_in_a_spec_is_an_input_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = plant(
        "    limit: {lower: 0 mm, upper: 40 mm, velocity: 50 mm/s, effort: 20 N}\n",
        "    limit: {lower: 0 mm, upper: 40 mm, velocity: 50 mm/s, effort: 20 N}\n"
        f"    mimic: {{joint: {FOLLOWER}, multiplier: -1, offset: -10 mm}}\n",
        TEXT,
    )
    spec = tmp_path / "gripper.yaml"
    spec.write_text(text)
    assert main(["validate", str(spec)]) == 2
    err = capsys.readouterr().err
    cycle = [x for x in err.splitlines() if "JOINT007" in x]
    assert len(cycle) == 2 and all("mimic cycle" in x for x in cycle), err
    assert cycle[0].startswith(f"{spec}:{line_of(text, '- name: finger_left_joint')}:")
    assert cycle[1].startswith(f"{spec}:{line_of(text, '- name: finger_right_joint')}:")
    assert "Traceback" not in err
