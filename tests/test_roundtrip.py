"""The read-back comparisons catch any single edited field of the written files."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.prove.semantic_roundtrip import controllers_roundtrip, ros2_control_roundtrip, srdf_roundtrip
from descgen.prove.urdf_roundtrip import urdf_roundtrip
from descgen.render import render_package

from .conftest import EXAMPLE

ROBOT = load_spec(EXAMPLE).robot
FILES = render_package(ROBOT, "specs/warehouse_arm.yaml")
URDF = "urdf/warehouse_arm.urdf"
SRDF = "srdf/warehouse_arm.srdf"


def test_clean_files_compare_equal() -> None:
    where = Path("/pkg")
    assert urdf_roundtrip(FILES, ROBOT, where) == []
    assert ros2_control_roundtrip(FILES, ROBOT, where) == []
    assert srdf_roundtrip(FILES, ROBOT, where) == []
    assert controllers_roundtrip(FILES, ROBOT, where) == []


def test_yourdfpy_loads_the_urdf() -> None:
    import yourdfpy

    urdf = yourdfpy.URDF.load(io.StringIO(FILES[URDF]), build_scene_graph=True, load_meshes=False)
    assert urdf.validate()
    assert set(urdf.actuated_joint_names) == {
        "left_wheel_joint",
        "right_wheel_joint",
        "lift_joint",
        "shoulder_pan_joint",
        "shoulder_lift_joint",
        "elbow_joint",
    }


def _mutated(value: str, attr: str) -> str:
    tokens = value.split()
    try:
        numbers = [float(t) for t in tokens]
    except ValueError:
        if attr == "type":
            return {
                "revolute": "prismatic",
                "prismatic": "revolute",
                "continuous": "revolute",
                "fixed": "continuous",
                "system": "actuator",
                "planar": "fixed",
            }.get(value, value + "x")
        return value + "_x"
    numbers[0] += 0.001
    return " ".join(repr(n) for n in numbers)


def _fields(text: str) -> list[tuple[int, str | None]]:
    """(element index, attribute name or None for the element's text) for every field."""
    root = etree.fromstring(text.encode())
    out: list[tuple[int, str | None]] = []
    for i, e in enumerate(root.iter()):
        if not isinstance(e.tag, str):
            continue
        out += [(i, a) for a in e.attrib]
        if e.text and e.text.strip():
            out.append((i, None))
    return out


def _mutate(text: str, index: int, attr: str | None) -> str:
    root = etree.fromstring(text.encode())
    e = list(root.iter())[index]
    if attr is None:
        e.text = _mutated(e.text.strip(), "")
    else:
        e.set(attr, _mutated(e.get(attr), attr))
    return etree.tostring(root, encoding="unicode")


URDF_FIELDS = _fields(FILES[URDF])
SRDF_FIELDS = _fields(FILES[SRDF])


def test_there_are_many_fields() -> None:
    assert len(URDF_FIELDS) > 300 and len(SRDF_FIELDS) > 40


@pytest.mark.parametrize(("index", "attr"), URDF_FIELDS)
def test_every_urdf_field_edit_is_reported(index: int, attr: str | None) -> None:
    files = dict(FILES)
    files[URDF] = _mutate(FILES[URDF], index, attr)
    found = urdf_roundtrip(files, ROBOT, Path("/pkg")) + ros2_control_roundtrip(files, ROBOT, Path("/pkg"))
    assert found, f"edit of element {index} {attr} went unnoticed"
    assert all(f.severity == "error" and f.code in ("GEN030", "GEN032") for f in found)


@pytest.mark.parametrize(("index", "attr"), SRDF_FIELDS)
def test_every_srdf_field_edit_is_reported(index: int, attr: str | None) -> None:
    files = dict(FILES)
    files[SRDF] = _mutate(FILES[SRDF], index, attr)
    assert srdf_roundtrip(files, ROBOT, Path("/pkg")), f"edit of element {index} {attr} went unnoticed"


def test_urdf_mismatch_names_field_values_and_line() -> None:
    files = dict(FILES)
    files[URDF] = FILES[URDF].replace(
        '<axis xyz="0 1 0"/>\n    <limit lower="-2.6179938779914944"',
        '<axis xyz="0 0 1"/>\n    <limit lower="-2.6179938779914944"',
    )
    assert files[URDF] != FILES[URDF]
    [f] = urdf_roundtrip(files, ROBOT, Path("/pkg"))
    assert "joint:elbow_joint/axis: model (0.0, 1.0, 0.0), URDF (0.0, 0.0, 1.0)" in f.message
    line = next(i for i, t in enumerate(files[URDF].splitlines(), 1) if '<joint name="elbow_joint"' in t)
    assert f.where.line == line and f.where.file == "/pkg/urdf/warehouse_arm.urdf"


def test_controllers_yaml_edit_is_reported() -> None:
    files = dict(FILES)
    files["config/ros2_controllers.yaml"] = FILES["config/ros2_controllers.yaml"].replace(
        "wheel_radius: 0.085", "wheel_radius: 0.08"
    )
    [f] = controllers_roundtrip(files, ROBOT, Path("/pkg"))
    assert "diff_drive_controller" in f.message


def test_controllers_check_reads_the_written_yaml() -> None:
    from descgen.prove.controllers import controllers_yaml

    assert controllers_yaml(FILES, ROBOT, Path("/pkg")) == []
    files = dict(FILES)
    files["config/ros2_controllers.yaml"] = (
        FILES["config/ros2_controllers.yaml"]
        .replace("joints: [lift_joint,", "joints: [wrist_joint, lift_joint,")
        .replace("state_interfaces: [position, velocity]", "state_interfaces: [position, effort]")
    )
    messages = [f.message for f in controllers_yaml(files, ROBOT, Path("/pkg"))]
    assert "controller 'arm_controller' joints names 'wrist_joint', not a URDF joint" in messages
    assert "controller 'arm_controller' reads 'lift_joint/effort', not exported" in messages
