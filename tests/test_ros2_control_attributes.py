"""The ``<ros2_control>`` block's own attributes as Jazzy's component_parser reads them (jazzy,
hardware_interface >= 4.43.0: attribute values stripped of blanks, booleans true/false in any case;
docs/ros2_control_parser_jazzy.md), in the model an audit builds, so that audit and import judge
the same block."""

from __future__ import annotations

from pathlib import Path

import pytest

from descgen.read.description import Options, load_description

URDF = """<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <ros2_control name="first" type="{type}" {async_attr}>
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>
  <ros2_control name="second">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
  </ros2_control>
</robot>
"""


@pytest.mark.parametrize(
    ("kind", "attr", "expected"),
    [
        ("actuator", 'is_async=" TRUE "', True),
        ("system", 'is_async="false"', False),
        (" sensor ", "", None),
        ("system", 'is_async="yes"', None),  # parse_bool throws: not a boolean the model can hold
    ],
)
def test_block_type_and_is_async_are_read(tmp_path: Path, kind: str, attr: str, expected: bool | None) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(URDF.replace("{type}", kind).replace("{async_attr}", attr))
    robot, _ = load_description(path, Options())
    rc = robot.ros2_control
    assert rc is not None
    first, second = rc.hardware_blocks()
    assert (first.name, first.type, first.is_async) == ("first", kind.strip(), expected)
    assert (second.name, second.type, second.is_async) == ("second", "system", None)  # the parser's default
    assert rc.is_async is expected


def test_a_block_jazzy_refuses_is_one_verdict_from_import_to_audit(tmp_path: Path) -> None:
    """tests/rules/CTRL066/bad3.urdf holds four places Jazzy's parser throws. import keeps the
    block verbatim (pass-through) and waives the four as imported; validate and check judge the
    pass-through as audit judges the generated URDF: the same four, waived, and no error left."""
    from .conftest import ROOT
    from .helpers import cli

    spec = tmp_path / "specs" / "a.yaml"
    ran = cli("import", ROOT / "tests" / "rules" / "CTRL066" / "bad3.urdf", "-o", spec, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-1500:]
    ran = cli("validate", spec, cwd=tmp_path)
    assert ran.returncode == 0 and ran.stderr.count("[CTRL066]") == 4, ran.stderr[-2000:]
    assert cli("generate", spec, cwd=tmp_path).returncode == 0
    assert cli("check", spec, cwd=tmp_path).returncode == 0
    urdf = tmp_path / "generated" / "arm_description" / "urdf" / "arm.urdf"
    ran = cli("audit", urdf, cwd=tmp_path)
    assert ran.returncode == 0 and "0 error, 1 warning, 0 info, 4 waived" in ran.stdout, ran.stdout + ran.stderr[-1500:]
    ran = cli("audit", urdf, "--no-waivers", cwd=tmp_path)
    assert ran.returncode == 1 and ran.stderr.count("error[CTRL066]") == 4, ran.stderr[-1500:]
