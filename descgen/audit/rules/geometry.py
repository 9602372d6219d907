"""GEOM: visual and collision geometry, and the mesh files they name."""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import Collision, Link, MeshState, Robot, Visual
from descgen.physics import inertia
from descgen.physics.bodies import PLACEHOLDER, dims, moving_links, welded_count


@rule("GEOM001", "moving-link-without-collision", "warning")
def moving_link_without_collision(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a link that a joint moves, that has visual geometry but no collision geometry
    (on itself or on any link welded to it by fixed joints).
    ## Why is this bad?
    Planners and simulators see through it: the arm can be planned straight through the
    part you can see.
    """
    moving = moving_links(robot)
    colliding = welded_count(robot, lambda other: other.collisions)
    for lk in robot.links:
        collides = colliding.get(lk.name, 0) > 0
        if lk.name in moving and lk.visuals and not collides:
            yield at(
                "GEOM001",
                lk,
                f"moving link '{lk.name}' has visual but no collision geometry",
                "add a collision primitive (a box or cylinder around the visual is enough)",
            )


@rule("GEOM002", "collision-visual-size-mismatch", "warning")
def collision_visual_size_mismatch(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares the volume of a link's collision primitives with its visual primitives and
    flags a ratio beyond 10 either way.
    ## Why is this bad?
    A collision shape ten times too big blocks valid motions; ten times too small lets
    real collisions through. Usually one of them is in the wrong unit.
    """
    for lk in robot.links:
        if not lk.visuals or not lk.collisions:
            continue
        vv = [inertia.volume(v.geometry) if v.geometry else None for v in lk.visuals]
        cv = [inertia.volume(c.geometry) if c.geometry else None for c in lk.collisions]
        if any(x is None for x in vv + cv):
            continue
        if max((d for shape in lk.visuals for d in dims(shape.geometry)), default=0.0) < PLACEHOLDER:
            continue  # a marker visual on a collision stand-in
        v, c = sum(x for x in vv if x), sum(x for x in cv if x)
        if v > 0 and c > 0 and not 0.1 <= c / v <= 10:
            yield at(
                "GEOM002",
                lk,
                f"link '{lk.name}' collision volume is {c / v:.3g} times its visual volume",
                "make the collision geometry match what you see",
            )


def _meshes(robot: Robot, state: MeshState) -> Iterator[tuple[Link, Visual | Collision, str]]:
    """(link, shape, filename) for every mesh the reader resolved to ``state``
    (ok | missing | escapes | unresolved; see audit/inputs.mesh_status)."""
    status = dict(robot.mesh_status)
    if not status:
        return
    for lk in robot.links:
        for shape in lk.shapes():
            name = getattr(shape.geometry, "filename", None)
            if name and status.get(name) == state:
                yield lk, shape, name


@rule("GEOM003", "mesh-file-missing", "error")
def mesh_file_missing(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a mesh whose file does not exist (resolved against the description's folder and
    `--package-path` for `package://`).
    ## Why is this bad?
    RViz shows nothing and collision checking silently loses the part.
    """
    for lk, shape, name in _meshes(robot, "missing"):
        yield at(
            "GEOM003",
            shape,
            f"link '{lk.name}' mesh '{name}' does not exist",
            "fix the path or add the file",
            subject=lk.subject,
        )


@rule("GEOM004", "mesh-escapes-package", "error")
def mesh_escapes_package(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a mesh path that leaves its package folder (`..` past the package root, or an
    absolute path outside every package folder given; one inside is GEOM006).
    ## Why is this bad?
    It works on the author's machine only: installed packages cannot reach it.
    """
    for lk, shape, name in _meshes(robot, "escapes"):
        yield at(
            "GEOM004",
            shape,
            f"link '{lk.name}' mesh '{name}' points outside its package",
            "use package://<pkg>/<path inside the package>",
            subject=lk.subject,
        )


@rule("GEOM006", "mesh-absolute-path", "warning")
def mesh_absolute_path(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a mesh named by an absolute path or `file://` that lies in a package the search
    finds: what a Xacro's `file://$(find pkg)/meshes/x.dae` expands to.
    ## Why is this bad?
    The description works where it is expanded, but `robot_description` then carries that
    machine's path: RViz or MoveIt on another computer, or in a container, loads nothing.
    `package://` is resolved by each reader against its own installed packages.
    ## Example
    `<mesh filename="file://$(find my_robot)/meshes/base.dae"/>`
    ## Use instead
    `<mesh filename="package://my_robot/meshes/base.dae"/>` (`import` writes it so: IMP036).
    """
    for lk, shape, name in _meshes(robot, "ok"):
        if name.startswith("file://") or name.startswith("/"):
            yield at(
                "GEOM006",
                shape,
                f"link '{lk.name}' mesh '{name}' is this machine's absolute path into a package",
                "write package://<pkg>/<path inside the package>: every machine resolves it against its own packages",
                subject=lk.subject,
            )


@rule("GEOM005", "mesh-not-resolvable", "warning")
def mesh_not_resolvable(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a `package://` mesh whose package cannot be found (no `--package-path` holds it,
    or the URI names no package at all, as in `package:///abs/path`).
    ## Why is this bad?
    resource_retriever fails the same way on the robot: the part is invisible and has no
    collision shape. (Give --package-path to check the file itself.)
    """
    for lk, shape, name in _meshes(robot, "unresolved"):
        yield at(
            "GEOM005",
            shape,
            f"link '{lk.name}' mesh '{name}' names a package that cannot be found",
            "fix the package name, or pass --package-path",
            subject=lk.subject,
        )
