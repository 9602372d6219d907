"""``descgen control``'s loop: a trajectory through the read-update-write cycle at the
controller manager's ``update_rate``, recording desired, commanded and measured positions."""

from __future__ import annotations

import math
from pathlib import Path

from descgen.codes.control import CTRL022, CTRL030, CTRL033
from descgen.commands.control.load import load_system
from descgen.commands.control.manager import GripperActionController, JointTrajectoryController, Point
from descgen.commands.control.record import run_record
from descgen.commands.control.system import Plant
from descgen.commands.control.trajectory import Trajectory
from descgen.commands.control.verdict import Outcome
from descgen.core.findings import InputError
from descgen.core.model import Robot

DEFAULT_TOLERANCE = {"prismatic": 0.01, "other": math.radians(3)}


def run(package: Path, robot: Robot, trajectory: Trajectory, duration: float | None, plant: Plant) -> Outcome:
    cm = load_system(package, robot, plant)
    jtc = cm.controllers.get(trajectory.controller)
    if not isinstance(jtc, JointTrajectoryController | GripperActionController):
        raise InputError(
            [
                CTRL022.finding(
                    f"no joint_trajectory_controller or gripper action controller named "
                    f"'{trajectory.controller}' in the controllers file",
                    "name the arm's or the gripper's controller",
                    "trajectory",
                    trajectory.where,
                )
            ]
        )
    foreign = [j for j in trajectory.joints if j not in jtc.joints]
    if foreign or not trajectory.points:
        raise InputError(
            [
                (CTRL033 if foreign else CTRL030).finding(
                    f"controller '{trajectory.controller}' does not command {', '.join(foreign)}"
                    if foreign
                    else "the trajectory has no points: nothing would run",
                    f"its joints are {', '.join(jtc.joints)}" if foreign else "add at least one point",
                    "trajectory",
                    trajectory.where,
                )
            ]
        )
    end = duration if duration is not None else trajectory.points[-1].time + 1.0
    dt = 1.0 / cm.update_rate
    # the goal is given in the trajectory's joint order; the controller has its own
    order = {n: i for i, n in enumerate(trajectory.joints)}
    points = [
        Point(p.time, tuple(p.positions[order[j]] if j in order else math.nan for j in jtc.joints))
        for p in trajectory.points
    ]
    cm.step(0.0)  # one cycle so the controller sees measured state before the goal arrives
    jtc.follow(points, 0.0)
    out = Outcome(cm, record=run_record(package, trajectory.where.file, duration, plant))
    settles = isinstance(jtc, GripperActionController)  # a gripper goal is judged when it is due
    kinds = {j.name: j.type for j in robot.joints}
    for name in jtc.joints:
        out.tracking[name] = 0.0
        out.tolerance[name] = DEFAULT_TOLERANCE["prismatic" if kinds.get(name) == "prismatic" else "other"]
    for k in range(1, round(end * cm.update_rate) + 1):
        t = k * dt
        cm.step(t)
        for name in jtc.joints:
            desired = jtc.desired.get(name, math.nan)
            commanded = cm.by_name[name].commands.get("position", math.nan)
            measured = cm.state(name, "position")
            out.rows.append((t, name, desired, commanded, measured))
            if not math.isnan(desired) and not math.isnan(measured) and (not settles or _at_point(t, points, dt)):
                out.tracking[name] = max(out.tracking[name], abs(desired - measured))
    return out


def _at_point(t: float, points: list[Point], dt: float) -> bool:
    """``t`` is the cycle at which a point (a gripper goal) is due."""
    return any(abs(t - p.time) < dt / 2 for p in points)
