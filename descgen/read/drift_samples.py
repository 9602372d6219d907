"""What ``descgen drift`` compares the model with: joint values and the measured pose of one frame
per sample, from a CSV or a rosbag2 recording (docs/calibration.md).

- CSV: header ``time``, one column per moving joint (named as in the spec; rad or m), then
  ``x,y,z`` (m) of the frame in the base, optionally ``qx,qy,qz,qw``.
- rosbag2: ``/joint_states`` (sensor_msgs/JointState) and a pose topic, geometry_msgs/PoseStamped
  (the pose of the frame in header.frame_id) or TransformStamped; joint values are interpolated
  linearly at each pose's header stamp, and a pose with no joint state within MAX_GAP_S on both
  sides is dropped (counted). The recording is read once, message by message; what is kept is
  one row of numbers per sample.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from descgen.codes.command import CAL012
from descgen.core.findings import InputError, Where

MAX_GAP_S = 0.1
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
    try:
        if path.stat().st_size > MAX_CSV_BYTES:
            raise refuse(path, f"larger than {MAX_CSV_BYTES // 2**20} MiB", "split the samples")
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise refuse(path, f"cannot read the samples: {getattr(exc, 'strerror', None) or exc}", "give a CSV") from None
    reader = csv.reader(io.StringIO(text))
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
    rows: list[list[float]] = []
    for i, row in enumerate(reader, start=2):
        if not row or all(not c.strip() for c in row):
            continue
        try:
            values = [float(row[k]) for k in cols]
        except (ValueError, IndexError):
            raise refuse(path, f"row {i} is not a number in every column the fit needs", "fix the row", i) from None
        if not all(math.isfinite(v) for v in values):
            raise refuse(path, f"row {i} holds a value that is not finite", "fix the row", i)
        rows.append(values)
    data = np.asarray(rows, dtype=float).reshape(-1, len(wanted))
    n_j = len(joints)
    return Samples(
        data[:, 0],
        {j: data[:, 1 + k] for k, j in enumerate(joints)},
        data[:, 1 + n_j : 4 + n_j],
        data[:, 4 + n_j : 8 + n_j] if with_quat else None,
        None,
    )


def _stamp(header: Any) -> float:
    return int(header.stamp.sec) + int(header.stamp.nanosec) * 1e-9


def read_bag(path: Path, joints: Sequence[str], pose_topic: str, joint_topic: str = "/joint_states") -> Samples:
    from rosbags.typesys import Stores, get_typestore

    from descgen.infra.bag_decompress import open_reader

    ts = get_typestore(Stores.ROS2_JAZZY)
    folder = path.parent if path.is_file() else path
    try:
        reader = open_reader(folder)
    except Exception as exc:  # rosbags raises ReaderError, YAML and OS errors on unusable input
        raise refuse(path, f"cannot read the recording: {str(exc)[:200]}", "give a rosbag2 folder") from None
    try:
        conns = list(reader.connections)
        by_topic = {c.topic: c for c in conns}
        for topic in (joint_topic, pose_topic):
            if topic not in by_topic:
                raise refuse(path, f"topic {topic!r} is not in the recording", "list topics with `ros2 bag info`")
        if by_topic[pose_topic].msgtype not in POSE_TYPES:
            raise refuse(
                path,
                f"{pose_topic} is {by_topic[pose_topic].msgtype}, not PoseStamped or TransformStamped",
                "give the topic of the tracker's or the driver's pose",
            )
        js_t: list[float] = []
        js_q: list[list[float]] = []
        p_t: list[float] = []
        p_v: list[list[float]] = []
        base: str | None = None
        index = {j: k for k, j in enumerate(joints)}
        for conn, _log, raw in reader.messages(connections=[by_topic[joint_topic], by_topic[pose_topic]]):
            msg: Any = ts.deserialize_cdr(raw, conn.msgtype)
            if conn.topic == joint_topic:
                row = [math.nan] * len(joints)
                for name, value in zip(msg.name, msg.position, strict=False):
                    k = index.get(name)
                    if k is not None:
                        row[k] = float(value)
                js_t.append(_stamp(msg.header))
                js_q.append(row)
            else:
                if conn.msgtype.endswith("PoseStamped"):
                    p, o = msg.pose.position, msg.pose.orientation
                else:
                    p, o = msg.transform.translation, msg.transform.rotation
                base = base or msg.header.frame_id or None
                p_t.append(_stamp(msg.header))
                p_v.append([p.x, p.y, p.z, o.x, o.y, o.z, o.w])
    finally:
        reader.close()
    if not js_t or not p_t:
        raise refuse(path, "the recording has no joint states or no poses", "record both topics")
    jt = np.asarray(js_t)
    jq = np.asarray(js_q)
    order = np.argsort(jt, kind="stable")
    jt, jq = jt[order], jq[order]
    missing = [j for k, j in enumerate(joints) if np.all(np.isnan(jq[:, k]))]
    if missing:
        raise refuse(path, f"{joint_topic} never gives joint {missing[0]!r}", "record every joint of the chain")
    pt = np.asarray(p_t)
    pv = np.asarray(p_v)
    # a pose is kept when joint states bracket it within MAX_GAP_S on both sides
    after = np.searchsorted(jt, pt, side="left")
    ok = (after > 0) & (after < len(jt))
    prev = jt[np.clip(after - 1, 0, len(jt) - 1)]
    nxt = jt[np.clip(after, 0, len(jt) - 1)]
    exact = np.isin(pt, jt)
    ok = exact | (ok & (pt - prev <= MAX_GAP_S) & (nxt - pt <= MAX_GAP_S))
    q = {}
    for k, j in enumerate(joints):
        good = ~np.isnan(jq[:, k])
        q[j] = np.interp(pt[ok], jt[good], jq[good, k])
    return Samples(pt[ok], q, pv[ok, :3], pv[ok, 3:], base, int((~ok).sum()))


__all__ = ["Samples", "read_bag", "read_csv"]
