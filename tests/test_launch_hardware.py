"""The generated launch files take ``hardware:=mock|gazebo|real`` (default mock) and hand it to
xacro, which selects the <hardware> plugin. ROS's launch is not installable here, so the launch
file runs against a recorder of the launch API (the classes Jazzy's launch and launch_ros define,
holding their arguments); the command it builds is then run through xacro's own evaluator, the
oracle for what robot_state_publisher receives. Expected plugins come from the spec by hand."""

from __future__ import annotations

import shlex
import sys
import types
from pathlib import Path
from typing import Any

import pytest
from lxml import etree

from descgen.read.xacro_file import expand
from tests.helpers import EXAMPLE_TEXT, ROOT, plant

PKG = ROOT / "generated" / "warehouse_arm_description"


class _Recorded:
    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self.args, self.kwargs = args, kwargs


def _launch_api(monkeypatch: pytest.MonkeyPatch) -> None:
    """launch, launch.actions, launch.substitutions, launch_ros.* with recording classes."""
    names = {
        "launch": ["LaunchDescription"],
        "launch.actions": ["DeclareLaunchArgument"],
        "launch.substitutions": ["Command", "FindExecutable", "LaunchConfiguration", "PathJoinSubstitution"],
        "launch_ros": [],
        "launch_ros.actions": ["Node"],
        "launch_ros.parameter_descriptions": ["ParameterValue"],
        "launch_ros.substitutions": ["FindPackageShare"],
    }
    for module, classes in names.items():
        mod = types.ModuleType(module)
        for cls in classes:
            setattr(mod, cls, type(cls, (_Recorded,), {}))
        monkeypatch.setitem(sys.modules, module, mod)


def _description(launch_file: Path, monkeypatch: pytest.MonkeyPatch) -> Any:
    _launch_api(monkeypatch)
    namespace: dict[str, Any] = {}
    exec(compile(launch_file.read_text(), str(launch_file), "exec"), namespace)  # our own generated file
    return namespace["generate_launch_description"]()


def _entities(description: Any) -> list[Any]:
    (entities,) = description.args
    return list(entities)


def _resolve(part: Any, package: Path, hardware: str) -> str:
    """A launch substitution as launch would perform it, for this package and argument value."""
    kind = type(part).__name__
    if isinstance(part, str):
        return part
    if kind == "FindExecutable":
        return str(part.kwargs["name"])
    if kind == "FindPackageShare":
        return str(package)
    if kind == "PathJoinSubstitution":
        return "/".join(_resolve(p, package, hardware) for p in part.args[0])
    if kind == "LaunchConfiguration":
        assert part.args == ("hardware",)
        return hardware
    raise AssertionError(f"unexpected substitution {kind}")


def _robot_description(description: Any) -> Any:
    for node in _entities(description):
        if type(node).__name__ == "Node" and node.kwargs.get("package") == "robot_state_publisher":
            (params,) = node.kwargs["parameters"]
            return params["robot_description"]
    raise AssertionError("no robot_state_publisher")


def _plugin_for(launch_file: Path, package: Path, hardware: str, monkeypatch: pytest.MonkeyPatch) -> str:
    """The <hardware> plugin of the URDF the launch file's xacro command produces."""
    value = _robot_description(_description(launch_file, monkeypatch))
    (command,) = value.args
    words = shlex.split("".join(_resolve(p, package, hardware) for p in command.args[0]))
    assert words[0] == "xacro"
    xacro_file = Path(words[1])
    args = dict(w.split(":=", 1) for w in words[2:])
    text = expand(xacro_file, str(xacro_file), args, package_paths=[package.parent], trusted=True)
    return (etree.fromstring(text).findtext("ros2_control/hardware/plugin") or "").strip()


@pytest.mark.parametrize("launch", ["display.launch.py", "control.launch.py"])
def test_hardware_argument_is_declared_with_its_choices(launch: str, monkeypatch: pytest.MonkeyPatch) -> None:
    (declared,) = [
        e
        for e in _entities(_description(PKG / "launch" / launch, monkeypatch))
        if type(e).__name__ == "DeclareLaunchArgument"
    ]
    assert declared.args == ("hardware",)
    # specs/warehouse_arm.yaml: mock_components by default, variants gazebo and real
    assert declared.kwargs["default_value"] == "mock"
    assert declared.kwargs["choices"] == ["mock", "gazebo", "real"]


@pytest.mark.parametrize("launch", ["display.launch.py", "control.launch.py"])
@pytest.mark.parametrize(
    ("hardware", "plugin"),
    [
        ("mock", "mock_components/GenericSystem"),
        ("gazebo", "gz_ros2_control/GazeboSimSystem"),
        ("real", "warehouse_arm_driver/WarehouseArmSystem"),
    ],
)
def test_the_launch_argument_reaches_xacro(
    launch: str, hardware: str, plugin: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    assert _plugin_for(PKG / "launch" / launch, PKG, hardware, monkeypatch) == plugin


def test_a_robot_without_variants_declares_no_hardware_argument(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from descgen.audit.spec import load_spec
    from descgen.render import render_package

    variants = EXAMPLE_TEXT[EXAMPLE_TEXT.index("    variants:\n") : EXAMPLE_TEXT.index("  update_rate:")]
    spec = tmp_path / "robot.yaml"
    spec.write_text(plant(variants, ""))
    robot = load_spec(spec).robot
    assert robot.ros2_control is not None and robot.ros2_control.plugin == "mock_components/GenericSystem"
    launch = tmp_path / "display.launch.py"
    launch.write_text(render_package(robot, "robot.yaml")["launch/display.launch.py"])
    entities = _entities(_description(launch, monkeypatch))
    assert [type(e).__name__ for e in entities] == ["Node", "Node", "Node"]
    assert _plugin_for(launch, PKG, "ignored", monkeypatch) == "mock_components/GenericSystem"
    (command,) = _robot_description(_description(launch, monkeypatch)).args
    assert not any(isinstance(p, str) and "hardware:=" in p for p in command.args[0])
