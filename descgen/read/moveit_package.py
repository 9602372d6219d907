"""A MoveIt config package read beside a robot, and audited with the MOVEIT rules.

``descgen audit URDF --moveit-config DIR`` and ``check`` (on the generated
``<robot>_moveit_config``) both come here. The package's SRDF and ros2_controllers.yaml are
read only when the caller has none: an ``--srdf``/``--controllers`` given on the command line,
or a spec's own semantics and controllers, win.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

from descgen.audit.registry import RULES, run
from descgen.core.findings import Finding, Where
from descgen.core.model import Robot, Ros2Control
from descgen.infra.safeio import read_in_folder
from descgen.read.controllers import read_controllers_file
from descgen.read.moveit_config import config_folder, find_srdf, read_moveit_config
from descgen.read.srdf import read_srdf_text


def attach(
    robot: Robot, path: Path, *, read_srdf: bool = True, read_controllers: bool = True
) -> tuple[Robot, list[Finding]]:
    """``robot`` with ``moveit_config`` set (and the package's SRDF and ros2_controllers.yaml
    when asked and present), plus what their readers reported. InputError when unusable."""
    config = read_moveit_config(path)
    folder = config_folder(path)
    found: list[Finding] = []
    srdf = find_srdf(folder, robot.name) if read_srdf else None
    if srdf is not None:
        semantic, name, more = read_srdf_text(read_in_folder(srdf, path, "SRDF"), str(srdf))
        found += more
        robot = dataclasses.replace(robot, semantic=dataclasses.replace(semantic, robot_name=name))
        config = dataclasses.replace(config, srdf_file=str(srdf))
    yaml_file = folder / "ros2_controllers.yaml"
    if read_controllers and os.path.lexists(yaml_file):
        text = read_in_folder(yaml_file, path, "controllers YAML").decode("utf-8", "replace")
        cf = read_controllers_file(text, str(yaml_file))
        found += cf.found
        rc = robot.ros2_control or Ros2Control("", where=Where(str(yaml_file)))
        robot = dataclasses.replace(
            robot,
            ros2_control=dataclasses.replace(
                rc, controllers=cf.controllers, update_rate=cf.update_rate, update_rate_where=cf.update_rate_where
            ),
        )
        config = dataclasses.replace(config, ros2_controllers_file=str(yaml_file))
    return dataclasses.replace(robot, moveit_config=config), found


def moveit_codes() -> list[str]:
    run(Robot(""), codes=())  # registers every rule module
    return sorted(c for c in RULES if c.startswith("MOVEIT"))


def audit_moveit_config(robot: Robot, config_dir: Path) -> list[Finding]:
    """The MOVEIT findings for the MoveIt config package (or its config/ folder) ``config_dir``
    read beside ``robot``. The package's SRDF and ros2_controllers.yaml stand in only for what
    the robot lacks. InputError (exit 2) when a file cannot be read."""
    has_controllers = robot.ros2_control is not None and bool(robot.ros2_control.controllers)
    full, found = attach(robot, config_dir, read_srdf=robot.semantic is None, read_controllers=not has_controllers)
    return found + run(full, codes=moveit_codes())
