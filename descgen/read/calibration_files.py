"""Calibration files as their tools write them (docs/calibration.md, docs/calibration-formats.md).

- Universal Robots' kinematics YAML, written by ``ur_calibration`` and read by the UR
  description's ``ur_common.xacro`` (``kinematics_params:=``): under ``kinematics:``, one whole
  joint origin per key (x, y, z, roll, pitch, yaw; m, rad) and ``hash``.
- easy_handeye2's result YAML: ``parameters:`` (calibration_type, frames) and ``transform:``
  (translation x, y, z in m; rotation quaternion x, y, z, w).
- A CSV of joint zero offsets: header ``joint,offset`` and optionally ``unit`` (SI without it).

Files are data: read with a safe YAML loader, bounded in size, every number checked finite.
"""

from __future__ import annotations

import contextlib
import csv
import io
import math
from pathlib import Path
from typing import Any

from descgen.codes.command import CAL010
from descgen.core.findings import InputError, Where
from descgen.core.model import Pose
from descgen.core.record import record

MAX_BYTES = 4 * 2**20

# UR's kinematics keys and the joints ur_macro.xacro gives their origins to (ur_common.xacro
# read_model_data; ur_macro.xacro: <joint name="${tf_prefix}shoulder_pan_joint"> ... <origin xyz="${shoulder_x} ...)
UR_JOINTS = {
    "shoulder": "shoulder_pan_joint",
    "upper_arm": "shoulder_lift_joint",
    "forearm": "elbow_joint",
    "wrist_1": "wrist_1_joint",
    "wrist_2": "wrist_2_joint",
    "wrist_3": "wrist_3_joint",
}
_ORIGIN_KEYS = ("x", "y", "z", "roll", "pitch", "yaw")


@record
class UrKinematics:
    """Whole origins of the six UR joints (unprefixed names), and the calibration's hash."""

    origins: tuple[tuple[str, Pose], ...]
    hash: str | None


@record
class HandEye:
    """An easy_handeye2 result: the pose of ``child`` (the tracking base frame: the camera) in
    ``parent`` (the robot's effector frame for eye-in-hand, its base frame for eye-on-base)."""

    parent: str
    child: str
    xyz: tuple[float, float, float]
    quat_xyzw: tuple[float, float, float, float]
    kind: str


def _refuse(path: Path, why: str, line: int = 0) -> InputError:
    return InputError(
        [
            CAL010.finding(
                f"cannot read the calibration file: {why}",
                "see docs/calibration.md for the formats descgen reads",
                "file:" + path.name,
                Where(str(path), line),
            )
        ]
    )


def _text(path: Path) -> str:
    from descgen.infra.safeio import Codes, read_bounded

    # a regular file of at most MAX_BYTES, or CAL010 (a FIFO or a device would never end)
    data = read_bounded(path, "calibration", MAX_BYTES, codes=Codes(CAL010, CAL010, CAL010))
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise _refuse(path, "not UTF-8 text") from None


def _yaml(path: Path) -> Any:
    import yaml

    try:
        return yaml.safe_load(_text(path))
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise _refuse(path, f"not YAML: {getattr(exc, 'problem', None) or exc}", mark.line + 1 if mark else 0) from None


def _number(path: Path, value: Any, where: str) -> float:
    if isinstance(value, str):  # yaml-cpp 0.9 writes 1e-05, which YAML 1.1 reads as text (xacro passes it on)
        with contextlib.suppress(ValueError):
            value = float(value)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _refuse(path, f"{where} is {value!r}, not a number")
    if not math.isfinite(value):
        raise _refuse(path, f"{where} is {value!r}, not a finite number")
    return float(value)


def _mapping(path: Path, value: Any, where: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise _refuse(path, f"{where} is not a mapping")
    return value


def read_ur(path: Path) -> UrKinematics:
    doc = _mapping(path, _yaml(path), "the file")
    kin = _mapping(path, doc.get("kinematics"), "kinematics")
    origins: list[tuple[str, Pose]] = []
    for key, joint in UR_JOINTS.items():
        entry = _mapping(path, kin.get(key), f"kinematics.{key}")
        v = [_number(path, entry.get(k), f"kinematics.{key}.{k}") for k in _ORIGIN_KEYS]
        origins.append((joint, Pose((v[0], v[1], v[2]), (v[3], v[4], v[5]))))
    h = kin.get("hash", doc.get("hash"))
    return UrKinematics(tuple(origins), str(h) if h is not None else None)


def read_handeye(path: Path) -> HandEye:
    doc = _mapping(path, _yaml(path), "the file")
    params = _mapping(path, doc.get("parameters"), "parameters")
    transform = _mapping(path, doc.get("transform"), "transform")
    t = _mapping(path, transform.get("translation"), "transform.translation")
    r = _mapping(path, transform.get("rotation"), "transform.rotation")
    xyz = tuple(_number(path, t.get(k), f"transform.translation.{k}") for k in "xyz")
    quat = tuple(_number(path, r.get(k), f"transform.rotation.{k}") for k in "xyzw")
    n = math.sqrt(sum(c * c for c in quat))
    if abs(n - 1.0) > 1e-3:
        raise _refuse(path, f"transform.rotation has norm {n:.6f}, not a unit quaternion")
    kind = str(params.get("calibration_type", ""))
    if kind not in ("eye_in_hand", "eye_on_base"):
        raise _refuse(path, f"parameters.calibration_type is {kind!r}, not eye_in_hand or eye_on_base")
    frame_key = "robot_effector_frame" if kind == "eye_in_hand" else "robot_base_frame"
    parent, child = params.get(frame_key), params.get("tracking_base_frame")
    if not isinstance(parent, str) or not parent or not isinstance(child, str) or not child:
        raise _refuse(path, f"parameters.{frame_key} and parameters.tracking_base_frame must name frames")
    q = tuple(c / n for c in quat)
    parent, child = parent.lstrip("/"), child.lstrip("/")  # easy_handeye2's README writes /base_link; tf2 does not
    return HandEye(parent, child, xyz, q, kind)  # type: ignore[arg-type]


def read_offsets_csv(path: Path) -> tuple[tuple[str, str, str, int], ...]:
    """(joint, the offset's number as written, its unit or "" for the joint's SI unit, line) per row."""
    rows = list(csv.reader(io.StringIO(_text(path))))
    if not rows or [c.strip() for c in rows[0][:2]] != ["joint", "offset"]:
        raise _refuse(path, "the header must be joint,offset (and optionally ,unit)", 1)
    header = [c.strip() for c in rows[0]]
    unit_col = header.index("unit") if "unit" in header else None
    out: list[tuple[str, str, str, int]] = []
    for i, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) < len(header):
            raise _refuse(path, f"row {i} has {len(row)} columns, the header {len(header)}", i)
        joint, value = row[0].strip(), row[1].strip()
        try:
            number = float(value)
        except ValueError:
            raise _refuse(path, f"row {i}: offset {value!r} is not a number", i) from None
        if not math.isfinite(number) or not joint:
            raise _refuse(path, f"row {i}: needs a joint name and a finite offset", i)
        unit = row[unit_col].strip() if unit_col is not None else ""
        out.append((joint, value, unit, i))
    if not out:
        raise _refuse(path, "no rows")
    return tuple(out)


__all__ = ["UR_JOINTS", "HandEye", "UrKinematics", "read_handeye", "read_offsets_csv", "read_ur"]
