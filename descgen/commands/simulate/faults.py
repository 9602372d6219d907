"""Planted faults the gravity run must catch, each in a copy of the robot (or of the run's setup).

They are the mistakes that make a robot "look correct in RViz but fall over in simulation":
a mass in grams typed as kilograms, an inertia a million times too small, a centre of mass
far outside the base, and an actuator with no damping and a huge gear.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

from descgen.commands.simulate import Outcome, Settings, simulate
from descgen.core.findings import Finding
from descgen.core.model import Inertia, Link, Pose, Robot
from descgen.physics.bodies import moving_links
from descgen.physics.extent import robot_span

GEAR = 1e4  # a gear no servo of the robot has: its gain and force times 10,000


@dataclass(frozen=True)
class Planted:
    robot: Robot
    settings: Settings
    what: str


@dataclass(frozen=True)
class SimFault:
    name: str
    description: str
    expects: tuple[str, ...]  # codes of which one must appear in the run
    plant: Callable[[Robot, Settings], Planted | None]


@dataclass(frozen=True)
class SimResult:
    fault: SimFault
    what: str
    caught: bool
    by: tuple[Finding, ...] = ()
    applicable: bool = True


def _swap(robot: Robot, old: Link, new: Link) -> Robot:
    return dataclasses.replace(robot, links=tuple(new if lk is old else lk for lk in robot.links))


def _weighed(robot: Robot, names: set[str] | None = None) -> list[Link]:
    return [
        lk
        for lk in robot.links
        if (names is None or lk.name in names) and lk.inertial is not None and (lk.inertial.mass or 0.0) > 0
    ]


def mass_x1000(robot: Robot, settings: Settings) -> Planted | None:
    """The heaviest moving link's mass ×1000 (grams typed as kilograms)."""
    pool = _weighed(robot, moving_links(robot))
    if not pool:
        return None
    link = max(pool, key=lambda lk: lk.inertial.mass or 0.0 if lk.inertial else 0.0)
    assert link.inertial is not None and link.inertial.mass is not None
    new = dataclasses.replace(link, inertial=dataclasses.replace(link.inertial, mass=link.inertial.mass * 1000))
    return Planted(_swap(robot, link, new), settings, f"link {link.name} mass ×1000")


def inertia_x1e_6(robot: Robot, settings: Settings) -> Planted | None:
    """Every moving link's inertia tensor ×1e-6 (kg*mm^2 typed as kg*m^2)."""
    pool = [lk for lk in _weighed(robot, moving_links(robot)) if lk.inertial and lk.inertial.inertia]
    if not pool:
        return None
    out = robot
    for link in pool:
        i = link.inertial
        assert i is not None and i.inertia is not None
        t = i.inertia
        small = Inertia(*(1e-6 * v for v in (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz)))
        out = _swap(out, link, dataclasses.replace(link, inertial=dataclasses.replace(i, inertia=small)))
    return Planted(out, settings, f"inertia ×1e-6 in {', '.join(lk.name for lk in pool)}")


def com_outside(robot: Robot, settings: Settings) -> Planted | None:
    """The root body's heaviest link's centre of mass moved sideways by the robot's span (far
    outside any footprint), on a free base."""
    root = robot.root()
    pool = _weighed(robot, set(robot.body_of(root))) if root else []
    if not pool:
        return None
    link = max(pool, key=lambda lk: lk.inertial.mass or 0.0 if lk.inertial else 0.0)
    i = link.inertial
    assert i is not None
    x, y, z = i.origin.xyz
    shift = max(robot_span(robot), 0.5)
    moved = dataclasses.replace(i, origin=Pose((x, y + shift, z), i.origin.rpy))
    return Planted(
        _swap(robot, link, dataclasses.replace(link, inertial=moved)),
        dataclasses.replace(settings, base="floor"),
        f"link {link.name} centre of mass moved {shift:.3g} m sideways",
    )


def no_damping_huge_gear(robot: Robot, settings: Settings) -> Planted | None:
    """Every servo without damping and with a gear of 10,000."""
    return Planted(
        robot, dataclasses.replace(settings, gear=GEAR, damping=0.0), f"servos with no damping and gear {GEAR:g}"
    )


CATALOGUE: tuple[SimFault, ...] = (
    SimFault(
        "mass-x1000", "a link mass in grams typed as kilograms", ("SIM012", "SIM013", "SIM010", "SIM011"), mass_x1000
    ),
    SimFault("inertia-x1e-6", "inertia in kg*mm^2 typed as kg*m^2", ("SIM010", "SIM011", "SIM012"), inertia_x1e_6),
    SimFault("com-outside", "a centre of mass far outside the base footprint", ("SIM013",), com_outside),
    SimFault(
        "no-damping-huge-gear",
        "a joint with no damping and a huge gear",
        ("SIM010", "SIM011", "SIM012"),
        no_damping_huge_gear,
    ),
)


def plant_all(
    robot: Robot,
    settings: Settings,
    catalogue: tuple[SimFault, ...] = CATALOGUE,
) -> list[SimResult]:
    """Run each planted fault; caught when the run fails with an expected code."""
    out = []
    for fault in catalogue:
        planted = fault.plant(robot, settings)
        if planted is None:
            out.append(SimResult(fault, "not applicable", False, applicable=False))
            continue
        outcome: Outcome = simulate(planted.robot, planted.settings)
        by = tuple(f for f in outcome.findings if f.code in fault.expects and f.severity == "error")
        out.append(SimResult(fault, planted.what, bool(by), by))
    return out
