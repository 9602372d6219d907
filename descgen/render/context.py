"""The template context: the model plus everything derived for the outputs."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import yaml
from markupsafe import Markup

from descgen.core import display
from descgen.core.model import CollisionMatrix, DisabledPair, Robot
from descgen.meshes.paths import other_packages
from descgen.meshes.paths import package_name as package_name  # the one definition, re-exported
from descgen.physics import collision, derive
from descgen.physics.poses import worst_mm
from descgen.read.params import typed
from descgen.render.control_blocks import control_blocks, control_depends
from descgen.render.formatting import num, vec, xacro_text
from descgen.render.views import Values, calibration_keys, items, name_writer
from descgen.spec.passthrough import for_xacro

# exec_depends of what the launch files start and what controller_manager loads
_BASE_DEPENDS = ["joint_state_publisher_gui", "launch", "launch_ros", "robot_state_publisher", "rviz2", "xacro"]
_CONTROL_DEPENDS = ["controller_manager", "ros2_control"]


def _controller_package(type_: str) -> str:
    return type_.split("/")[0]


def _plain(value: object) -> object:
    """Model parameter values (tuples of pairs for mappings) as plain YAML data."""
    if isinstance(value, tuple) and value and all(isinstance(v, tuple) and len(v) == 2 for v in value):
        return {str(k): _plain(v) for k, v in value}
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, float):
        return 0.0 if value == 0 else value
    return value


class _Dumper(yaml.SafeDumper):
    """Block style, spec order, and lists of scalars on one line (as ROS configs are written)."""


def _represent_list(dumper: yaml.SafeDumper, data: list[Any]) -> yaml.Node:
    flow = all(not isinstance(v, dict | list) for v in data)
    return dumper.represent_sequence("tag:yaml.org,2002:seq", data, flow_style=flow)


_Dumper.add_representer(list, _represent_list)


def _represent_str(dumper: yaml.SafeDumper, data: str) -> yaml.Node:
    # rcl types a plain scalar by its own rules (docs/ros2_parameters.md): y, on, 010, 1e3 and inf
    # are no strings to the controller manager, though PyYAML would leave them plain
    style = "'" if not isinstance(typed(data, False, False), str) else None
    return dumper.represent_scalar("tag:yaml.org,2002:str", data, style=style)


_Dumper.add_representer(str, _represent_str)


def node_key(robot: Robot, node: str) -> str:
    """A node's key in the controllers YAML. In a namespace the nodes are /<ns>/controller_manager
    and /<ns>/<controller>: a bare key names /controller_manager (rclcpp adds the leading /)
    and would reach none of them."""
    return f"/{robot.namespace.strip('/')}/{node}" if robot.namespace else node


def controllers_doc(robot: Robot) -> dict[str, Any]:
    rc = robot.ros2_control
    if rc is None:
        return {}
    cm: dict[str, Any] = {"update_rate": round(rc.update_rate or 100)}
    doc: dict[str, Any] = {node_key(robot, "controller_manager"): {"ros__parameters": cm}}
    for c in rc.controllers:
        cm[c.name] = {"type": c.type}
    for c in rc.controllers:
        params = {str(k): _plain(v) for k, v in c.params}
        if c.type.startswith("diff_drive_controller/"):
            params.update(derive.wheel_params(robot, c))
        if params:
            doc[node_key(robot, c.name)] = {"ros__parameters": params}
    return doc


def controllers_yaml(robot: Robot) -> str:
    text = yaml.dump(controllers_doc(robot), Dumper=_Dumper, sort_keys=False, default_flow_style=False, width=100)
    return text.rstrip("\n")


def calibration_yaml(robot: Robot, nominal: bool) -> str:
    """config/calibration/default.yaml (the robot as measured) or nominal.yaml: the origin of
    every calibrated joint, under the key the Xacro reads it by (views.calibration_keys), with
    the joint's name and the provenance beside it."""
    keys = calibration_keys(robot)
    joints: dict[str, Any] = {}
    for e in robot.calibration:
        p = e.nominal if nominal else e.calibrated
        entry: dict[str, Any] = {"joint": e.joint}
        if not nominal:
            entry["source"] = e.source
            if e.sensor is not None:
                entry["sensor"] = e.sensor
        entry.update(zip(("x", "y", "z"), map(float, p.xyz), strict=True))
        entry.update(zip(("roll", "pitch", "yaw"), map(float, p.rpy), strict=True))
        joints[keys[e.joint]] = entry
    doc: dict[str, Any] = {"joints": joints}
    if not nominal:
        doc["sources"] = {
            src.name: {
                k: v
                for k, v in (("method", src.method), ("tool", src.tool), ("file", src.file), ("date", src.date))
                if v is not None
            }
            | ({"hash": src.hash} if src.hash else {})
            for src in robot.calibration_sources
        }
    return yaml.dump(doc, Dumper=_Dumper, sort_keys=False, default_flow_style=False, width=100).rstrip("\n")


def _mm3(v: tuple[float, float, float] | None) -> str:
    return "n/a" if v is None else display.mm(v)


def known_pose_tables(robot: Robot) -> list[dict[str, Any]]:
    """Rows of evidence/known_poses.md, one table per pose."""
    from descgen.physics.poses import evaluate

    rows = evaluate(robot)
    tables = []
    for kp in robot.known_poses:
        joints = []
        for name, value in kp.joints:
            j = robot.joint(name)
            joints.append((name, j.show(value) if j else f"{value:.6g}"))
        tables.append(
            {
                "name": kp.name,
                "source": kp.source,
                "joints": joints,
                "rows": [
                    {
                        "frame": r.measurement.frame,
                        "relative_to": r.relative_to,
                        "measured": _mm3(r.measurement.xyz),
                        "model": _mm3(r.model),
                        "error": _mm3(r.error),
                        # to the digits the tolerance judges, as poses, the viewer and the images show it
                        "worst": worst_mm(r.error, r.measurement.tolerance),
                        "tolerance": f"{r.measurement.tolerance * 1000:g}",
                        "verdict": "pass" if r.ok else "**FAIL**",
                        "source": r.measurement.source or "",
                    }
                    for r in rows
                    if r.pose is kp
                ],
            }
        )
    return tables


def frame_graph(robot: Robot) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """Nodes (with diagram-safe ids) and edges of the frame tree, for frames.md and frames.dot."""
    from descgen.physics.frames import edges

    es = edges(robot)
    ids: dict[str, str] = {}  # frames in order of first appearance (a dict: 1000 links are 2000 lookups)
    for e in es:
        for n in (e.parent, e.child):
            if n not in ids:
                ids[n] = f"f{len(ids)}"
    nodes = [{"id": i, "label": n} for n, i in ids.items()]  # escaped by the template's filter
    rows = [
        {
            "parent": e.parent,
            "child": e.child,
            "parent_id": ids[e.parent],
            "child_id": ids[e.child],
            "owner": e.owner,
            "topic": e.topic,
            "static": e.static,
            "joint": e.joint,
            "via": e.via,
        }
        for e in es
    ]
    return nodes, rows


def _frames(robot: Robot, xacro: bool) -> dict[str, list[dict[str, Any]]]:
    """frames.md's and frames.dot's graph (the plain context's; the Xacro has no use for it)."""
    nodes, rows = frame_graph(robot) if not xacro else ([], [])
    return {"frame_nodes": nodes, "frame_edges": rows}


GZ_SIM_PLUGIN = ("gz_ros2_control-system", "gz_ros2_control::GazeboSimROS2ControlPlugin")


def control_extras(robot: Robot, xacro: bool, controllers_file: str | None = None) -> dict[str, Any]:
    """Sensors, gpios and hardware variants of the ros2_control block, with escaped texts.

    The Xacro gets every variant (selected by ``hardware:=``) and the gz_ros2_control sim
    plugin under ``hardware:=gazebo``; a plain URDF gets the block of the model's own plugin,
    and the sim plugin only when that plugin is Gazebo's and ``controllers_file`` is given (the
    proof of the gazebo variant; the committed URDF is the mock variant)."""
    from descgen.spec.models import GZ_PLUGIN

    rc = robot.ros2_control
    text = xacro_text if xacro else str
    if rc is None:
        return {"control_sensors": [], "control_gpios": [], "hw_variants": [], "hw_variant_names": [], "gz_sim": None}
    shown = name_writer(robot, xacro)

    def params(items: tuple[tuple[str, str], ...]) -> list[tuple[str, str]]:
        return [(k, text(v)) for k, v in items]

    names = [v.name for v in rc.variants]
    package = package_name(robot)
    if xacro:
        gz_file = f"$(find {package})/config/ros2_controllers.yaml" if "gazebo" in names else None
    else:
        gz_file = controllers_file if rc.plugin == GZ_PLUGIN else None
    return {
        "control_sensors": [{"name": shown(c.name), "state": c.state, "params": params(c.params)} for c in rc.sensors],
        "control_gpios": [replace(g, name=shown(g.name)) for g in rc.gpios],
        "hw_variants": [{"name": v.name, "plugin": v.plugin, "params": params(v.params)} for v in rc.variants]
        if xacro
        else [],
        "hw_variant_names": names,
        "gz_sim": None
        if gz_file is None
        else {"filename": GZ_SIM_PLUGIN[0], "name": GZ_SIM_PLUGIN[1], "parameters": gz_file},
    }


def build(robot: Robot, xacro: bool) -> dict[str, Any]:
    """Context for one template family: ``xacro`` chooses property references and
    xacro-escaped free text over plain numbers and text."""
    prefix = robot.prefix.value if robot.prefix is not None else ""
    values = Values(xacro=xacro, calibrated=calibration_keys(robot), prefix=prefix)
    shown = values.name
    element_items, macros = items(robot, values)
    text = xacro_text if xacro else str
    materials = [
        {
            "name": text(m.name),
            "rgba": vec(m.rgba) if m.rgba else None,
            "texture": text(m.texture) if m.texture else None,
        }
        for m in robot.materials
    ]
    rc = robot.ros2_control
    controllers = rc.controllers if rc else ()
    depends = list(_BASE_DEPENDS)
    if rc is not None:
        depends += _CONTROL_DEPENDS + sorted({_controller_package(c.type) for c in controllers})
        depends += control_depends(rc)
    sem = robot.semantic
    disabled: list[DisabledPair] = []
    if sem is not None:
        explicit = {frozenset((d.link1, d.link2)) for d in sem.disabled_collisions}
        # a sampled matrix (descgen/physics/collision.py) replaces the adjacent-only default
        computed = (
            list(sem.matrix.pairs)
            if sem.matrix is not None
            else [DisabledPair(a, b, "Adjacent") for a, b in derive.adjacent_pairs(robot)]
        )
        disabled = [d for d in computed if frozenset((d.link1, d.link2)) not in explicit]
        disabled += list(sem.disabled_collisions)
    root = robot.root() or (robot.links[0].name if robot.links else "base_link")
    extent = max((abs(c) for j in robot.joints for c in j.origin.xyz), default=1.0)
    return {
        "robot": robot,
        "description": text(robot.description) if robot.description else None,
        "items": element_items,
        "macros": macros,
        "props": values.props,
        "materials": materials,
        "ros2_control": rc,
        "hw_params": [(k, text(v)) for k, v in rc.params] if rc else [],
        "control_blocks": control_blocks(robot, xacro),
        "control_joints": derive.interfaces_with_limits(robot),
        "control_mimic": {shown(cj.name): cj.mimic for cj in rc.joints if cj.mimic is not None} if rc else {},
        # the Xacro's prefix argument (its default) and the launch files' namespace
        "name_prefix": prefix,
        # hardware:=mujoco's model, as mujoco_ros2_control reads it: a plain path (render/mjcf.py)
        "mujoco_model": f"$(find {package_name(robot)})/mujoco/{robot.name}.xml",
        "namespace": robot.namespace.strip("/") if robot.namespace else "",
        **control_extras(robot, xacro),
        "controllers": controllers,
        "plugin": rc.plugin if rc else "",
        "controllers_yaml": controllers_yaml(robot),
        # verbatim XML, already checked (spec/models.py); Xacro: every $ stays data
        "passthrough": [Markup(for_xacro(x) if xacro else x) for x in robot.passthrough],
        "semantic": sem,
        "disabled": disabled,
        "matrix": _matrix_summary(sem.matrix, disabled) if sem is not None and sem.matrix is not None else None,
        "fixed_frame": root,
        "poses": known_pose_tables(robot) if not xacro else [],
        **_frames(robot, xacro),
        "view_distance": num(max(2.0, 4 * extent)),
        "view_focal_z": num(0.5),
        "waivers": robot.waivers,
        "calibration": bool(robot.calibration),
        "calibration_default": calibration_yaml(robot, nominal=False) if robot.calibration and not xacro else "",
        "calibration_nominal": calibration_yaml(robot, nominal=True) if robot.calibration and not xacro else "",
        "package": {
            "name": package_name(robot),
            "version": robot.package.version,
            "description": robot.description or f"Robot description of {robot.name}",
            "maintainer": robot.package.maintainer,
            "email": robot.package.email,
            "license": robot.package.license,
            # another package's meshes are used from that package, installed beside this one
            "exec_depends": sorted({*depends, *other_packages(robot)} - {package_name(robot)}),
            # every folder of the package (render_package fills it in: it knows the files)
            "install_dirs": [],
        },
    }


def _matrix_summary(matrix: CollisionMatrix, disabled: list[DisabledPair]) -> dict[str, Any]:
    """Settings and per-reason counts of the collision matrix, for the SRDF comment and
    evidence/collision_matrix.md (counts are of what the SRDF lists, User pairs included)."""
    s = matrix.settings
    reasons = ("Adjacent", "Default", "Always", "Never", "User")
    counts = {r: sum(1 for d in disabled if d.reason == r) for r in reasons}
    counts["other"] = len(disabled) - sum(counts.values())
    return {
        "seed": s.seed,
        "samples": s.samples,
        "fraction": num(s.fraction),
        "padding": num(s.padding),
        "state": matrix.state,
        "hash": matrix.input_hash,
        "libraries": collision.libraries_text(matrix.libraries),  # what computed the pairs: read back from the SRDF
        "counts": counts,
        "checked": matrix.checked,
        "enabled": max(0, matrix.checked - len({frozenset((d.link1, d.link2)) for d in disabled})),
        "skipped": list(matrix.skipped),
        "pairs": disabled,
    }
