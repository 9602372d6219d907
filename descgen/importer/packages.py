"""``package_paths:`` of an imported spec: the folders that hold the packages its
``package://`` meshes name, recorded relative to the spec (descgen/mesh_paths.py), so
``validate`` and ``generate`` find the same files as the audit did.

A spec may only record folders inside its project (mesh_paths.project_root); a package
found elsewhere cannot be recorded, and that is said (IMP012), not silently dropped.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from .. import model as m
from ..findings import Finding, Where
from ..mesh_paths import PACKAGE_NAME, project_root, split_package_uri
from ..readers.xacro_file import find_package


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
    return Finding(
        "IMP012",
        "warning",
        f"package '{pkg}' (named by package:// meshes) is found in {folder}, outside the spec's project "
        f"{project}: the spec cannot record it under package_paths:",
        "copy the package into the project (e.g. beside specs/) and add its folder under package_paths:, "
        "or write the spec (-o) into a project that holds it; until then validate cannot find its meshes",
        f"package:{pkg}",
        Where(str(folder)),
    )
