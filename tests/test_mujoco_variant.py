"""``hardware:=mujoco`` (descgen/render/mjcf.py, descgen/prove/mujoco_model.py; docs/mujoco_ros2_control.md).

Oracles: the real xacro expands the variant; MuJoCo compiles the written MJCF from its file, as
mujoco_ros2_control's ``mj_loadXML`` does; the expected joints, ranges, masses and actuators are
read from the generated URDF with lxml (not from descgen's model); a mimic gripper is stepped in
MuJoCo and the follower must track the leader by the URDF's multiplier and offset.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import mujoco
import numpy as np
import pytest
import xacro
from lxml import etree

from tests.helpers import ROOT, cli

EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
PLUGIN = "mujoco_ros2_control/MujocoSystemInterface"


def _with_mujoco(text: str, variant: str = 'mujoco: {params: {headless: "true"}}') -> str:
    anchor = "        params: {device: /dev/ttyACM0, baud_rate: 115200}\n"
    assert anchor in text
    return text.replace(anchor, anchor + f"      {variant}\n", 1)


@pytest.fixture(scope="module")
def package(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("mujoco")
    shutil.copytree(EXAMPLE.parent, root / "specs")
    spec = root / "specs" / "warehouse_arm.yaml"
    spec.write_text(_with_mujoco(spec.read_text()))
    r = cli("generate", spec)
    assert r.returncode == 0, r.stderr[-3000:]
    assert cli("check", spec).returncode == 0
    return root / "generated" / "warehouse_arm_description"


def test_the_variant_expands_to_the_plugin_and_its_model(package: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import xacro.substitution_args as sa

    monkeypatch.setattr(sa, "_eval_find", lambda pkg: str(package.parent / pkg))  # as ament_index answers
    doc = etree.fromstring(
        xacro.process_file(str(package / "urdf" / "warehouse_arm.urdf.xacro"), mappings={"hardware": "mujoco"})
        .toxml()
        .encode()
    )
    hw = doc.find("ros2_control/hardware")
    assert hw.findtext("plugin") == PLUGIN
    params = {p.get("name"): p.text for p in hw.findall("param")}
    assert params["headless"] == "true"
    assert Path(params["mujoco_model"]) == package / "mujoco" / "warehouse_arm.xml"
    assert Path(params["mujoco_model"]).is_file()


def test_mujoco_compiles_the_file_and_it_is_the_urdfs_robot(package: Path) -> None:
    model = mujoco.MjModel.from_xml_path(str(package / "mujoco" / "warehouse_arm.xml"))
    urdf = etree.parse(str(package / "urdf" / "warehouse_arm.urdf")).getroot()
    for j in urdf.findall("joint"):
        if j.get("type") == "fixed":
            continue
        i = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, j.get("name"))
        assert i >= 0, j.get("name")
        limit = j.find("limit")
        if j.get("type") != "continuous":
            want = [float(limit.get("lower")), float(limit.get("upper"))]
            assert np.allclose(model.jnt_range[i], want, rtol=1e-5, atol=1e-6), j.get("name")
    masses = sum(float(m.get("value")) for m in urdf.iter("mass"))
    assert np.isclose(model.body_mass.sum(), masses, rtol=1e-5)
    commanded = {
        e.get("name"): e.find("command_interface").get("name")
        for e in urdf.find("ros2_control").findall("joint")
        if e.find("command_interface") is not None
    }
    actuators = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a): a for a in range(model.nu)}
    assert set(actuators) == set(commanded)
    for name, command in commanded.items():
        a = actuators[name]
        # as the plugin classifies an actuator (sif.cpp:128): a position bias, else a velocity one, else a motor
        bias = model.actuator_biasprm[a]
        kind = "position" if bias[1] != 0 else "velocity" if bias[2] != 0 else "effort"
        assert kind == command, name
    # a wheeled base: on a floor, free, with the joint mujoco_ros2_control publishes odometry for
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "floating_base_joint") >= 0


def test_the_launch_file_runs_mujoco_ros2_control_under_hardware_mujoco(package: Path) -> None:
    launch = (package / "launch" / "control.launch.py").read_text()
    compile(launch, "control.launch.py", "exec")
    assert 'package="mujoco_ros2_control",\n            executable="ros2_control_node"' in launch
    assert "condition=IfCondition(mujoco)" in launch and "condition=UnlessCondition(mujoco)" in launch
    assert '"mujoco"]' in launch  # a choice of the hardware argument


def test_the_proof_fails_on_a_wrong_model(package: Path) -> None:
    from descgen.audit.spec import load_spec
    from descgen.prove.mujoco_model import mujoco_model

    robot = load_spec(package.parent.parent / "specs" / "warehouse_arm.yaml").robot
    text = (package / "mujoco" / "warehouse_arm.xml").read_text()
    assert mujoco_model({"mujoco/warehouse_arm.xml": text}, robot, package) == []
    no_elbow = text.replace('<general name="elbow_joint"', '<general name="elbow"')
    assert no_elbow != text
    found = mujoco_model({"mujoco/warehouse_arm.xml": no_elbow}, robot, package)
    assert [f.code for f in found] == ["GEN097", "GEN097"]
    assert any("'elbow_joint' (position) has no actuator" in f.message for f in found)


GRIPPER = """\
name: jaw
links:
  - name: base_link
    collision: [{geometry: {box: {size: [100 mm, 100 mm, 20 mm]}}}]
    inertial: {mass: 1 kg, from: collision}
  - name: finger_a
    collision: [{geometry: {box: {size: [10 mm, 10 mm, 40 mm]}}}]
    inertial: {mass: 50 g, from: collision}
  - name: finger_b
    collision: [{geometry: {box: {size: [10 mm, 10 mm, 40 mm]}}}]
    inertial: {mass: 50 g, from: collision}
joints:
  - name: jaw_a
    type: prismatic
    parent: base_link
    child: finger_a
    origin: {xyz: [20 mm, 0, 30 mm]}
    axis: [1, 0, 0]
    limit: {lower: 0, upper: 40 mm, effort: 20 N, velocity: 100 mm/s}
  - name: jaw_b
    type: prismatic
    parent: base_link
    child: finger_b
    origin: {xyz: [-20 mm, 0, 30 mm]}
    axis: [1, 0, 0]
    limit: {lower: -40 mm, upper: 0, effort: 20 N, velocity: 100 mm/s}
    mimic: {joint: jaw_a, multiplier: -1, offset: 0}
ros2_control:
  name: JawSystem
  hardware:
    plugin: mock_components/GenericSystem
    variants:
      mujoco: {}
  update_rate: 100 Hz
  joints:
    - {name: jaw_a, command: [position], state: [position, velocity]}
    - {name: jaw_b, state: [position, velocity], mimic: true}
  controllers:
    - {name: joint_state_broadcaster, type: joint_state_broadcaster/JointStateBroadcaster}
"""


def test_a_mimic_joint_follows_its_leader_in_mujoco(tmp_path: Path) -> None:
    spec = tmp_path / "specs" / "jaw.yaml"
    spec.parent.mkdir()
    spec.write_text(GRIPPER)
    r = cli("generate", spec)
    assert r.returncode == 0, r.stderr[-3000:]
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "generated" / "jaw_description" / "mujoco" / "jaw.xml"))
    assert model.nu == 1 and model.neq == 1  # the leader's actuator; the follower's equality
    data = mujoco.MjData(model)
    data.ctrl[0] = 0.02  # close the leader to 20 mm
    for _ in range(3000):
        mujoco.mj_step(model, data)
    a = data.qpos[model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "jaw_a")]]
    b = data.qpos[model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "jaw_b")]]
    assert abs(a - 0.02) < 2e-3  # the position actuator got there
    assert abs(b - (-1.0 * a + 0.0)) < 1e-3  # and jaw_b = -1 * jaw_a + 0, the URDF's mimic


@pytest.mark.parametrize(
    "variant", ["mujoco: {plugin: mujoco_ros2_control/MujocoSystem}", 'mujoco: {params: {mujoco_model: "/tmp/x.xml"}}']
)
def test_another_plugin_or_model_is_refused(tmp_path: Path, variant: str) -> None:
    shutil.copytree(EXAMPLE.parent, tmp_path / "specs")
    spec = tmp_path / "specs" / "warehouse_arm.yaml"
    spec.write_text(_with_mujoco(spec.read_text(), variant))
    r = cli("validate", spec)
    assert r.returncode == 2 and "error[SPEC149]" in r.stderr, r.stderr[-2000:]


# -- what the review of the variant found --------------------------------------------------------------


def test_the_file_is_installed_and_its_plugin_a_dependency(package: Path) -> None:
    cmake = (package / "CMakeLists.txt").read_text()
    installed = next(line for line in cmake.splitlines() if line.strip().startswith("DIRECTORY"))
    assert "mujoco" in installed.split()
    deps = [e.text for e in etree.parse(str(package / "package.xml")).getroot().findall("exec_depend")]
    assert "mujoco_ros2_control" in deps


def test_jazzys_mujoco_reads_it_too(package: Path) -> None:
    """mujoco_vendor 3.4.0 refuses the ``input`` attribute MuJoCo 4 writes on a general actuator."""
    assert " input=" not in (package / "mujoco" / "warehouse_arm.xml").read_text()


def test_the_arm_settles_holding_its_start_pose(package: Path) -> None:
    model = mujoco.MjModel.from_xml_path(str(package / "mujoco" / "warehouse_arm.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    # the free base stands on the floor: no shape below it at the start
    lowest = min(
        float(
            (
                data.geom_xpos[g]
                + data.geom_xmat[g].reshape(3, 3) @ (model.geom_aabb[g][:3] + model.geom_aabb[g][3:] * s)
            )[2]
        )
        for g in range(model.ngeom)
        if model.geom_type[g] != mujoco.mjtGeom.mjGEOM_PLANE
        for s in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).T.reshape(-1, 3)
    )
    assert 0.0 <= lowest < 0.01
    arm = ["lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]
    for _ in range(int(3.0 / model.opt.timestep)):  # hold every position actuator at zero for 3 s
        mujoco.mj_step(model, data)
    speeds = [abs(data.qvel[model.jnt_dofadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, j)]]) for j in arm]
    assert max(speeds) < 0.01  # JTC's stopped_velocity_tolerance


def test_each_commanded_joint_gets_the_actuator_its_commands_need(tmp_path: Path) -> None:
    """The plugin refuses position on a velocity or effort actuator without PIDs: position wins."""
    text = GRIPPER.replace("{name: jaw_a, command: [position]", "{name: jaw_a, command: [effort, velocity, position]")
    spec = tmp_path / "specs" / "jaw.yaml"
    spec.parent.mkdir()
    spec.write_text(text)
    assert cli("generate", spec).returncode == 0
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "generated" / "jaw_description" / "mujoco" / "jaw.xml"))
    assert model.actuator_biasprm[0][1] != 0  # a position actuator


def test_a_link_without_inertial_adds_no_mass(tmp_path: Path) -> None:
    text = GRIPPER.replace(
        "joints:\n",
        "  - name: flange\njoints:\n  - {name: flange_joint, type: fixed, parent: base_link, child: flange}\n",
        1,
    )
    spec = tmp_path / "specs" / "jaw.yaml"
    spec.parent.mkdir()
    spec.write_text(text)
    r = cli("generate", spec)
    assert r.returncode == 0, r.stderr[-2000:]


def test_the_proof_sees_kinematics_gear_and_forces(package: Path) -> None:
    from descgen.audit.spec import load_spec
    from descgen.prove.mujoco_model import mujoco_model

    robot = load_spec(package.parent.parent / "specs" / "warehouse_arm.yaml").robot
    text = (package / "mujoco" / "warehouse_arm.xml").read_text()
    elbow = text.index('name="elbow_joint"')
    flipped = text[:elbow] + text[elbow:].replace('axis="0 1 0"', 'axis="0 -1 0"', 1)
    assert flipped != text
    moved = text.replace('<body name="forearm_link" pos="0.3 0 0"', '<body name="forearm_link" pos="1.3 0 0"')
    assert moved != text
    geared = text.replace('<general name="elbow_joint"', '<general name="elbow_joint" gear="50"')

    def forearm_inertial(change: str) -> str:
        root = etree.fromstring(text.encode())
        e = root.find(".//body[@name='forearm_link']/inertial")
        if change == "heavy":
            e.set("diaginertia", " ".join(str(100 * float(v)) for v in e.get("diaginertia").split()))
        else:
            x, y, z = (float(v) for v in e.get("pos").split())
            e.set("pos", f"{x + 0.2} {y} {z}")
        return etree.tostring(root, encoding="unicode")

    heavy, shifted = forearm_inertial("heavy"), forearm_inertial("shifted")
    for wrong, needle in ((flipped, "'elbow_joint' axis"), (moved, "body 'forearm_link' is not where"),
                          (geared, "gear of 50"), (heavy, "'forearm_link' inertia is not"),
                          (shifted, "'forearm_link' centre of mass")):  # fmt: skip
        found = mujoco_model({"mujoco/warehouse_arm.xml": wrong}, robot, package)
        assert any(needle in f.message for f in found), (needle, [f.message for f in found])


def test_one_block_only(tmp_path: Path) -> None:
    block = "  blocks:\n    - name: Other\n      hardware:\n        plugin: mock_components/GenericSystem\n"
    text = GRIPPER.replace("  controllers:", block + "        variants: {mujoco: {}}\n  controllers:")
    spec = tmp_path / "specs" / "jaw.yaml"
    spec.parent.mkdir()
    spec.write_text(text)
    r = cli("validate", spec)
    assert r.returncode == 2 and "error[SPEC149]" in r.stderr and "blocks" in r.stderr, r.stderr[-2000:]


def test_without_mujoco_installed_generate_says_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    spec = tmp_path / "specs" / "jaw.yaml"
    spec.parent.mkdir()
    spec.write_text(GRIPPER)
    monkeypatch.setitem(sys.modules, "mujoco", None)  # import mujoco raises ImportError
    r = cli("generate", spec)
    assert r.returncode == 2 and "error[GEN096]" in r.stderr and "not installed" in r.stderr, r.stderr[-2000:]
