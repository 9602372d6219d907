"""Render the description package from the model with jinja2 (templates only format)."""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Collection
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
from jinja2.exceptions import SecurityError
from jinja2.sandbox import ImmutableSandboxedEnvironment

from descgen.codes.generate import GEN061, GEN065
from descgen.core.cache_dir import cache_folder
from descgen.core.findings import InputError, Where
from descgen.core.model import WAIVERS_FILE, Robot
from descgen.infra import keys
from descgen.infra.evidence_hash import sha256
from descgen.infra.safeio import MIB, Codes, read_in_folder
from descgen.meshes.paths import MESH_FOLDER, own_meshes
from descgen.render import context, escaping, header, mjcf
from descgen.render.escaping import TextEscaping, escape_text
from descgen.render.formatting import comment, dot, mdcell, mdcode, mermaid, num, pyinner, pystr, vec, yamlstr

XML_TEMPLATES = ("xml.j2", "urdf.j2", "xacro.j2", "srdf.j2")


def default_templates() -> Path:
    return Path(str(resources.files("descgen.templates")))


@functools.cache
def _bytecode_cache(sandboxed: bool) -> jinja2.BytecodeCache | None:
    """Compiled templates kept in the user cache folder (descgen/core/cache_dir.py), like Python's
    own __pycache__: compiling the 40-odd templates is half of a warm ``check``. jinja2 keys an
    entry by the template's name and file and recompiles when the source's checksum differs;
    None (compile every time) when caching is off or the folder cannot be made.

    The code depends on more than the source, so the folder is named by a key of the rest
    (descgen/infra/keys.py): jinja2's version, the environment (the sandbox compiles calls
    through ``environment.call``, which checks them; plain code calls directly: one loaded by
    the other crashes, or skips the sandbox's checks) and the code generator (escaping.py, by
    its bytes). Not by the rest of descgen's source: no other module shapes the compiled code,
    and a folder per edit would pile up (nothing prunes them)."""
    generator = sha256(Path(escaping.__file__).read_bytes())
    kind = "sandbox" if sandboxed else "plain"
    key = keys.key("compiled templates", 1, {"environment": kind, "generator": generator}, ("Jinja2",), keys.NOTHING)
    folder = cache_folder(f"jinja2-{kind}-{key[:16]}")
    if folder is None:
        return None
    return jinja2.FileSystemBytecodeCache(str(folder))


class _Environment(jinja2.Environment):
    code_generator_class = TextEscaping
    escape_text = staticmethod(escape_text)


class _SandboxedEnvironment(ImmutableSandboxedEnvironment):
    """The sandbox checks what a template reaches for at run time (attributes, calls); the
    compiled output calls escape_text directly, as it calls markupsafe's escape otherwise."""

    code_generator_class = TextEscaping
    escape_text = staticmethod(escape_text)


MAX_TEMPLATE_BYTES = 1 * MIB  # descgen's largest template is a few kB
_TEMPLATE_CODES = Codes(unreadable=GEN065, not_regular=GEN065, too_large=GEN065)


class FolderLoader(jinja2.BaseLoader):
    """Templates of a folder that is input (a spec's ``templates:``, ``--templates``), read like
    any other input (docs/security.md): a template must be a regular file inside the folder, links
    resolved, of at most 1 MiB, else GEN065 at the template (exit 2), before a byte is rendered. A
    link to /proc/self/environ would otherwise render the environment into the package, and a FIFO
    block. Only ``*.j2`` files directly in the folder are templates. A name that is not in the
    folder falls through to the defaults."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder

    def get_source(self, environment: jinja2.Environment, template: str) -> tuple[str, str, Any]:
        from jinja2.loaders import split_template_path  # refuses ".." and absolute names

        parts = split_template_path(template)
        # a template is a file of the folder named *.j2, as descgen's own are: not any file a
        # spec's folder happens to hold ({% include ".git/config" %} with ``templates: ..``)
        if len(parts) != 1 or not parts[0].endswith(".j2") or parts[0].startswith("."):
            raise jinja2.TemplateNotFound(template)
        path = self.folder.joinpath(*parts)
        if not os.path.lexists(path):
            raise jinja2.TemplateNotFound(template)
        data = read_in_folder(path, self.folder, "template", MAX_TEMPLATE_BYTES, code=GEN065, codes=_TEMPLATE_CODES)
        text = data.decode("utf-8", "replace")
        seen = _mtime(path)
        return text, str(path), lambda: _mtime(path) == seen

    def list_templates(self) -> list[str]:
        return sorted(p.name for p in self.folder.iterdir() if p.is_file() and not p.is_symlink())


def _mtime(path: Path) -> float | None:
    try:
        return os.stat(path).st_mtime
    except (OSError, ValueError):
        return None


def environment(templates: Path | None = None, sandboxed: bool = False) -> jinja2.Environment:
    """Templates from ``templates`` (a team's overrides, by file name) before the defaults.

    ``sandboxed``: the overrides were named by a spec (``templates:``), which is someone
    else's data, so they render in jinja2's immutable sandbox (no ``__class__`` walks to
    Python, no mutation); a folder named with --templates is the user's own code."""
    loaders: list[jinja2.BaseLoader] = []
    if templates is not None:
        loaders.append(FolderLoader(templates))
    loaders.append(jinja2.FileSystemLoader(str(default_templates())))
    make = _SandboxedEnvironment if sandboxed else _Environment
    env = make(
        loader=jinja2.ChoiceLoader(loaders),
        bytecode_cache=_bytecode_cache(sandboxed),
        autoescape=jinja2.select_autoescape(enabled_extensions=XML_TEMPLATES, default_for_string=False, default=False),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
    )
    env.filters["num"] = num
    env.filters["vec"] = vec
    env.filters["comment"] = comment
    env.filters["mdcell"] = mdcell
    # every output language gets its own escaping (docs/security.md, "Every file descgen writes")
    for f in (dot, mdcode, mermaid, pyinner, pystr, yamlstr):
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
    if robot.semantic is not None and robot.semantic.matrix is not None:
        files.append(("evidence/collision_matrix.md", "collision_matrix.md.j2", False))
        files.append(("evidence/sweep.md", "sweep.md.j2", False))  # descgen/prove/sweep.py
    files += [("evidence/frames.md", "frames.md.j2", False), ("evidence/frames.dot", "frames.dot.j2", False)]
    if robot.calibration:  # read by the Xacro (calibration:=FILE)
        files += [
            ("config/calibration/default.yaml", "calibration_default.yaml.j2", False),
            ("config/calibration/nominal.yaml", "calibration_nominal.yaml.j2", False),
        ]
    if robot.waivers:  # read by descgen audit of the package's files (descgen/read/package_waivers.py)
        files.append((WAIVERS_FILE, "descgen-waivers.yaml.j2", False))
    return files


def install_dirs(robot: Robot) -> list[str]:
    """The folders CMake installs to share/<package>: those of the generated files, and
    ``meshes`` when the robot has meshes of its own. ``evidence`` is for reviewers of the
    source tree, not for a robot at run time, so it is not installed."""
    folders = {path.split("/")[0] for path, _, _ in outputs(robot) if "/" in path} - {"evidence"}
    folders |= {mjcf.FOLDER} if mjcf.wanted(robot) else set()  # hardware:=mujoco's model, found by $(find)
    return sorted(folders | ({MESH_FOLDER} if own_meshes(robot) else set()))


def render_package(
    robot: Robot,
    spec_display: str,
    templates: Path | None = None,
    sandboxed: bool = False,
    only: Collection[str] | None = None,
    sweep: Callable[[Robot], dict[str, Any]] | None = None,
) -> dict[str, str]:
    """Every file of ``<robot>_description/``, path -> text, each with its header; or only the
    paths in ``only`` (generate needs the URDF alone before the collision matrix exists, and
    building the other contexts, the sweep's above all, would be thrown away). ``sweep`` gives
    the table of evidence/sweep.md (descgen/prove/sweep.py: context), which a robot with a
    sampled collision matrix has; it is called only when that file is rendered."""
    env = environment(templates, sandboxed)
    wanted = [(path, template, xacro) for path, template, xacro in outputs(robot) if only is None or path in only]
    contexts = {x: context.build(robot, xacro=x) for x in sorted({xacro for _, _, xacro in wanted})}
    for ctx in contexts.values():
        ctx["package"]["install_dirs"] = install_dirs(robot)
    sweep_doc = "evidence/sweep.md"
    if robot.semantic is not None and robot.semantic.matrix is not None and (only is None or sweep_doc in only):
        if sweep is None:
            raise ValueError("a robot with a collision matrix renders evidence/sweep.md: pass its sweep table")
        contexts[False]["sweep"] = sweep(robot)
    out: dict[str, str] = {}
    for path, template, xacro in wanted:
        body = _render(env, template, contexts[xacro], templates)
        out[path] = header.add(path, body, spec_display, robot.spec_hash or "0" * 64)
    mujoco_model = mjcf.path(robot)
    if mjcf.wanted(robot) and (only is None or mujoco_model in only):  # hardware:=mujoco's model
        out[mujoco_model] = header.add(mujoco_model, mjcf.model(robot).text, spec_display, robot.spec_hash or "0" * 64)
    return dict(sorted(out.items()))


def _render(env: jinja2.Environment, template: str, ctx: dict[str, Any], templates: Path | None) -> str:
    """One template rendered; an override that does not parse, fails, or (sandboxed) reaches
    for what the sandbox refuses is an input error at the template, never a traceback."""
    try:
        return env.get_template(template).render(ctx)
    except jinja2.TemplateError as exc:
        file = getattr(exc, "filename", None) or str((templates or default_templates()) / template)
        line = getattr(exc, "lineno", None) or 0
        refused = isinstance(exc, SecurityError)
        raise InputError(
            [
                GEN061.finding(
                    f"template {template} "
                    + ("asks for what the template sandbox refuses" if refused else "failed")
                    + f": {exc.message or type(exc).__name__}",
                    "templates named by a spec render in jinja2's sandbox: use only the context's values and "
                    "filters; or fix the template",
                    f"file:{template}",
                    Where(file, line),
                )
            ]
        ) from None
