"""NAME: unique and usable names."""

from __future__ import annotations

import re
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import Joint, Link, Robot

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


@rule("NAME001", "duplicate-link-name", "error")
def duplicate_link_name(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds two links with the same name.
    ## Why is this bad?
    urdfdom refuses the file; tf would have two frames with one id.
    """
    seen: dict[str, object] = {}
    for lk in robot.links:
        if lk.name in seen:
            first = getattr(seen[lk.name], "where", None)
            yield at(
                "NAME001",
                lk,
                f"duplicate link name '{lk.name}' (first at {first})",
                "rename one of them; each rigid body needs one identity",
            )
        else:
            seen[lk.name] = lk


@rule("NAME002", "duplicate-joint-name", "error")
def duplicate_joint_name(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds two joints with the same name.
    ## Why is this bad?
    urdfdom refuses the file; joint_states and ros2_control address joints by name.
    """
    seen: dict[str, object] = {}
    for j in robot.joints:
        if j.name in seen:
            first = getattr(seen[j.name], "where", None)
            yield at("NAME002", j, f"duplicate joint name '{j.name}' (first at {first})", "rename one of them")
        else:
            seen[j.name] = j


@rule("NAME003", "unusable-name", "warning")
def unusable_name(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags movable joint names that are not plain identifiers ([A-Za-z][A-Za-z0-9_]*), and
    link names that cannot be tf frame ids (empty, a leading '/', blanks).
    ## Why is this bad?
    ros2_control builds `<joint>/<interface>` and parameter paths such as `gains.<joint>.p`
    from joint names (fixed joints never reach it); tf refuses frame ids starting with '/'.
    """
    for lk in robot.links:
        if not lk.name or lk.name.startswith("/") or any(c.isspace() for c in lk.name):
            yield at(
                "NAME003",
                lk,
                f"link name '{lk.name}' cannot be a tf frame id (empty, leading '/' or blank)",
                "use letters, digits and _, starting with a letter",
            )
    elems: list[Link | Joint] = [j for j in robot.joints if j.type != "fixed"]
    for elem in elems:
        if not _IDENT.match(elem.name):
            message = f"name '{elem.name}' is not a plain identifier"
            yield at("NAME003", elem, message, "use letters, digits and _, starting with a letter")
