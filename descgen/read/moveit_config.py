"""A MoveIt config package folder -> :class:`descgen.core.moveit_model.MoveItConfig`.

Reads ``config/joint_limits.yaml``, ``moveit_controllers.yaml``, ``kinematics.yaml`` and
``initial_positions.yaml`` with the bounded reader (descgen/infra/safeio.py) and the located YAML
loader (descgen/infra/yamlsource.py: alias bombs, depth and size are refused there), keeping the
file:line:col of every value. A file that cannot be read, or whose root is not a mapping,
is an InputError (exit 2); a value of the wrong type becomes a TypeProblem for the rules.

The parameter types are the ones MoveIt declares at moveit/moveit2 ``jazzy``
(docs/reference/moveit_config.md): robot_model_loader.cpp and Pilz's
joint_limits_rosparam.hpp for joint_limits.yaml, moveit_simple_controller_manager.cpp for the
controllers, kinematics_parameters.yaml and kdl_kinematics_parameters.yaml for kinematics.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

from descgen.codes.read import MOVEIT020, MOVEIT021, READ044
from descgen.core.findings import InputError, Where
from descgen.core.moveit_model import (
    InitialPosition,
    JointLimits,
    KinematicsGroup,
    MoveItConfig,
    MoveItController,
    TypeProblem,
)
from descgen.infra.safeio import read_in_folder, refuse_outside
from descgen.infra.yamlsource import MAX_BYTES, Document, loads

FILES = (
    "joint_limits.yaml",
    "moveit_controllers.yaml",
    "kinematics.yaml",
    "initial_positions.yaml",
    "pilz_cartesian_limits.yaml",
)
# pilz_cartesian_limits.yaml: MoveItConfigsBuilder loads it by default (moveit_configs_builder.py,
# jazzy: to_moveit_configs -> pilz_cartesian_limits -> load_yaml) and the Pilz planner reads doubles
_PILZ_DOUBLES = ("max_trans_vel", "max_trans_acc", "max_trans_dec", "max_rot_vel")

# joint_limits.<joint>: each double and the has_* flag under which MoveIt reads it (None: always
# read). robot_model_loader reads min/max_position unconditionally; Pilz reads the rest only
# when the flag is true. A value MoveIt never reads cannot fail its type.
_LIMIT_DOUBLES: dict[str, str | None] = {
    "max_position": None,
    "min_position": None,
    "max_velocity": "has_velocity_limits",
    "max_acceleration": "has_acceleration_limits",
    "max_jerk": "has_jerk_limits",
    "max_effort": "has_effort_limits",
    "k_position": "has_soft_limits",
    "k_velocity": "has_soft_limits",
    "soft_lower_limit": "has_soft_limits",
    "soft_upper_limit": "has_soft_limits",
}
_LIMIT_FLAGS = (
    "has_position_limits",
    "has_velocity_limits",
    "has_acceleration_limits",
    "has_jerk_limits",
    "has_effort_limits",
    "has_soft_limits",
    "angle_wraparound",
)
_SCALING = ("default_velocity_scaling_factor", "default_acceleration_scaling_factor")
_KINEMATICS_DOUBLES = (
    "kinematics_solver_search_resolution",
    "kinematics_solver_timeout",
    "epsilon",
    "orientation_vs_position",
)

P = tuple[str | int, ...]


def _got(value: object) -> str:
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list):
        return "list"
    if isinstance(value, dict):
        return "mapping"
    return "null" if value is None else type(value).__name__


def _shown(value: object) -> str:
    text = repr(value) if isinstance(value, str) else str(value).lower() if isinstance(value, bool) else str(value)
    return text if len(text) <= 60 else text[:57] + "..."


class _File:
    """One YAML file: typed getters that record a TypeProblem and read a wrong value as None."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.problems: list[TypeProblem] = []

    def where(self, path: P, key: bool = False) -> Where:
        return self.doc.where(path, key)

    def _wrong(self, path: P, expected: str, value: object) -> None:
        dotted = ".".join(map(str, path))
        self.problems.append(TypeProblem(dotted, expected, _got(value), _shown(value), self.where(path)))

    def mapping(self, data: dict[str, Any], path: P) -> dict[str, Any] | None:
        value = data.get(str(path[-1]))
        if value is None:
            return None
        if not isinstance(value, dict):
            self._wrong(path, "mapping", value)
            return None
        return value

    def double(self, data: dict[str, Any], path: P, *, read: bool = True) -> float | None:
        """A ROS double: ``1`` is an integer parameter, and rclcpp refuses it where a double is
        declared (ParameterTypeException). ``read=False``: MoveIt never reads it, no problem."""
        key = str(path[-1])
        if key not in data:
            return None
        value = data[key]
        if isinstance(value, bool) or not isinstance(value, int | float):
            if read:
                self._wrong(path, "double", value)
            return None
        if isinstance(value, int):
            if read:
                self._wrong(path, "double", value)
            return float(value) if abs(value) < 1e300 else None
        return value if math.isfinite(value) else None

    def number(self, data: dict[str, Any], path: P) -> float | None:
        """Any number (read by Python, where 1 and 1.0 are the same)."""
        value = data.get(str(path[-1]))
        if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(float(value)):
            self._wrong(path, "number", value)
            return None
        return float(value)

    def boolean(self, data: dict[str, Any], path: P) -> bool | None:
        key = str(path[-1])
        if key not in data:
            return None
        value = data[key]
        if not isinstance(value, bool):
            self._wrong(path, "bool", value)
            return None
        return value

    def string(self, data: dict[str, Any], path: P) -> str | None:
        key = str(path[-1])
        if key not in data:
            return None
        value = data[key]
        if not isinstance(value, str):
            self._wrong(path, "string", value)
            return None
        return value

    def strings(self, data: dict[str, Any], path: P) -> tuple[str, ...] | None:
        key = str(path[-1])
        if key not in data:
            return None
        value = data[key]
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            self._wrong(path, "string array", value)
            return None
        return tuple(value)


def _load(path: Path, root: Path) -> _File:
    shown = str(path)
    raw = read_in_folder(path, root, "MoveIt config YAML", MAX_BYTES, display=shown)
    text = raw.decode("utf-8-sig", "replace")
    try:
        doc = loads(text, shown)
    except InputError as exc:
        if any(f.code == "YAML004" for f in exc.findings):  # its hint speaks of specs
            raise _not_mapping(shown, "the file is empty", Where(shown, 1, 1)) from None
        raise
    if not isinstance(doc.data, dict):
        raise _not_mapping(shown, f"the file is {_got(doc.data)}, not a YAML mapping", doc.where(()))
    return _File(doc)


def _not_mapping(shown: str, message: str, where: Where) -> InputError:
    name = Path(shown).name
    return InputError(
        [
            MOVEIT020.finding(
                f"{name}: {message}",
                "MoveIt loads this file as ROS parameters: write it as 'key: value' lines "
                "(see moveit_resources' panda_moveit_config/config)",
                "file",
                where,
            )
        ]
    )


def config_folder(path: Path) -> Path:
    """A package folder stands for its ``config/``; a config folder for itself."""
    return path / "config" if (path / "config").is_dir() else path


def find_srdf(folder: Path, robot_name: str) -> Path | None:
    """The SRDF MoveItConfigsBuilder would take: ``<robot>.srdf``, else the only ``*.srdf``.
    The robot's name (an audited URDF's, anyone's text) is a file name only when it is one plain
    component: ``../../x`` never becomes a path out of the folder."""
    plain = robot_name not in ("", ".", "..") and "/" not in robot_name and "\x00" not in robot_name
    named = folder / f"{robot_name}.srdf"
    if plain and named.is_file():
        return named
    found = sorted(p for p in folder.glob("*.srdf") if p.is_file())
    return found[0] if len(found) == 1 else None


def read_moveit_config(path: Path) -> MoveItConfig:
    """Every MoveIt YAML file of the package or config folder ``path`` (absent files are None)."""
    folder = config_folder(path)
    shown = str(folder)
    if not folder.is_dir():
        raise InputError(
            [
                MOVEIT021.finding(
                    "not a folder" if folder.exists() else "folder not found",
                    "name a MoveIt config package (the folder that holds config/joint_limits.yaml)",
                    "file",
                    Where(shown),
                )
            ]
        )
    refuse_outside(folder, path, "config folder", code=READ044, display=shown)  # config/ a link out
    present = {name: folder / name for name in FILES if os.path.lexists(folder / name)}
    if not present:
        raise InputError(
            [
                MOVEIT021.finding(
                    f"no MoveIt config files here (none of {', '.join(FILES)})",
                    "name a MoveIt config package, as the Setup Assistant lays it out (config/, launch/)",
                    "file",
                    Where(shown),
                )
            ]
        )
    problems: list[TypeProblem] = []
    config = MoveItConfig(shown, Where(shown))
    fields: dict[str, Any] = {}
    if "joint_limits.yaml" in present:
        f = _load(present["joint_limits.yaml"], path)
        fields |= _joint_limits(f)
        problems += f.problems
    if "moveit_controllers.yaml" in present:
        f = _load(present["moveit_controllers.yaml"], path)
        fields |= _controllers(f)
        problems += f.problems
    if "kinematics.yaml" in present:
        f = _load(present["kinematics.yaml"], path)
        fields |= {"kinematics_file": f.doc.file, "kinematics": _kinematics(f)}
        problems += f.problems
    if "pilz_cartesian_limits.yaml" in present:
        f = _load(present["pilz_cartesian_limits.yaml"], path)
        block = f.mapping(f.doc.data, ("cartesian_limits",))
        for key in _PILZ_DOUBLES:
            if block is not None:
                f.double(block, ("cartesian_limits", key))
        fields |= {"pilz_cartesian_limits_file": f.doc.file}
        problems += f.problems
    if "initial_positions.yaml" in present:
        f = _load(present["initial_positions.yaml"], path)
        fields |= {"initial_positions_file": f.doc.file, "initial_positions": _initial(f)}
        problems += f.problems
    return MoveItConfig(**{**config.__dict__, **fields, "type_problems": tuple(problems)})


def _joint_limits(f: _File) -> dict[str, Any]:
    data = f.doc.data
    for key in _SCALING:
        f.double(data, (key,))
    block = f.mapping(data, ("joint_limits",))
    entries: list[JointLimits] = []
    for joint, entry in (block or {}).items():
        path: P = ("joint_limits", joint)
        if not isinstance(entry, dict):
            f.mapping(block or {}, path)
            continue
        flags = {k: f.boolean(entry, (*path, k)) for k in _LIMIT_FLAGS}
        values = {
            k: f.double(entry, (*path, k), read=flag is None or flags[flag] is True)
            for k, flag in _LIMIT_DOUBLES.items()
        }
        marks = tuple((str(k), f.where((*path, str(k)))) for k in entry)
        entries.append(
            JointLimits(
                str(joint),
                f.where(path, key=True),
                flags["has_velocity_limits"],
                values["max_velocity"],
                flags["has_acceleration_limits"],
                values["max_acceleration"],
                values["min_position"],
                values["max_position"],
                marks,
            )
        )
    where = f.where(("joint_limits",), key=True) if block is not None else Where(f.doc.file, 1, 1)
    return {"joint_limits_file": f.doc.file, "joint_limits": tuple(entries), "joint_limits_where": where}


def _controllers(f: _File) -> dict[str, Any]:
    base: P = ("moveit_simple_controller_manager",)
    msc = f.mapping(f.doc.data, base) or {}
    names = f.strings(msc, (*base, "controller_names"))
    names_where = f.where((*base, "controller_names"), key=True) if "controller_names" in msc else None
    sections = [k for k in msc if k != "controller_names"]
    out: list[MoveItController] = []
    for i, name in enumerate([*(names or ()), *(s for s in sections if s not in (names or ()))]):
        listed = names is not None and name in names
        path: P = (*base, name)
        entry = msc.get(name)
        if entry is not None and not isinstance(entry, dict):
            f.mapping(msc, path)
            entry = None
        if entry is None:
            index = (names or ()).index(name) if listed else i
            out.append(MoveItController(name, f.where((*base, "controller_names", index)), listed, False))
            continue
        type_ = f.string(entry, (*path, "type"))
        if type_ in ("GripperCommand", "ParallelGripperCommand"):
            f.double(entry, (*path, "max_effort"))
        if type_ == "ParallelGripperCommand":
            f.double(entry, (*path, "max_velocity"))
        if type_ == "GripperCommand":
            f.boolean(entry, (*path, "parallel"))
            f.boolean(entry, (*path, "allow_failure"))
            f.string(entry, (*path, "command_joint"))
        out.append(
            MoveItController(
                name,
                f.where(path, key=True),
                listed,
                True,
                f.string(entry, (*path, "action_ns")),
                type_,
                f.boolean(entry, (*path, "default")),
                f.strings(entry, (*path, "joints")),
                tuple((str(k), f.where((*path, str(k)))) for k in entry),
            )
        )
    return {"controllers_file": f.doc.file, "controllers": tuple(out), "controller_names_where": names_where}


def _kinematics(f: _File) -> tuple[KinematicsGroup, ...]:
    out = []
    for group, entry in f.doc.data.items():
        if not isinstance(entry, dict):
            f.mapping(f.doc.data, (group,))
            continue
        for key in _KINEMATICS_DOUBLES:
            f.double(entry, (group, key))
        solver = f.string(entry, (group, "kinematics_solver"))
        out.append(
            KinematicsGroup(str(group), f.where((group,), key=True), solver, f.where((group, "kinematics_solver")))
        )
    return tuple(out)


def _initial(f: _File) -> tuple[InitialPosition, ...]:
    block = f.mapping(f.doc.data, ("initial_positions",))
    if block is None:
        if "initial_positions" not in f.doc.data:
            f.problems.append(TypeProblem("initial_positions", "mapping", "absent", "", Where(f.doc.file, 1, 1)))
        return ()
    return tuple(
        InitialPosition(str(j), f.number(block, ("initial_positions", j)), f.where(("initial_positions", j)))
        for j in block
    )
