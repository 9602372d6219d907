"""A spec's ``prefix:`` and ``namespace:`` (descgen/spec/prefix.py; docs/multi-robot.md).

Oracles: the real xacro expands the generated Xacro with ``prefix:=right_``; the names expected
are the committed example URDF's own names (lxml) with the prefix written before them by hand;
each planted slip (a frame, a controllers-YAML joint and a ros2_control joint without the
prefix) is located by hand in the file it was planted in.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
import xacro
from lxml import etree

from tests.helpers import ROOT, cli

EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
COMMITTED = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"


def _names(urdf: etree._Element) -> tuple[set[str], set[str]]:
    return {e.get("name") for e in urdf.findall("link")}, {e.get("name") for e in urdf.findall("joint")}


def _without_moveit(text: str) -> str:
    """The spec text without its top-level ``moveit:`` block."""
    lines = text.splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.startswith("moveit:"))
    end = next((i for i in range(start + 1, len(lines)) if lines[i][:1] not in (" ", "\n", "#")), len(lines))
    return "".join(lines[:start] + lines[end:])


@pytest.fixture(scope="module")
def package(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The example with ``prefix: left_`` and ``namespace: left``, generated (and checked)."""
    root = tmp_path_factory.mktemp("prefixed")
    shutil.copytree(EXAMPLE.parent, root / "specs")
    spec = root / "specs" / "warehouse_arm.yaml"
    text = spec.read_text(encoding="utf-8")
    text = text.replace("\nname: warehouse_arm\n", "\nname: warehouse_arm\nprefix: left_\nnamespace: left\n", 1)
    spec.write_text(_without_moveit(text))  # the MoveIt package does not run in a namespace yet (SPEC148)
    r = cli("generate", spec, "--out", root / "generated")
    assert r.returncode == 0, r.stderr[-3000:]
    r = cli("check", spec, "--out", root / "generated")
    assert r.returncode == 0, r.stderr[-3000:]
    return root / "generated" / "warehouse_arm_description"


def test_every_name_carries_the_prefix_and_nothing_else_changes(package: Path) -> None:
    links, joints = _names(etree.parse(str(COMMITTED)).getroot())
    urdf = etree.parse(str(package / "urdf" / "warehouse_arm.urdf")).getroot()
    assert _names(urdf) == ({f"left_{n}" for n in links}, {f"left_{n}" for n in joints})
    committed = etree.parse(str(COMMITTED)).getroot()
    for j in committed.findall("joint"):  # the same origins, parents and children, prefixed
        mine = urdf.find(f"joint[@name='left_{j.get('name')}']")
        assert mine is not None
        assert mine.find("parent").get("link") == "left_" + j.find("parent").get("link")
        assert mine.find("origin").attrib == j.find("origin").attrib
    rc = urdf.find("ros2_control")
    assert all(e.get("name").startswith("left_") for e in rc.findall("joint"))


def test_the_xacro_takes_another_prefix(package: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(package.parent))
    doc = xacro.process_file(str(package / "urdf" / "warehouse_arm.urdf.xacro"), mappings={"prefix": "right_"})
    right = etree.fromstring(doc.toxml().encode())
    links, joints = _names(etree.parse(str(COMMITTED)).getroot())
    assert _names(right) == ({f"right_{n}" for n in links}, {f"right_{n}" for n in joints})
    controlled = {e.get("name") for e in right.find("ros2_control").findall("joint")}
    assert controlled and all(n.startswith("right_") for n in controlled)
    # a block name is the hardware component's, one controller manager's own: left as the UR description leaves it
    assert right.find("ros2_control").get("name") == "WarehouseArmSystem"


def test_controllers_srdf_and_launch_use_the_prefix_and_the_namespace(package: Path) -> None:
    import yaml

    doc = yaml.safe_load((package / "config" / "ros2_controllers.yaml").read_text())
    assert set(doc) == {"/left/controller_manager", "/left/diff_drive_controller", "/left/arm_controller"}
    dd = doc["/left/diff_drive_controller"]["ros__parameters"]
    assert dd["left_wheel_names"] == ["left_left_wheel_joint"]
    assert (dd["odom_frame_id"], dd["base_frame_id"]) == ("left_odom", "left_base_footprint")
    arm = doc["/left/arm_controller"]["ros__parameters"]["joints"]
    assert arm and all(j.startswith("left_") for j in arm)
    srdf = etree.parse(str(package / "srdf" / "warehouse_arm.srdf")).getroot()
    named = [e.get("name") for e in srdf.iter("joint")] + [e.get("link1") for e in srdf.iter("disable_collisions")]
    assert named and all(n.startswith("left_") for n in named)
    launch = (package / "launch" / "control.launch.py").read_text()
    compile(launch, "control.launch.py", "exec")
    assert launch.count('namespace="/left"') == 2 + 3  # robot_state_publisher, ros2_control_node, 3 spawners (absolute)
    assert launch.count('"/left/controller_manager"') == 3


def test_the_generated_package_audits_clean_and_together_with_another_prefix(
    package: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(package.parent))
    xa = package / "urdf" / "warehouse_arm.urdf.xacro"
    left = tmp_path / "left.urdf"
    right = tmp_path / "right.urdf"
    left.write_text(xacro.process_file(str(xa)).toxml())
    right.write_text(xacro.process_file(str(xa), mappings={"prefix": "right_"}).toxml())
    pp = ("--package-path", str(package.parent))
    r = cli("audit", xa, *pp, "--controllers", package / "config" / "ros2_controllers.yaml", "--format", "json")
    codes = [f["code"] for f in json.loads(r.stdout)["findings"] if f["severity"] == "error"]
    assert "NAME014" not in codes and r.returncode == 0, codes
    r = cli("audit", left, right, "--together", *pp, "--format", "json")
    assert not [f for f in json.loads(r.stdout)["findings"] if f["code"].startswith("GRAPH")]
    r = cli("audit", left, left, "--together", *pp, "--format", "json")
    joints = len(etree.parse(str(left)).getroot().findall("joint"))
    assert [f["code"] for f in json.loads(r.stdout)["findings"]].count("GRAPH001") == joints


def test_each_name_left_without_the_prefix_is_found(package: Path, tmp_path: Path) -> None:
    copy = tmp_path / "warehouse_arm_description"
    shutil.copytree(package, copy)
    xa = copy / "urdf" / "warehouse_arm.urdf.xacro"
    text = xa.read_text()
    # a frame: the tool link's element and the joint that publishes it
    assert text.count('"$(arg prefix)tool_link"') == 3  # its <link>, its joint's <child>, the camera's <parent>
    xa.write_text(
        text.replace('<link name="$(arg prefix)tool_link"/>', '<link name="tool_link"/>')
        .replace('<child link="$(arg prefix)tool_link"/>', '<child link="tool_link"/>')
        .replace('<parent link="$(arg prefix)tool_link"/>', '<parent link="tool_link"/>')
    )
    rc = copy / "urdf" / "warehouse_arm.ros2_control.xacro"
    rc.write_text(rc.read_text().replace('<joint name="$(arg prefix)elbow_joint">', '<joint name="elbow_joint">', 1))
    cy = copy / "config" / "ros2_controllers.yaml"
    cy.write_text(cy.read_text().replace("left_shoulder_pan_joint,", "shoulder_pan_joint,", 1))
    r = cli(
        "audit", xa, "--package-path", tmp_path, "--controllers", cy, "--format", "json", "--no-waivers"
    )  # fmt: skip
    found = [(f["subject"], Path(f["file"]).name) for f in json.loads(r.stdout)["findings"] if f["code"] == "NAME014"]
    assert sorted(found) == sorted(
        [
            ("link:tool_link", "warehouse_arm.urdf.xacro"),
            ("ros2_control:elbow_joint", "warehouse_arm.ros2_control.xacro"),
            ("controller:arm_controller", "ros2_controllers.yaml"),
        ]
    )
    assert r.returncode == 1


@pytest.mark.parametrize(
    ("line", "code"),
    [("prefix: 'left-'", "SPEC140"), ("prefix: '1left_'", "SPEC140"), ("namespace: 'left//arm'", "SPEC141"),
     ("namespace: 'left/'", "SPEC141"), ("namespace: 'a b'", "SPEC141"),
     ("namespace: left", "SPEC148")],  # the example has moveit:
)  # fmt: skip
def test_a_prefix_or_namespace_that_is_no_name_is_refused(tmp_path: Path, line: str, code: str) -> None:
    shutil.copytree(EXAMPLE.parent, tmp_path / "specs")
    spec = tmp_path / "specs" / "warehouse_arm.yaml"
    spec.write_text(spec.read_text().replace("\nname: warehouse_arm\n", f"\nname: warehouse_arm\n{line}\n", 1))
    r = cli("validate", spec)
    assert r.returncode == 2 and f"error[{code}]" in r.stderr, r.stderr[-2000:]


CORPUS = ROOT / "tests" / "data" / "jazzy_corpus"
UR_ARGS = {"ur_type": "ur5e", "name": "ur5e", "use_mock_hardware": "true"}


def _joints(root: etree._Element) -> dict[str, tuple[str, str, str, str]]:
    """Each joint's parent, child and origin, as written."""
    out = {}
    for j in root.findall("joint"):
        o = j.find("origin")
        out[j.get("name")] = (
            j.find("parent").get("link"),
            j.find("child").get("link"),
            o.get("xyz") if o is not None else "",
            o.get("rpy") if o is not None else "",
        )
    return out


def test_import_reads_the_ur_tf_prefix_as_the_spec_prefix(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The UR description with tf_prefix:=left_ imports as ``prefix: left_`` with bare names; the
    package generated from it, expanded with prefix:=right_, is the UR Xacro with tf_prefix:=right_."""
    spec = tmp_path / "specs" / "ur.yaml"
    args = [x for k, v in {**UR_ARGS, "tf_prefix": "left_"}.items() for x in ("--xacro-arg", f"{k}:={v}")]
    r = cli(
        "import", CORPUS / "ur_robot_driver" / "urdf" / "ur.urdf.xacro", *args, "--package-path", CORPUS,
        "--controllers", CORPUS / "ur_robot_driver" / "config" / "ur_controllers.yaml",
        "--launch-arg", "tf_prefix:=left_", "-o", spec,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr[-3000:]
    assert "info[IMP041]" in r.stderr
    text = spec.read_text()
    assert "\nprefix: left_\n" in text and text.count("left_") == 1  # written once, taken out of every name
    r = cli("generate", spec, "--package-path", CORPUS)
    assert r.returncode == 0, r.stderr[-3000:]
    package = tmp_path / "generated" / "ur5e_description"
    import xacro.substitution_args as sa

    # $(find P) answered as ament_index answers it in an install space: the generated package, or the corpus's P/
    found = {"ur5e_description": package}
    monkeypatch.setattr(sa, "_eval_find", lambda pkg: str(found.get(pkg, CORPUS / pkg)))
    ours = xacro.process_file(str(package / "urdf" / "ur5e.urdf.xacro"), mappings={"prefix": "right_"})
    theirs = xacro.process_file(
        str(CORPUS / "ur_robot_driver" / "urdf" / "ur.urdf.xacro"), mappings={**UR_ARGS, "tf_prefix": "right_"}
    )
    a, b = etree.fromstring(ours.toxml().encode()), etree.fromstring(theirs.toxml().encode())
    assert _names(a) == _names(b)
    assert _joints(a) == _joints(b)
    ctl = lambda root: sorted(e.get("name") for e in root.find("ros2_control").iter("joint"))  # noqa: E731
    assert ctl(a) == ctl(b) and all(n.startswith("right_") for n in ctl(a))


def test_what_the_review_found_is_right(package: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The virtual joint hangs from the robot's own odometry frame; in a namespace the diff drive
    does not put the namespace before its frames (Jazzy's tf_frame_prefix_enable defaults to true,
    docs/reference/ros2_control.md); Gazebo's controller manager runs in the namespace; the
    ros2_control Xacro expands on its own."""
    import yaml

    srdf = etree.parse(str(package / "srdf" / "warehouse_arm.srdf")).getroot()
    vj = srdf.find("virtual_joint")
    assert (vj.get("parent_frame"), vj.get("child_link")) == ("left_odom", "left_base_footprint")
    doc = yaml.safe_load((package / "config" / "ros2_controllers.yaml").read_text())
    assert doc["/left/diff_drive_controller"]["ros__parameters"]["tf_frame_prefix_enable"] is False
    assert "tf_frame_prefix_enable" not in doc["/left/arm_controller"]["ros__parameters"]  # a JTC has none
    import xacro.substitution_args as sa

    monkeypatch.setattr(sa, "_eval_find", lambda pkg: str(package.parent / pkg))  # as ament_index answers
    gz = etree.fromstring(
        xacro.process_file(str(package / "urdf" / "warehouse_arm.urdf.xacro"), mappings={"hardware": "gazebo"})
        .toxml()
        .encode()
    )
    assert gz.findtext("gazebo/plugin/ros/namespace") == "/left"
    alone = etree.fromstring(
        xacro.process_file(str(package / "urdf" / "warehouse_arm.ros2_control.xacro"), mappings={"prefix": "r_"})
        .toxml()
        .encode()
    )
    assert {e.get("name") for e in alone.iter("joint")} >= {"r_lift_joint", "r_elbow_joint"}


def test_a_prefix_that_the_pass_would_not_give_back_is_imported_name_for_name(tmp_path: Path) -> None:
    """A controller frame id without the Xacro's prefix: the prefix pass would write it prefixed,
    so the spec keeps every name as the description has it (no prefix:), proven."""
    rules = ROOT / "tests" / "rules" / "NAME014"
    ctl = tmp_path / "c.yaml"
    ctl.write_text(
        (rules / "good.controllers.yaml").read_text().replace("odom_frame_id: left_odom", "odom_frame_id: odom")
    )
    spec = tmp_path / "specs" / "cart.yaml"
    r = cli("import", rules / "good.xacro", "--controllers", ctl, "-o", spec)
    assert r.returncode == 0 and "round trip proven" in r.stdout + r.stderr, r.stderr[-2000:]
    text = spec.read_text()
    assert "\nprefix:" not in text and "left_base_link" in text


def test_the_ur_drivers_real_hardware_keeps_its_tf_prefix(tmp_path: Path) -> None:
    """ur_robot_driver's real hardware has <param name="tf_prefix">: written empty in the spec, it
    takes the spec's prefix back (the import's round trip proves it)."""
    spec = tmp_path / "specs" / "ur.yaml"
    args = {**UR_ARGS, "use_mock_hardware": "false", "tf_prefix": "left_"}
    r = cli(
        "import", CORPUS / "ur_robot_driver" / "urdf" / "ur.urdf.xacro",
        *[x for k, v in args.items() for x in ("--xacro-arg", f"{k}:={v}")], "--package-path", CORPUS,
        "--controllers", CORPUS / "ur_robot_driver" / "config" / "ur_controllers.yaml",
        "--launch-arg", "tf_prefix:=left_", "-o", spec,
    )  # fmt: skip
    assert r.returncode == 0 and "round trip proven" in r.stdout + r.stderr, r.stderr[-3000:]
    assert "\nprefix: left_\n" in spec.read_text()


def test_frame_leaves_and_interface_names_in_controller_params() -> None:
    """pose_broadcaster's tf.child_frame_id is a frame (prefixed); an interface named like a link
    is an interface (not prefixed)."""
    from descgen.core.findings import Where
    from descgen.core.model import Controller, Link, Robot, Ros2Control
    from descgen.spec.prefix import prefixed

    pose = Controller("pose", "pose_broadcaster/PoseBroadcaster", (("tf", (("child_frame_id", "tool_measured"),)),))
    gpio = Controller("io", "gpio_controllers/GpioCommandController", (("interfaces", ("caster_link",)),))
    robot = Robot("r", links=(Link("caster_link"),), ros2_control=Ros2Control("hw", controllers=(pose, gpio)))
    rc = prefixed(robot, "left_", Where("x")).ros2_control
    assert rc is not None
    got = {c.name: dict(c.params) for c in rc.controllers}
    assert got["pose"]["tf"] == (("child_frame_id", "left_tool_measured"),)
    assert got["io"]["interfaces"] == ("caster_link",)
