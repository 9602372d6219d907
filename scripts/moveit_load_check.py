"""Load a generated MoveIt config package with the real moveit_configs_utils and compare what it
loads with the spec, by hand (issue 15). Not a test: moveit_configs_utils is not on PyPI and
needs ROS 2 Python packages, so this runs on a maintainer's machine, not in CI.

What it does
  1. `MoveItConfigsBuilder(ROBOT, package_name=ROBOT_moveit_config).to_moveit_configs()`
     against generated/ (ament_index_python is a stand-in mapping package names to folders).
  2. Compares every loaded dict with values computed here from the spec YAML (yaml + pint,
     not descgen): robot_description (xacro of the package's config/ROBOT.urdf.xacro, which the
     builder prefers) == the committed URDF but for the mock hardware's initial values, which are
     the initial state's (initial_positions.yaml), robot_description_semantic
     == the committed SRDF, kinematics, joint_limits (floats, accelerations), planning pipelines,
     moveit_controllers (action_ns, default), Pilz cartesian limits.
  3. Runs generate_launch_description() of every generated launch file (the moveit_configs_utils
     generate_*_launch functions), checks the files they include exist, and evaluates every
     Node's parameters with launch_ros (normalize_parameters + evaluate_parameters), which is
     where a value launch_ros cannot type (an empty list, a mixed list) fails.

Needs (pure Python sources; put each source root on --pythonpath unless a ROS 2 install is
sourced): moveit2 (branch jazzy: moveit_configs_utils), ros2/launch (jazzy: launch),
ros2/launch_ros (jazzy: launch_ros), PickNikRobotics/launch_param_builder, moveit/srdfdom
(ros2), ros/urdf_parser_py (ros2, src/); pip: lark, osrf-pycommon (for launch); pyyaml, lxml,
xacro, pint (in .venv). rclpy, lifecycle_msgs and composition_interfaces are stubbed when not
importable: launch_ros imports them, building configs never uses them (a stub raises if called).

Run:
  .venv/bin/python scripts/moveit_load_check.py --moveit2 /tmp/mcu \\
      --pythonpath /tmp/mo_site --pythonpath /tmp/ros_src/launch --pythonpath /tmp/ros_src/launch_ros \\
      --pythonpath /tmp/ros_src --pythonpath /tmp/ros_src/updp/src
Exit 0 when every check passes, 1 otherwise.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import sys
import tempfile
import textwrap
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import yaml
from lxml import etree

ROOT = Path(__file__).resolve().parents[1]

# The MoveIt Setup Assistant's defaults (moveit2 jazzy: moveit_setup_framework/templates/config/
# pilz_cartesian_limits.yaml; group_meta_config.hpp; srdf_config.cpp), used when the spec is silent.
PILZ_DEFAULTS = {"max_trans_vel": 1.0, "max_trans_acc": 2.25, "max_trans_dec": -5.0, "max_rot_vel": 1.57}
KDL = "kdl_kinematics_plugin/KDLKinematicsPlugin"
# Controller types MoveIt's simple controller manager drives (reference/ros2_control_jazzy.md §8).
ACTION_TYPES = {
    "joint_trajectory_controller/JointTrajectoryController": ("FollowJointTrajectory", "follow_joint_trajectory"),
    "position_controllers/GripperActionController": ("GripperCommand", "gripper_cmd"),
    "effort_controllers/GripperActionController": ("GripperCommand", "gripper_cmd"),
    "parallel_gripper_action_controller/GripperActionController": ("ParallelGripperCommand", "gripper_cmd"),
}

STUB_HELPER = '''
"""Stand-ins for ROS modules that launch_ros imports but building configs never uses."""
import itertools
_ids = itertools.count(1)
class _Meta(type):
    # class constants such as lifecycle_msgs.msg.Transition.TRANSITION_CREATE: distinct ints
    def __getattr__(cls, name):
        if name.startswith("__"):
            raise AttributeError(name)
        value = next(_ids)
        setattr(cls, name, value)
        return value
class _Unavailable(metaclass=_Meta):
    def __init__(self, *a, **k):
        raise NotImplementedError(f"{type(self).__module__}.{type(self).__name__} is a stub")
def module_getattr(modname):
    def __getattr__(name):
        if name.startswith("__"):
            raise AttributeError(name)
        if name.startswith("validate_") or name.startswith("get_"):
            def unavailable(*a, **k):
                raise NotImplementedError(f"{modname}.{name} is a stub")
            return unavailable
        return _Meta(name, (_Unavailable,), {"__module__": modname})
    return __getattr__
'''
STUBBED_ROS = {
    "rclpy": ["parameter", "validate_namespace", "validate_node_name", "executors", "logging"],
    "lifecycle_msgs": ["msg", "srv"],
    "composition_interfaces": ["srv"],
}
AMENT_STUB = '''
"""Stand-in for ament_index_python.packages: package name -> share folder, from a fixed map."""
import os
class PackageNotFoundError(KeyError):
    pass
SHARE = {share!r}
def get_package_share_directory(package_name, print_warning=True):
    try:
        return SHARE[package_name]
    except KeyError:
        raise PackageNotFoundError(f"package '{{package_name}}' not found (stub)") from None
def get_package_prefix(package_name):
    return os.path.dirname(os.path.dirname(get_package_share_directory(package_name)))
'''


def write_stubs(root: Path, share: dict[str, str]) -> list[str]:
    """Write the stand-in modules under root; return the names of what was stubbed."""
    stubbed = ["ament_index_python.packages"]
    (root / "ament_index_python").mkdir()
    (root / "ament_index_python" / "__init__.py").write_text("")
    (root / "ament_index_python" / "packages.py").write_text(AMENT_STUB.format(share=share))
    (root / "_ros_stub.py").write_text(STUB_HELPER)
    for package, modules in STUBBED_ROS.items():
        if importlib.util.find_spec(package) is not None:
            continue  # a real ROS install is on the path: use it
        (root / package).mkdir()
        for module in ["__init__", *modules]:
            name = package if module == "__init__" else f"{package}.{module}"
            text = f"from _ros_stub import module_getattr\n__getattr__ = module_getattr({name!r})\n"
            (root / package / f"{module}.py").write_text(text)
            stubbed.append(name)
    return stubbed


# ---------------------------------------------------------------- expected values from the spec


def si(text: str | float, unit: str) -> float:
    """A spec quantity ("120 deg/s", "5 ms") in the SI unit `unit`, through pint."""
    import pint

    ureg = pint.UnitRegistry()
    if isinstance(text, (int, float)):
        return float(text)
    return float(ureg.Quantity(str(text).replace("^", "**")).to(unit).magnitude)


def planning_joints(spec: dict[str, Any]) -> list[str]:
    """Movable joints on the chain of every group (the example's groups are chains)."""
    parent = {j["child"]: j for j in spec["joints"]}
    names: set[str] = set()
    for group in spec["semantic"]["groups"]:
        chain = group["chain"]
        link = chain["tip"]
        while link != chain["base"]:
            joint = parent[link]
            if joint["type"] != "fixed" and "mimic" not in joint:
                names.add(joint["name"])
            link = joint["parent"]
    return sorted(names)


def expected_joint_limits(spec: dict[str, Any]) -> dict[str, Any]:
    moveit = spec["moveit"]
    joints = {j["name"]: j for j in spec["joints"]}
    limits: dict[str, Any] = {}
    for name in planning_joints(spec):
        limit = joints[name]["limit"]
        linear = joints[name]["type"] == "prismatic"
        acc = limit["acceleration"]
        acc = acc["value"] if isinstance(acc, dict) else acc
        limits[name] = {
            "has_velocity_limits": True,
            "max_velocity": si(limit["velocity"], "m/s" if linear else "rad/s"),
            "has_acceleration_limits": True,
            "max_acceleration": si(acc, "m/s**2" if linear else "rad/s**2"),
        }
    return {
        "default_velocity_scaling_factor": float(moveit.get("default_velocity_scaling_factor", 0.1)),
        "default_acceleration_scaling_factor": float(moveit.get("default_acceleration_scaling_factor", 0.1)),
        "joint_limits": limits,
    }


def expected_kinematics(spec: dict[str, Any]) -> dict[str, Any]:
    out = {}
    given = spec["moveit"].get("kinematics", {})
    for group in spec["semantic"]["groups"]:
        settings = given.get(group["name"])
        if settings is None and "chain" not in group:
            continue
        settings = settings or {}
        out[group["name"]] = {
            "kinematics_solver": settings.get("solver", KDL),
            "kinematics_solver_search_resolution": float(settings.get("search_resolution", 0.005)),
            "kinematics_solver_timeout": si(settings.get("timeout", 0.005), "s"),
        }
    return out


def expected_controllers(spec: dict[str, Any]) -> dict[str, Any]:
    groups = set(planning_joints(spec))
    managed: dict[str, Any] = {}
    for c in spec.get("ros2_control", {}).get("controllers", []):
        if c["type"] not in ACTION_TYPES:
            continue
        joints = c.get("params", {}).get("joints") or [c.get("params", {}).get("joint")]
        if not set(joints) <= groups:
            continue
        kind, ns = ACTION_TYPES[c["type"]]
        managed[c["name"]] = {"type": kind, "action_ns": ns, "default": True, "joints": joints}
    return {
        "moveit_controller_manager": "moveit_simple_controller_manager/MoveItSimpleControllerManager",
        "moveit_simple_controller_manager": {"controller_names": list(managed), **managed},
    }


def expected_pilz(spec: dict[str, Any]) -> dict[str, float]:
    given = spec["moveit"].get("pilz_cartesian_limits", {})
    units = {"max_trans_vel": "m/s", "max_trans_acc": "m/s**2", "max_trans_dec": "m/s**2", "max_rot_vel": "rad/s"}
    return {k: si(given.get(k, PILZ_DEFAULTS[k]), u) for k, u in units.items()}


def expected_initial_positions(spec: dict[str, Any]) -> dict[str, float]:
    """The initial state's SI value per planning joint (moveit.initial_state, else the collision
    matrix's default state; a group state names a known pose or lists joints); a joint the state
    does not set gets MoveIt's default: 0, or the middle of its bounds when 0 is outside them."""
    semantic = spec["semantic"]
    name = spec["moveit"].get("initial_state") or semantic.get("collision_matrix", {}).get("default_state")
    values: dict[str, Any] = {}
    for state in semantic.get("group_states", []):
        if state["name"] == name:
            values = state.get("joints") or next(k for k in spec["known_poses"] if k["name"] == state["pose"])["joints"]
    joints = {j["name"]: j for j in spec["joints"]}
    out: dict[str, float] = {}
    for joint in planning_joints(spec):
        unit = "m" if joints[joint]["type"] == "prismatic" else "rad"
        if joint in values:
            out[joint] = si(values[joint], unit)
            continue
        limit = joints[joint]["limit"]
        lower, upper = si(limit["lower"], unit), si(limit["upper"], unit)
        out[joint] = 0.0 if lower <= 0.0 <= upper else (lower + upper) / 2
    return out


# ---------------------------------------------------------------- comparisons


def mock_start(robot_description: str, urdf: bytes, want: dict[str, float]) -> list[str]:
    """The builder's robot_description starts each planning joint's position state at the
    initial state (issue 15: config/<robot>.urdf.xacro hands initial_positions.yaml to the
    description's ros2_control Xacro), and with those params set back to the committed URDF's
    text it equals that URDF: nothing else differs."""
    parser = etree.XMLParser(remove_comments=True, remove_blank_text=True)
    got = etree.fromstring(robot_description.encode(), parser)
    plain = etree.fromstring(urdf, parser)
    problems: list[str] = []
    seen = set()
    for j, p in zip(got.iterfind("ros2_control/joint"), plain.iterfind("ros2_control/joint"), strict=True):
        path = "state_interface[@name='position']/param[@name='initial_value']"
        for e, e0 in zip(j.iterfind(path), p.iterfind(path), strict=True):
            name = j.get("name", "")
            if name in want:
                seen.add(name)
                if not math.isclose(float(e.text or "nan"), want[name], rel_tol=1e-12, abs_tol=1e-15):
                    problems.append(f"{name} starts at {e.text!r}, the state says {want[name]!r}")
            elif e.text != e0.text:
                problems.append(f"{name} starts at {e.text!r}, not the URDF's {e0.text!r}")
            e.text = e0.text
    problems += [f"{n}: no position initial_value" for n in sorted(set(want) - seen)]
    rest = diff_xml(etree.tostring(got), etree.tostring(plain))
    return problems + ([f"otherwise: {rest}"] if rest else [])


def canonical(xml: str | bytes) -> list[tuple[str, tuple[tuple[str, str], ...], str]]:
    """Elements in document order (tag, sorted attributes, stripped text); comments and
    whitespace dropped, so a pretty-printed file equals xacro's toxml() of the same tree."""
    data = xml.encode() if isinstance(xml, str) else xml
    tree = etree.fromstring(data, etree.XMLParser(remove_comments=True, remove_blank_text=True))
    return [(str(e.tag), tuple(sorted(e.attrib.items())), (e.text or "").strip()) for e in tree.iter()]


def diff_xml(a: str | bytes, b: str | bytes) -> str:
    ca, cb = canonical(a), canonical(b)
    if ca == cb:
        return ""
    for i, (x, y) in enumerate(zip(ca, cb, strict=False)):
        if x != y:
            return f"element {i}: {x} != {y}"
    return f"{len(ca)} elements != {len(cb)}"


def diff_values(got: Any, want: Any, path: str = "") -> list[str]:
    """Differences between two YAML values; floats must be floats (MoveIt declares doubles)."""
    if isinstance(want, dict):
        if not isinstance(got, dict):
            return [f"{path}: {got!r} is not a mapping"]
        out = [f"{path}.{k}: missing" for k in want if k not in got]
        out += [f"{path}.{k}: unexpected" for k in got if k not in want]
        for k in want:
            if k in got:
                out += diff_values(got[k], want[k], f"{path}.{k}")
        return out
    if isinstance(want, float):
        if type(got) is not float:
            return [f"{path}: {got!r} is {type(got).__name__}, not float"]
        return [] if math.isclose(got, want, rel_tol=1e-12, abs_tol=1e-15) else [f"{path}: {got!r} != {want!r}"]
    return [] if got == want and type(got) is type(want) else [f"{path}: {got!r} != {want!r}"]


class Report:
    def __init__(self) -> None:
        self.rows: list[tuple[str, bool, str]] = []

    def check(self, name: str, problems: list[str] | str) -> None:
        problems = [problems] if isinstance(problems, str) else problems
        problems = [p for p in problems if p]
        self.rows.append((name, not problems, "; ".join(problems)))
        mark = "ok  " if not problems else "FAIL"
        print(f"{mark} {name}" + (f": {'; '.join(problems)}" if problems else ""), flush=True)

    @property
    def ok(self) -> bool:
        return all(ok for _, ok, _ in self.rows)


def check_configs(configs: Any, spec: dict[str, Any], desc: Path, pkg: Path, report: Report) -> None:
    robot = spec["name"]
    want = expected_initial_positions(spec)
    report.check(
        f"robot_description == xacro(config/{robot}.urdf.xacro) == urdf/{robot}.urdf with the mock hardware at {want}",
        mock_start(
            configs.robot_description["robot_description"], (desc / "urdf" / f"{robot}.urdf").read_bytes(), want
        ),
    )
    semantic = configs.robot_description_semantic["robot_description_semantic"]
    # the config SRDF is the description's with any '$' escaped for xacro (${'$'}): what the
    # builder expands from it is the description's SRDF, and the same file when nothing is escaped
    report.check(
        f"robot_description_semantic == description package's srdf/{robot}.srdf",
        diff_xml(semantic, (desc / "srdf" / f"{robot}.srdf").read_bytes()),
    )
    config_srdf = (pkg / "config" / f"{robot}.srdf").read_bytes()
    if b"$" not in config_srdf:
        report.check(f"robot_description_semantic == config/{robot}.srdf", diff_xml(semantic, config_srdf))
    report.check(
        "robot_description_kinematics",
        diff_values(configs.robot_description_kinematics, {"robot_description_kinematics": expected_kinematics(spec)}),
    )
    report.check(
        "joint_limits (robot_description_planning)",
        diff_values(configs.joint_limits, {"robot_description_planning": expected_joint_limits(spec)}),
    )
    report.check(
        "pilz_cartesian_limits",
        diff_values(
            configs.pilz_cartesian_limits, {"robot_description_planning": {"cartesian_limits": expected_pilz(spec)}}
        ),
    )
    want_exec = {"moveit_manage_controllers": True, **expected_controllers(spec)}
    report.check("trajectory_execution (moveit_controllers.yaml)", diff_values(configs.trajectory_execution, want_exec))
    pipelines = configs.planning_pipelines
    problems = []
    if pipelines.get("default_planning_pipeline") != "ompl":
        problems.append(f"default pipeline {pipelines.get('default_planning_pipeline')!r}")
    for name in pipelines.get("planning_pipelines", []):
        if not pipelines.get(name, {}).get("planning_plugins"):
            problems.append(f"{name}: no planning_plugins")
    if "pilz_industrial_motion_planner" not in pipelines.get("planning_pipelines", []):
        problems.append("no Pilz pipeline")
    report.check(f"planning_pipelines {pipelines.get('planning_pipelines')}", problems)
    merged = configs.to_dict()
    report.check(
        "to_dict(): Pilz limits merged into robot_description_planning",
        diff_values(
            merged.get("robot_description_planning", {}),
            {**expected_joint_limits(spec), "cartesian_limits": expected_pilz(spec)},
        ),
    )


# ---------------------------------------------------------------- launch files


def walk(entities: list[Any]) -> Iterator[Any]:
    for e in entities:
        yield e
        sub = getattr(e, "entities", None)
        if isinstance(sub, list):
            yield from walk(sub)


def check_launch(pkg: Path, report: Report) -> None:
    from launch import LaunchContext
    from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
    from launch_ros.actions import Node
    from launch_ros.utilities import evaluate_parameters, normalize_parameters

    for path in sorted((pkg / "launch").glob("*.launch.py")):
        problems: list[str] = []
        spec = importlib.util.spec_from_file_location(path.stem.replace(".", "_"), path)
        assert spec and spec.loader
        module = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(module)
            description = module.generate_launch_description()
        except Exception as exc:  # the oracle's own failure is the finding
            report.check(f"launch/{path.name}: generate_launch_description()", f"{type(exc).__name__}: {exc}")
            continue
        context = LaunchContext()
        entities = list(walk(description.entities))
        for e in entities:
            if isinstance(e, DeclareLaunchArgument) and e.default_value is not None:
                from launch.utilities import perform_substitutions

                context.launch_configurations[e.name] = perform_substitutions(context, e.default_value)
        nodes = 0
        included: list[str] = []
        for e in entities:
            if isinstance(e, IncludeLaunchDescription):
                # Loading the included file is what launch does when it runs the include.
                source = e.launch_description_source
                try:
                    source.get_launch_description(context)
                    included.append(Path(source.location).name)
                except Exception as exc:
                    problems.append(f"include {source.location}: {type(exc).__name__}: {exc}")
            if isinstance(e, Node):
                nodes += 1
                params = e._Node__parameters  # what Node.execute() evaluates
                if params:
                    try:
                        evaluate_parameters(context, normalize_parameters(params))
                    except Exception as exc:
                        problems.append(
                            f"{e.node_package}/{e.node_executable}: parameters: {type(exc).__name__}: {exc}"
                        )
        kinds = sorted({type(e).__name__ for e in entities})
        loaded = f"; includes {', '.join(included)}" if included else ""
        report.check(f"launch/{path.name}: {nodes} Node(s), {', '.join(kinds)}{loaded}", problems)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--moveit2", type=Path, required=True, help="moveit2 checkout (jazzy) or its moveit_configs_utils parent"
    )
    parser.add_argument("--pythonpath", type=Path, action="append", default=[], help="extra source root (repeatable)")
    parser.add_argument("--spec", type=Path, default=ROOT / "specs" / "warehouse_arm.yaml")
    parser.add_argument("--generated", type=Path, default=ROOT / "generated")
    args = parser.parse_args(argv)

    spec = yaml.safe_load(args.spec.read_text())
    robot = spec["name"]
    desc = (args.generated / f"{robot}_description").resolve()
    pkg = (args.generated / f"{robot}_moveit_config").resolve()
    mcu = args.moveit2.resolve() / "moveit_configs_utils"
    share = {"moveit_configs_utils": str(mcu), f"{robot}_description": str(desc), f"{robot}_moveit_config": str(pkg)}

    stub_dir = Path(tempfile.mkdtemp(prefix="moveit_load_check_"))
    sys.path[:0] = [str(stub_dir), str(mcu), *map(str, args.pythonpath)]
    stubbed = write_stubs(stub_dir, share)
    print(f"stubbed: {', '.join(stubbed)}", flush=True)

    from moveit_configs_utils import MoveItConfigsBuilder

    report = Report()
    configs: Any = None
    try:
        builder = MoveItConfigsBuilder(robot, package_name=f"{robot}_moveit_config")
        # the builder's own choice of URDF (name-mangled private attributes, moveit_configs_builder.py)
        chosen = (builder._MoveItConfigsBuilder__urdf_package, builder._MoveItConfigsBuilder__urdf_file_path)
        report.check(
            f"the builder loads config/{robot}.urdf.xacro of the MoveIt package",
            [] if chosen == (pkg, Path("config") / f"{robot}.urdf.xacro") else f"it loads {chosen}",
        )
        configs = builder.to_moveit_configs()
    except Exception as exc:
        report.check("MoveItConfigsBuilder(...).to_moveit_configs()", f"{type(exc).__name__}: {exc}")
    if configs is not None:
        report.check("MoveItConfigsBuilder(...).to_moveit_configs()", [])
        check_configs(configs, spec, desc, pkg, report)
    check_launch(pkg, report)
    passed = sum(ok for _, ok, _ in report.rows)
    print(textwrap.dedent(f"{passed}/{len(report.rows)} checks passed"))
    return 0 if report.ok else 1


if __name__ == "__main__":
    sys.exit(main())
