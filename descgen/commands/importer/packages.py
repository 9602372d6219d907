"""The packages of an imported spec: ``package_paths:``, the folders that hold the packages
its ``package://`` meshes name, recorded relative to the spec (descgen/meshes/paths.py), so
``validate`` and ``generate`` find the same files as the audit did; and ``package.name``, the
generated package's own name, when ``<robot>_description`` cannot be it.

A spec may only record folders inside its project (mesh_paths.project_root); a package found
elsewhere is named on the command line instead (``--package-path``), and that is said (IMP012).

The generated package's name must be a REP 144 name (``2dof_planar_description`` is not) and
must not be a package the meshes come from: UR's robot ``ur`` would generate ``ur_description``,
the very package whose meshes it references; two packages of one name shadow each other in a
workspace, and the spec would name its own package for the meshes (SPEC062). The imported
package is then ``<robot>_descgen_description``, beside the upstream one (IMP014).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from descgen.codes.importer import IMP012, IMP014
from descgen.core import model as m
from descgen.core.findings import Finding, Where
from descgen.meshes.paths import PACKAGE_NAME, project_root, split_package_uri
from descgen.read.xacro_file import find_package
from descgen.spec.models import rep144_problem, suggest_package_name


def _packages(robot: m.Robot) -> list[str]:
    """Packages named by ``package://`` meshes, in the order they are first named."""
    found: dict[str, None] = {}
    for lk in robot.links:
        for shape in lk.shapes():
            g = shape.geometry
            if isinstance(g, m.Mesh) and (uri := split_package_uri(g.filename)) and PACKAGE_NAME.fullmatch(uri[0]):
                found.setdefault(uri[0])
    return list(found)


def package_paths(
    robot: m.Robot, description: Path, spec: Path, given: Sequence[Path]
) -> tuple[list[str], list[Finding]]:
    """(folders to record, relative to ``spec``; IMP012 for a package outside the project).

    The search is the audit's (mesh_paths.mesh_status): ``--package-path`` folders in order,
    then the description's package's parent and its own folder."""
    base = description.resolve().parent
    search = [*given, base.parent, base]
    spec_dir = spec.resolve().parent
    project = project_root(spec)
    folders: list[str] = []
    problems: list[Finding] = []
    for pkg in _packages(robot):
        folder = next((f for f in search if find_package(pkg, [f]) is not None), None)
        if folder is None:
            continue  # not found at all: the audit reports its meshes (GEOM)
        target = folder.resolve()
        if not target.is_relative_to(project):
            problems.append(_outside(pkg, target, project))
            continue
        rel = Path(os.path.relpath(target, spec_dir)).as_posix()
        if rel not in folders:
            folders.append(rel)
    return folders, problems


def _outside(pkg: str, folder: Path, project: Path) -> Finding:
    return IMP012.finding(
        f"package '{pkg}' (named by package:// meshes) is in {folder}, outside the spec's project "
        f"{project}, so the spec does not record it (package_paths: stay inside the project)",
        f"pass --package-path {folder} to validate, generate and check; the generated package references "
        f"its meshes and depends on {pkg} (exec_depend)",
        f"package:{pkg}",
        Where(str(folder)),
    )


def package_name(robot: m.Robot, where: Where) -> tuple[str | None, list[Finding]]:
    """(``package.name`` to write, or None when ``<robot>_description`` is right; IMP014 saying why)."""
    derived = f"{robot.name}_description"
    taken = set(_packages(robot))
    name = derived if rep144_problem(derived) is None else suggest_package_name(derived)
    while name in taken:
        name = f"{name.removesuffix('_description')}_descgen_description"
    if name == derived:
        return None, []
    why = (
        f"'{derived}' is the package the meshes come from (package://{derived}/...)"
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
