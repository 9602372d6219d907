"""An SRDF shipped as ``*.srdf.xacro`` is expanded as xacro expands it (issue 28), and a file that is
no SRDF is refused (READ047), never read as an empty one. The fixture's defect is checked with
the real xacro and lxml first, so the test does not rest on descgen's reading of it."""

from __future__ import annotations

from pathlib import Path

import xacro
from lxml import etree

from .helpers import cli

RULES = Path(__file__).resolve().parent / "rules"
URDF = RULES / "SRDF002" / "good.urdf"  # elbow_joint: limit lower=-2 upper=2

SRDF_XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="elbow_home" default="3"/>
  <xacro:macro name="arm_groups" params="prefix">
    <group name="${prefix}arm">
      <chain base_link="base_link" tip_link="tool_link"/>
    </group>
    <group_state name="home" group="${prefix}arm">
      <joint name="shoulder_joint" value="0"/>
      <joint name="elbow_joint" value="$(arg elbow_home)"/>
    </group_state>
  </xacro:macro>
  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>
  <xacro:arm_groups prefix=""/>
</robot>
"""


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_fixture_plants_a_state_outside_the_limits_as_xacro_expands_it(tmp_path: Path) -> None:
    doc = xacro.process_file(str(_write(tmp_path, "arm.srdf.xacro", SRDF_XACRO)))
    root = etree.fromstring(doc.toxml().encode())
    (elbow,) = root.findall("group_state/joint[@name='elbow_joint']")
    assert float(elbow.get("value")) == 3.0  # the URDF allows [-2, 2]


def test_an_srdf_xacro_is_expanded_and_its_defect_found(tmp_path: Path) -> None:
    srdf = _write(tmp_path, "arm.srdf.xacro", SRDF_XACRO)
    ran = cli("audit", URDF, "--srdf", srdf)
    assert ran.returncode == 1, ran.stderr
    # where the state is written (line 8, in the macro) and the call that expanded it (line 14)
    assert f"{srdf}:8:5: error[SRDF002]: state 'home' sets 'elbow_joint'" in ran.stderr, ran.stderr
    assert f"in macro called from {srdf}:14:3" in ran.stderr
    # the same --xacro-arg as a URDF Xacro takes: a value inside the limits, no finding
    ok = cli("audit", URDF, "--srdf", srdf, "--xacro-arg", "elbow_home:=1")
    assert "[SRDF002]" not in ok.stderr, ok.stderr


def test_a_urdf_given_as_the_srdf_is_refused(tmp_path: Path) -> None:
    ran = cli("audit", URDF, "--srdf", URDF)
    assert ran.returncode == 2
    assert "error[READ047]: not an SRDF: it has <link> and <joint> elements: it is a URDF" in ran.stderr


def test_an_srdf_xacro_not_named_so_is_refused_not_read_as_empty(tmp_path: Path) -> None:
    srdf = _write(tmp_path, "arm.srdf", SRDF_XACRO)
    ran = cli("audit", URDF, "--srdf", srdf)
    assert ran.returncode == 2
    assert f"{srdf}:2:" in ran.stderr and "error[READ047]: not an SRDF: it still holds Xacro" in ran.stderr


def test_a_file_of_another_kind_is_refused(tmp_path: Path) -> None:
    ran = cli("audit", URDF, "--srdf", _write(tmp_path, "x.srdf", "<launch/>\n"))
    assert ran.returncode == 2 and "error[READ047]: not an SRDF: its root is <launch>, not <robot>" in ran.stderr


def test_import_reads_the_srdf_xacro_not_an_empty_srdf(tmp_path: Path) -> None:
    import yaml

    from descgen.commands.importer.run import ImportOptions, import_description
    from descgen.read.description import Options

    srdf = _write(tmp_path, "arm.srdf.xacro", SRDF_XACRO)
    outcome = import_description(URDF, ImportOptions(Options(srdf=srdf, xacro_args={"elbow_home": "1"})))
    semantic = yaml.safe_load(outcome.imported.spec_text)["semantic"]
    assert [g["name"] for g in semantic["groups"]] == ["arm"]
    (home,) = semantic["group_states"]
    assert home["name"] == "home" and home["group"] == "arm"
    assert home["joints"]["elbow_joint"]["value"] == "1 rad"  # the --xacro-arg value, not the default 3
    assert outcome.proven
