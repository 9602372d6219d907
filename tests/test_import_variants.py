"""``descgen import --variant``: one spec with a Xacro's hardware variants, each proven.

Oracles: lxml on the original expansions (each variant expanded on its own, as a user would
with xacro), yaml.safe_load on the written spec; the generated Xacro expanded per hardware:=
value is compared with the original expansion of that variant.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen.cli import main
from descgen.read.xacro_file import expand_located
from tests.helpers import ROOT, cli

CORPUS = ROOT / "tests" / "data" / "xacro_corpus"
DIFFBOT = CORPUS / "ros2_control_demo_example_2" / "urdf" / "diffbot.urdf.xacro"
MOCK, REAL = "mock:use_mock_hardware:=true", "real:use_mock_hardware:=false"


def _expand(path: Path, args: dict[str, str], paths: tuple[Path, ...] = (CORPUS,)) -> etree._Element:
    xml = expand_located(path, str(path), args, paths, False).xml
    return etree.fromstring(xml, etree.XMLParser(remove_comments=True, resolve_entities=False))


def _hardware(root: etree._Element) -> list[tuple[str, str, dict[str, str]]]:
    return [
        (
            b.get("name", ""),
            (b.findtext("hardware/plugin") or "").strip(),
            {p.get("name", ""): (p.text or "").strip() for p in b.findall("hardware/param")},
        )
        for b in root.findall("ros2_control")
    ]


def _import(capsys: pytest.CaptureFixture[str], tmp_path: Path, path: Path, *extra: str) -> tuple[int, str]:
    out = tmp_path / "robot.yaml"
    code = main(["import", str(path), "--package-path", str(CORPUS), "-o", str(out), *extra])
    return code, capsys.readouterr().err


def _spec_hardware(spec: Path) -> dict[str, object]:
    return yaml.safe_load(spec.read_text())["ros2_control"]["hardware"]  # type: ignore[no-any-return]


def _canonical(block: etree._Element, drop: set[tuple[str, str, str]]) -> bytes:
    """The block as C14N bytes without the params generate adds (IMP022); layout and the
    spelling of an interface param's number (0.0 or 0) are not data. Hardware params stay text."""
    b = etree.fromstring(etree.tostring(block))
    for owner in b:
        for iface in owner if isinstance(owner.tag, str) else ():
            for p in list(iface.findall("param")):
                if (owner.get("name"), iface.get("name"), p.get("name")) in drop:
                    iface.remove(p)
    for e in b.iter():
        e.tail = None
        if len(e):
            e.text = None
        elif e.text is not None:
            e.text = e.text.strip()
    for p in b.iterfind("*/*/param"):  # interface params: ros2_control reads them with stod
        p.text = repr(float(p.text or ""))
    return etree.tostring(b, method="c14n")


def test_diffbot_mock_and_real_variants_are_one_proven_spec(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, err = _import(capsys, tmp_path, DIFFBOT, "--variant", MOCK, "--variant", REAL)
    assert code == 0, err
    assert "round trip proven" in err and "IMP030" in err and "IMP020" not in err
    hw = _spec_hardware(tmp_path / "robot.yaml")
    ((_, mock_plugin, mock_params),) = _hardware(_expand(DIFFBOT, {"use_mock_hardware": "true"}))
    ((_, real_plugin, real_params),) = _hardware(_expand(DIFFBOT, {"use_mock_hardware": "false"}))
    assert hw == {
        "plugin": mock_plugin,
        "params": mock_params,
        "variants": {"real": {"plugin": real_plugin, "params": real_params}},
    }


def test_the_order_of_variants_does_not_matter(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # a bug taking the first variant as the spec's own hardware would write the vendor plugin there
    code, err = _import(capsys, tmp_path, DIFFBOT, "--variant", REAL, "--variant", MOCK)
    assert code == 0, err
    assert _spec_hardware(tmp_path / "robot.yaml")["plugin"] == "mock_components/GenericSystem"


@pytest.mark.parametrize(
    ("variants", "code_"),
    [
        ((MOCK,), "IMP027"),  # one variant: nothing to vary
        ((REAL, "gazebo:use_mock_hardware:=false"), "IMP027"),  # no mock
        ((MOCK, MOCK), "IMP027"),  # twice
        (("mock:use_mock_hardware:=false", "real:use_mock_hardware:=true"), "IMP029"),  # swapped
        ((MOCK, "gazebo:use_mock_hardware:=false"), "IMP029"),  # not gz_ros2_control
    ],
)
def test_unusable_variant_sets_are_refused(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, variants: tuple[str, ...], code_: str
) -> None:
    code, err = _import(capsys, tmp_path, DIFFBOT, *(a for v in variants for a in ("--variant", v)))
    assert code == 2 and f"error[{code_}]" in err, err
    assert "Traceback" not in err and not (tmp_path / "robot.yaml").exists()


def _robot_package(tmp_path: Path, changes_link: bool) -> Path:
    """A Xacro whose argument ``sim`` switches the hardware and, with ``changes_link``, a link."""
    pkg = tmp_path / "varbot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>varbot</name></package>")
    radius = "${0.06 if sim else 0.05}" if changes_link else "0.05"
    (pkg / "urdf" / "varbot.urdf.xacro").write_text(
        f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="varbot">
  <xacro:arg name="sim" default="false"/>
  <xacro:property name="sim" value="$(arg sim)"/>
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="arm">
    <visual><geometry><cylinder radius="{radius}" length="0.2"/></geometry></visual>
    <inertial><mass value="0.5"/><inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="2"/>
  </joint>
  <ros2_control name="varbot" type="system">
    <hardware>
      <xacro:if value="${{sim}}"><plugin>gz_ros2_control/GazeboSimSystem</plugin></xacro:if>
      <xacro:unless value="${{sim}}"><plugin>mock_components/GenericSystem</plugin></xacro:unless>
    </hardware>
    <joint name="j1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""
    )
    return pkg / "urdf" / "varbot.urdf.xacro"


def test_a_variant_that_changes_a_link_is_refused(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = _robot_package(tmp_path, changes_link=True)
    code, err = _import(capsys, tmp_path, path, "--variant", "mock:sim:=false", "--variant", "gazebo:sim:=true")
    assert code == 2, err
    (line,) = [x for x in err.splitlines() if "error[IMP028]" in x]
    assert "link[@name='arm']" in line or "arm" in line
    assert "radius" in line and "0.05" in line and "0.06" in line  # the first difference, named
    assert not (tmp_path / "robot.yaml").exists()


def test_a_gazebo_variant_round_trips_through_the_generated_xacro(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = _robot_package(tmp_path, changes_link=False)
    code, err = _import(capsys, tmp_path, path, "--variant", "mock:sim:=false", "--variant", "gazebo:sim:=true")
    assert code == 0, err
    assert _spec_hardware(tmp_path / "robot.yaml") == {
        "plugin": "mock_components/GenericSystem",
        "variants": {"gazebo": {"plugin": "gz_ros2_control/GazeboSimSystem"}},
    }


def test_the_round_trip_proves_each_variant(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A renderer that writes the real variant's params wrongly must fail the import (exit 1)."""
    from descgen.commands.importer import variants

    real = variants.hardware

    def wrong(ex: tuple[variants.Expanded, ...], where: object) -> dict[str, dict[str, object]]:
        out = real(ex, where)  # type: ignore[arg-type]
        for hw in out.values():
            hw["variants"]["real"]["params"]["example_param_hw_stop_duration_sec"] = "4.0"
        return out

    monkeypatch.setattr(variants, "hardware", wrong)
    code, err = _import(capsys, tmp_path, DIFFBOT, "--variant", MOCK, "--variant", REAL)
    assert code == 1 and "hardware:=real" in err and "IMP001" in err, err
    assert not (tmp_path / "robot.yaml").exists()


# -- UR: ur5e with use_mock_hardware true/false, the real UR driver's plugin and params ----------

# The hardware selection of ur_robot_driver's urdf/ur.ros2_control.xacro (Universal_Robots_ROS2_Driver,
# jazzy): use_mock_hardware picks mock_components/GenericSystem, else ur_robot_driver's plugin with
# its connection params. The driver is not vendored; this wrapper reuses ur_description's macros.
_UR_CONTROL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find ur_description)/urdf/inc/ur_joint_control.xacro" />
  <xacro:include filename="$(find ur_description)/urdf/inc/ur_sensors.xacro" />
  <xacro:macro name="ur_ros2_control" params="name tf_prefix use_mock_hardware:=false mock_sensor_commands:=false
      robot_ip initial_positions">
    <ros2_control name="${name}" type="system">
      <hardware>
        <xacro:if value="${use_mock_hardware}">
          <plugin>mock_components/GenericSystem</plugin>
          <param name="mock_sensor_commands">${mock_sensor_commands}</param>
          <param name="state_following_offset">0.0</param>
          <param name="calculate_dynamics">true</param>
        </xacro:if>
        <xacro:unless value="${use_mock_hardware}">
          <plugin>ur_robot_driver/URPositionHardwareInterface</plugin>
          <param name="robot_ip">${robot_ip}</param>
          <param name="script_filename">/opt/ur/external_control.urscript</param>
          <param name="output_recipe_filename">/opt/ur/rtde_output_recipe.txt</param>
          <param name="input_recipe_filename">/opt/ur/rtde_input_recipe.txt</param>
          <param name="headless_mode">false</param>
          <param name="reverse_port">50001</param>
          <param name="script_sender_port">50002</param>
          <param name="tf_prefix">${tf_prefix}</param>
          <param name="non_blocking_read">true</param>
          <param name="servoj_gain">2000</param>
          <param name="servoj_lookahead_time">0.03</param>
          <param name="use_tool_communication">false</param>
          <param name="keep_alive_count">2</param>
        </xacro:unless>
      </hardware>
      <xacro:ur_joint_control_description tf_prefix="${tf_prefix}" initial_positions="${initial_positions}"/>
      <xacro:ur_sensors tf_prefix="${tf_prefix}"/>
    </ros2_control>
  </xacro:macro>
</robot>
"""


def _ur_package(tmp_path: Path) -> Path:
    pkg = tmp_path / "ur_variants"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>ur_variants</name></package>")
    (pkg / "urdf" / "ur.ros2_control.xacro").write_text(_UR_CONTROL)
    top = (CORPUS / "ur_description" / "urdf" / "ur_mocked.urdf.xacro").read_text()
    top = top.replace("$(find ur_description)/urdf/ros2_control_mock_hardware.xacro", "ur.ros2_control.xacro")
    top = top.replace(
        '<xacro:arg name="mock_sensor_commands" default="false" />',
        '<xacro:arg name="mock_sensor_commands" default="false" />\n  <xacro:arg name="use_mock_hardware" '
        'default="false" />\n  <xacro:arg name="robot_ip" default="192.168.56.101" />',
    )
    top = top.replace(
        'mock_sensor_commands="$(arg mock_sensor_commands)"',
        'mock_sensor_commands="$(arg mock_sensor_commands)"\n    use_mock_hardware="$(arg use_mock_hardware)"\n'
        '    robot_ip="$(arg robot_ip)"',
    )
    assert top.count("use_mock_hardware") == 3 and "ur.ros2_control.xacro" in top
    (pkg / "urdf" / "ur.urdf.xacro").write_text(top)
    return pkg / "urdf" / "ur.urdf.xacro"


@pytest.mark.slow
def test_ur5e_mock_and_real_hardware(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = _ur_package(tmp_path)
    common = {"ur_type": "ur5e", "name": "ur5e"}
    code, err = _import(
        capsys,
        tmp_path,
        path,
        *("--xacro-arg", "ur_type:=ur5e", "--xacro-arg", "name:=ur5e"),
        *("--variant", MOCK, "--variant", REAL),
    )
    assert code == 0, err
    spec = tmp_path / "robot.yaml"
    hw = _spec_hardware(spec)
    ((_, mock_plugin, mock_params),) = _hardware(_expand(path, common | {"use_mock_hardware": "true"}))
    real_root = _expand(path, common | {"use_mock_hardware": "false"})
    ((_, real_plugin, real_params),) = _hardware(real_root)
    assert real_plugin == "ur_robot_driver/URPositionHardwareInterface" and len(real_params) == 13
    # YAML may read '2000' back as text or a number: the spec keeps each param's text
    assert {k: str(v) for k, v in hw["variants"]["real"]["params"].items()} == real_params  # type: ignore[index]
    assert (hw["plugin"], {k: str(v) for k, v in hw["params"].items()}) == (mock_plugin, mock_params)  # type: ignore[index]

    # generate, check, and each variant's generated block against the original (lxml C14N)
    out = tmp_path / "gen"
    for cmd in ("generate", "check"):
        ran = cli(cmd, spec, "--out", out, "--package-path", CORPUS, cwd=tmp_path)
        assert ran.returncode == 0, ran.stderr[-2000:]
    (package,) = out.iterdir()
    xacro = package / "urdf" / "ur5e.urdf.xacro"
    for name, args in (("mock", {"use_mock_hardware": "true"}), ("real", {"use_mock_hardware": "false"})):
        ((original,),) = [_expand(path, common | args).findall("ros2_control")]
        ((written,),) = [_expand(xacro, {"hardware": name}, (out,)).findall("ros2_control")]
        # IMP022: generate adds command min/max and state initial_value where the original has none
        mine = {(o.get("name"), i.get("name"), p.get("name")) for o in original for i in o for p in i.findall("param")}
        added = {
            key
            for o in written
            for i in o
            for p in i.findall("param")
            if (key := (o.get("name"), i.get("name"), p.get("name"))) not in mine
        }
        assert all(k[2] in ("min", "max", "initial_value") for k in added), added
        assert _canonical(original, set()) == _canonical(written, added), name
