"""The MoveIt config package (issue 15): spec accelerations and ``moveit:``, the files of
``<robot>_moveit_config`` read back by independent parsers (yaml.safe_load, ast, lxml) and
compared with hand-computed values, and generate/check on the second package."""

from __future__ import annotations

import ast
import json
import math
import shutil
from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen.cli import main
from descgen.commands.generate import plan
from descgen.prove import moveit as proof
from descgen.render.moveit import yfloat

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
PKG = ROOT / "generated" / "warehouse_arm_moveit_config"
DESC = ROOT / "generated" / "warehouse_arm_description"
MINI = ROOT / "tests" / "data" / "moveit" / "mini_arm.yaml"
ARM_JOINTS = {"lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"}
# the functions of moveit_configs_utils/launches.py on jazzy (read there, not from our code)
UPSTREAM_LAUNCHES = {
    "generate_rsp_launch",
    "generate_moveit_rviz_launch",
    "generate_setup_assistant_launch",
    "generate_static_virtual_joint_tfs_launch",
    "generate_spawn_controllers_launch",
    "generate_warehouse_db_launch",
    "generate_move_group_launch",
    "generate_demo_launch",
}


def _load(rel: str, pkg: Path = PKG) -> object:
    return yaml.safe_load((pkg / rel).read_text(encoding="utf-8"))


def _floats(node: object) -> list[tuple[str, object]]:
    """Every number in a loaded YAML document that is not a float (bools aside)."""
    bad: list[tuple[str, object]] = []
    if isinstance(node, dict):
        for k, v in node.items():
            if isinstance(v, int) and not isinstance(v, bool):
                bad.append((str(k), v))
            bad += _floats(v)
    elif isinstance(node, list):
        for v in node:
            bad += _floats(v)
    return bad


# --- the committed example, read back ------------------------------------------------------------


def test_joint_limits_are_the_spec_values_in_si_and_floats() -> None:
    doc = _load("config/joint_limits.yaml")
    assert isinstance(doc, dict)
    limits = doc["joint_limits"]
    assert set(limits) == ARM_JOINTS
    # hand computation from specs/warehouse_arm.yaml (M15, M17, M19, M21 and the A1 choices)
    want = {
        "lift_joint": (0.10, 0.2),
        "shoulder_pan_joint": (30 * 2 * math.pi / 60, math.radians(360)),
        "shoulder_lift_joint": (math.radians(90), math.radians(180)),
        "elbow_joint": (math.radians(120), math.radians(240)),
    }
    for name, (vel, acc) in want.items():
        got = limits[name]
        assert got["has_velocity_limits"] is True and got["has_acceleration_limits"] is True
        assert got["max_velocity"] == pytest.approx(vel, rel=1e-15)
        assert got["max_acceleration"] == acc  # exact: converted once, written shortest round-trip
    assert doc["default_velocity_scaling_factor"] == 0.1
    assert doc["default_acceleration_scaling_factor"] == 0.1
    assert _floats(doc) == []


def test_every_number_in_the_moveit_yaml_is_a_float() -> None:
    for rel in ("joint_limits", "kinematics", "pilz_cartesian_limits", "initial_positions"):
        assert _floats(_load(f"config/{rel}.yaml")) == [], rel


def test_controllers_serve_the_arm_chain_with_action_ns() -> None:
    doc = _load("config/moveit_controllers.yaml")
    assert isinstance(doc, dict)
    assert doc["moveit_controller_manager"] == "moveit_simple_controller_manager/MoveItSimpleControllerManager"
    smcm = doc["moveit_simple_controller_manager"]
    assert smcm["controller_names"] == ["arm_controller"]
    arm = smcm["arm_controller"]
    assert arm["type"] == "FollowJointTrajectory"
    assert arm["action_ns"] == "follow_joint_trajectory"
    assert arm["default"] is True
    # the group's joints by an lxml walk of the URDF from tool_link up to arm_base_link
    urdf = etree.parse(str(DESC / "urdf" / "warehouse_arm.urdf"))
    parent_joint = {j.find("child").get("link"): j for j in urdf.getroot().findall("joint")}
    chain, link = [], "tool_link"
    while link != "arm_base_link":
        j = parent_joint[link]
        if j.get("type") != "fixed":
            chain.append(j.get("name"))
        link = j.find("parent").get("link")
    assert arm["joints"] == list(reversed(chain))
    # and they are the joints the ros2_control controller commands
    ros2 = _load("config/ros2_controllers.yaml")
    assert isinstance(ros2, dict)
    assert ros2["arm_controller"]["ros__parameters"]["joints"] == arm["joints"]


def test_initial_positions_are_the_ready_state() -> None:
    doc = _load("config/initial_positions.yaml")
    assert isinstance(doc, dict)
    # known pose 'ready': lift 150 mm, elbow -90 deg, the others 0 (collision_matrix.default_state)
    assert doc["initial_positions"] == {
        "lift_joint": 0.15,
        "shoulder_pan_joint": 0.0,
        "shoulder_lift_joint": 0.0,
        "elbow_joint": -math.pi / 2,
    }


def test_kinematics_and_pilz_limits() -> None:
    assert _load("config/kinematics.yaml") == {
        "arm": {
            "kinematics_solver": "kdl_kinematics_plugin/KDLKinematicsPlugin",
            "kinematics_solver_search_resolution": 0.005,
            "kinematics_solver_timeout": 0.005,
        }
    }
    assert _load("config/pilz_cartesian_limits.yaml") == {
        "cartesian_limits": {"max_trans_vel": 1.0, "max_trans_acc": 2.25, "max_trans_dec": -5.0, "max_rot_vel": 1.57}
    }


def test_launch_files_parse_and_call_moveit_configs_utils() -> None:
    launches = sorted((PKG / "launch").glob("*.launch.py"))
    names = {p.name.removesuffix(".launch.py") for p in launches}
    # demo.launch.py includes these by path (launches.py generate_demo_launch)
    assert {"demo", "rsp", "move_group", "moveit_rviz", "spawn_controllers", "warehouse_db"} <= names
    # the planar virtual joint is odometry's: no static identity publisher for it
    assert "static_virtual_joint_tfs" not in names
    for path in launches:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        imported = {
            a.name
            for n in ast.walk(tree)
            if isinstance(n, ast.ImportFrom) and n.module == "moveit_configs_utils.launches"
            for a in n.names
        }
        function = f"generate_{path.name.removesuffix('.launch.py')}_launch"
        assert imported == {function} and function in UPSTREAM_LAUNCHES
        calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call)]
        builder = [c for c in calls if isinstance(c.func, ast.Name) and c.func.id == "MoveItConfigsBuilder"]
        assert len(builder) == 1
        assert [ast.literal_eval(a) for a in builder[0].args] == ["warehouse_arm"]
        assert {k.arg: ast.literal_eval(k.value) for k in builder[0].keywords} == {
            "package_name": "warehouse_arm_moveit_config"
        }
        assert any(isinstance(c.func, ast.Attribute) and c.func.attr == "to_moveit_configs" for c in calls)
        assert any(isinstance(c.func, ast.Name) and c.func.id == function for c in calls)


def test_setup_assistant_points_at_the_description_and_srdf() -> None:
    doc = _load(".setup_assistant")
    assert isinstance(doc, dict)
    cfg = doc["moveit_setup_assistant_config"]
    assert cfg["urdf"]["package"] == "warehouse_arm_description"
    assert (DESC / cfg["urdf"]["relative_path"]).is_file()
    srdf = PKG / cfg["srdf"]["relative_path"]
    # the builder's own fallback name (config/<robot>.srdf), and the same SRDF as the description's
    assert srdf == PKG / "config" / "warehouse_arm.srdf"
    ours, theirs = etree.parse(str(srdf)).getroot(), etree.parse(str(DESC / "srdf" / "warehouse_arm.srdf")).getroot()
    assert etree.tostring(ours) == etree.tostring(theirs)
    # demo.launch.py runs ros2_control_node with this package's config/ros2_controllers.yaml
    assert _load("config/ros2_controllers.yaml") == _load("config/ros2_controllers.yaml", DESC)


def test_package_xml_depends_on_the_description() -> None:
    root = etree.parse(str(PKG / "package.xml")).getroot()
    assert root.get("format") == "3"
    assert root.findtext("name") == "warehouse_arm_moveit_config"
    deps = [e.text for e in root.iter("exec_depend")]
    assert "warehouse_arm_description" in deps and "moveit_configs_utils" in deps
    assert len(deps) == len(set(deps))
    cmake = (PKG / "CMakeLists.txt").read_text(encoding="utf-8")
    assert "install(DIRECTORY config launch" in cmake and "install(FILES .setup_assistant" in cmake


# --- generate and check on small specs -------------------------------------------------------------


def _spec(tmp_path: Path, text: str | None = None) -> Path:
    spec = tmp_path / "mini_arm.yaml"
    spec.write_text(text if text is not None else MINI.read_text(encoding="utf-8"), encoding="utf-8")
    return spec


def test_mini_arm_whole_number_acceleration_is_written_as_float(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert main(["generate", str(_spec(tmp_path)), "--out", str(out)]) == 0
    pkg = out / "mini_arm_moveit_config"
    text = (pkg / "config" / "joint_limits.yaml").read_text(encoding="utf-8")
    assert "max_acceleration: 1.0\n" in text
    doc = _load("config/joint_limits.yaml", pkg)
    assert isinstance(doc, dict)
    assert doc["joint_limits"]["j2"]["max_acceleration"] == 1.0
    assert doc["joint_limits"]["j1"]["max_acceleration"] == math.radians(120)
    assert doc["default_velocity_scaling_factor"] == 0.5
    assert _floats(doc) == []
    pilz = _load("config/pilz_cartesian_limits.yaml", pkg)
    assert pilz == {
        "cartesian_limits": {
            "max_trans_vel": 0.5,
            "max_trans_acc": 2.25,
            "max_trans_dec": -5.0,
            "max_rot_vel": math.radians(90),
        }
    }
    assert _load("config/initial_positions.yaml", pkg) == {"initial_positions": {"j1": math.radians(30), "j2": 0.01}}
    assert main(["check", str(tmp_path / "mini_arm.yaml"), "--out", str(out)]) == 0


def test_missing_acceleration_is_exit_2_at_the_joint_and_writes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = MINI.read_text(encoding="utf-8").replace(", acceleration: 120 deg/s^2", "")
    spec = _spec(tmp_path, text)
    line = text.splitlines().index("  - name: j1") + 1
    out = tmp_path / "out"
    assert main(["generate", str(spec), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{spec}:{line}:" in err and "error[SPEC110]" in err and "'j1'" in err
    assert "add 'acceleration: <value> deg/s^2'" in err
    assert "Traceback" not in err
    assert not out.exists() or not any(out.iterdir())


def test_without_moveit_no_package_is_written_or_required(tmp_path: Path) -> None:
    text = MINI.read_text(encoding="utf-8")
    text = text[: text.index("moveit:")]
    spec = _spec(tmp_path, text)
    out = tmp_path / "out"
    assert main(["generate", str(spec), "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["mini_arm_description"]
    assert main(["check", str(spec), "--out", str(out)]) == 0


def test_check_fails_on_a_hand_edited_joint_limits(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec, out = _spec(tmp_path), tmp_path / "out"
    assert main(["generate", str(spec), "--out", str(out)]) == 0
    target = out / "mini_arm_moveit_config" / "config" / "joint_limits.yaml"
    target.write_text(target.read_text(encoding="utf-8").replace("max_acceleration: 1.0", "max_acceleration: 9.0"))
    capsys.readouterr()
    assert main(["check", str(spec), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "GEN004" in err and "mini_arm_moveit_config/config/joint_limits.yaml" in err
    # generate refuses to overwrite the edit
    assert main(["generate", str(spec), "--out", str(out)]) == 1
    assert "max_acceleration: 9.0" in target.read_text(encoding="utf-8")


def test_check_fails_on_a_missing_moveit_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec, out = _spec(tmp_path), tmp_path / "out"
    assert main(["generate", str(spec), "--out", str(out)]) == 0
    (out / "mini_arm_moveit_config" / "config" / "moveit_controllers.yaml").unlink()
    capsys.readouterr()
    assert main(["check", str(spec), "--out", str(out)]) == 1
    assert "GEN006" in capsys.readouterr().err


def test_proof_catches_an_integer_limit_and_a_wrong_value(tmp_path: Path) -> None:
    p = plan(_spec(tmp_path), tmp_path / "out")
    files = dict(p.moveit_files)
    assert p.moveit_dir is not None
    assert proof.check(files, p.robot, p.moveit_dir) == []
    files["config/joint_limits.yaml"] = files["config/joint_limits.yaml"].replace(
        "max_acceleration: 1.0", "max_acceleration: 1"
    )
    found = proof.check(files, p.robot, p.moveit_dir)
    # the proof (GEN091) and the MOVEIT audit any MoveIt config gets (MOVEIT003), the latter
    # pointed at the package's own file, not at the scratch copy it audited
    assert sorted(f.code for f in found) == ["GEN091", "MOVEIT003"]
    audit = next(f for f in found if f.code == "MOVEIT003")
    assert audit.where.file == str(p.moveit_dir / "config" / "joint_limits.yaml")
    assert audit.where.line > 0
    files["config/joint_limits.yaml"] = files["config/joint_limits.yaml"].replace(
        "max_acceleration: 1\n", "max_acceleration: 2.0\n"
    )
    assert [f.code for f in proof.check(files, p.robot, p.moveit_dir)] == ["GEN090"]
    files = dict(p.moveit_files)
    files["config/moveit_controllers.yaml"] = files["config/moveit_controllers.yaml"].replace(
        "    action_ns: follow_joint_trajectory\n", ""
    )
    assert sorted(f.code for f in proof.check(files, p.robot, p.moveit_dir)) == ["GEN090", "MOVEIT007"]
    files = dict(p.moveit_files)
    files["launch/demo.launch.py"] += "def (:\n"
    assert [f.code for f in proof.check(files, p.robot, p.moveit_dir)] == ["GEN092"]


def test_group_without_controller_is_a_warning(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = MINI.read_text(encoding="utf-8").replace("    - name: arm_controller\n", "    - name: other_controller\n")
    text = text.replace(
        "joint_trajectory_controller/JointTrajectoryController", "forward_command_controller/ForwardCommandController"
    )
    text = text.replace(
        "params: {joints: [j1, j2], command_interfaces: [position], state_interfaces: [position, velocity]}",
        "params: {joints: [j1, j2], interface_name: position}",
    )
    assert main(["validate", str(_spec(tmp_path, text))]) == 0
    err = capsys.readouterr().err
    assert "warning[SPEC114]" in err and "'arm'" in err


@pytest.mark.parametrize(
    ("old", "new", "code"),
    [
        ("acceleration: 120 deg/s^2", "acceleration: 2 m/s^2", "UNIT003"),  # a linear unit on a revolute joint
        ("acceleration: 1 m/s^2", "acceleration: 1 m/s", "UNIT003"),
        ("acceleration: 1 m/s^2", "acceleration: -1 m/s^2", "SPEC116"),
        ("initial_state: home", "initial_state: nowhere", "SPEC113"),
        ("  initial_state: home\n", "  initial_state: home\n  kinematics: {hand: {}}\n", "SPEC112"),
        ("default_velocity_scaling_factor: 0.5", "default_velocity_scaling_factor: 1.5", ""),
    ],
)
def test_bad_moveit_input_is_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], old: str, new: str, code: str
) -> None:
    text = MINI.read_text(encoding="utf-8")
    assert old in text
    assert main(["validate", str(_spec(tmp_path, text.replace(old, new)))]) == 2
    err = capsys.readouterr().err
    assert f"error[{code}" in err and "Traceback" not in err


def _renamed(joint: str) -> str:
    """The mini arm with joint j1 renamed everywhere, written by yaml.safe_dump."""
    doc = yaml.safe_load(MINI.read_text(encoding="utf-8"))
    doc["joints"][0]["name"] = joint
    doc["joints"][1]["parent"] = doc["joints"][0]["child"]
    doc["ros2_control"]["joints"][0]["name"] = joint
    doc["ros2_control"]["controllers"][1]["params"]["joints"] = [joint, "j2"]
    state = doc["semantic"]["group_states"][0]["joints"]
    state[joint] = state.pop("j1")
    return yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)


def test_hostile_names_are_refused_or_escaped(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = MINI.read_text(encoding="utf-8")
    # a group or controller name with a quote or a line break is refused by the name pattern
    for old, new in (("{name: arm,", '{name: "arm\\"x",'), ("- name: arm_controller", '- name: "arm\\ncontroller"')):
        assert old in text
        assert main(["validate", str(_spec(tmp_path, text.replace(old, new)))]) == 2
        err = capsys.readouterr().err
        assert "error[SPEC050]" in err and "Traceback" not in err
    # a joint name ROS accepts that YAML would misread unquoted: escaped, read back as itself
    hostile = 'j1:"q"#x'
    spec, out = _spec(tmp_path, _renamed(hostile)), tmp_path / "out"
    assert main(["generate", str(spec), "--out", str(out)]) == 0, capsys.readouterr().err
    pkg = out / "mini_arm_moveit_config"
    limits = _load("config/joint_limits.yaml", pkg)
    assert isinstance(limits, dict) and set(limits["joint_limits"]) == {hostile, "j2"}
    ctrl = _load("config/moveit_controllers.yaml", pkg)
    assert isinstance(ctrl, dict)
    assert ctrl["moveit_simple_controller_manager"]["arm_controller"]["joints"] == [hostile, "j2"]
    initial = _load("config/initial_positions.yaml", pkg)
    assert isinstance(initial, dict) and set(initial["initial_positions"]) == {hostile, "j2"}


def test_yfloat_always_reads_back_as_the_same_float() -> None:
    for v in (1.0, 0.0, -0.0, 0.1, 1e-05, 1e16, -5.0, math.pi, 123456789.0):
        text = yfloat(v)
        back = yaml.safe_load(text)
        assert isinstance(back, float) and back == v, text


def test_schema_shows_acceleration_and_moveit(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["schema"]) == 0
    schema = json.loads(capsys.readouterr().out)
    defs = schema["$defs"]
    assert "acceleration" in defs["LimitSpec"]["properties"]
    assert "moveit" in schema["properties"]
    assert {"kinematics", "initial_state", "pilz_cartesian_limits"} <= set(defs["MoveItSpec"]["properties"])


def test_committed_example_is_what_generate_writes(tmp_path: Path) -> None:
    """The committed package equals a fresh render (check compares it too; this pins the layout)."""
    p = plan(EXAMPLE, ROOT / "generated")
    assert sorted(p.moveit_files) == sorted(str(f.relative_to(PKG)) for f in PKG.rglob("*") if f.is_file())
    for rel, text in p.moveit_files.items():
        assert (PKG / rel).read_text(encoding="utf-8") == text, rel
    shutil.rmtree(tmp_path, ignore_errors=True)


def test_initial_positions_without_a_state_are_moveits_defaults(tmp_path: Path) -> None:
    text = MINI.read_text(encoding="utf-8").replace("  initial_state: home\n", "")
    text = text.replace("lower: 0 mm, upper: 100 mm", "lower: 20 mm, upper: 100 mm").replace("j2: 10 mm", "j2: 30 mm")
    p = plan(_spec(tmp_path, text), tmp_path / "out")
    doc = yaml.safe_load(p.moveit_files["config/initial_positions.yaml"])
    # RevoluteJointModel::getVariableDefaultPositions: 0 if within bounds, else the middle
    assert doc == {"initial_positions": {"j1": 0.0, "j2": (0.02 + 0.1) / 2}}


def test_builder_finds_our_files_by_its_own_lookup_rules() -> None:
    """The file lookups of moveit_configs_utils (jazzy @4d84106, moveit_configs_builder.py),
    restated by hand: what scripts/moveit_load_check.py proved with the real builder, kept in CI.
    trajectory_execution() globs config/*_controllers.yaml and, with more than one match, takes
    the first of moveit, moveit2, <robot> (else RuntimeError); the default pipelines include
    Pilz, so pilz_cartesian_limits.yaml must exist (else ParameterBuilderFileNotFoundError); a
    config/*_planning.yaml would replace the default pipeline of that name; the YAML is read with
    yaml.FullLoader."""
    import re

    config = PKG / "config"
    names = [m.group(1) for f in config.iterdir() if (m := re.search(r"^(.*)_controllers.yaml$", f.name))]
    assert sorted(names) == ["moveit", "ros2"]
    chosen = next(n for n in ["moveit", "moveit2", "warehouse_arm"] if n in names)
    assert chosen == "moveit"
    assert (config / "pilz_cartesian_limits.yaml").is_file()
    assert not [f.name for f in config.iterdir() if re.search(r"^(.*)_planning.yaml$", f.name)]
    for f in sorted(config.glob("*.yaml")):
        text = f.read_text()
        assert yaml.load(text, Loader=yaml.FullLoader) == yaml.safe_load(text), f.name
    sa = yaml.safe_load((PKG / ".setup_assistant").read_text())["moveit_setup_assistant_config"]
    assert (DESC / sa["urdf"]["relative_path"]).is_file()
    assert (PKG / sa["srdf"]["relative_path"]).is_file()
    assert "xacro_args" not in sa["urdf"]  # the Xacro's defaults (hardware:=mock) are what the builder expands


# --- the demo's mock hardware starts at the initial state (config/<robot>.urdf.xacro) -------------


def _xacro(path: Path, packages: dict[str, Path], monkeypatch: pytest.MonkeyPatch, **args: str) -> etree._Element:
    """``path`` expanded by the xacro library itself (not descgen's sandbox), ``$(find)``
    answered from ``packages`` as ament_index would answer it in an install space."""
    import xacro
    import xacro.substitution_args as sa

    monkeypatch.setattr(sa, "_eval_find", lambda pkg: str(packages[pkg]))
    doc = xacro.process_file(str(path), mappings=dict(args))
    return etree.fromstring(doc.toxml().encode("utf-8"), etree.XMLParser(remove_blank_text=True, remove_comments=True))


def _initial_values(doc: etree._Element) -> dict[str, str]:
    """joint -> text of its position state's initial_value param, read with lxml."""
    out: dict[str, str] = {}
    for j in doc.iterfind("ros2_control/joint"):
        for e in j.iterfind("state_interface[@name='position']/param[@name='initial_value']"):
            out[j.get("name", "")] = e.text or ""
    return out


def _canonical(doc: etree._Element) -> bytes:
    return etree.tostring(doc, method="c14n")


def test_builder_xacro_starts_the_mock_hardware_at_the_ready_state(monkeypatch: pytest.MonkeyPatch) -> None:
    """What MoveItConfigsBuilder loads (config/<robot>.urdf.xacro exists, so it wins over
    .setup_assistant: moveit_configs_builder.py jazzy) expanded by xacro: the arm joints start at
    state 'ready' of specs/warehouse_arm.yaml (lift 150 mm, elbow -90 deg, the others 0), the
    wheels keep their spec value 0, and nothing else differs from the description's URDF."""
    wrapper = PKG / "config" / "warehouse_arm.urdf.xacro"
    packages = {"warehouse_arm_description": DESC, "warehouse_arm_moveit_config": PKG}
    doc = _xacro(wrapper, packages, monkeypatch)
    got = {k: float(v) for k, v in _initial_values(doc).items()}
    assert got == {
        "left_wheel_joint": 0.0,
        "right_wheel_joint": 0.0,
        "lift_joint": 0.15,
        "shoulder_pan_joint": 0.0,
        "shoulder_lift_joint": 0.0,
        "elbow_joint": -math.pi / 2,
    }
    plain = etree.parse(str(DESC / "urdf" / "warehouse_arm.urdf"), etree.XMLParser(remove_blank_text=True))
    urdf = plain.getroot()
    etree.strip_tags(urdf, etree.Comment)
    for j in doc.iterfind("ros2_control/joint"):
        for e in j.iterfind("state_interface[@name='position']/param[@name='initial_value']"):
            e.text = "0"  # the one intended difference, undone
    assert _canonical(doc) == _canonical(urdf)


def test_description_xacro_alone_keeps_the_spec_initial_values(monkeypatch: pytest.MonkeyPatch) -> None:
    """The plain description package does not change: without initial_positions_file the
    ros2_control Xacro gives the spec's initial values (0), byte-equal to the committed URDF."""
    xacro_file = DESC / "urdf" / "warehouse_arm.urdf.xacro"
    doc = _xacro(xacro_file, {"warehouse_arm_description": DESC}, monkeypatch)
    assert set(_initial_values(doc).values()) == {"0"}
    urdf = etree.parse(str(DESC / "urdf" / "warehouse_arm.urdf"), etree.XMLParser(remove_blank_text=True)).getroot()
    etree.strip_tags(urdf, etree.Comment)
    assert _canonical(doc) == _canonical(urdf)
    # and the arg works on its own: a team's own file (a joint it does not name keeps 0)
    assert "initial_positions_file" in xacro_file.with_name("warehouse_arm.ros2_control.xacro").read_text()


def test_hostile_joint_name_reaches_the_mock_start_intact(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A joint name with a quote, a backslash and braces (all legal for ROS; '}' would end
    xacro's ${}) is looked up as itself: the mock hardware starts it at state 'home' (30 deg)."""
    hostile = "j1'}{\\x"
    spec, out = _spec(tmp_path, _renamed(hostile)), tmp_path / "out"
    assert main(["generate", str(spec), "--out", str(out)]) == 0
    packages = {
        "mini_arm_description": out / "mini_arm_description",
        "mini_arm_moveit_config": out / "mini_arm_moveit_config",
    }
    doc = _xacro(out / "mini_arm_moveit_config" / "config" / "mini_arm.urdf.xacro", packages, monkeypatch)
    got = {k: float(v) for k, v in _initial_values(doc).items()}
    assert got == {hostile: math.radians(30), "j2": 0.01}


def test_check_refuses_a_template_that_drops_the_initial_positions(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A team's override of the ros2_control Xacro that writes fixed initial values: the builder
    would start the demo at 0, so generate stops with GEN093 at the MoveIt package's Xacro."""
    templates = tmp_path / "templates"
    templates.mkdir()
    source = (ROOT / "descgen" / "templates" / "robot.ros2_control.xacro.j2").read_text(encoding="utf-8")
    assert "{% set initial_from_file = true %}" in source
    (templates / "robot.ros2_control.xacro.j2").write_text(source.replace("{% set initial_from_file = true %}", ""))
    out = tmp_path / "out"
    assert main(["generate", str(_spec(tmp_path)), "--out", str(out), "--templates", str(templates)]) != 0
    err = capsys.readouterr().err
    assert "error[GEN093]" in err and "mini_arm.urdf.xacro" in err and "j1" in err
    assert "Traceback" not in err
    assert not (out / "mini_arm_moveit_config").exists()
