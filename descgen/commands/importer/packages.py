"""The packages of an imported spec: ``package_paths:``, the folders that hold the packages
its ``package://`` meshes name, recorded relative to the spec (descgen/meshes/paths.py), so
``validate`` and ``generate`` find the same files as the audit did; and ``package.name``, the
generated package's own name, when ``<robot>_description`` cannot be it.

A folder named with ``--package-path`` (or the description's own) is recorded relative to the
spec, inside the project or not (a workspace beside it, ``../../ws/src``); one the sourced
environment gave (AMENT_PREFIX_PATH, ROS_PACKAGE_PATH) is not: any machine that sources its
workspace finds it the same way (descgen/meshes/packages.py), and a path to this machine's
/opt/ros would be wrong on the next.

The generated package's name must be a REP 144 name (``2dof_planar_description`` is not) and
must not be a package the meshes come from: UR's robot ``ur`` would generate ``ur_description``,
the very package whose meshes it references; two packages of one name shadow each other in a
workspace, and the spec would name its own package for the meshes (SPEC062). The imported
package is then ``<robot>_descgen_description``, beside the upstream one (IMP014).
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from descgen.codes.importer import IMP014, IMP036
from descgen.core import model as m
from descgen.core.findings import Finding, Where
from descgen.meshes.packages import Owners, environment
from descgen.meshes.paths import named_packages, package_root
from descgen.read.xacro_file import find_package
from descgen.spec.models import rep144_problem, suggest_package_name


def package_paths(
    robot: m.Robot, description: Path, spec: Path, given: Sequence[Path]
) -> tuple[list[str], list[Finding]]:
    """(folders to record, relative to ``spec``; findings, none today).

    The search is the audit's (mesh_paths.mesh_status): the given folders in order (the
    command's search: --package-path, then the environment's), then the description's own
    package, nothing else, so the spec finds what the audit found. A package found through
    the environment is not recorded (the module's docstring)."""
    search = [*given, package_root(description.resolve().parent)]
    sourced = set(environment(os.environ))
    spec_dir = spec.resolve().parent
    folders: list[str] = []
    for pkg in named_packages(robot):
        folder = next((f for f in search if find_package(pkg, [f]) is not None), None)
        if folder is None or folder in sourced:
            continue  # not found at all (the audit reports its meshes: GEOM), or found as ROS finds it
        rel = Path(os.path.relpath(folder.resolve(), spec_dir)).as_posix()
        if rel not in folders:
            folders.append(rel)
    return folders, []


# an absolute path in a pass-through text or attribute, up to a quote, space, markup or separator
_ABSOLUTE = re.compile(r"/[^\s\"'<>;:,]+")


def symbolic(xml: str, search: Sequence[Path]) -> str:
    """``xml`` (a pass-through element) with every absolute path into a package written
    ``$(find pkg)/...``: what the Xacro said before it was expanded on this machine (a Gazebo
    plugin's ``<parameters>$(find pkg)/config/controllers.yaml</parameters>``), so the spec and
    the generated package hold no path of this machine, and package.xml depends on ``pkg``
    (:class:`~descgen.meshes.packages.Owners` says which package a path is in)."""
    owners = Owners(search)

    def replace(m: re.Match[str]) -> str:
        text = m.group()
        path = "/" + text.lstrip("/")  # file:///x matches from its second slash: keep those before
        found = owners.of(path)
        if found is None:
            return text
        return text[: len(text) - len(path)] + f"$(find {found[0]})" + (f"/{found[2]}" if found[2] else "")

    return _ABSOLUTE.sub(replace, xml)


def package_meshes(robot: m.Robot, search: Sequence[Path], shown: str) -> tuple[m.Robot, list[Finding]]:
    """``robot`` with every mesh named by an absolute path or ``file://`` that lies in a package
    (a Xacro's ``file://$(find pkg)/meshes/x.dae`` expanded) named ``package://pkg/meshes/x.dae``,
    and an IMP036 for each name so changed."""
    owners = Owners(search)
    renamed: dict[str, str] = {}
    for lk in robot.links:
        for shape in lk.shapes():
            g = shape.geometry
            if not isinstance(g, m.Mesh) or g.filename in renamed:
                continue
            written = g.filename.removeprefix("file://")
            if not os.path.isabs(written):
                continue
            inside = owners.of(written)
            if inside is not None and inside[2]:
                renamed[g.filename] = f"package://{inside[0]}/{inside[2]}"
    if not renamed:
        return robot, []

    def shape_(s: m.Visual | m.Collision) -> m.Visual | m.Collision:
        g = s.geometry
        if isinstance(g, m.Mesh) and g.filename in renamed:
            return dataclasses.replace(s, geometry=dataclasses.replace(g, filename=renamed[g.filename]))
        return s

    links = tuple(
        dataclasses.replace(
            lk,
            visuals=tuple(shape_(v) for v in lk.visuals),  # type: ignore[misc]
            collisions=tuple(shape_(c) for c in lk.collisions),  # type: ignore[misc]
        )
        for lk in robot.links
    )
    found = [
        IMP036.finding(
            f"mesh '{old}' is written '{new}' (it lies in that package; the path is this machine's)",
            "nothing to do: package:// finds the same file wherever the package is installed",
            f"mesh:{new}",
            Where(shown),
        )
        for old, new in renamed.items()
    ]
    return dataclasses.replace(robot, links=links), found


def package_name(robot: m.Robot, where: Where) -> tuple[str | None, list[Finding]]:
    """(``package.name`` to write, or None when ``<robot>_description`` is right; IMP014 saying why)."""
    derived = f"{robot.name}_description"
    taken = set(named_packages(robot))
    name = derived if rep144_problem(derived) is None else suggest_package_name(derived)
    while name in taken:
        name = f"{name.removesuffix('_description')}_descgen_description"
    if name == derived:
        return None, []
    why = (
        f"'{derived}' is a package the description names (its meshes, or $(find {derived}) in pass-through)"
        if derived in taken
        else f"'{derived}' is not a ROS package name: {rep144_problem(derived)} (REP 144)"
    )
    return name, [
        IMP014.finding(
            f"the generated package is named '{name}' (package.name): {why}",
            "rename it under package: if you like (a REP 144 name that no other package has); the robot keeps its name",
            "package",
            where,
        )
    ]


def with_package_name(data: dict[str, Any], name: str) -> dict[str, Any]:
    """``package: {name: ...}`` right after the robot's name, where a reader looks for it."""
    head = {k: data[k] for k in ("name",) if k in data}
    return head | {"package": {"name": name}} | {k: v for k, v in data.items() if k not in head}
