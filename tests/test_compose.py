"""A spec's ``compose:`` (descgen/spec/compose.py; docs/multi-robot.md): two copies of the example
robot mounted on a cell floor behind ``left_`` and ``right_``.

Oracles: lxml counts of the committed example URDF (names and joints, written with the prefixes by
hand), yourdfpy's forward kinematics of the committed URDF and of the composed one (a mounted
frame sits where the example puts it, moved by the mount's offset, a hand-written vector).
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml
import yourdfpy
from lxml import etree

from tests.helpers import ROOT, cli

EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
COMMITTED = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"

CELL = """\
name: warehouse_cell
description: two WA-1 arms on one floor
links:
  - name: world
  - name: cell_floor
    visual:
      - geometry: {box: {size: [4 m, 4 m, 10 mm]}}
    collision:
      - geometry: {box: {size: [4 m, 4 m, 10 mm]}}
joints:
  - name: floor_joint
    type: fixed
    parent: world
    child: cell_floor
compose:
  - spec: warehouse_arm.yaml
    prefix: left_
    parent: cell_floor
    origin: {xyz: [0, 1 m, 5 mm]}
  - spec: warehouse_arm.yaml
    prefix: right_
    parent: cell_floor
    origin: {xyz: [0, -1 m, 5 mm]}
"""


def _project(root: Path, cell: str = CELL) -> Path:
    shutil.copytree(EXAMPLE.parent, root / "specs")
    spec = root / "specs" / "cell.yaml"
    spec.write_text(cell)
    return spec


@pytest.fixture(scope="module")
def cell(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("cell")
    spec = _project(root)
    r = cli("generate", spec)
    assert r.returncode == 0, r.stderr[-3000:]
    assert "SPEC145" in r.stderr  # each base's odometry tf turned off, said so
    r = cli("check", spec)
    assert r.returncode == 0, r.stderr[-3000:]
    return root / "generated" / "warehouse_cell_description"


def test_both_copies_are_there_behind_their_prefixes(cell: Path) -> None:
    example = etree.parse(str(COMMITTED)).getroot()
    links = [e.get("name") for e in example.findall("link")]
    joints = [e.get("name") for e in example.findall("joint")]
    urdf = etree.parse(str(cell / "urdf" / "warehouse_cell.urdf")).getroot()
    got_links = {e.get("name") for e in urdf.findall("link")}
    got_joints = {e.get("name") for e in urdf.findall("joint")}
    assert got_links == {"world", "cell_floor", *(f"left_{n}" for n in links), *(f"right_{n}" for n in links)}
    mounts = {"left_base_footprint_mount_joint", "right_base_footprint_mount_joint"}
    assert got_joints == {"floor_joint", *mounts, *(f"left_{n}" for n in joints), *(f"right_{n}" for n in joints)}
    blocks = urdf.findall("ros2_control")
    assert [b.get("name") for b in blocks] == ["left_WarehouseArmSystem", "right_WarehouseArmSystem"]
    for b, prefix in zip(blocks, ("left_", "right_"), strict=True):
        assert all(j.get("name").startswith(prefix) for j in b.findall("joint"))


def test_each_mounted_frame_is_where_the_example_puts_it_moved_by_the_mount(cell: Path) -> None:
    example = yourdfpy.URDF.load(str(COMMITTED), build_scene_graph=True, load_meshes=False)
    composed = yourdfpy.URDF.load(str(cell / "urdf" / "warehouse_cell.urdf"), build_scene_graph=True, load_meshes=False)
    for frame in ("tool_link", "camera_optical_frame", "left_wheel_link"):
        base = example.get_transform(frame, "base_footprint")
        for prefix, offset in (("left_", (0.0, 1.0, 0.005)), ("right_", (0.0, -1.0, 0.005))):
            got = composed.get_transform(prefix + frame, "world")
            assert np.allclose(got[:3, :3], base[:3, :3], atol=1e-12)
            assert np.allclose(got[:3, 3], base[:3, 3] + np.array(offset), atol=1e-12)


def test_one_controller_manager_with_each_robots_controllers(cell: Path) -> None:
    doc = yaml.safe_load((cell / "config" / "ros2_controllers.yaml").read_text())
    cm = doc["controller_manager"]["ros__parameters"]
    names = [k for k in cm if k != "update_rate"]
    # one joint_state_broadcaster (the first robot's, no joint list) publishes every joint; the
    # second robot's would publish them all again, so composing leaves it out
    expected = ["left_joint_state_broadcaster", *(f"{p}{c}" for p in ("left_", "right_")
                for c in ("diff_drive_controller", "arm_controller"))]  # fmt: skip
    assert sorted(names) == sorted(expected)
    for p in ("left_", "right_"):
        arm = doc[f"{p}arm_controller"]["ros__parameters"]["joints"]
        assert arm and all(j.startswith(p) for j in arm)
        dd = doc[f"{p}diff_drive_controller"]["ros__parameters"]
        assert dd["enable_odom_tf"] is False  # the base is fixed to the floor now (SPEC145)


def test_the_generated_files_audit_clean(cell: Path) -> None:
    r = cli(
        "audit", cell / "urdf" / "warehouse_cell.urdf",
        "--srdf", cell / "srdf" / "warehouse_cell.srdf",
        "--controllers", cell / "config" / "ros2_controllers.yaml",
        "--format", "json",
    )  # fmt: skip
    errors = [f for f in json.loads(r.stdout)["findings"] if f["severity"] == "error"]
    assert r.returncode == 0 and errors == []


def test_the_evidence_page_lists_the_composition(cell: Path) -> None:
    r = cli("report", cell.parent.parent / "specs" / "cell.yaml")
    assert r.returncode == 0, r.stderr[-2000:]
    page = (cell / "evidence" / "README.md").read_text()
    assert (
        "| warehouse\\_arm | warehouse\\_arm.yaml | left\\_ | cell\\_floor | left\\_base\\_footprint\\_mount\\_joint |"
        in page
    )
    assert "| warehouse\\_arm | warehouse\\_arm.yaml | right\\_ | cell\\_floor |" in page
    assert "Verdict: FAIL" not in page


@pytest.mark.parametrize(
    ("edit", "code", "needle"),
    [
        (("spec: warehouse_arm.yaml\n    prefix: right_", "spec: ../../etc/passwd\n    prefix: right_"), "SPEC142",
         "leaves the project folder"),
        (("spec: warehouse_arm.yaml\n    prefix: right_", "spec: none.yaml\n    prefix: right_"), "SPEC142",
         "is not a file"),
        (("spec: warehouse_arm.yaml\n    prefix: right_", "spec: cell.yaml\n    prefix: right_"), "SPEC142",
         "a cycle"),
        (("prefix: right_\n    parent: cell_floor", "prefix: right_\n    parent: ceiling"), "SPEC143",
         "'ceiling' is not a frame of warehouse_cell"),
        (("prefix: right_", "prefix: left_"), "SPEC144", "is already a link here"),
        (("spec: warehouse_arm.yaml\n    prefix: right_", "spec: world_arm.yaml\n    prefix: right_"), "SPEC144",
         "root is the global frame 'world'"),
        (("spec: warehouse_arm.yaml\n    prefix: right_", "spec: prefixed_arm.yaml\n    prefix: right_"), "SPEC144",
         "has its own prefix: 'p_'"),
        (("spec: warehouse_arm.yaml", "spec: mujoco_arm.yaml"), "SPEC144",  # both copies have it
         "both robots have a mujoco hardware variant"),
    ],
)  # fmt: skip
def test_a_composition_that_cannot_work_is_refused(
    tmp_path: Path, edit: tuple[str, str], code: str, needle: str
) -> None:
    old, new = edit
    assert old in CELL
    spec = _project(tmp_path, CELL.replace(old, new))
    arm = (spec.parent / "warehouse_arm.yaml").read_text()
    # the example hung from a 'world' root, and the example with a prefix of its own
    world = arm.replace("links:\n", "links:\n  - name: world\n", 1).replace(
        "joints:\n", "joints:\n  - {name: world_joint, type: fixed, parent: world, child: base_footprint}\n", 1
    )
    (spec.parent / "world_arm.yaml").write_text(world)
    anchor = "        params: {device: /dev/ttyACM0, baud_rate: 115200}\n"
    (spec.parent / "mujoco_arm.yaml").write_text(arm.replace(anchor, anchor + "      mujoco: {}\n", 1))
    (spec.parent / "prefixed_arm.yaml").write_text(
        arm.replace("\nname: warehouse_arm\n", "\nname: warehouse_arm\nprefix: p_\n", 1)
    )
    r = cli("validate", spec)
    assert r.returncode == 2
    assert any(f"error[{code}]" in line and needle in line for line in r.stderr.splitlines()), r.stderr[-3000:]


def test_a_composed_spec_change_makes_the_cell_stale(cell: Path, tmp_path: Path) -> None:
    root = tmp_path / "p"
    shutil.copytree(cell.parent.parent, root)
    arm = root / "specs" / "warehouse_arm.yaml"
    arm.write_text(arm.read_text().replace("WA-1 warehouse mobile manipulator", "WA-2 warehouse mobile manipulator"))
    r = cli("check", root / "specs" / "cell.yaml")
    assert r.returncode == 1 and "GEN005" in r.stderr


ARM = """\
name: tiny_arm
links:
  - name: base_link
    collision: [{geometry: {box: {size: [100 mm, 100 mm, 100 mm]}}}]
    inertial: {mass: 1 kg, from: collision}
  - name: arm_link
    collision: [{geometry: {box: {size: [50 mm, 50 mm, 300 mm]}}}]
    inertial: {mass: 500 g, from: collision}
joints:
  - name: arm_joint
    type: revolute
    parent: base_link
    child: arm_link
    origin: {xyz: [0, 0, 100 mm]}
    axis: [1, 1, 0]
    limit: {lower: -90 deg, upper: 90 deg, effort: 10 N*m, velocity: 1 rad/s}
waivers:
  - {code: SRDF003, subject: "disable_collisions:base_link:arm_link", reason: a two-name subject}
"""


def test_copies_side_by_side_are_no_mirrored_limbs_and_keep_their_waivers(tmp_path: Path) -> None:
    """left_arm_joint and right_arm_joint read as a mirrored pair (JOINT009) unless the rule knows
    they are two mounted copies; a waiver's every name goes behind the prefix."""
    (tmp_path / "specs").mkdir()
    (tmp_path / "specs" / "tiny_arm.yaml").write_text(ARM)
    cell = CELL.replace("warehouse_arm.yaml", "tiny_arm.yaml")
    (tmp_path / "specs" / "cell.yaml").write_text(cell)
    r = cli("validate", tmp_path / "specs" / "cell.yaml")
    assert "JOINT009" not in r.stderr, r.stderr[-2000:]
    from descgen.audit.spec import load_spec

    robot = load_spec(tmp_path / "specs" / "cell.yaml", rules=False).robot
    subjects = {w.subject for w in robot.waivers}
    assert subjects == {f"disable_collisions:{p}base_link:{p}arm_link" for p in ("left_", "right_")}
