"""Self-collisions along each joint's sweep: pinocchio's collision API (coal), as the matrix.

The robot goes to pinocchio as a URDF written from the model with only what collision
needs: links with their collision shapes, joints with origin, axis and limits. A mesh is
named by the file the model resolved it to (``Robot.mesh_files``: inside the folders the
user named, checked before reading), so nothing else is opened; a mesh the model could not
resolve is left out and its link reported. Mimic followers are ordinary joints here: every
configuration sets them from their leader (descgen/physics/mimic.py) before pinocchio sees it.

A pair collides when coal finds the shapes closer than the padding (the matrix's security
margin). A run is a stretch of consecutive grid steps in which one pair collides.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Callable, Mapping, Sequence

from lxml import etree

from descgen.core.model import ONE_DOF, Mesh, Robot
from descgen.core.record import record
from descgen.physics import collision
from descgen.physics.sweep.motion import JointMotion, joint_values
from descgen.physics.urdf_xml import geometry, origin, xyz


@record
class Run:
    """``link1`` and ``link2`` collide from grid step ``first`` to ``last`` of ``joint``."""

    joint: str
    link1: str
    link2: str
    first: int
    last: int


def available() -> bool:
    """pinocchio (the ``collision`` extra) is installed."""
    return importlib.util.find_spec("pinocchio") is not None


def unresolved_meshes(robot: Robot) -> list[str]:
    """Links with a collision mesh the model did not resolve to a file (left out here)."""
    files = dict(robot.mesh_files)
    return [
        lk.name
        for lk in robot.links
        if any(isinstance(c.geometry, Mesh) and c.geometry.filename not in files for c in lk.collisions)
    ]


def pinocchio_urdf(robot: Robot) -> str:
    """The model as a URDF for pinocchio: collision shapes, joints, limits; meshes by file."""
    files = dict(robot.mesh_files)
    root = etree.Element("robot", name=robot.name or "robot")
    for lk in robot.links:
        link = etree.SubElement(root, "link", name=lk.name)
        for c in lk.collisions:
            g = c.geometry
            if g is None or (isinstance(g, Mesh) and g.filename not in files):
                continue
            el = etree.SubElement(link, "collision")
            origin(el, c.origin)
            geometry(el, g, files[g.filename] if isinstance(g, Mesh) else None)
    for j in robot.joints:
        if j.parent is None or j.child is None:
            continue
        el = etree.SubElement(root, "joint", name=j.name, type=j.type)
        etree.SubElement(el, "parent", link=j.parent)
        etree.SubElement(el, "child", link=j.child)
        origin(el, j.origin)
        if j.axis is not None and j.type != "fixed":
            etree.SubElement(el, "axis", xyz=xyz(j.axis))
        if j.type in ONE_DOF:
            lm = j.limit
            lower = lm.lower if lm and lm.lower is not None else 0.0
            upper = lm.upper if lm and lm.upper is not None else 0.0
            etree.SubElement(el, "limit", lower=repr(lower), upper=repr(upper), effort="0", velocity="0")
    return etree.tostring(root, encoding="unicode")


def runs(
    robot: Robot,
    motions: Sequence[JointMotion],
    state: Mapping[str, float],
    padding: float,
    progress: Callable[[str], None] | None = None,
) -> list[Run]:
    """Every collision run of every joint's sweep. InputError (GEN070's finding) when
    pinocchio cannot load the geometry; the caller reports it as a sweep finding."""
    scene = collision.load_scene(robot, pinocchio_urdf(robot), {}, "", padding)
    found: list[Run] = []
    for n, m in enumerate(motions, 1):
        if progress is not None:
            progress(f"sweep {n}/{len(motions)}: {m.joint.name}")
        pairs = [frozenset(p) for p in m.pairs if frozenset(p) in scene.link_pairs]
        if not pairs:
            continue
        order = {frozenset(p): p for p in m.pairs}
        collision.activate(scene, pairs)
        hits: dict[frozenset[str], list[int]] = {}
        for k, v in enumerate(m.values):
            q = collision.configuration(scene, joint_values(robot, state, m.joint.name, v))
            for p in collision.colliding(scene, q, pairs, switch=False):
                hits.setdefault(p, []).append(k)
        for p in sorted(hits, key=lambda p: m.pairs.index(order[p])):
            a, b = order[p]
            steps = hits[p]
            start = prev = steps[0]
            for k in steps[1:]:
                if k != prev + 1:
                    found.append(Run(m.joint.name, a, b, start, prev))
                    start = k
                prev = k
            found.append(Run(m.joint.name, a, b, start, prev))
    return found
