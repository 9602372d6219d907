"""What ``descgen drift`` compares the model with: joint values and the measured pose of one frame
per sample, from a CSV or a rosbag2 recording (docs/calibration.md).

- CSV: header ``time``, one column per moving joint (named as in the spec; rad or m), then
  ``x,y,z`` (m) of the frame in the base, optionally ``qx,qy,qz,qw``.
- rosbag2: ``/joint_states`` (sensor_msgs/JointState) and a pose topic, geometry_msgs/PoseStamped
  (the pose of the frame in header.frame_id) or TransformStamped; joint values are interpolated
  linearly at each pose's header stamp, and a pose with no joint state within MAX_GAP_S on both
  sides is dropped (counted). The recording is read once, message by message, holding a few
  seconds of joint states (_Pairing); what is kept is one row of numbers per sample.
"""

from __future__ import annotations

import bisect
import csv
import math
from array import array
from collections import deque
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from descgen.codes.command import CAL012
from descgen.core.findings import InputError, Where

MAX_GAP_S = 0.1
HORIZON_S = 2.0  # how late a message may arrive (log order against stamps) and still be paired
MAX_CSV_BYTES = 512 * 2**20
POSE_TYPES = ("geometry_msgs/msg/PoseStamped", "geometry_msgs/msg/TransformStamped")


@dataclass(frozen=True)
class Samples:
    t: np.ndarray  # (n,) seconds
    q: dict[str, np.ndarray]  # joint -> (n,)
    xyz: np.ndarray  # (n, 3) m
    quat: np.ndarray | None  # (n, 4) x, y, z, w
    base: str | None  # the frame the poses are in, where the input says
    dropped: int = 0


def refuse(path: Path, why: str, hint: str, line: int = 0) -> InputError:
    return InputError([CAL012.finding(why, hint, "file:" + path.name, Where(str(path), line))])


def read_csv(path: Path, joints: Sequence[str]) -> Samples:
    """The samples of a CSV, read row by row into one flat array of numbers (8 bytes a value)."""
    from descgen.infra.safeio import Codes, check_file

    # a regular file within the bound, or CAL012 (a FIFO or a device would never end)
    check_file(path, "samples CSV", MAX_CSV_BYTES, codes=Codes(CAL012, CAL012, CAL012))
    try:
        with path.open(encoding="utf-8", newline="") as fh:
            return _read_csv(path, csv.reader(fh), joints)
    except (OSError, UnicodeDecodeError) as exc:
        raise refuse(path, f"cannot read the samples: {getattr(exc, 'strerror', None) or exc}", "give a CSV") from None
    except csv.Error as exc:
        raise refuse(path, f"not CSV: {exc}", "give a CSV") from None


def _read_csv(path: Path, reader: Iterator[list[str]], joints: Sequence[str]) -> Samples:
    header = [c.strip() for c in next(reader, [])]
    if not header or header[0] != "time":
        raise refuse(path, "the header must start with time", "time,<joints...>,x,y,z[,qx,qy,qz,qw]", 1)
    missing = [c for c in (*joints, "x", "y", "z") if c not in header]
    if missing:
        raise refuse(
            path,
            f"the samples have no column {missing[0]!r}",
            "add a column per moving joint of the chain, and x,y,z",
            1,
        )
    with_quat = all(c in header for c in ("qx", "qy", "qz", "qw"))
    wanted = ["time", *joints, "x", "y", "z", *(("qx", "qy", "qz", "qw") if with_quat else ())]
    cols = [header.index(c) for c in wanted]
    flat = array("d")
    for i, row in enumerate(reader, start=2):
        if not row or all(not c.strip() for c in row):
            continue
        try:
            values = [float(row[k]) for k in cols]
        except (ValueError, IndexError):
            raise refuse(path, f"row {i} is not a number in every column the fit needs", "fix the row", i) from None
        if not all(math.isfinite(v) for v in values):
            raise refuse(path, f"row {i} holds a value that is not finite", "fix the row", i)
        if with_quat:
            unit = _unit_quaternion(values[-7:])
            if unit is None:
                n = math.sqrt(sum(c * c for c in values[-4:]))
                raise refuse(path, f"row {i}: qx,qy,qz,qw has norm {n:.6f}, not a unit quaternion", "fix the row", i)
            values[-4:] = unit[3:]
        flat.extend(values)
    data = np.frombuffer(flat, dtype=float).reshape(-1, len(wanted)).copy()
    n_j = len(joints)
    return Samples(
        data[:, 0],
        {j: data[:, 1 + k] for k, j in enumerate(joints)},
        data[:, 1 + n_j : 4 + n_j],
        data[:, 4 + n_j : 8 + n_j] if with_quat else None,
        None,
    )


QUAT_SLACK = 1e-3  # how far from unit length a measured quaternion may be (then normalised)


def _unit_quaternion(values: Sequence[float]) -> tuple[float, ...] | None:
    """x, y, z and the normalised quaternion; None when a value is not finite or the
    quaternion is not within QUAT_SLACK of unit length."""
    if not all(math.isfinite(v) for v in values):
        return None
    n = math.sqrt(sum(c * c for c in values[3:7]))
    if abs(n - 1.0) > QUAT_SLACK:
        return None
    return (*values[:3], *(c / n for c in values[3:7]))


def _stamp(header: Any) -> float:
    return int(header.stamp.sec) + int(header.stamp.nanosec) * 1e-9


class _Pairing:
    """Poses paired with joint values as the recording streams by, in bounded memory: per joint,
    the joint states of the last HORIZON_S seconds (several publishers may each give some joints);
    a pose waits until every joint has a state MAX_GAP_S past its stamp (a state logged late within
    that still counts; or until HORIZON_S passes), then
    takes each joint's value interpolated between the states around its stamp, when both are
    within MAX_GAP_S of it. What is kept is one row of numbers per paired pose."""

    def __init__(self, joints: Sequence[str]) -> None:
        self.joints = list(joints)
        self.index = {j: k for k, j in enumerate(joints)}
        self.times: list[list[float]] = [[] for _ in joints]
        self.values: list[list[float]] = [[] for _ in joints]
        self.latest = [-math.inf] * len(joints)
        self.seen = [False] * len(joints)
        self.pending: deque[tuple[float, tuple[float, ...]]] = deque()
        self.out_t = array("d")
        self.out_q = array("d")
        self.out_p = array("d")
        self.dropped = 0

    def joint_state(self, t: float, names: Sequence[str], positions: Sequence[float]) -> None:
        for name, value in zip(names, positions, strict=False):
            k = self.index.get(name)
            if k is None or not math.isfinite(value):
                continue
            times, values = self.times[k], self.values[k]
            if not times or t >= times[-1]:
                times.append(t)
                values.append(float(value))
                self.latest[k] = t
            else:  # a late message still lands in order
                at = bisect.bisect_right(times, t)
                times.insert(at, t)
                values.insert(at, float(value))
            self.seen[k] = True
            if times[0] < self.latest[k] - 2 * HORIZON_S:  # trimmed now and then, not per message
                cut = bisect.bisect_left(times, self.latest[k] - HORIZON_S)
                del times[: cut - 1], values[: cut - 1]  # one state before the horizon stays, as a bracket
        self._flush(min(self.latest) - MAX_GAP_S)

    def pose(self, t: float, values: tuple[float, ...]) -> None:
        self.pending.append((t, values))
        self._flush(min(self.latest) - MAX_GAP_S)

    def _flush(self, ready: float) -> None:
        pending = self.pending
        if not pending:
            return
        newest = max(self.latest)
        while pending and (pending[0][0] <= ready or pending[0][0] < newest - HORIZON_S):
            t, values = pending.popleft()
            q = [self._at(k, t) for k in range(len(self.joints))]
            if any(v is None for v in q):
                self.dropped += 1
                continue
            self.out_t.append(t)
            self.out_q.extend(q)  # type: ignore[arg-type]
            self.out_p.extend(values)

    def _at(self, k: int, t: float) -> float | None:
        times, values = self.times[k], self.values[k]
        i = bisect.bisect_left(times, t)
        if i < len(times) and times[i] == t:
            return values[i]
        if i == 0 or i == len(times) or t - times[i - 1] > MAX_GAP_S or times[i] - t > MAX_GAP_S:
            return None
        w = (t - times[i - 1]) / (times[i] - times[i - 1])
        return values[i - 1] + w * (values[i] - values[i - 1])

    def finish(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        self._flush(math.inf)
        n = len(self.out_t)
        return (
            np.frombuffer(self.out_t, dtype=float).copy(),
            np.frombuffer(self.out_q, dtype=float).reshape(n, len(self.joints)).copy(),
            np.frombuffer(self.out_p, dtype=float).reshape(n, 7).copy(),
        )


def read_bag(path: Path, joints: Sequence[str], pose_topic: str, joint_topic: str = "/joint_states") -> Samples:
    from rosbags.typesys import Stores, get_typestore

    from descgen.infra.bag_decompress import open_reader

    ts = get_typestore(Stores.ROS2_JAZZY)
    folder = path.parent if path.is_file() else path
    try:
        reader = open_reader(folder)
    except Exception as exc:  # rosbags raises ReaderError, YAML and OS errors on unusable input
        raise refuse(path, f"cannot read the recording: {str(exc)[:200]}", "give a rosbag2 folder") from None
    pairing = _Pairing(joints)
    base: str | None = None
    poses = 0
    try:
        by_topic = {c.topic: c for c in reader.connections}
        for topic in (joint_topic, pose_topic):
            if topic not in by_topic:
                raise refuse(path, f"topic {topic!r} is not in the recording", "list topics with `ros2 bag info`")
        if by_topic[joint_topic].msgtype != "sensor_msgs/msg/JointState":
            raise refuse(
                path,
                f"{joint_topic} is {by_topic[joint_topic].msgtype}, not sensor_msgs/msg/JointState",
                "record the joint states (joint_state_broadcaster's /joint_states)",
            )
        if by_topic[pose_topic].msgtype not in POSE_TYPES:
            raise refuse(
                path,
                f"{pose_topic} is {by_topic[pose_topic].msgtype}, not PoseStamped or TransformStamped",
                "give the topic of the tracker's or the driver's pose",
            )
        for conn, _log, raw in reader.messages(connections=[by_topic[joint_topic], by_topic[pose_topic]]):
            msg: Any = ts.deserialize_cdr(raw, conn.msgtype)
            if conn.topic == joint_topic:
                pairing.joint_state(_stamp(msg.header), msg.name, msg.position)
                continue
            if conn.msgtype.endswith("PoseStamped"):
                p, o = msg.pose.position, msg.pose.orientation
            else:
                p, o = msg.transform.translation, msg.transform.rotation
            poses += 1
            values = _unit_quaternion((p.x, p.y, p.z, o.x, o.y, o.z, o.w))
            if values is None:  # a tracker that lost the marker sends NaN or a zero quaternion
                pairing.dropped += 1
                continue
            base = base or msg.header.frame_id or None
            pairing.pose(_stamp(msg.header), values)
    finally:
        reader.close()
    if not poses:
        raise refuse(path, f"{pose_topic} has no messages", "record the measured pose")
    t, q, pv = pairing.finish()
    # a joint no state gave has no column: the caller says which of its chain's joints are missing
    given = {j: q[:, k] for k, j in enumerate(joints) if pairing.seen[k]}
    return Samples(t, given, pv[:, :3], pv[:, 3:], base, pairing.dropped)


__all__ = ["Samples", "read_bag", "read_csv"]
