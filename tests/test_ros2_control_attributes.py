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


# -- rw_rate, thread_priority and <hardware><group>: read, kept in the spec, written back ------------

BLOCKS = Path(__file__).parent / "data" / "ros2_control_blocks" / "rates_and_groups.urdf"


def test_rates_priority_and_group_are_read_as_the_parser_reads_them() -> None:
    robot, _ = load_description(BLOCKS)
    assert robot.ros2_control is not None
    got = [(b.name, b.rw_rate, b.thread_priority, b.group) for b in robot.ros2_control.hardware_blocks()]
    # the file, by hand: arm is async at 50 Hz with priority 30; gripper 25 Hz, not async; both in bus1
    assert got == [("arm", 50, 30, "bus1"), ("gripper", 25, None, "bus1")]


@pytest.mark.parametrize(
    ("rate", "priority", "is_async", "expected"),
    [
        ("50abc", None, "false", (50, None)),  # std::stoi reads the leading integer
        (" 20 ", None, "false", (20, None)),  # stripped first
        ("-5", None, "false", (None, None)),  # the parser throws (CTRL066): no rate
        (None, "30", "false", (None, None)),  # read only for an async block
        (None, "0", "true", (None, None)),  # [1-9][0-9]*: the parser throws
    ],
)
def test_odd_values_read_as_the_parser_would(
    tmp_path: Path, rate: str | None, priority: str | None, is_async: str, expected: tuple[object, object]
) -> None:
    attrs = f'is_async="{is_async}"' + (f' rw_rate="{rate}"' if rate is not None else "")
    attrs += f' thread_priority="{priority}"' if priority is not None else ""
    path = tmp_path / "r.urdf"
    path.write_text(URDF.format(type="system", async_attr=attrs))
    robot, _ = load_description(path)
    assert robot.ros2_control is not None
    first = robot.ros2_control.hardware_blocks()[0]
    assert (first.rw_rate, first.thread_priority) == expected


def test_import_keeps_them_in_the_spec_and_generate_writes_them_back(tmp_path: Path) -> None:
    import yaml
    from lxml import etree

    from tests.helpers import cli

    spec = tmp_path / "specs" / "duo.yaml"
    r = cli("import", BLOCKS, "-o", spec)
    assert r.returncode == 0 and "round trip proven" in r.stdout + r.stderr, r.stderr[-2000:]
    data = yaml.safe_load(spec.read_text())
    rc = data["ros2_control"]
    assert (rc["rw_rate"], rc["thread_priority"], rc["hardware"]["group"]) == ("50 Hz", 30, "bus1")
    assert (rc["blocks"][0]["rw_rate"], rc["blocks"][0]["hardware"]["group"]) == ("25 Hz", "bus1")
    assert "passthrough" not in data
    assert cli("generate", spec).returncode == 0
    urdf = etree.parse(str(tmp_path / "generated" / "duo_description" / "urdf" / "duo.urdf")).getroot()
    written = [
        (b.get("rw_rate"), b.get("thread_priority"), b.findtext("hardware/group")) for b in urdf.iter("ros2_control")
    ]
    assert written == [("50", "30", "bus1"), ("25", None, "bus1")]


def test_a_rate_written_otherwise_than_plainly_stays_verbatim(tmp_path: Path) -> None:
    from tests.helpers import cli

    odd = tmp_path / "odd.urdf"
    odd.write_text(BLOCKS.read_text().replace('rw_rate="25"', 'rw_rate="25abc"'))
    spec = tmp_path / "specs" / "odd.yaml"
    r = cli("import", odd, "-o", spec)
    assert r.returncode == 0, r.stderr[-2000:]
    import yaml

    assert "IMP021" in r.stderr  # the block is kept as written, in pass-through
    kept = [p["xml"] for p in yaml.safe_load(spec.read_text())["passthrough"]]
    assert any('rw_rate="25abc"' in x for x in kept)


@pytest.mark.parametrize(
    ("added", "code"),
    [("  rw_rate: 12.5 Hz\n", "SPEC146"), ("  thread_priority: 40\n", "SPEC147")],
)
def test_a_rate_or_priority_ros2_control_would_misread_is_refused(tmp_path: Path, added: str, code: str) -> None:
    import shutil

    from tests.helpers import ROOT, cli

    shutil.copytree(ROOT / "specs", tmp_path / "specs")
    spec = tmp_path / "specs" / "warehouse_arm.yaml"
    text = spec.read_text()
    anchor = "  update_rate: 100 Hz\n"
    assert anchor in text
    spec.write_text(text.replace(anchor, anchor + added, 1))
    r = cli("validate", spec)
    assert r.returncode == 2 and f"error[{code}]" in r.stderr, r.stderr[-2000:]
