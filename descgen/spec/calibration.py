"""Spec ``calibration:`` -> the calibration layer of the model, and the joints it moves.

The joints keep their nominal origin in :class:`~descgen.core.model.JointCalibration` and take
the calibrated one (descgen/physics/calibration.py says what a correction means), so every
check, proof and output downstream sees the robot as measured, and the outputs can still
show the nominal model beside it (CAL001-CAL004).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from descgen.codes.spec import CAL001, CAL002, CAL003, CAL004, CAL005
from descgen.core import model as m
from descgen.core.findings import Finding, Where
from descgen.physics.calibration import calibrated_origin, correction_size
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.geometry import pose

# beyond these a correction is more likely a slip than a calibration (CAL004)
LARGE_SHIFT_M = 0.020
LARGE_TURN_RAD = math.radians(5.0)


def apply(conv: Converter, spec: s.CalibrationSpec, joints: list[m.Joint], sensors: list[m.Sensor]) -> m.Robot:
    """A robot holding only the calibrated joints (in ``joints`` order) and the layer; the
    caller copies both into its robot."""
    by_name = {j.name: i for i, j in enumerate(joints)}
    sensor_joint = {sn.name: sn.joint for sn in sensors}
    entries: list[m.JointCalibration] = []
    seen: set[str] = set()
    path = ("calibration",)
    for name, jc in spec.joints.items():
        at = (*path, "joints", name)
        where = conv.where(at)
        _cited(conv, spec, jc.source, f"joint:{name}", (*at, "source"))
        if name not in by_name:
            conv.error(
                CAL002,
                f"calibration.joints names {name!r}, which is not a joint of the robot",
                "name one of the robot's joints (the name as the URDF writes it, prefix included)",
                f"joint:{name}",
                where,
            )
            continue
        j = joints[by_name[name]]
        offset = 0.0
        if jc.offset is not None:
            if j.type not in m.ONE_DOF:
                conv.error(
                    CAL003,
                    f"joint {name!r} is {j.type}: it has no zero to offset",
                    "correct its origin (calibration.joints.<name>.origin) instead",
                    f"joint:{name}",
                    conv.where((*at, "offset")),
                )
            else:
                offset = conv.joint_value(name, jc.offset, (*at, "offset"))
        dxyz = tuple(float(v.si) for v in jc.origin.xyz)
        drpy = tuple(float(v.si) for v in jc.origin.rpy)
        cal = calibrated_origin(j, j.origin, offset, dxyz, drpy)  # type: ignore[arg-type]
        entries.append(m.JointCalibration(name, jc.source, j.origin, cal, offset, dxyz, drpy, None, where))  # type: ignore[arg-type]
        seen.add(name)
    for name, sc in spec.sensors.items():
        at = (*path, "sensors", name)
        where = conv.where(at)
        _cited(conv, spec, sc.source, f"sensor:{name}", (*at, "source"))
        jn = sensor_joint.get(name)
        if jn is None or jn in seen:
            conv.error(
                CAL002,
                f"calibration.sensors names {name!r}, which is not a sensor of the spec"
                if jn is None
                else f"sensor {name!r} is calibrated twice: its joint {jn!r} is also under calibration.joints",
                "name a sensor of sensors: once; its mount goes under calibration.sensors",
                f"sensor:{name}",
                where,
            )
            continue
        j = joints[by_name[jn]]
        measured = pose(sc.origin)
        d = tuple(a - b for a, b in zip(measured.xyz, j.origin.xyz, strict=True))
        r = tuple(a - b for a, b in zip(measured.rpy, j.origin.rpy, strict=True))
        entries.append(m.JointCalibration(jn, sc.source, j.origin, measured, 0.0, d, r, name, where))  # type: ignore[arg-type]
        seen.add(jn)
    for e in entries:
        _large(conv, joints[by_name[e.joint]], e)
    moved = {e.joint: e.calibrated for e in entries}
    sources = tuple(
        m.CalibrationSource(n, src.method, src.tool, src.file, src.date, src.hash) for n, src in spec.sources.items()
    )
    return m.Robot(
        "calibration",
        joints=tuple(replace(j, origin=moved[j.name]) for j in joints if j.name in moved),
        calibration=tuple(entries),
        calibration_sources=sources,
    )


def _cited(conv: Converter, spec: s.CalibrationSpec, source: str, subject: str, at: tuple[str, ...]) -> None:
    if source not in spec.sources:
        known = ", ".join(sorted(spec.sources)) or "none yet"
        conv.error(
            CAL001,
            f"{subject} cites calibration source {source!r}, which calibration.sources does not name",
            f"add it under calibration.sources (method, tool, file, date), or cite one of: {known}",
            subject,
            conv.where(at),
        )


def _large(conv: Converter, j: m.Joint, e: m.JointCalibration) -> None:
    """CAL004: how far the calibrated child frame is from the nominal one, at q = 0."""
    shift, turn = correction_size(j, e)
    if shift > LARGE_SHIFT_M or turn > LARGE_TURN_RAD:
        subject = f"sensor:{e.sensor}" if e.sensor else f"joint:{e.joint}"
        conv.error(
            CAL004,
            f"the calibration moves the child frame of joint {e.joint!r} by {shift * 1000:.1f} mm and turns it by "
            f"{math.degrees(turn):.2f} deg from the nominal model",
            "check the unit and the frame the values are in; if the nominal value is wrong, correct it in the spec",
            subject,
            e.where,
        )


def drift_check(spec_path: Path, ds: s.DriftCheckSpec, where: Where) -> tuple[m.DriftCheck | None, list[Finding]]:
    """``calibration.drift`` with its samples resolved beside the spec (CAL005 when the path is
    absolute, leaves the project or is not a regular file)."""
    from descgen.meshes.paths import project_root

    written = ds.samples
    target = (spec_path.parent / written).resolve()
    why = None
    if Path(written).is_absolute():
        why = "is absolute"
    elif not target.is_relative_to(project_root(spec_path).resolve()):
        why = f"leaves the project folder {project_root(spec_path).name}/"
    elif not target.is_file():
        why = "is not a regular file" if target.exists() else "does not exist"
    if why is not None:
        return None, [
            CAL005.finding(
                f"calibration.drift.samples {written!r} {why}",
                "name a CSV relative to the spec, inside the project",
                "calibration",
                where,
            )
        ]
    tolerance = ds.tolerance.si if ds.tolerance is not None else 0.001
    return m.DriftCheck(str(target), ds.frame, ds.base, tolerance, tuple(ds.parameters), where), []
