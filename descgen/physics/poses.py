"""Known poses: measured frame positions against forward kinematics of the model.

Joints a pose does not list are at zero, and mimic joints follow their leaders
(``descgen.physics.mimic``), as they do on the robot. Plain floats (``descgen.physics.zero_pose``): every
``check`` evaluates the known poses, and numpy's import would be ~60 ms of it."""

from __future__ import annotations

import math

from descgen.core import display
from descgen.core.findings import Finding
from descgen.core.model import ONE_DOF, FrameMeasurement, KnownPose, Robot, Vec3
from descgen.core.record import record
from descgen.physics import calibration, mimic, zero_pose

EPS = 1e-9  # a measurement exactly at its tolerance passes, whatever the float rounding


@record
class Row:
    pose: KnownPose
    measurement: FrameMeasurement
    model: Vec3 | None  # None: the frame is not in the tree
    error: Vec3 | None  # model - measured
    relative_to: str

    @property
    def worst(self) -> float:
        return worst(self.error)

    @property
    def distance(self) -> float:
        if not self.error:
            return float("inf")
        x, y, z = self.error
        return math.sqrt(x * x + y * y + z * z)

    @property
    def ok(self) -> bool:
        return passes(self.error, self.measurement.tolerance)

    @property
    def verdict(self) -> str:
        return verdict(self.error, self.measurement.tolerance)


# One error measure and one tolerance rule for a known pose, wherever it is shown (poses,
# POSE010, view, the pose images and the evidence page): the largest difference along an axis
# of the measurement's base frame, the way the tolerance is written ("each coordinate within").


def worst(error: Vec3 | None) -> float:
    """The largest axis difference of ``model - measured`` (metres); inf when not in the model."""
    return max(abs(e) for e in error) if error else float("inf")


def passes(error: Vec3 | None, tolerance: float) -> bool:
    return error is not None and worst(error) <= tolerance + EPS


def verdict(error: Vec3 | None, tolerance: float) -> str:
    """``0.8 mm, tol 2 mm, pass``: the error to the digits its tolerance can judge."""
    if error is None:
        return "not in the model, FAIL"
    shown = f"{worst_mm(error, tolerance)} mm, tol {tolerance * 1000:g} mm"
    return f"{shown}, {'pass' if passes(error, tolerance) else 'FAIL'}"


def worst_mm(error: Vec3 | None, tolerance: float) -> str:
    """The largest axis difference in millimetres, to the digits the tolerance judges (one more
    than its own), and more where a failing value would round onto the tolerance ("2.0" of 2 mm
    that fails reads "2.04"); "n/a" when the frame is not in the model."""
    if error is None:
        return "n/a"
    value, tol = worst(error) * 1000, tolerance * 1000
    digits = display.mm_digits(tolerance)
    while not passes(error, tolerance) and round(value, digits) <= tol and digits < 9:
        digits += 1
    return f"{value:.{digits}f}"


def evaluate(robot: Robot) -> list[Row]:
    rows: list[Row] = []
    root = robot.root() or ""
    for kp in robot.known_poses:
        poses = zero_pose.forward(calibration.for_pose(robot, kp), dict(kp.joints))
        for fm in kp.frames:
            t = zero_pose.relative(poses, fm.frame, fm.relative_to)
            if t is None:
                rows.append(Row(kp, fm, None, None, fm.relative_to or root))
                continue
            x, y, z = t[1]
            model = (x + 0.0, y + 0.0, z + 0.0)
            error = tuple(m - x for m, x in zip(model, fm.xyz, strict=True))
            rows.append(Row(kp, fm, model, (error[0], error[1], error[2]), fm.relative_to or root))
    return rows


def _mm(v: Vec3) -> str:
    return f"({display.mm(v)}) mm"


def path_joints(robot: Robot, frame: str, base: str | None) -> list[str]:
    """Joints between ``base`` (or the root) and ``frame``, with what each contributes."""
    chain = robot.path_to_root(frame)
    if base is not None:
        above = {j.name for j in robot.path_to_root(base)}
        chain = [j for j in chain if j.name not in above]
    out = []
    for j in chain:
        part = f"{j.name} ({j.type}, origin {_mm(j.origin.xyz)}"
        if any(j.origin.rpy):
            part += f" rpy {tuple(round(math.degrees(a), 3) for a in j.origin.rpy)} deg"
        if j.type in ONE_DOF and j.axis is not None:
            part += f", axis {tuple(j.axis)}"
        rel = mimic.relation(robot, j.name)
        if rel is not None:  # a measured mimic finger that is off may be a wrong multiplier or offset
            part += f", mimic: q = {mimic.formula(robot, rel)}"
        out.append(part + ")")
    return out


def findings(robot: Robot, rows: list[Row] | None = None) -> list[Finding]:
    out = []
    for row in rows if rows is not None else evaluate(robot):
        if row.ok or row.model is None:
            continue  # an unknown frame is an input error (POSE002)
        fm, kp = row.measurement, row.pose
        joints = path_joints(calibration.for_pose(robot, kp), fm.frame, fm.relative_to)
        # as many digits as the tolerance judges, so the model's value can be pasted as the fix
        d = display.mm_digits(fm.tolerance)
        message = (
            f"known pose '{kp.name}': {fm.frame} measured at ({display.mm(fm.xyz, d)}) mm but the model puts it at "
            f"({display.mm(row.model, d)}) mm "
            f"(off by {row.worst * 1000:.{d}f} mm on one axis, tolerance {fm.tolerance * 1000:g} mm"
            f"{'; source ' + fm.source if fm.source else ''}); joints on the path: {', '.join(joints) or 'none'}"
        )
        out.append(
            Finding(
                "POSE010",
                "error",
                message,
                "one of these joints' origin, axis or parent is wrong, or the measurement is",
                f"pose:{kp.name}",
                fm.where,
            )
        )
    return out
