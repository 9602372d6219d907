"""Render the description package from the model with jinja2 (templates only format)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import jinja2

from ..model import Robot
from . import context, header
from .formatting import comment, dot, mdcell, mermaid, num, pyinner, pystr, vec, yamlstr

XML_TEMPLATES = ("xml.j2", "urdf.j2", "xacro.j2", "srdf.j2")


def default_templates() -> Path:
    return Path(str(resources.files("descgen.templates")))


def environment(templates: Path | None = None) -> jinja2.Environment:
    """Templates from ``templates`` (a team's overrides, by file name) before the defaults."""
    loaders: list[jinja2.BaseLoader] = []
    if templates is not None:
        loaders.append(jinja2.FileSystemLoader(str(templates)))
    loaders.append(jinja2.FileSystemLoader(str(default_templates())))
    env = jinja2.Environment(
        loader=jinja2.ChoiceLoader(loaders),
        autoescape=jinja2.select_autoescape(enabled_extensions=XML_TEMPLATES, default_for_string=False, default=False),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
    )
    env.filters["num"] = num
    env.filters["vec"] = vec
    env.filters["comment"] = comment
    env.filters["mdcell"] = mdcell
    # every output language gets its own escaping (DESIGN.md, "Trust boundary")
    for f in (dot, mermaid, pyinner, pystr, yamlstr):
        env.filters[f.__name__] = f
    return env


def outputs(robot: Robot) -> list[tuple[str, str, bool]]:
    """(path in the package, template, uses the Xacro context) for every file."""
    n = robot.name
    files = [
        ("package.xml", "package.xml.j2", False),
        ("CMakeLists.txt", "CMakeLists.txt.j2", False),
        (f"urdf/{n}.urdf.xacro", "robot.urdf.xacro.j2", True),
        (f"urdf/{n}.urdf", "robot.urdf.j2", False),
        ("launch/display.launch.py", "display.launch.py.j2", False),
        (f"rviz/{n}.rviz", "robot.rviz.j2", False),
    ]
    if robot.ros2_control is not None:
        files += [
            (f"urdf/{n}.ros2_control.xacro", "robot.ros2_control.xacro.j2", True),
            ("config/ros2_controllers.yaml", "ros2_controllers.yaml.j2", False),
            ("launch/control.launch.py", "control.launch.py.j2", False),
        ]
    if robot.semantic is not None:
        files.append((f"srdf/{n}.srdf", "robot.srdf.j2", False))
    if robot.known_poses:
        files.append(("evidence/known_poses.md", "known_poses.md.j2", False))
    files += [("evidence/frames.md", "frames.md.j2", False), ("evidence/frames.dot", "frames.dot.j2", False)]
    return files


def render_package(robot: Robot, spec_display: str, templates: Path | None = None) -> dict[str, str]:
    """Every file of ``<robot>_description/``, path -> text, each with its header."""
    env = environment(templates)
    contexts = {False: context.build(robot, xacro=False), True: context.build(robot, xacro=True)}
    out: dict[str, str] = {}
    for path, template, xacro in outputs(robot):
        body = env.get_template(template).render(contexts[xacro])
        out[path] = header.add(path, body, spec_display, robot.spec_hash or "0" * 64)
    return dict(sorted(out.items()))
