"""GEOM040-043: what Gazebo's URDF->SDF conversion (sdformat ``src/parser_urdf.cc``) silently
changes or drops. Jazzy's Gazebo Harmonic uses sdformat14; the behaviour below is the same in
sdformat12 (Debian 12), which only logs it at debug level (docs/reference/consumers.md §2).

- ``ReduceFixedJoints``: every fixed joint whose parent is not ``world`` is lumped: the child's
  inertial, visuals and collisions move into the parent, unless ``<gazebo reference="joint">``
  sets ``preserveFixedJoint`` (or the legacy ``disableFixedJointLumping``);
- ``CreateSDF``: a link (other than ``world``) with no ``<inertial>`` or mass <= 0 after lumping,
  whose parent joint is not lumped, "is not modeled in sdf": the link, its parent joint and its
  whole subtree are left out;
- ``CreateJoint``: floating and planar joints get no ``<joint>`` element at all;
- lower > upper limits are swapped ("switching the two").
"""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import MULTI_DOF, WITH_LIMITS, Joint, Robot


def _lumped(robot: Robot, j: Joint) -> bool:
    """sdformat's FixedJointShouldBeReduced, and ReduceFixedJoints never lumps into ``world``."""
    return j.type == "fixed" and j.name not in robot.sdf_preserved_joints and j.parent != "world"


def _own_mass(robot: Robot, link: str) -> float:
    lk = robot.link(link)
    if lk is None or lk.inertial is None or lk.inertial.mass is None:
        return 0.0
    return lk.inertial.mass


def _lumped_masses(robot: Robot) -> dict[str, float]:
    """Each link's mass after fixed-joint lumping: its own plus every lumped child's.

    One pass, children before parents and without recursion: a chain of 10,000 welded links
    must neither overflow the stack nor cost n² (summing each link's subtree anew would)."""
    order: list[str] = []
    seen: set[str] = set()
    stack = list(robot.roots())
    while stack:
        link = stack.pop()
        if link in seen:
            continue
        seen.add(link)
        order.append(link)
        stack.extend(j.child for j in robot.child_joints(link) if j.child is not None and j.child not in seen)
    mass: dict[str, float] = {}
    for link in reversed(order):
        total = _own_mass(robot, link)
        for j in robot.child_joints(link):
            if j.child is not None and j.child in mass and _lumped(robot, j):
                total += mass[j.child]
        mass[link] = total
    return mass


def _subtree(robot: Robot, link: str) -> tuple[int, int]:
    """(links, joints) below ``link``, the link itself not counted."""
    below = robot.descendants(link)
    return len(below), sum(1 for n in below if robot.parent_joint(n) is not None)


@rule("GEOM040", "massless-link-dropped-by-sdformat", "warning")
def massless_link_dropped(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds the links Gazebo leaves out: a link with no `<inertial>` or a mass <= 0 after
    sdformat lumped its fixed children into it, whose own parent joint is not a lumped fixed
    joint (a moving joint, the root, or a fixed joint kept by `preserveFixedJoint`). Only the
    topmost such link is reported; everything below it is gone too.
    ## Why is this bad?
    sdformat's URDF->SDF conversion (parser_urdf.cc, `CreateSDF`) writes "link[X] is not
    modeled in sdf" and skips the link, its parent joint and its whole subtree (sdformat12
    only logs it at debug level). RViz and check_urdf show the robot whole; in Gazebo the
    wheel or the arm is simply missing, and gz_ros2_control skips its joints with a warning.
    ## Use instead
    Give the link an `<inertial>` with a positive mass (a small realistic value), or attach a
    massless frame with a fixed joint that sdformat may lump.
    """
    mass = _lumped_masses(robot)
    seen: set[str] = set()
    # depth first in document order, as a stack: the topmost dropped link hides its subtree
    stack: list[tuple[str, bool]] = [(root, False) for root in reversed(robot.roots())]
    while stack:
        link, parent_lumped = stack.pop()
        if link in seen:
            continue
        seen.add(link)
        if link != "world" and not parent_lumped and mass.get(link, 0.0) <= 0:
            yield _dropped(robot, link)
            continue
        children = [(j.child, _lumped(robot, j)) for j in robot.child_joints(link) if j.child is not None]
        stack.extend(reversed(children))


def _dropped(robot: Robot, link: str) -> Finding:
    lk = robot.link(link)
    j = robot.parent_joint(link)
    links, joints = _subtree(robot, link)
    why = "no <inertial>" if lk is None or lk.inertial is None else "a mass <= 0"
    lost = f" with its parent joint '{j.name}'" if j is not None else " (the root link)"
    return at(
        "GEOM040",
        lk if lk is not None else j,
        f"link '{link}' has {why} and no lumped fixed child brings mass: Gazebo's URDF->SDF "
        f"conversion drops it{lost} and the {links} link(s) and {joints} joint(s) below it",
        "give the link an <inertial> with a positive mass",
        subject=f"link:{link}",
    )


@rule("GEOM041", "fixed-joints-lumped-by-sdformat", "info")
def fixed_joints_lumped(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Lists, once per robot, the fixed joints sdformat lumps into their parent link (every fixed
    joint not kept by `<gazebo reference="joint"><preserveFixedJoint>true</preserveFixedJoint>`
    and not attached to `world`).
    ## Why is this bad?
    In Gazebo those child links are not links any more but frames of the parent
    (parser_urdf.cc, `ReduceFixedJoints`): their mass, visuals and collisions move into the
    parent, a `<gazebo reference="child_link">` sensor or plugin is re-attached to the
    parent, and anything that looks the link up by name in the simulator (a contact sensor, a
    link-attacher, an entity query) does not find it.
    ## Use instead
    Nothing, when the merge is what you want. Keep a link that the simulator must see with
    `<gazebo reference="joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>`.
    """
    merged = [j for j in robot.joints if _lumped(robot, j) and j.child is not None]
    if not merged:
        return
    first = merged[0]
    shown = ", ".join(f"{j.child} into {j.parent}" for j in merged[:8]) + (" ..." if len(merged) > 8 else "")
    yield at(
        "GEOM041",
        first,
        f"Gazebo merges {len(merged)} fixed joint(s) into their parent links: {shown}",
        'add <gazebo reference="JOINT"><preserveFixedJoint>true</preserveFixedJoint></gazebo> '
        "for a link the simulator must keep",
        subject="robot",
    )


@rule("GEOM042", "joint-dropped-by-sdformat", "warning")
def floating_planar_dropped(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds floating and planar joints.
    ## Why is this bad?
    sdformat's URDF->SDF conversion (parser_urdf.cc, `CreateJoint`) writes no `<joint>` for
    them: the child link stays in the Gazebo model unattached, free, and falls or drifts,
    while RViz shows it where the URDF put it. A ros2_control joint of that name is skipped
    by gz_ros2_control with only a warning.
    ## Use instead
    Describe a mobile base's motion with the base's own plugin or controller (e.g. a diff-drive
    on wheel joints) and the SRDF virtual joint, not a planar or floating URDF joint.
    """
    controlled = {cj.name for cj in robot.ros2_control.joints} if robot.ros2_control else set()
    for j in robot.joints:
        if j.type in MULTI_DOF:
            extra = "; its ros2_control joint loses control in Gazebo" if j.name in controlled else ""
            yield at(
                "GEOM042",
                j,
                f"{j.type} joint '{j.name}' is dropped by Gazebo's URDF->SDF conversion: link "
                f"'{j.child}' is left unattached{extra}",
                "move the base with a controller or plugin and keep the planar/floating joint in the SRDF",
            )


@rule("GEOM043", "limits-swapped-by-sdformat", "warning")
def limits_swapped(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a revolute or prismatic joint whose lower limit is above its upper limit.
    ## Why is this bad?
    Consumers disagree on what it means: sdformat's URDF->SDF conversion swaps the two with a
    warning ("lowStop > highStop, switching the two", parser_urdf.cc), MuJoCo makes the joint
    unlimited, and ros2_control and MoveIt reject every position. The robot in Gazebo moves
    where the real controller refuses to go.
    ## Use instead
    Write lower <= upper in the URDF (JOINT004 reports the same defect for every consumer).
    """
    for j in robot.joints:
        lm = j.limit
        if j.type not in WITH_LIMITS or lm is None or lm.lower is None or lm.upper is None:
            continue
        if lm.lower > lm.upper:
            yield at(
                "GEOM043",
                lm if lm.where.line else j,
                f"joint '{j.name}' lower limit {j.show(lm.lower)} is above upper {j.show(lm.upper)}: "
                "Gazebo swaps them, MuJoCo drops the limits",
                "swap lower and upper in the URDF",
                subject=j.subject,
            )
