"""Trajectory files (controller, joints, points of time_from_start and positions), read and
checked so that a run can neither crash on one nor pass without running anything. Times and
positions are read with the spec's quantity parser (``descgen.core.units``) and its rules."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from descgen.codes import Code, raisable
from descgen.codes.control import CTRL020, CTRL030, CTRL031
from descgen.commands.control.manager import Point
from descgen.core import units
from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import Robot
from descgen.infra.yamlsource import Document, load

# simulated time of one run (--duration and time_from_start): at least one cycle, and at most
# ten minutes, which the loop model runs in about a minute; longer is a typo, not a test
MIN_DURATION_S = 0.01
MAX_DURATION_S = 600.0
_KEYS = ("controller", "joints", "points")
_POINT_KEYS = ("time_from_start", "positions")


@dataclass
class Trajectory:
    controller: str
    joints: list[str]
    points: list[Point]
    where: Where = field(default_factory=lambda: Where("<trajectory>"))  # the file, for messages


class _Problems:
    """The findings of one trajectory file, each placed at its YAML node."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.found: list[Finding] = []

    def __call__(
        self, where: tuple[str | int, ...], message: str, hint: str, code: Code = CTRL020, key: bool = False
    ) -> None:
        self.found.append(code.finding(message, hint, "trajectory", self.doc.where(where, key=key)))


def read_trajectory(path: Path, robot: Robot) -> Trajectory:
    """A trajectory file (controller, joints, points of time_from_start and positions), checked
    so that a run can neither crash on it nor pass without running anything."""
    doc = load(path, what="trajectory")
    data = doc.data
    bad = _Problems(doc)
    if not isinstance(data, dict):
        bad((), "a trajectory is a mapping (controller, joints, points)", "see the README")
        raise InputError(bad.found)
    for k in data:
        if k not in _KEYS:
            bad((k,), f"unknown key {k!a}", f"a trajectory has {', '.join(_KEYS)}", key=True)
    controller = data.get("controller")
    if not isinstance(controller, str) or not controller:
        bad(("controller",), "controller: expected the name of a joint_trajectory_controller", "e.g. arm_controller")
    joints = _joints(data, robot, bad)
    points = _points(data, joints, robot, bad)
    if bad.found:
        raise InputError(bad.found)
    return Trajectory(str(controller), joints or [], points, doc.where(()))


def _joints(data: dict[str, Any], robot: Robot, bad: _Problems) -> list[str] | None:
    raw = data.get("joints")
    if not isinstance(raw, list) or not raw:
        bad(("joints",), "joints: expected a non-empty list of joint names", "e.g. joints: [elbow_joint]", CTRL030)
        return None
    ok = True
    for i, name in enumerate(raw):
        if not isinstance(name, str):
            bad(("joints", i), f"joints: {name!a} is not a joint name", "write the joint's name")
            ok = False
        elif robot.joint(name) is None:
            bad(("joints", i), f"unknown joint {name!a}", "name a joint of the robot")
        elif raw.index(name) != i:
            bad(("joints", i), f"joint {name!a} is listed twice", "list each joint once")
    return [str(j) for j in raw] if ok else None


def _points(data: dict[str, Any], joints: list[str] | None, robot: Robot, bad: _Problems) -> list[Point]:
    raw = data.get("points")
    if raw is None or raw == []:
        bad(("points",), "the trajectory has no points: nothing would run", "add at least one point", CTRL030)
        return []
    if not isinstance(raw, list):
        bad(("points",), "points: expected a list of points", "write points as a YAML list")
        return []
    points: list[Point] = []
    last: float | None = None
    for i, p in enumerate(raw):
        if not isinstance(p, dict):
            bad(("points", i), f"point {i + 1} is not a mapping", "write {time_from_start: ..., positions: [...]}")
            continue
        for k in p:
            if k not in _POINT_KEYS:
                bad(
                    ("points", i, k),
                    f"point {i + 1}: unknown key {k!a}",
                    "a point has time_from_start and positions",
                    key=True,
                )
        t = _time(p, i, bad)
        if t is not None and last is not None and t <= last:
            bad(
                ("points", i, "time_from_start"),
                f"point {i + 1}: time_from_start {t:g} s is not after the previous point's {last:g} s",
                "list points in increasing time",
                CTRL031,
            )
        last = t if t is not None else last
        values = _positions(p, i, joints, robot, bad)
        if t is not None and values is not None:
            points.append(Point(t, values))
    return points


def _time(p: dict[str, Any], i: int, bad: _Problems) -> float | None:
    if "time_from_start" not in p:
        bad(("points", i), f"point {i + 1} has no time_from_start", 'write e.g. time_from_start: "2 s"')
        return None
    try:
        return units.duration(p["time_from_start"], 0.0, MAX_DURATION_S)
    except units.QuantityError as exc:
        bad(("points", i, "time_from_start"), f"time_from_start: {exc.message}", exc.hint, raisable(exc.code))
        return None


def _positions(
    p: dict[str, Any], i: int, joints: list[str] | None, robot: Robot, bad: _Problems
) -> tuple[float, ...] | None:
    raw = p.get("positions")
    if not isinstance(raw, list):
        bad(("points", i, "positions"), f"point {i + 1}: positions must be a list", 'write e.g. positions: ["0 deg"]')
        return None
    if joints is None:
        return None
    if len(raw) != len(joints):
        bad(
            ("points", i, "positions"),
            f"{len(raw)} positions for {len(joints)} joints",
            "give one position per joint",
        )
        return None
    values = []
    for k, (name, value) in enumerate(zip(joints, raw, strict=True)):
        j = robot.joint(name)
        kind = "length" if j is not None and j.type == "prismatic" else "angle"
        try:
            values.append(units.to_si(value, kind))
        except units.QuantityError as exc:
            bad(("points", i, "positions", k), exc.message, exc.hint, raisable(exc.code))
    return tuple(values) if len(values) == len(joints) else None
