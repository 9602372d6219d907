"""``descgen audit A B --together``: robots of one ROS graph (descgen/audit/together.py).

Expected findings are read off the fixtures by hand (tests/data/together/: each defect is planted
at the line named); the count oracle for two copies of the example robot is lxml's count of the
generated URDF's joints; the good pair is expanded by the real xacro with two prefixes.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import xacro
from lxml import etree

from tests.helpers import ROOT, cli

DATA = ROOT / "tests" / "data" / "together"
EXAMPLE_SPEC = ROOT / "specs" / "warehouse_arm.yaml"
EXAMPLE_URDF = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"
PREFIXED = ROOT / "tests" / "rules" / "NAME014" / "good.xacro"


def _graph(stdout: str) -> list[tuple[str, str, str, int]]:
    found = json.loads(stdout)["findings"]
    return [(f["code"], f["subject"], Path(f["file"]).name, f["line"]) for f in found if f["code"].startswith("GRAPH")]


def test_each_collision_of_a_base_and_an_arm_at_its_place(tmp_path: Path) -> None:
    for name in ("a.urdf", "b.urdf", "a.controllers.yaml", "b.controllers.yaml"):
        shutil.copy(DATA / name, tmp_path / name)
    r = cli(
        "audit", "a.urdf", "b.urdf", "--together", "--format", "json",
        "--controllers", "a.controllers.yaml", "--controllers", "b.controllers.yaml",
        cwd=tmp_path,
    )  # fmt: skip
    assert r.returncode == 1, r.stderr
    assert _graph(r.stdout) == [
        ("GRAPH001", "frame:base_link", "b.urdf", 14),  # B's base_wheel_joint re-parents A's base_link
        ("GRAPH002", "joint:base_wheel_joint", "b.urdf", 14),  # a moving joint of both
        ("GRAPH003", "ros2_control:base_footprint_joint", "b.urdf", 27),  # B's hardware claims A's joint
        ("GRAPH003", "controller:arm_controller", "b.controllers.yaml", 13),  # and B's controller names it
        ("GRAPH004", "frame:mount_link", "b.urdf", 6),  # B's root is A's mount_link: one tree
    ]


def test_alone_each_robot_has_none_of_them(tmp_path: Path) -> None:
    for name in ("a.urdf", "b.urdf"):
        r = cli("audit", str(DATA / name), "--format", "json", cwd=tmp_path)
        assert _graph(r.stdout) == []


def test_two_unprefixed_copies_collide_on_every_frame_and_moving_joint() -> None:
    root = etree.parse(str(EXAMPLE_URDF)).getroot()
    joints = root.findall("joint")
    moving = [j for j in joints if j.get("type") != "fixed"]
    r = cli("audit", EXAMPLE_SPEC, EXAMPLE_SPEC, "--together", "--format", "json")
    codes = [c for c, *_ in _graph(r.stdout)]
    assert codes.count("GRAPH001") == len(joints) > 0
    assert codes.count("GRAPH002") == len(moving) > 0
    assert "GRAPH003" not in codes  # each copy's controllers name its own joints
    assert r.returncode == 1


def test_two_prefixed_copies_share_a_graph_cleanly(tmp_path: Path) -> None:
    paths = []
    for prefix in ("left_", "right_"):
        doc = xacro.process_file(str(PREFIXED), mappings={"prefix": prefix})
        path = tmp_path / f"{prefix}cart.urdf"
        path.write_text(doc.toxml())
        paths.append(path)
    r = cli("audit", *paths, "--together", "--format", "json", cwd=tmp_path)
    assert _graph(r.stdout) == []  # both hang from 'world', which neither publishes
    alone = [cli("audit", p, "--format", "json", cwd=tmp_path).returncode for p in paths]
    assert r.returncode == max(alone)


def test_one_file_per_description_or_none(tmp_path: Path) -> None:
    a, b = DATA / "a.urdf", DATA / "b.urdf"
    r = cli("audit", a, b, "--together", "--controllers", DATA / "a.controllers.yaml")
    assert r.returncode == 2
    assert "error[GRAPH010]: --controllers is given 1 time(s) for 2 URDF or Xacro file(s)" in r.stderr
    r = cli("audit", a, "--controllers", DATA / "a.controllers.yaml", "--controllers", DATA / "b.controllers.yaml")
    assert r.returncode == 2
    assert "error[GRAPH010]: --controllers is given 2 times" in r.stderr
    r = cli("audit", a, b, "--together")  # no controllers at all: each robot as it is
    assert r.returncode == 1 and "GRAPH001" in r.stderr


def test_a_moveit_config_is_one_robots(tmp_path: Path) -> None:
    r = cli("audit", DATA / "a.urdf", DATA / "b.urdf", "--together", "--moveit-config", tmp_path)
    assert r.returncode == 2 and "error[GRAPH010]: --moveit-config is given with --together" in r.stderr


def test_two_specs_in_two_namespaces_share_no_joint_states(tmp_path: Path) -> None:
    """Frames still collide (one /tf for all), joints do not (each namespace its /joint_states)."""
    shutil.copytree(EXAMPLE_SPEC.parent, tmp_path / "specs")
    text = EXAMPLE_SPEC.read_text()
    moveit = text.index("\nmoveit:")
    end = text.index("\nknown_poses:")
    base = text[:moveit] + text[end:]  # the MoveIt package does not run in a namespace (SPEC148)
    for ns in ("a", "b"):
        (tmp_path / "specs" / f"{ns}.yaml").write_text(
            base.replace("\nname: warehouse_arm\n", f"\nname: warehouse_arm\nnamespace: {ns}\n", 1)
        )
    r = cli("audit", tmp_path / "specs" / "a.yaml", tmp_path / "specs" / "b.yaml", "--together", "--format", "json")
    codes = [c for c, *_ in _graph(r.stdout)]
    assert "GRAPH001" in codes and "GRAPH002" not in codes
