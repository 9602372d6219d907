"""TOPO: the links and joints form one tree."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

from descgen.audit.registry import at, rule
from descgen.core.findings import Finding
from descgen.core.model import Robot


def _isolated(robot: Robot) -> set[str]:
    used = {j.parent for j in robot.joints} | {j.child for j in robot.joints}
    return {lk.name for lk in robot.links if lk.name not in used} if len(robot.links) > 1 else set()


@rule("TOPO001", "not-one-root", "error")
def not_one_root(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks that exactly one link has no parent joint.
    ## Why is this bad?
    urdfdom refuses two roots ("two root links") or none (a cycle); robot_state_publisher
    and MoveIt need one tree.
    """
    isolated = _isolated(robot)
    roots = [r for r in robot.roots() if r not in isolated]
    if robot.links and not roots and not isolated:
        yield at(
            "TOPO001",
            robot,
            "no root link: every link is the child of a joint (a cycle)",
            "make exactly one link the child of no joint",
            subject="robot",
        )
    if len(roots) > 1:
        for name in roots[1:]:
            lk = robot.link(name)
            yield at(
                "TOPO001",
                lk,
                f"second root link '{name}' (first is '{roots[0]}')",
                f"attach '{name}' to the tree with a joint",
                subject=f"link:{name}",
            )


@rule("TOPO002", "link-with-two-parents", "error")
def link_with_two_parents(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a link that is the child of more than one joint.
    ## Why is this bad?
    urdfdom silently accepts it and shows the link twice; transforms become ambiguous.
    """
    counts = Counter(j.child for j in robot.joints if j.child)
    for j in robot.joints:
        if j.child and counts[j.child] > 1 and robot.parent_joint(j.child) is not j:
            first = robot.parent_joint(j.child)
            yield at(
                "TOPO002",
                j,
                f"link '{j.child}' already has parent joint '{first.name if first else '?'}'",
                "give each link one parent joint; rename the child or remove one joint",
            )


@rule("TOPO003", "kinematic-cycle", "error")
def kinematic_cycle(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds joints that lead from a link back to itself.
    ## Why is this bad?
    A URDF is a tree; urdfdom fails with "no root" or loops, and tf cannot resolve frames.
    """
    parent_of = {}
    for j in robot.joints:
        if j.child and j.parent and j.child not in parent_of:
            parent_of[j.child] = j
    done: set[str] = set()  # links known to end at a root (or already reported)
    for start in parent_of:
        seen: list[str] = []
        on_path: set[str] = set()
        cur: str | None = start
        while cur is not None and cur in parent_of and cur not in done and cur not in on_path:
            seen.append(cur)
            on_path.add(cur)
            cur = parent_of[cur].parent
        if cur is not None and cur in on_path:
            loop = seen[seen.index(cur) :]
            j = parent_of[min(loop)]
            names = " -> ".join(parent_of[x].name for x in loop)
            yield at(
                "TOPO003",
                j,
                f"joints form a cycle: {names}",
                "break the loop: one of these joints has the wrong parent or child",
            )
        done.update(seen)


@rule("TOPO004", "dangling-joint", "error")
def dangling_joint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds joints whose parent or child link is missing or undefined, or equal.
    ## Why is this bad?
    urdfdom fails to build the tree ("missing a parent and/or child link").
    """
    names = {lk.name for lk in robot.links}
    for j in robot.joints:
        for role, link in (("parent", j.parent), ("child", j.child)):
            if not link:
                yield at("TOPO004", j, f"joint '{j.name}' has no {role} link", f"add the {role} link")
            elif link not in names:
                yield at(
                    "TOPO004",
                    j,
                    f"joint '{j.name}' {role} '{link}' is not a link",
                    _did_you_mean(link, names) or f"define link '{link}' or fix the name",
                )
        if j.parent and j.parent == j.child:
            yield at(
                "TOPO004", j, f"joint '{j.name}' connects '{j.parent}' to itself", "the child must be another link"
            )


@rule("TOPO005", "orphan-link", "error")
def orphan_link(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds links that no joint connects to the rest of the robot.
    ## Why is this bad?
    The link is a second root; urdfdom rejects the file and tf never sees the frame.
    """
    for name in sorted(_isolated(robot), key=[lk.name for lk in robot.links].index):
        yield at(
            "TOPO005",
            robot.link(name),
            f"link '{name}' is not connected by any joint",
            "add a joint to its parent, or remove the link",
            subject=f"link:{name}",
        )


def _did_you_mean(name: str, choices: set[str]) -> str:
    import difflib

    close = difflib.get_close_matches(name, sorted(choices), n=1, cutoff=0.6)
    return f"did you mean '{close[0]}'?" if close else ""
