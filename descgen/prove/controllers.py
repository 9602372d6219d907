"""Check: the written controllers YAML loads, and every joint and interface it names
exists in the URDF's ros2_control block (read back from the rendered files)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from descgen.codes.generate import GEN003
from descgen.core.findings import Finding, Where
from descgen.core.model import Controller, Robot
from descgen.core.xmlcompare import parse
from descgen.read import params as rcl
from descgen.render.context import node_key

_JOINT_LISTS = ("joints", "left_wheel_names", "right_wheel_names")


def exported_interfaces(urdf_text: str) -> tuple[set[tuple[str, str]], set[tuple[str, str]], set[str]]:
    """(command, state) interfaces per joint or sensor in the ``<ros2_control>`` blocks, and URDF joints."""
    root = parse(urdf_text)
    command: set[tuple[str, str]] = set()
    state: set[tuple[str, str]] = set()
    for block in root.iter("ros2_control"):
        for j in (*block.iter("joint"), *block.iter("sensor")):
            command |= {(j.get("name", ""), c.get("name", "")) for c in j.iter("command_interface")}
            state |= {(j.get("name", ""), c.get("name", "")) for c in j.iter("state_interface")}
    urdf_joints = {j.get("name", "") for j in root if j.tag == "joint"}
    return command, state, urdf_joints


# libyaml's scanner and parser when PyYAML was built with them (as descgen/infra/yamlsource.py reads
# specs): ~8x faster on the files the proofs read back. The constructor and resolver are
# SafeLoader's own, so the values and their types are the same (tests/test_result_cache.py)
_SAFE: type[yaml.SafeLoader] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def safe_load(text: str) -> Any:
    """``yaml.safe_load`` of ``text``, through libyaml when it is there."""
    return yaml.load(text, Loader=_SAFE)  # a safe loader: SafeLoader or its libyaml twin


def controllers_yaml(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    from descgen.physics.control_claims import JOINT_PARAMS, claims_of, split

    path = "config/ros2_controllers.yaml"
    if path not in files:
        return []
    loc = Where(str(where / path))
    out: list[Finding] = []
    try:
        doc: Any = safe_load(files[path])
    except yaml.YAMLError as exc:
        return [GEN003.finding(f"controllers YAML does not load: {exc}", "check the template", "file:" + path, loc)]
    # and as the controller manager loads it: rcl's parser types plain scalars its own way (an
    # unquoted y is true, 1e3 a double), so what PyYAML reads back must also be what ROS reads
    out += _as_ros_loads(files[path], str(where / path), doc, path)
    command, state, urdf_joints = exported_interfaces(files[f"urdf/{robot.name}.urdf"])
    cm = (doc or {}).get(node_key(robot, "controller_manager"), {}).get("ros__parameters", {})
    if not isinstance(cm.get("update_rate"), int):
        out.append(
            GEN003.finding(
                "controller_manager update_rate is not an integer",
                "write the rate as a whole number of Hz",
                "file:" + path,
                loc,
            )
        )
    for name, entry in cm.items():
        if not isinstance(entry, dict) or "type" not in entry:
            continue
        params = (doc.get(node_key(robot, name)) or {}).get("ros__parameters", {})
        c = Controller(name, str(entry["type"]), tuple((k, _tuple(v)) for k, v in params.items()))
        known = claims_of(c)
        for key in JOINT_PARAMS if known.known else _JOINT_LISTS:
            value = params.get(key)
            for joint in [value] if isinstance(value, str) else value or []:
                if joint not in urdf_joints:
                    out.append(
                        GEN003.finding(
                            f"controller '{name}' {key} names '{joint}', not a URDF joint",
                            "fix the joint name in the spec",
                            f"controller:{name}",
                            loc,
                        )
                    )
        for pairs, exported, verb, kind in (
            ([split(k) for k in known.command], command, "claims", "command"),
            ([split(k) for k in known.state], state, "reads", "state"),
        ):
            for joint, iface in pairs:
                if (joint, iface) not in exported:
                    out.append(
                        GEN003.finding(
                            f"controller '{name}' {verb} '{joint}/{iface}', not exported",
                            f"add the {kind} interface in ros2_control",
                            f"controller:{name}",
                            loc,
                        )
                    )
    return out


def _tuple(v: object) -> object:
    return tuple(v) if isinstance(v, list) else v


def _flat(value: Any, prefix: str = "") -> dict[str, Any]:
    if not isinstance(value, dict):
        return {prefix: tuple(value) if isinstance(value, list) else value}
    out: dict[str, Any] = {}
    for k, v in value.items():
        out.update(_flat(v, f"{prefix}.{k}" if prefix else str(k)))
    return out


def _as_ros_loads(text: str, file: str, doc: Any, path: str) -> list[Finding]:
    """Findings where rcl (descgen/read/params.py) reads the file otherwise than yaml.safe_load."""
    loaded = rcl.parse(text, file)
    out = [
        GEN003.finding(
            f"controllers YAML does not load in ROS: {p.message}", "check the template", "file:" + path, p.where
        )
        for p in loaded.problems
        if p.kind == "error"
    ]
    for node in loaded.nodes:
        # rcl names a node absolutely (/left/arm_controller); the file's key may be relative
        entry = (doc.get(node.name) or doc.get(node.name.lstrip("/"), {})) if isinstance(doc, dict) else {}
        yaml_params = _flat(entry.get("ros__parameters", {})) if isinstance(entry, dict) else {}
        for q in node.params:
            theirs = yaml_params.get(q.name)
            if theirs != q.value or type(theirs) is not type(q.value):
                out.append(
                    GEN003.finding(
                        f"{node.name.lstrip('/')}.{q.name} reads as {q.value!r} in ROS but {theirs!r} in YAML",
                        "quote the value (render/context.py quotes what rcl would type otherwise)",
                        "file:" + path,
                        q.where,
                    )
                )
    return out
