"""INER011 and INER005 decide a repeated part once (a memo keyed on what the verdict depends
on): links equal in all but one input must still get their own verdicts. Expected verdicts are
hand computations from the shapes and tensors below."""

from __future__ import annotations

from descgen.audit.registry import run
from descgen.core.model import Box, Collision, Inertia, Inertial, Joint, Limit, Link, Pose, Robot


def _link(name: str, side: float, moment: float, com: float = 0.0) -> Link:
    return Link(
        name,
        collisions=(Collision(Box((side, side, side))),),
        inertial=Inertial(1.0, Pose((com, 0.0, 0.0)), Inertia(moment, 0.0, 0.0, moment, 0.0, moment)),
    )


def _robot(links: list[Link]) -> Robot:
    base = Link("base")
    joints = tuple(
        Joint(f"j_{lk.name}", "revolute", "base", lk.name, axis=(0.0, 0.0, 1.0), limit=Limit(-1.0, 1.0, 1e6, 1.0))
        for lk in links
    )
    return Robot("r", (base, *links), joints)


def _flagged(robot: Robot, code: str) -> list[str]:
    return sorted(f.subject.removeprefix("link:") for f in run(robot, codes=[code]))


def test_iner011_each_distinct_part_gets_its_own_verdict() -> None:
    # 1 kg in a cube of side 0.1 m: the farthest point from an axis through the centre is
    # 0.05 * sqrt(2) away, so the bound is 1 * 0.005 kg*m^2 and twice it (the margin) 0.01.
    # In a cube of side 0.02 m the bound is 2e-4 kg*m^2.
    robot = _robot(
        [
            _link("ok", 0.1, 0.001),  # 0.2 of the bound
            _link("heavy", 0.1, 0.05),  # same shape, 10 times the bound
            _link("ok_again", 0.1, 0.001),  # a repeat of "ok"
            _link("small", 0.02, 0.001),  # the tensor of "ok" in a smaller shape: 5 times
            _link("heavy_again", 0.1, 0.05),  # a repeat of "heavy"
        ]
    )
    assert _flagged(robot, "INER011") == ["heavy", "heavy_again", "small"]


def test_iner005_each_distinct_box_gets_its_own_verdict() -> None:
    # a cube of side 0.1 m around the origin; a centre of mass 0.5 m along x is 0.45 m outside
    # it, over a quarter of the box's diagonal (0.043 m); a cube of side 2 m contains it
    robot = _robot(
        [
            _link("inside", 0.1, 0.001),
            _link("outside", 0.1, 0.001, com=0.5),  # the box of "inside" again
            _link("big", 2.0, 0.5, com=0.5),  # the centre of "outside" in a larger box
            _link("outside_again", 0.1, 0.001, com=0.5),
        ]
    )
    assert _flagged(robot, "INER005") == ["outside", "outside_again"]
