"""Known poses the import adds: one at zero and one per SRDF group state, each with the
positions of the robot's tips computed by forward kinematics of the imported model.

They are model values, not measurements: their job is to pin the robot as it was imported,
so a later edit of an origin, an axis or a limit that moves a tip is caught by ``descgen
poses`` and ``generate``. The tolerance is tiny (0.001 mm): the spec gives back the very
same floats, so forward kinematics of the loaded spec gives back the same positions.
"""

from __future__ import annotations

import math
import re
from typing import Any

from descgen.commands.importer.spec import SpecWriter
from descgen.core import model as m
from descgen.physics import kinematics, mimic
from descgen.spec.convert import POSITION
from descgen.spec.models import NAME_PATTERN, is_element_name

TOLERANCE = 1e-6  # m: 0.001 mm
# a pose only names what validate accepts: a bad name fails where it is
_NAME = re.compile(NAME_PATTERN)  # pose names
COMMENT = "model value (forward kinematics of the imported description), not a measurement"


def tips(robot: m.Robot) -> list[str]:
    """The leaf links of the tree (no joint below them), in the description's order."""
    parents = {j.parent for j in robot.joints}
    return [lk.name for lk in robot.links if lk.name not in parents]


def _group_tips(robot: m.Robot, group: m.Group | None) -> list[str]:
    """A group's chain tips, else the child links of its joints that no other of them holds up,
    else the robot's tips."""
    if group is None:
        return tips(robot)
    found = [tip for _, tip in group.chains]
    joints = [j for j in (robot.joint(n) for n in group.joints) if j is not None]
    parents = {j.parent for j in joints}
    found += [j.child for j in joints if j.child is not None and j.child not in parents]
    found += [lk for lk in group.links if lk not in parents]
    unique = list(dict.fromkeys(found))
    return unique or tips(robot)


def _free(robot: m.Robot, values: tuple[tuple[str, float], ...]) -> dict[str, float]:
    """The state's values for joints that exist, move with one degree of freedom and follow no
    leader (a mimic joint's value is its leader's business: POSE020/021)."""
    out: dict[str, float] = {}
    for name, v in values:
        j = robot.joint(name)
        if (
            not is_element_name(name)
            or j is None
            or j.type not in m.ONE_DOF
            or not math.isfinite(v)
            or mimic.relation(robot, name) is not None
        ):
            continue
        out[name] = v
    return out


def _pose(
    robot: m.Robot, w: SpecWriter, name: str, q: dict[str, float], frames: list[str], source: str
) -> dict[str, Any] | None:
    at = kinematics.forward(robot, q)
    measured = []
    for frame in frames:
        t = at.get(frame)
        if t is None or not is_element_name(frame):  # unconnected, or a name validate refuses (elsewhere)
            continue
        xyz = [w.q(float(t[i, 3]) + 0.0, "length", "offset") for i in range(3)]
        measured.append({"frame": frame, "xyz": xyz, "tolerance": w.q(TOLERANCE, "length", "tolerance")})
    if not measured:
        return None
    joints = {}
    for jn, v in q.items():
        j = robot.joint(jn)
        assert j is not None
        joints[jn] = w.q(v, *POSITION.get(j.type, ("angle", "joint_angle")))
    out: dict[str, Any] = {"name": name, "description": COMMENT}
    if joints:
        out["joints"] = joints
    out["frames"] = measured
    out["source"] = source
    out["nominal"] = True  # a calibration added later moves the robot, not these model values
    return out


def known_poses(robot: m.Robot, w: SpecWriter, source: str) -> list[dict[str, Any]]:
    """``zero`` and one pose per group state (named after it, with its group when two states
    share a name)."""
    if robot.root() is None or mimic.problems(robot):
        return []  # no tree or a broken mimic: forward kinematics would pin a wrong robot
    out = []
    zero = _pose(robot, w, "zero", {}, tips(robot), source)
    if zero is not None:
        out.append(zero)
    sem = robot.semantic
    states = sem.states if sem is not None else ()
    groups = {g.name: g for g in (sem.groups if sem is not None else ())}
    taken = {"zero"}
    for s in states:
        name = s.name if s.name not in taken else f"{s.group}_{s.name}"
        if name in taken or not _NAME.fullmatch(name):
            continue  # an invalid state name fails validate at the state already
        frames = _group_tips(robot, groups.get(s.group))
        pose = _pose(robot, w, name, _free(robot, s.values), frames, w.source_of(s.where))
        if pose is not None:
            taken.add(name)
            out.append(pose)
    return out
