"""``descgen audit``: read any description (spec, URDF, Xacro; plus SRDF and controllers
YAML) into the model, resolve its mesh files, and run every rule."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..findings import Finding, Where
from ..model import Mesh, MeshState, Robot, Ros2Control
from ..readers.controllers import read_controllers_text
from ..readers.srdf import read_srdf_text
from ..readers.urdf import read_urdf_text
from ..readers.xacro_file import expand, find_package
from ..safeio import check_file, read_bounded, read_head
from .registry import run


@dataclass(frozen=True)
class Options:
    srdf: Path | None = None
    controllers: Path | None = None
    xacro_args: Mapping[str, str] = field(default_factory=dict)
    package_paths: Sequence[Path] = ()
    trust_xacro: bool = False  # expand with xacro's own evaluator (runs the file's Python)


def kind_of(path: Path) -> str:
    name = path.name.lower()
    if name.endswith((".yaml", ".yml")):
        return "spec"
    if name.endswith(".xacro"):
        return "xacro"
    if name.endswith(".urdf"):
        return "urdf"
    head = read_head(path, 4096)  # not read_bytes()[:4096]: that reads all of a 1 GB file (or /dev/zero)
    return "xacro" if b"xmlns:xacro" in head else "urdf"


def _package_root(start: Path) -> Path:
    for folder in (start, *start.parents):
        if (folder / "package.xml").is_file():
            return folder
    return start


def mesh_status(robot: Robot, description: Path, package_paths: Sequence[Path]) -> dict[str, MeshState]:
    """ok | missing | escapes | unresolved, for every mesh filename."""
    out: dict[str, MeshState] = {}
    base = description.resolve().parent
    for lk in robot.links:
        for shape in lk.shapes():
            g = shape.geometry
            if not isinstance(g, Mesh) or g.filename in out:
                continue
            try:
                out[g.filename] = _mesh_state(g.filename, base, package_paths)
            except (OSError, ValueError):
                # a name longer than the OS allows, a symlink loop, a NUL byte: no file can be there
                out[g.filename] = "missing"
    return out


def _mesh_state(name: str, base: Path, package_paths: Sequence[Path]) -> MeshState:
    if name.startswith("package://"):
        pkg, _, rest = name[len("package://") :].partition("/")
        root = find_package(pkg, [*package_paths, base.parent, base]) if pkg else None
        if root is None:
            return "unresolved"
        target = (root / rest).resolve()
        root = root.resolve()
    elif name.startswith("file://") or name.startswith("/"):
        return "escapes"
    else:
        root = _package_root(base).resolve()
        target = (base / name).resolve()
    if not target.is_relative_to(root):
        return "escapes"
    return "ok" if target.is_file() else "missing"


def load_description(path: Path, options: Options = Options()) -> tuple[Robot, list[Finding]]:
    """The model of one description and what its readers reported. InputError when unusable."""
    shown = str(path)
    check_file(path, "description", display=shown)  # missing, a FIFO, a device, too large: before any read
    kind = kind_of(path)
    found: list[Finding] = []
    if kind == "spec":
        from ..spec import load_spec

        robot = load_spec(path, shown, rules=False).robot
    else:
        if kind == "xacro":
            data = expand(path, shown, options.xacro_args, options.package_paths, options.trust_xacro)
        else:
            data = read_bounded(path, "URDF", display=shown)
        display = f"{shown} (expanded)" if kind == "xacro" else shown
        robot, found = read_urdf_text(data, display)
    if options.srdf is not None:
        semantic, srdf_name, more = read_srdf_text(_read(options.srdf, "SRDF"), str(options.srdf))
        found += more
        robot = dataclasses.replace(robot, semantic=dataclasses.replace(semantic, robot_name=srdf_name))
    if options.controllers is not None:
        controllers, rate, more = read_controllers_text(
            _read(options.controllers, "controllers YAML").decode("utf-8", "replace"), str(options.controllers)
        )
        found += more
        rc = robot.ros2_control or Ros2Control("", where=Where(str(options.controllers)))
        robot = dataclasses.replace(
            robot, ros2_control=dataclasses.replace(rc, controllers=controllers, update_rate=rate)
        )
    status = mesh_status(robot, path, options.package_paths)
    return dataclasses.replace(robot, mesh_status=tuple(status.items())), found


def _read(path: Path, what: str) -> bytes:
    return read_bounded(path, what)


def audit(path: Path, options: Options = Options()) -> list[Finding]:
    """Every finding for one description: what its readers reported, then every rule."""
    robot, found = load_description(path, options)
    return found + run(robot)
