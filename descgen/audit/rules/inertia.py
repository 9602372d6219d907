"""INER: masses and inertia tensors that a simulator can use."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from ...findings import Finding
from ...model import Robot
from ..registry import at, rule


def _moving_links(robot: Robot) -> set[str]:
    """Links that some non-fixed joint moves (that joint's child and everything below)."""
    moving: set[str] = set()
    todo = [j.child for j in robot.joints if j.type != "fixed" and j.child]
    while todo:
        name = todo.pop()
        if name in moving:
            continue  # also ends cycles
        moving.add(name)
        todo += [j.child for j in robot.child_joints(name) if j.child]
    return moving


def _carries_geometry(robot: Robot, link: str) -> bool:
    lk = robot.link(link)
    return bool(lk and (lk.visuals or lk.collisions))


@rule("INER001", "non-positive-mass", "error")
def non_positive_mass(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a link with an inertial whose mass is missing, zero or negative.
    ## Why is this bad?
    urdfdom accepts negative mass; physics engines reject it or explode.
    """
    for lk in robot.links:
        if lk.inertial is None:
            continue
        mass = lk.inertial.mass
        if mass is None:
            yield at(
                "INER001", lk.inertial, f"link '{lk.name}' inertial has no mass", "add <mass value>", subject=lk.subject
            )
        elif mass <= 0:
            yield at(
                "INER001",
                lk.inertial,
                f"link '{lk.name}' mass is {mass:.6g} kg",
                "write the measured mass (> 0)",
                subject=lk.subject,
            )


@rule("INER002", "moving-link-without-mass", "error")
def moving_link_without_mass(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a link with geometry that a moving joint carries but that has no inertial.
    ## Why is this bad?
    Simulators drop or mis-simulate massless bodies; gravity compensation and the
    static-torque check ignore it.
    """
    for name in sorted(_moving_links(robot)):
        lk = robot.link(name)
        if lk is not None and lk.inertial is None and _carries_geometry(robot, name):
            yield at("INER002", lk, f"moving link '{name}' has geometry but no inertial", "add mass and inertia")


@rule("INER003", "inertia-not-positive-definite", "error")
def inertia_not_positive_definite(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks that each inertia tensor has positive principal moments.
    ## Why is this bad?
    A tensor with a zero or negative eigenvalue is not a rigid body; urdfdom accepts it.
    """
    for lk in robot.links:
        if lk.inertial is None or lk.inertial.inertia is None:
            continue
        eig = np.linalg.eigvalsh(np.array(lk.inertial.inertia.matrix()))
        if eig.min() <= 0:
            yield at(
                "INER003",
                lk.inertial,
                f"link '{lk.name}' inertia has principal moments {_fmt(eig)}: not positive definite",
                "recompute the tensor (or use from: collision)",
                subject=lk.subject,
            )


@rule("INER004", "inertia-triangle-inequality", "error")
def inertia_triangle_inequality(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks the principal moments satisfy A + B >= C for every ordering.
    ## Why is this bad?
    No real mass distribution violates it; the numbers were mistyped or mixed units.
    """
    for lk in robot.links:
        if lk.inertial is None or lk.inertial.inertia is None:
            continue
        eig = np.sort(np.linalg.eigvalsh(np.array(lk.inertial.inertia.matrix())))
        if eig.min() > 0 and eig[0] + eig[1] < eig[2] * (1 - 1e-9):
            yield at(
                "INER004",
                lk.inertial,
                f"link '{lk.name}' principal moments {_fmt(eig)} break the triangle inequality",
                "recompute the tensor; a value may be in the wrong unit",
                subject=lk.subject,
            )


def _fmt(values: object) -> str:
    return "[" + ", ".join(f"{float(v):.4g}" for v in values) + "]"  # type: ignore[attr-defined]
