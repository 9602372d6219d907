"""descgen simulate: MuJoCo compiles the robot, reports what it refuses and changes, and a short
gravity run holds the joints at a pose. Oracles: MuJoCo itself compiling the same URDF, and hand
computations (a pendulum's period and static sag, a box's mass at 1000 kg/m^3)."""

from __future__ import annotations

import json
import math
import struct
import sys
from pathlib import Path

import pytest

mujoco = pytest.importorskip("mujoco", reason="descgen simulate needs the optional mujoco package (descgen[sim])")

from descgen.audit.spec import load_spec  # noqa: E402
from descgen.commands.simulate import Settings, gravity, simulate  # noqa: E402
from descgen.commands.simulate.faults import CATALOGUE, plant_all  # noqa: E402
from descgen.render.mujoco_urdf import emit  # noqa: E402
from tests.helpers import ROOT, cli, run_cli  # noqa: E402

SPEC = ROOT / "specs" / "warehouse_arm.yaml"
G = 9.81


def _codes(stderr: str) -> list[str]:
    return [line.split("[", 1)[1].split("]", 1)[0] for line in stderr.splitlines() if "[" in line and ": " in line]


def _inertial(mass: float, com: str = "0 0 0", i: float = 1e-3) -> str:
    return (
        f'<inertial><origin xyz="{com}"/><mass value="{mass}"/>'
        f'<inertia ixx="{i}" iyy="{i}" izz="{i}" ixy="0" ixz="0" iyz="0"/></inertial>'
    )


def pendulum(
    mass: float = 1.0, length: float = 0.5, effort: float = 49.05, extra: str = "", limit: str = "", ic: float = 1e-3
) -> str:
    """A link hanging off a revolute joint about +y, its centre of mass ``length`` along +x (a
    horizontal arm: the largest gravity torque, m g L)."""
    limit = limit or f'<limit lower="-3" upper="3" effort="{effort}" velocity="1"/>'
    return f"""<robot name="pendulum">
  <link name="base">{_inertial(5.0)}<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>
  <link name="arm">{_inertial(mass, f"{length} 0 0", ic)}</link>
  <joint name="hinge" type="revolute"><origin xyz="0 0 1"/><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/>{limit}</joint>
  {extra}
</robot>
"""


def _write(tmp_path: Path, text: str, name: str = "robot.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# -- the example and the planted faults ---------------------------------------------------------


@pytest.mark.parametrize("pose", [None, "ready", "side_reach"])
def test_example_holds_every_pose_on_the_floor(pose: str | None) -> None:
    ran = cli("simulate", SPEC, *(["--pose", pose] if pose else []), "--format", "json")
    doc = json.loads(ran.stdout)
    assert ran.returncode == 0, ran.stdout
    assert doc["summary"]["error"] == 0
    # the spec's SRDF virtual joint is planar and its root base_footprint: free on the floor
    assert doc["simulate"]["base"] == "floor"
    assert doc["simulate"]["tilt_deg"] < 1.0
    assert {s["joint"] for s in doc["simulate"]["servos"]} == {
        "lift_joint",
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
        "left_wheel_joint",
        "right_wheel_joint",
    }


def test_example_reports_what_mujoco_changes_silently() -> None:
    ran = cli("simulate", SPEC, "--base", "fixed")
    assert ran.returncode == 0, ran.stderr
    # fixed joints of the spec (base, caster, arm mount, tool, 2 sensors, optical) fuse; on a
    # fixed base the root fuses into the world too
    fused = next(line for line in ran.stderr.splitlines() if "[SIM004]" in line)
    assert "8 link(s)" in fused and "base_footprint" in fused and "camera_optical_frame" in fused
    assert "[SIM005]" in ran.stderr and "all 11 visual(s)" in ran.stderr  # 11 visuals in the spec, by count
    # on a fixed base the chassis box is world geometry, and the wheels sit inside it
    assert "[SIM015]" in ran.stderr and "left_wheel_link/world" in ran.stderr


@pytest.mark.parametrize("base", ["floor", "fixed"])
@pytest.mark.parametrize("fault", CATALOGUE, ids=lambda f: f.name)
def test_each_planted_fault_fails_the_run(base: str, fault: object) -> None:
    robot = load_spec(SPEC).robot
    [result] = plant_all(robot, Settings(pose="ready", base=base), catalogue=(fault,))  # type: ignore[arg-type]
    assert result.applicable and result.caught, result.what


def test_com_outside_the_footprint_tips_the_base_and_only_it() -> None:
    robot = load_spec(SPEC).robot
    [result] = plant_all(robot, Settings(), catalogue=tuple(f for f in CATALOGUE if f.name == "com-outside"))
    assert [f.code for f in result.by] == ["SIM013"]


# -- hand-computed expectations -----------------------------------------------------------------


def test_static_sag_of_a_held_pendulum_is_gravity_torque_over_kp(tmp_path: Path) -> None:
    """kp = effort / 0.04 rad = 1226.25 N*m/rad; m g L = 1 * 9.81 * 0.5 = 4.905 N*m: 0.004 rad of sag."""
    path = _write(tmp_path, pendulum())
    ran = cli("simulate", path, "--format", "json")
    doc = json.loads(ran.stdout)
    assert ran.returncode == 0, ran.stderr
    [servo] = doc["simulate"]["servos"]
    assert servo["kp"] == pytest.approx(1226.25)
    assert doc["simulate"]["drift"]["hinge"] == pytest.approx(0.004, rel=0.03)
    assert doc["simulate"]["base"] == "fixed"  # root "base", no SRDF


def test_a_pendulum_its_effort_cannot_hold_falls(tmp_path: Path) -> None:
    """m g L = 4.905 N*m against an effort of 3 N*m: the joint must leave the pose."""
    ran = cli("simulate", _write(tmp_path, pendulum(effort=3.0)))
    assert ran.returncode == 1
    assert "error[SIM012]" in ran.stderr and "joint hinge drifted" in ran.stderr


def test_the_emitted_urdf_swings_with_the_hand_computed_period() -> None:
    """Small swings of a compound pendulum: T = 2 pi sqrt(I_pivot / (m g L)), I_pivot = I_c + m L^2."""
    from descgen.read.urdf import read_urdf_text

    m, length, ic = 2.0, 0.4, 0.01
    text = pendulum(mass=m, length=length, ic=ic)
    robot, _ = read_urdf_text(text.encode(), "pendulum.urdf")
    model = mujoco.MjModel.from_xml_string(emit(robot).text)
    model.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
    model.opt.timestep = 0.0005
    data = mujoco.MjData(model)
    # about +y, q turns +x towards -z: hanging straight down is +90 deg
    data.qpos[0] = math.pi / 2 + 0.02
    crossings, prev = [], data.qpos[0] - math.pi / 2
    while data.time < 5.0:
        mujoco.mj_step(model, data)
        now = data.qpos[0] - math.pi / 2
        if prev > 0 >= now:
            crossings.append(data.time)
        prev = now
    period = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert period == pytest.approx(2 * math.pi * math.sqrt((ic + m * length**2) / (m * G * length)), rel=2e-3)


def test_mass_from_geometry_is_water_of_the_collision_volume(tmp_path: Path) -> None:
    """No <inertial>, a 0.1 m cube: MuJoCo gives 1000 kg/m^3 * 0.001 m^3 = 1 kg."""
    box = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    text = pendulum().replace(f'<link name="arm">{_inertial(1.0, "0.5 0 0")}</link>', f'<link name="arm">{box}</link>')
    ran = cli("simulate", _write(tmp_path, text))
    line = next(ln for ln in ran.stderr.splitlines() if "[SIM006]" in ln)
    assert "link arm has no <inertial>; MuJoCo gives it 1 kg" in line


# -- what MuJoCo refuses, each confirmed by MuJoCo compiling the same URDF ------------------------


def _mujoco_refuses(text: str) -> str:
    with pytest.raises(ValueError) as exc:
        mujoco.MjModel.from_xml_string(text)
    return str(exc.value)


def test_every_refused_body_is_reported_in_one_run(tmp_path: Path) -> None:
    massless = pendulum().replace(_inertial(1.0, "0.5 0 0"), _inertial(0.0, "0.5 0 0"))
    assert "mjMINVAL" in _mujoco_refuses(massless)
    triangle = (
        '<link name="tip"><inertial><mass value="1"/>'
        '<inertia ixx="0.001" iyy="0.001" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        '<joint name="wrist" type="revolute"><parent link="arm"/><child link="tip"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
    )
    assert "A + B >= C" in _mujoco_refuses(pendulum(extra=triangle))
    ran = cli("simulate", _write(tmp_path, massless.replace("</robot>", triangle + "</robot>")))
    assert ran.returncode == 1
    codes = _codes(ran.stderr)
    assert codes.count("SIM001") == 1 and codes.count("SIM002") == 1, ran.stderr
    assert "body arm" in ran.stderr and "body tip" in ran.stderr
    assert "MuJoCo refused the model" in ran.stdout


def test_inverted_limits_become_an_unlimited_joint(tmp_path: Path) -> None:
    text = pendulum(limit='<limit lower="1" upper="-1" effort="49.05" velocity="1"/>')
    assert not mujoco.MjModel.from_xml_string(text).jnt_limited[0]  # the oracle: MuJoCo's own model
    ran = cli("simulate", _write(tmp_path, text))
    assert "warning[SIM007]" in ran.stderr and "joint hinge: lower 1 rad" in ran.stderr


def test_well_ordered_limits_are_not_reported(tmp_path: Path) -> None:
    ran = cli("simulate", _write(tmp_path, pendulum()))
    assert "SIM007" not in ran.stderr and ran.returncode == 0


# -- meshes: resolved within the named folders, handed over in memory -----------------------------


def _stl_cube(half: float) -> bytes:
    """A binary STL of a cube (12 triangles), written by hand."""
    v = [(x, y, z) for x in (-half, half) for y in (-half, half) for z in (-half, half)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1)]
    faces += [(2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    out = b"\0" * 80 + struct.pack("<I", len(faces))
    for a, b, c in faces:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in (a, b, c)) + b"\0\0"
    return out


def _package(tmp_path: Path, mesh_name: str, data: bytes) -> Path:
    pkg = tmp_path / "ws" / "bot_description"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>bot_description</name></package>")
    (pkg / "meshes" / mesh_name).write_bytes(data)
    return pkg


def _with_mesh(filename: str) -> str:
    mesh = f'<collision><geometry><mesh filename="{filename}"/></geometry></collision>'
    return pendulum().replace(f"{_inertial(1.0, '0.5 0 0')}</link>", f"{_inertial(1.0, '0.5 0 0')}{mesh}</link>")


def test_a_package_mesh_reaches_mujoco(tmp_path: Path) -> None:
    pkg = _package(tmp_path, "cube.stl", _stl_cube(0.05))
    path = _write(pkg, _with_mesh("package://bot_description/meshes/cube.stl"))
    ran = cli("simulate", path, "--package-path", tmp_path / "ws")
    assert ran.returncode == 0 and "SIM008" not in ran.stderr, ran.stderr
    robot = __import__("descgen.read.description", fromlist=["x"]).load_description(path)[0]
    emitted = emit(robot)
    model = mujoco.MjModel.from_xml_string(emitted.text, emitted.assets)
    assert model.nmesh == 1 and model.mesh_vertnum[0] == 8  # the hand-written cube's 8 corners


@pytest.mark.parametrize(
    ("filename", "why"),
    [
        ("package://bot_description/meshes/gone.stl", "is not a file inside"),
        ("package://bot_description/meshes/cube.dae", "COLLADA file that cannot be read"),  # converted when readable
        ("../../../../../../etc/hostname", "is not a file inside"),
        ("file:///etc/hostname", "is not a file inside"),
    ],
)
def test_a_mesh_mujoco_cannot_have_is_an_error_not_a_crash(tmp_path: Path, filename: str, why: str) -> None:
    pkg = _package(tmp_path, "cube.dae", b"<COLLADA/>")
    ran = cli("simulate", _write(pkg, _with_mesh(filename)), "--package-path", tmp_path / "ws")
    assert ran.returncode == 1 and "Traceback" not in ran.stderr
    line = next(ln for ln in ran.stderr.splitlines() if "[SIM008]" in ln)
    assert why in line and "link arm" in line


# -- bad input ----------------------------------------------------------------------------------


def test_unknown_pose_is_exit_2_listing_the_poses() -> None:
    ran = cli("simulate", SPEC, "--pose", "raedy")
    assert ran.returncode == 2 and ran.stdout == ""
    first, hint = ran.stderr.splitlines()[:2]
    assert "error[SIM014]: --pose 'raedy'" in first and "ready" in hint


def test_srdf_group_state_names_a_pose(tmp_path: Path) -> None:
    srdf = _write(
        tmp_path,
        '<robot name="pendulum"><group name="g"><joint name="hinge"/></group>'
        '<group_state name="up" group="g"><joint name="hinge" value="-1.5707963"/></group_state></robot>',
        "p.srdf",
    )
    ran = cli("simulate", _write(tmp_path, pendulum()), "--srdf", srdf, "--pose", "up", "--format", "json")
    doc = json.loads(ran.stdout)
    # straight up (-90 deg about +y) the arm has no gravity torque: the sag is far below the 0.004 rad of horizontal
    assert ran.returncode == 0 and doc["simulate"]["servos"][0]["target"] == pytest.approx(-1.5707963)
    assert doc["simulate"]["drift"]["hinge"] < 1e-3


def test_without_mujoco_it_says_how_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "mujoco", None)  # import mujoco now raises ImportError
    ran = cli("simulate", SPEC)
    assert ran.returncode == 2 and "error[SIM009]" in ran.stderr and "descgen[sim]" in ran.stderr


def test_servo_gains_come_from_effort_not_mass() -> None:
    """A wrong mass must show as sag: kp is effort / 0.04 rad (or / 0.008 m), whatever the links weigh."""
    robot = load_spec(SPEC).robot
    held = {s.joint: s for s in gravity.servos(robot, gravity.Setup("fixed", 1.0, ()))}
    assert held["shoulder_lift_joint"].kp == pytest.approx(40 / 0.04)  # effort 40 N*m in the spec
    assert held["lift_joint"].kp == pytest.approx(500 / 0.008)  # effort 500 N


def test_library_call_is_short_and_fast() -> None:
    out = simulate(load_spec(SPEC).robot, Settings(seconds=0.5, pose="ready"))
    assert not out.failed and out.report["steps"] == round(0.5 / gravity.TIMESTEP) and out.report["wall_s"] < 5


@pytest.mark.e2e
def test_end_to_end_exit_codes() -> None:
    ok = run_cli("simulate", str(SPEC), "--pose", "ready")
    assert ok.returncode == 0, ok.stderr
    assert "base floor, pose ready" in ok.stdout and "Traceback" not in ok.stderr
