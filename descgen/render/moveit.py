"""Render ``<robot>_moveit_config/`` from the model (templates ``moveit_*.j2`` only format).

The layout is the MoveIt Setup Assistant's on jazzy, so that
``MoveItConfigsBuilder("<robot>", package_name="<robot>_moveit_config").to_moveit_configs()``
loads it (moveit_configs_builder.py); docs/moveit_config.md gives each file's upstream source.
The SRDF and ros2_controllers.yaml are the description package's, byte for byte below their
headers: the builder reads the SRDF from this package, and demo.launch.py starts
ros2_control_node with this package's config/ros2_controllers.yaml. One exception: the builder
expands the SRDF with xacro, so a ``$`` in it (a disabled pair's reason) is written as xacro's
``${'$'}`` here (render.formatting.xacro_document), and xacro gives back the description's SRDF
(moveit/proof.py proves it).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from descgen.core import model as m
from descgen.physics import moveit_groups as derive
from descgen.render import _render, environment, header
from descgen.render.context import package_name
from descgen.render.formatting import xacro_document

# launch/<name>.launch.py -> the moveit_configs_utils.launches function it returns (launches.py, jazzy)
LAUNCHES = {
    "rsp": "generate_rsp_launch",
    "moveit_rviz": "generate_moveit_rviz_launch",
    "move_group": "generate_move_group_launch",
    "spawn_controllers": "generate_spawn_controllers_launch",
    "warehouse_db": "generate_warehouse_db_launch",
    "demo": "generate_demo_launch",
    "static_virtual_joint_tfs": "generate_static_virtual_joint_tfs_launch",
}

# exec_depends: the Setup Assistant's package.xml template, then what its launch bundles and the
# URDF config collect (launches.cpp, launches_config.cpp, urdf_config.cpp), the description first
_SA_DEPENDS = (
    "moveit_ros_move_group",
    "moveit_kinematics",
    "moveit_planners",
    "moveit_simple_controller_manager",
    "joint_state_publisher",
    "joint_state_publisher_gui",
    "tf2_ros",
    "xacro",
)
_BUNDLE_DEPENDS = {
    "rsp": ("robot_state_publisher",),
    "moveit_rviz": ("rviz2", "rviz_common", "rviz_default_plugins", "moveit_ros_visualization"),
    "move_group": ("moveit_ros_move_group",),
    "static_virtual_joint_tfs": ("tf2_ros",),
    "spawn_controllers": ("controller_manager",),
    "warehouse_db": ("warehouse_ros_mongo", "moveit_ros_warehouse"),
}


def moveit_package_name(robot: m.Robot) -> str:
    """The builder's default package name for ``MoveItConfigsBuilder(robot)``."""
    return f"{robot.name}_moveit_config"


def yfloat(x: float) -> str:
    """A YAML float that reads back as this exact float, always with a fraction or exponent:
    MoveIt declares limits PARAMETER_DOUBLE, and ``1`` would be read as an integer and abort
    move_group (moveit/moveit2#2776)."""
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"cannot write non-finite value {v!r}")
    text = repr(0.0 if v == 0 else v)
    if "e" in text and "." not in text.split("e")[0]:
        mantissa, exp = text.split("e")
        text = f"{mantissa}.0e{exp}"  # YAML 1.1 (PyYAML) reads 1e-05 as a string
    return text


def static_tfs(robot: m.Robot) -> bool:
    """Whether to write static_virtual_joint_tfs.launch.py: it publishes an identity transform
    for every SRDF virtual joint, which is right only for fixed ones (a planar or floating
    virtual joint is odometry's or localisation's transform, and a static one would fight it)."""
    vjs = robot.semantic.virtual_joints if robot.semantic else ()
    return bool(vjs) and all(v.type == "fixed" for v in vjs)


def launch_names(robot: m.Robot) -> list[str]:
    return [n for n in LAUNCHES if n != "static_virtual_joint_tfs" or static_tfs(robot)]


def outputs(robot: m.Robot) -> list[tuple[str, str]]:
    """(path in the package, template) for every rendered file (the two copies aside)."""
    files = [
        ("package.xml", "moveit_package.xml.j2"),
        ("CMakeLists.txt", "moveit_CMakeLists.txt.j2"),
        (".setup_assistant", "moveit_setup_assistant.yaml.j2"),
        ("config/kinematics.yaml", "moveit_kinematics.yaml.j2"),
        ("config/joint_limits.yaml", "moveit_joint_limits.yaml.j2"),
        ("config/pilz_cartesian_limits.yaml", "moveit_pilz_cartesian_limits.yaml.j2"),
        ("config/moveit_controllers.yaml", "moveit_controllers.yaml.j2"),
        ("config/initial_positions.yaml", "moveit_initial_positions.yaml.j2"),
        ("config/moveit.rviz", "moveit_rviz.j2"),
    ]
    if robot.ros2_control is not None:
        # the builder loads config/<robot>.urdf.xacro in preference to .setup_assistant's URDF; it
        # hands initial_positions.yaml to the description's Xacro, so the demo's mock hardware
        # starts at the initial state (without ros2_control there is no hardware to start)
        files.append((f"config/{robot.name}.urdf.xacro", "moveit_urdf.xacro.j2"))
    return files + [(f"launch/{n}.launch.py", "moveit_launch.py.j2") for n in launch_names(robot)]


def context(robot: m.Robot) -> dict[str, Any]:
    settings = robot.moveit
    assert settings is not None
    sem = robot.semantic
    names = launch_names(robot)
    depends = list(_SA_DEPENDS)
    for dep in [package_name(robot), "moveit_configs_utils", *(d for n in names for d in _BUNDLE_DEPENDS.get(n, ()))]:
        if dep not in depends:
            depends.append(dep)
    joint_limits = []
    for j in derive.planning_joints(robot):
        lm = j.limit
        velocity = lm.velocity if lm is not None and lm.velocity is not None else 0.0
        acceleration = lm.acceleration if lm is not None and lm.acceleration is not None else 0.0
        joint_limits.append(
            {
                "name": j.name,
                "has_velocity": velocity > 0.0,
                "max_velocity": velocity,
                "has_acceleration": acceleration > 0.0,
                "max_acceleration": acceleration,
            }
        )
    vjs = sem.virtual_joints if sem else ()
    groups = sem.groups if sem else ()
    return {
        "robot": robot,
        "moveit": settings,
        "package": {
            "name": moveit_package_name(robot),
            "version": robot.package.version,
            "maintainer": robot.package.maintainer,
            "email": robot.package.email,
            "license": robot.package.license,
            "exec_depends": depends,
        },
        "description_package": package_name(robot),
        "joint_limits": joint_limits,
        "controllers": derive.controllers(robot),
        "initial_positions": derive.initial_positions(robot),
        "initial_state": (st.name if (st := derive.initial_state(robot)) else None),
        "planning_frame": vjs[0].parent_frame if vjs else (robot.root() or robot.links[0].name),
        "first_group": groups[0].name if groups else "",
    }


def render(
    robot: m.Robot,
    description_files: dict[str, str],
    spec_display: str,
    templates: Path | None = None,
    sandboxed: bool = False,
) -> dict[str, str]:
    """Every file of ``<robot>_moveit_config/``, path -> text, each with its header."""
    env = environment(templates, sandboxed)
    env.filters["yfloat"] = yfloat
    ctx = context(robot)
    digest = robot.spec_hash or "0" * 64
    out: dict[str, str] = {}
    for path, template in outputs(robot):
        name = path.removeprefix("launch/").removesuffix(".launch.py")
        body = _render(env, template, {**ctx, "function": LAUNCHES.get(name, "")}, templates)
        out[path] = header.add(path, body, spec_display, digest)
    copies = {f"config/{robot.name}.srdf": f"srdf/{robot.name}.srdf", "config/ros2_controllers.yaml": None}
    if robot.ros2_control is not None:
        copies["config/ros2_controllers.yaml"] = "config/ros2_controllers.yaml"
    for path, source in copies.items():
        if source is None or source not in description_files:
            continue
        stamp = header.read(description_files[source])
        assert stamp is not None  # every rendered file has its header
        body = xacro_document(stamp.body) if path.endswith(".srdf") else stamp.body
        out[path] = header.add(path, body, spec_display, digest)
    return dict(sorted(out.items()))


__all__ = ["moveit_package_name", "render", "yfloat"]
