"""descgen import: exact units, sources, pass-through kept as data, the round trip, the corpus."""

from __future__ import annotations

import math
import random
from decimal import Decimal
from pathlib import Path

import numpy as np
import pytest
import yaml
from lxml import etree

from descgen.commands.importer.quantity import quantity
from descgen.core import units
from tests.corpus import descriptions, share
from tests.helpers import cli

URDF = """<?xml version="1.0"?>
<robot name="tiny">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  <link name="base_link">
    <visual><origin xyz="0 0 0.48514"/><geometry><box size="0.3 0.2 0.1"/></geometry>
      <material name="grey"/></visual>
    <inertial><mass value="2.5"/><origin xyz="0.01 0 0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
  </link>
  <link name="arm">
    <collision><geometry><cylinder radius="0.04" length="0.3"/></geometry></collision>
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0005"/></inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <origin xyz="0.1 0 0.2" rpy="0 1.5707963267948966 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-2.0943951023931953" upper="3.14159" effort="40" velocity="1.5"/>
    <dynamics damping="0.5" friction="0.1"/>
  </joint>
  <gazebo reference="arm"><material>Gazebo/${colour}</material>
    <plugin filename="$(find evil)/x.so" name="p"><!-- $(env HOME) --></plugin></gazebo>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type></transmission>
</robot>
"""


def _write(tmp_path: Path, text: str = URDF) -> Path:
    path = tmp_path / "tiny.urdf"
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("si", "kind", "unit", "written"),
    [
        (0.48514, "length", "mm", "485.14 mm"),  # 0.48514 * 1000 in floats is 485.14000000000004
        (1e-07, "length", "mm", "0.0001 mm"),
        (2.5, "mass", "g", "2500 g"),
        (math.pi / 2, "angle", "deg", "90 deg"),
        (0.1, "angle", "deg", "0.1 rad"),  # 5.729577951308233 deg would be longer than the radians
        (0.01, "inertia", "", "0.01 kg*m^2"),
    ],
)
def test_quantities_are_written_exactly(si: float, kind: str, unit: str, written: str) -> None:
    assert quantity(si, kind, unit) == written
    # the spec's own parser gives back the very same float
    assert units.to_si(written, kind) == si
    # and the text is the decimal product, not a float product (hand computation)
    if unit == "mm":
        assert Decimal(written.split()[0]) == Decimal(repr(si)) * 1000


def test_import_writes_a_spec_with_sources_that_generates_the_same_robot(tmp_path: Path) -> None:
    import yourdfpy

    src = _write(tmp_path)
    spec = tmp_path / "tiny.yaml"
    ran = cli("import", src, "-o", spec)
    assert ran.returncode == 0, ran.stderr
    assert "round trip proven" in ran.stderr
    data = yaml.safe_load(spec.read_text())
    assert data["require_sources"] is True
    base = data["links"][0]
    assert base["visual"][0]["origin"]["xyz"][2] == "485.14 mm"
    assert base["source"] == "tiny.urdf:4"  # the <link name="base_link"> line, counted by hand
    assert data["joints"][0]["limit"]["lower"] == "-120 deg"
    assert [p["xml"].split(">")[0].split()[0] for p in data["passthrough"]] == ["<gazebo", "<transmission"]
    assert "IMP003" in ran.stderr  # each pass-through element is listed in the report

    out = tmp_path / "gen"
    gen = cli("generate", spec, "--out", out)
    assert gen.returncode == 0, gen.stderr + gen.stdout
    urdf = out / "tiny_description" / "urdf" / "tiny.urdf"
    theirs = yourdfpy.URDF.load(str(urdf), load_meshes=False, build_scene_graph=False).robot
    ours = yourdfpy.URDF.load(str(src), load_meshes=False, build_scene_graph=False).robot
    for a, b in zip(
        sorted(ours.joints, key=lambda j: j.name), sorted(theirs.joints, key=lambda j: j.name), strict=True
    ):
        assert np.array_equal(a.origin, b.origin) and a.limit.lower == b.limit.lower and a.limit.upper == b.limit.upper
    assert theirs.links[0].visuals[0].origin[2, 3] == 0.48514


def test_pass_through_stays_data_through_xacro(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import xacro
    import xacro.substitution_args as sa

    # $(find pkg) is the one substitution left live (docs/packages.md): xacro gives the package's
    # folder where the robot is launched (ament_index there; a folder here)
    monkeypatch.setattr(sa, "_eval_find", lambda pkg: f"/opt/ws/share/{pkg}")

    spec = tmp_path / "tiny.yaml"
    assert cli("import", _write(tmp_path), "-o", spec).returncode == 0
    out = tmp_path / "gen"
    assert cli("generate", spec, "--out", out).returncode == 0
    doc = xacro.process_file(str(out / "tiny_description" / "urdf" / "tiny.urdf.xacro"))
    root = etree.fromstring(doc.toxml().encode())
    original = etree.fromstring(URDF.encode())
    for tag in ("gazebo", "transmission"):
        (a,) = original.findall(tag)
        (b,) = root.findall(tag)
        assert etree.tostring(b.find(".//material") if tag == "gazebo" else b.find("type")) is not None
        live = {"$(find evil)/x.so": "/opt/ws/share/evil/x.so"}
        assert [
            (e.tag, {k: live.get(v, v) for k, v in e.attrib.items()}, (e.text or "").strip()) for e in a.iter()
        ] == [(e.tag, dict(e.attrib), (e.text or "").strip()) for e in b.iter()]
    assert root.find("gazebo/material").text == "Gazebo/${colour}"  # never evaluated
    assert root.find("gazebo/plugin").get("filename") == "/opt/ws/share/evil/x.so"


def test_existing_output_is_not_replaced_without_force(tmp_path: Path) -> None:
    spec = tmp_path / "tiny.yaml"
    spec.write_text("mine\n")
    ran = cli("import", _write(tmp_path), "-o", spec)
    assert ran.returncode == 2 and "error[IMP007]" in ran.stderr
    assert spec.read_text() == "mine\n"
    assert cli("import", _write(tmp_path), "-o", spec, "--force").returncode == 0
    assert spec.read_text().startswith("# Imported from tiny.urdf")


def test_the_spec_is_written_with_the_mode_open_gives_under_the_umask(tmp_path: Path) -> None:
    """Written through a temporary file (mkstemp: 0600), then renamed: a teammate or a CI user
    must read it as any file the user makes."""
    import os

    old = os.umask(0o027)
    try:
        ran = cli("import", _write(tmp_path), "-o", tmp_path / "o.yaml")
    finally:
        os.umask(old)
    assert ran.returncode == 0, ran.stderr
    assert (tmp_path / "o.yaml").stat().st_mode & 0o777 == 0o640


def test_unusable_input_exits_2_without_traceback(tmp_path: Path) -> None:
    ran = cli("import", _write(tmp_path, "<robot name='x'><link name='a'></robot>"), "-o", tmp_path / "o.yaml")
    assert ran.returncode == 2 and "Traceback" not in ran.stderr and "error[" in ran.stderr
    assert not (tmp_path / "o.yaml").exists()


def test_a_round_trip_difference_exits_1_and_writes_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from descgen.commands.importer import spec as spec_writer

    real = spec_writer.quantity

    def off_by_a_micrometre(value: float, kind: str, unit: str) -> str | int:
        text = real(value, kind, unit)
        return "485.141 mm" if text == "485.14 mm" else text

    monkeypatch.setattr(spec_writer, "quantity", off_by_a_micrometre)
    out = tmp_path / "tiny.yaml"
    ran = cli("import", _write(tmp_path), "-o", out)
    assert ran.returncode == 1 and "error[IMP001]" in ran.stderr and "base_link" in ran.stderr
    assert not out.exists()


@pytest.mark.parametrize(
    "xml",
    [
        '<gazebo xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="x"/></gazebo>',
        "<link name='dup'/>",
        "<gazebo>",
    ],
)
def test_spec_refuses_pass_through_that_is_not_plain_xml(tmp_path: Path, xml: str) -> None:
    spec = tmp_path / "r.yaml"
    spec.write_text(yaml.safe_dump({"name": "r", "links": [{"name": "a"}], "passthrough": [{"xml": xml}]}))
    ran = cli("validate", spec)
    assert ran.returncode == 2 and "error[IMP010]" in ran.stderr


# -- the corpus: example-robot-data, compared with pinocchio ------------------------------------

CORPUS = [d for d in descriptions() if d[0].split("/")[0] in ("ur_description", "panda_description", "talos_data")]
SAMPLE = [d for d in CORPUS if d[0] in ("panda_description/urdf/panda.urdf", "talos_data/robots/talos_reduced.urdf")]


def _frames_and_inertias(urdf: Path, q: list[float] | None) -> tuple[dict[str, np.ndarray], list[np.ndarray]]:
    import pinocchio as pin

    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    pin.framesForwardKinematics(model, data, np.zeros(model.nq) if q is None else np.array(q))
    frames = {f.name: data.oMf[i].homogeneous for i, f in enumerate(model.frames)}
    inertias = [np.concatenate(([y.mass], y.lever, y.inertia.ravel())) for y in model.inertias]
    return frames, inertias


@pytest.mark.skipif(not SAMPLE, reason="example-robot-data is not installed")
@pytest.mark.parametrize(("ident", "urdf", "srdf"), SAMPLE, ids=[d[0] for d in SAMPLE])
def test_corpus_robot_generates_the_same_robot_for_pinocchio(
    tmp_path: Path, ident: str, urdf: Path, srdf: Path | None
) -> None:
    import pinocchio as pin

    spec = tmp_path / "r.yaml"
    args: list[str | Path] = ["import", urdf, "-o", spec, "--package-path", str(share())]
    if srdf is not None:
        args += ["--srdf", srdf]
    ran = cli(*args)
    assert ran.returncode == 0 and "round trip proven" in ran.stderr, ran.stderr[-2000:]
    # generate's own URDF, rendered in memory: generate itself also resolves package:// meshes,
    # which here live outside the project (site-packages)
    from descgen.audit.spec import load_spec_text
    from descgen.render import render_package

    robot = load_spec_text(spec.read_text(), "r.yaml", rules=False).robot
    written = tmp_path / "written.urdf"
    written.write_text(render_package(robot, "r.yaml")[f"urdf/{robot.name}.urdf"])
    model = pin.buildModelFromUrdf(str(urdf))
    rng = random.Random(ident)
    for _ in range(5):
        np.random.seed(rng.randrange(2**31))  # pinocchio draws from numpy's generator
        q = pin.randomConfiguration(model, *_bounded(model)).tolist()
        a, ia = _frames_and_inertias(urdf, q)
        b, ib = _frames_and_inertias(written, q)
        assert a.keys() == b.keys()
        for name in a:
            assert np.allclose(a[name], b[name], rtol=0, atol=1e-9), name
        for x, y in zip(ia, ib, strict=True):
            assert np.allclose(x, y, rtol=0, atol=1e-9)


def _bounded(model: object) -> tuple[np.ndarray, np.ndarray]:
    lo = np.array(model.lowerPositionLimit)  # type: ignore[attr-defined]
    hi = np.array(model.upperPositionLimit)  # type: ignore[attr-defined]
    lo = np.where(np.isfinite(lo), lo, -math.pi)
    hi = np.where(np.isfinite(hi), hi, math.pi)
    return lo, hi


# -- structure, known poses, semantics, package paths, audit parity ------------------------------

WHEELS = """<?xml version="1.0"?>
<robot name="cart">
  <link name="base_link"><visual><geometry><box size="0.4 0.3 0.1"/></geometry></visual></link>
  <link name="left_wheel"><visual><geometry><cylinder radius="0.05" length="0.02"/></geometry></visual>
    <inertial><mass value="0.5"/>
      <inertia ixx="0.000329" iyy="0.000329" izz="0.000625" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="right_wheel"><visual><geometry><cylinder radius="{radius}" length="0.02"/></geometry></visual>
    <inertial><mass value="0.5"/>
      <inertia ixx="0.000329" iyy="0.000329" izz="0.000625" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left_wheel"/>
    <origin xyz="0 0.2 0" rpy="-1.5707963267948966 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="right_wheel_joint" type="continuous"><parent link="base_link"/><child link="right_wheel"/>
    <origin xyz="0 -0.2 0" rpy="-1.5707963267948966 0 0"/><axis xyz="0 0 1"/></joint>
  <link name="cam_link"><visual><geometry><box size="0.02 0.08 0.02"/></geometry></visual></link>
  <joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="cam_link"/>
    <origin xyz="0.2 0 0.1"/></joint>
  <link name="cam_optical_frame"/>
  <joint name="cam_optical_joint" type="fixed"><parent link="cam_link"/><child link="cam_optical_frame"/>
    <origin xyz="0 0 0" rpy="{optical} 0 {optical}"/></joint>
</robot>
"""


def _import(tmp_path: Path, text: str, *extra: str | Path) -> tuple[dict, object]:
    src = tmp_path / "robot.urdf"
    src.write_text(text)
    spec = tmp_path / "robot.yaml"
    ran = cli("import", src, "-o", spec, *extra)
    assert ran.returncode == 0, ran.stderr
    return yaml.safe_load(spec.read_text()), ran


def test_identical_wheels_become_a_part_and_a_rep103_camera_a_sensor(tmp_path: Path) -> None:
    data, ran = _import(tmp_path, WHEELS.format(radius="0.05", optical="-1.5707963267948966"))
    assert "round trip proven" in ran.stderr  # type: ignore[attr-defined]
    (part,) = data["parts"]
    assert part["name"] == "wheel"  # the names' common ending
    assert [(i["link"], i["joint"]) for i in part["instances"]] == [
        ("left_wheel", "left_wheel_joint"),
        ("right_wheel", "right_wheel_joint"),
    ]
    (cam,) = data["sensors"]
    assert (cam["name"], cam["type"], cam["parent"]) == ("cam", "camera", "base_link")
    assert [lk["name"] for lk in data["links"]] == ["base_link"]
    # the generated URDF is the same robot for an independent parser
    import yourdfpy

    out = tmp_path / "gen"
    assert cli("generate", tmp_path / "robot.yaml", "--out", out).returncode == 0
    a = yourdfpy.URDF.load(str(tmp_path / "robot.urdf"), load_meshes=False)
    b = yourdfpy.URDF.load(str(out / "cart_description" / "urdf" / "cart.urdf"), load_meshes=False)
    assert sorted(a.link_map) == sorted(b.link_map)
    for name in a.link_map:
        assert np.allclose(a.get_transform(name), b.get_transform(name), rtol=0, atol=1e-12), name


def test_near_repeats_stay_links(tmp_path: Path) -> None:
    # one wheel 0.1 mm larger; an optical rotation rounded to 4 decimals is not REP 103's exact one
    data, _ = _import(tmp_path, WHEELS.format(radius="0.0501", optical="-1.5708"))
    assert "parts" not in data and "sensors" not in data
    assert {lk["name"] for lk in data["links"]} >= {"left_wheel", "right_wheel", "cam_optical_frame"}


ARM = """<?xml version="1.0"?>
<robot name="arm2">
  <link name="base"/><link name="upper"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="upper"/><child link="tool"/><origin xyz="0.3 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="tip"/>
  <joint name="tip_joint" type="fixed"><parent link="tool"/><child link="tip"/><origin xyz="0.2 0 0"/></joint>
</robot>
"""
SRDF = """<?xml version="1.0"?>
<robot name="arm2">
  <virtual_joint name="world_joint" type="floating" parent_frame="world" child_link="base"/>
  <group name="arm"><chain base_link="base" tip_link="upper"/><chain base_link="upper" tip_link="tip"/></group>
  <group name="whole"><joint name="world_joint"/></group>
  <group_state name="bent" group="arm"><joint name="j1" value="1.5707963267948966"/>
    <joint name="j2" value="-1.5707963267948966"/></group_state>
  <group_state name="placed" group="whole">
    <joint name="world_joint" value="0 0 0 0 0 0 1"/></group_state>
</robot>
"""


def test_known_poses_pin_the_tips_and_semantics_keep_every_chain(tmp_path: Path) -> None:
    (tmp_path / "arm2.srdf").write_text(SRDF)
    data, ran = _import(tmp_path, ARM, "--srdf", tmp_path / "arm2.srdf")
    assert "round trip proven" in ran.stderr  # type: ignore[attr-defined]
    arm = data["semantic"]["groups"][0]
    assert arm["chain"] == {"base": "base", "tip": "upper"} and arm["chains"] == [{"base": "upper", "tip": "tip"}]
    poses = {p["name"]: p for p in data["known_poses"]}
    assert set(poses) == {"zero", "bent", "placed"}  # one per group state, the multi-DOF one too
    assert "not a measurement" in poses["zero"]["description"]
    # by hand: at zero the tip is at x = 0.3 + 0.2; bent: j1 +90 deg puts upper's x along y,
    # j2 -90 deg turns back to x: tip at (0.2, 0.3, 0)
    assert poses["zero"]["frames"] == [{"frame": "tip", "xyz": ["500 mm", 0, 0], "tolerance": "0.001 mm"}]
    upper, tip = poses["bent"]["frames"]  # the tips of the group's two chains
    assert (upper["frame"], upper["xyz"]) == ("upper", [0, 0, 0])
    assert tip["frame"] == "tip"
    assert [units.to_si(str(v), "length") for v in tip["xyz"]] == pytest.approx([0.2, 0.3, 0.0], abs=1e-15)
    assert poses["bent"]["joints"] == {"j1": "90 deg", "j2": "-90 deg"}
    # the floating virtual joint's value is kept as a list (MoveIt's order), sourced at the
    # group state's SRDF line (counted by hand), and no longer reported as lost
    line = SRDF.splitlines().index('  <group_state name="placed" group="whole">') + 1
    placed = next(s for s in data["semantic"]["group_states"] if s["name"] == "placed")
    assert placed["joints"] == {"world_joint": {"value": [0, 0, 0, 0, 0, 0, 1], "source": f"arm2.srdf:{line}"}}
    assert "IMP011" not in ran.stderr  # type: ignore[attr-defined]
    assert cli("validate", tmp_path / "robot.yaml").returncode == 0
    ran_poses = cli("poses", tmp_path / "robot.yaml")
    assert ran_poses.returncode == 0, ran_poses.stdout + ran_poses.stderr


def test_package_meshes_record_package_paths_relative_to_the_spec(tmp_path: Path) -> None:
    pkg = tmp_path / "vendor" / "acme_meshes"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>acme_meshes</name></package>")
    (pkg / "meshes" / "base.stl").write_text("solid s\nendsolid s\n")
    src = tmp_path / "robot.urdf"
    src.write_text(
        '<robot name="m"><link name="base_link"><visual><geometry>'
        '<mesh filename="package://acme_meshes/meshes/base.stl"/></geometry></visual></link></robot>'
    )
    spec = tmp_path / "specs" / "m.yaml"
    ran = cli("import", src, "-o", spec, "--package-path", tmp_path / "vendor")
    assert ran.returncode == 0, ran.stderr
    assert yaml.safe_load(spec.read_text())["package_paths"] == ["../vendor"]
    assert cli("validate", spec).returncode == 0
    # a package outside the spec's project is recorded relative to the spec all the same (a
    # workspace beside the project), and every later command finds it without options
    elsewhere = tmp_path / "elsewhere" / "project" / "specs" / "m.yaml"
    far = cli("import", src, "-o", elsewhere, "--package-path", tmp_path / "vendor")
    assert far.returncode == 0, far.stderr
    assert yaml.safe_load(elsewhere.read_text())["package_paths"] == ["../../../vendor"]
    assert cli("validate", elsewhere).returncode == 0


def test_a_package_the_environment_finds_is_not_recorded(
    tmp_path: Path, tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch
) -> None:
    # an install prefix as colcon and ament lay it out: share/<pkg> and the ament index's marker,
    # away from the description (import also looks beside it)
    prefix = tmp_path_factory.mktemp("ws") / "install"
    pkg = prefix / "share" / "acme_meshes"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>acme_meshes</name></package>")
    (pkg / "meshes" / "base.stl").write_text("solid s\nendsolid s\n")
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / "acme_meshes"
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    src = tmp_path / "robot.urdf"
    src.write_text(
        '<robot name="m"><link name="base_link"><visual><geometry>'
        '<mesh filename="package://acme_meshes/meshes/base.stl"/></geometry></visual></link></robot>'
    )
    spec = tmp_path / "specs" / "m.yaml"
    assert cli("import", src, "-o", spec).returncode == 0  # not found: GEOM004 in the audit, spec written
    assert cli("validate", spec).returncode == 2  # SPEC062: the package is nowhere
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    spec.unlink()
    ran = cli("import", src, "-o", spec)
    assert ran.returncode == 0, ran.stderr
    assert "package_paths" not in yaml.safe_load(spec.read_text())  # this machine's install is not the spec's
    assert cli("validate", spec).returncode == 0  # found again through the sourced environment


DEFECTS = """<?xml version="1.0"?>
<robot name="broken">
  <link name="base_link"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="5" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <link name="arm"/>
  <joint name="elbow" type="revolute"><parent link="base_link"/><child link="arm"/><axis xyz="0 0 2"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_audit_of_the_imported_spec_finds_what_the_audit_of_the_file_finds(tmp_path: Path) -> None:
    from descgen.read.description import Options, audit

    src = tmp_path / "broken.urdf"
    src.write_text(DEFECTS)  # planted: inverted limits, a non-unit axis, inertia breaking the triangle rule
    spec = tmp_path / "broken.yaml"
    ran = cli("import", src, "-o", spec)
    assert ran.returncode == 0, ran.stderr
    original = {(f.code, f.subject) for f in audit(src, Options())}
    assert {"joint:elbow", "link:base_link"} <= {s for _, s in original}  # the planted defects are seen
    assert {(f.code, f.subject) for f in audit(spec, Options())} == original


@pytest.mark.skipif(not CORPUS, reason="example-robot-data is not installed")
@pytest.mark.parametrize("ident", ["panda_description/urdf/panda.urdf", "tiago_description/robots/tiago.urdf"])
def test_audit_parity_on_corpus_robots(tmp_path: Path, ident: str) -> None:
    from descgen.commands.importer.run import ImportOptions, import_description
    from descgen.read.description import Options, audit

    ((_, urdf, srdf),) = [d for d in descriptions() if d[0] == ident]
    paths = (share(),)
    spec = tmp_path / "r.yaml"
    outcome = import_description(urdf, ImportOptions(Options(srdf=srdf, package_paths=paths), spec_name=str(spec)))
    spec.write_text(outcome.imported.spec_text)
    original = {(f.code, f.subject) for f in audit(urdf, Options(srdf=srdf, package_paths=paths))}
    assert {(f.code, f.subject) for f in audit(spec, Options(package_paths=paths))} == original


def test_a_group_state_without_a_group_is_left_out_as_moveit_leaves_it(tmp_path: Path) -> None:
    """z1.srdf's states 'home' and 'arm_up' name no group: srdfdom requires one and skips the
    state, so MoveIt never has them. Import used to write group: '' (SPEC050: the spec could not
    be generated); now it leaves them out, says so (IMP040), and the robot generates."""
    root = share()
    if root is None:
        pytest.fail("example-robot-data is not installed (the test extra installs it)")
    robots = root / "example-robot-data" / "robots" / "z1_description"
    srdf = robots / "srdf" / "z1.srdf"
    assert etree.parse(str(srdf)).xpath("count(//group_state[not(@group)])") == 2
    spec = tmp_path / "z1.yaml"
    ran = cli("import", robots / "urdf" / "z1.urdf", "--srdf", srdf, "--package-path", root, "-o", spec)
    assert ran.returncode == 0, ran.stderr
    assert ran.stderr.count("warning[IMP040]") == 2
    states = yaml.safe_load(spec.read_text())["semantic"].get("group_states", [])
    assert all(s["group"] for s in states) and not {"home", "arm_up"} & {s["name"] for s in states}
    assert cli("generate", spec, "--out", tmp_path / "gen", "--package-path", root).returncode == 0
