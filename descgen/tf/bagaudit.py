"""``descgen tf-audit``: every sensor message of a recording looked up in tf at its own stamp.

Messages are replayed in log-time order; /tf and /tf_static feed a :class:`BufferCore`.
A sensor message logged at L is looked up (``target <- header.frame_id`` at
``header.stamp``) with only the transforms logged by ``L + wait``: what a node using a
tf2 MessageFilter with that timeout could have had. It never falls back to the latest
transform. Outcomes:

- ``ok``;
- ``disconnected``: the frame is unknown or not connected to the target;
- ``stale``: older than the buffer holds, no data for that time on a dynamic link (a gap),
  or interpolated across samples more than ``max_age`` away;
- ``future``: the message is stamped after it was logged (beyond ``wait``), so tf cannot
  have data for it.
"""

from __future__ import annotations

import itertools
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..findings import Finding, InputError, Where
from .buffer import BufferCore, TransformError

TF_TOPICS = ("/tf", "/tf_static")
HISTOGRAM_MS = (0, 10, 50, 100, 500)  # bucket edges of log time - stamp


@dataclass
class Report:
    lookups: int = 0
    counts: Counter[str] = field(default_factory=Counter)
    per_topic: dict[str, Counter[str]] = field(default_factory=dict)
    examples: list[dict[str, Any]] = field(default_factory=list)
    latency: Counter[str] = field(default_factory=Counter)
    results: list[tuple[str, int, str]] = field(default_factory=list)  # (topic, log ns, outcome) per lookup

    def as_dict(self) -> dict[str, Any]:
        return {
            "lookups": self.lookups,
            "ok": self.counts["ok"],
            "disconnected": self.counts["disconnected"],
            "stale": self.counts["stale"],
            "future": self.counts["future"],
            "per_topic": {
                t: {k: c[k] for k in ("ok", "disconnected", "stale", "future")}
                for t, c in sorted(self.per_topic.items())
            },
            "examples": self.examples,
            "latency_ms_histogram": dict(self.latency),
        }


def _bucket(ms: float) -> str:
    if ms < 0:
        return "<0 (stamped after arrival)"
    for lo, hi in itertools.pairwise(HISTOGRAM_MS):
        if ms < hi:
            return f"{lo}-{hi}"
    return f">={HISTOGRAM_MS[-1]}"


MAX_WAIT_S = 3600.0  # --wait and --max-age: beyond an hour the answer is the same
MAX_METADATA = 4 * 1024 * 1024  # a rosbag2 metadata.yaml is kilobytes, even for long recordings


def shown(name: str, limit: int = 80) -> str:
    """A name from a recording as it is printed: escaped (no control characters reach the
    terminal) and shortened."""
    text = name.encode("unicode_escape").decode("ascii")
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _unusable(code: str, path: Path, message: str, hint: str) -> InputError:
    return InputError([Finding(code, "error", message, hint, "file", Where(str(path)))])


def _one_line(exc: BaseException) -> str:
    """A library's error text on one line (YAML errors span several)."""
    return shown(" ".join(str(exc).split()) or type(exc).__name__, 300)


def _bag_folder(path: Path) -> Path:
    """The rosbag2 folder ``path`` names, checked for type and size before rosbags reads it."""
    hint = "give a rosbag2 folder (metadata.yaml with .mcap or .db3)"
    if path.is_file() and (path.parent / "metadata.yaml").is_file():
        path = path.parent  # the storage file or metadata.yaml inside a recording
    if not path.exists():
        raise _unusable("BAG014", path, "no such recording", hint)
    if not path.is_dir():
        raise _unusable("BAG014", path, "is a file, not a rosbag2 folder", hint)
    meta = path / "metadata.yaml"
    if not meta.exists():
        raise _unusable("BAG014", path, "holds no metadata.yaml, so it is not a rosbag2 folder", hint)
    if not meta.is_file():
        raise _unusable("BAG014", meta, "is not a regular file", hint)
    size = meta.stat().st_size
    if size > MAX_METADATA:
        raise _unusable(
            "BAG014", meta, f"is {size / 1e6:.1f} MB; a rosbag2 metadata.yaml is at most {MAX_METADATA >> 20} MB", hint
        )
    return path


def _open(path: Path) -> Any:
    from rosbags.rosbag2 import Reader

    bag = _bag_folder(path)
    try:
        reader = Reader(bag)
        reader.open()
    except Exception as exc:  # rosbags raises ReaderError, YAML and OS errors on unusable input
        raise _unusable(
            "BAG001",
            path,
            f"cannot read the recording: {_one_line(exc)}",
            "give a rosbag2 folder (metadata.yaml with .mcap or .db3)",
        ) from None
    return reader


def _stamp(header: Any) -> int:
    return int(header.stamp.sec) * 1_000_000_000 + int(header.stamp.nanosec)


def audit(
    path: Path,
    target: str,
    topics: tuple[str, ...] = (),
    wait_ns: int = 0,
    max_age_ns: int | None = None,
    cache_ns: int = 10_000_000_000,
    examples: int = 5,
) -> Report:
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    reader = _open(path)
    try:
        connections = list(reader.connections)
        chosen = (
            [c for c in connections if c.topic in topics]
            if topics
            else [
                c
                for c in connections
                if _has_header(ts, c.topic, c.msgtype) and c.msgtype != "sensor_msgs/msg/JointState"
            ]
        )
        missing = sorted(set(topics) - {c.topic for c in connections})
        if missing:
            raise InputError(
                [
                    Finding(
                        "BAG002",
                        "error",
                        f"topic {shown(missing[0])} is not in the recording",
                        "list topics with `ros2 bag info`",
                        "file",
                        Where(str(path)),
                    )
                ]
            )
        for c in chosen:
            if not _has_header(ts, c.topic, c.msgtype):
                raise _unusable(
                    "BAG013",
                    path,
                    f"topic {shown(c.topic)} ({shown(c.msgtype)}) has no header to look up",
                    "name a sensor topic whose messages have a std_msgs/Header",
                )
        tf_conns = [c for c in connections if c.topic in TF_TOPICS]
        tf_msgs: list[tuple[int, bool, Any]] = []
        sensors: list[tuple[int, str, Any]] = []
        for conn, log_ns, raw in reader.messages(connections=tf_conns + chosen):
            msg = ts.deserialize_cdr(raw, conn.msgtype)
            if conn.topic in TF_TOPICS:
                tf_msgs.append((log_ns, conn.topic == "/tf_static", msg))
            else:
                sensors.append((log_ns, conn.topic, msg))
    except InputError:
        raise
    except Exception as exc:  # a corrupt recording
        raise _unusable(
            "BAG001", path, f"cannot read the recording: {_one_line(exc)}", "check the recording's files"
        ) from None
    finally:
        reader.close()
    _check_lookups(path, target, topics, tf_msgs, sensors)
    tf_msgs.sort(key=lambda m: m[0])
    sensors.sort(key=lambda m: m[0] + wait_ns)
    buf = BufferCore(cache_ns)
    report = Report()
    i = 0
    for log_ns, topic, msg in sensors:
        deadline = log_ns + wait_ns
        while i < len(tf_msgs) and tf_msgs[i][0] <= deadline:
            for t in tf_msgs[i][2].transforms:
                tr, ro = t.transform.translation, t.transform.rotation
                buf.set_transform(
                    t.header.frame_id,
                    t.child_frame_id,
                    _stamp(t.header),
                    (tr.x, tr.y, tr.z),
                    (ro.x, ro.y, ro.z, ro.w),
                    static=tf_msgs[i][1],
                )
            i += 1
        stamp = _stamp(msg.header)
        frame = msg.header.frame_id
        outcome, detail = _lookup(buf, target, frame, stamp, deadline, max_age_ns)
        report.lookups += 1
        report.counts[outcome] += 1
        report.per_topic.setdefault(topic, Counter())[outcome] += 1
        report.latency[_bucket((log_ns - stamp) / 1e6)] += 1
        report.results.append((topic, log_ns, outcome))
        if outcome != "ok" and sum(1 for e in report.examples if e["outcome"] == outcome) < examples:
            report.examples.append(
                {
                    "topic": topic,
                    "outcome": outcome,
                    "log_time_ns": log_ns,
                    "stamp_ns": stamp,
                    "frame_id": frame,
                    "detail": detail,
                }
            )
    return report


def _has_header(ts: Any, topic: str, msgtype: str) -> bool:
    return (
        topic not in TF_TOPICS
        and msgtype in ts.types
        and "header" in getattr(ts.types[msgtype], "__dataclass_fields__", {})
    )


def _check_lookups(
    path: Path,
    target: str,
    topics: tuple[str, ...],
    tf_msgs: list[tuple[int, bool, Any]],
    sensors: list[tuple[int, str, Any]],
) -> None:
    """Refuse an audit that would pass without looking anything up."""
    if not sensors:
        what = f"the topics {', '.join(shown(t) for t in topics)} hold" if topics else "the recording has"
        raise _unusable(
            "BAG010",
            path,
            f"nothing to look up: {what} no sensor messages with a header",
            "name a recorded sensor topic with --topic (/tf, /tf_static and /joint_states are not looked up)",
        )
    frames = {m.header.frame_id for _, _, m in sensors}
    for _, _, msg in tf_msgs:
        for t in msg.transforms:
            frames.update((t.header.frame_id, t.child_frame_id))
    if target not in frames:
        known = ", ".join(shown(f, 40) for f in sorted(frames)[:8]) + (", ..." if len(frames) > 8 else "")
        raise _unusable(
            "BAG012",
            path,
            f"--target frame '{shown(target)}' appears nowhere in the recording (frames: {known})",
            "name a frame of the transform tree, e.g. odom or base_link",
        )


def _lookup(
    buf: BufferCore, target: str, frame: str, stamp: int, deadline: int, max_age_ns: int | None
) -> tuple[str, str]:
    try:
        buf.lookup(target, frame, stamp)
    except TransformError as exc:
        if exc.kind in ("lookup", "connectivity", "invalid"):
            return "disconnected", str(exc)
        if exc.kind == "future" and stamp > deadline:
            return "future", f"stamped {(stamp - deadline) / 1e6:.1f} ms after it could have been looked up: {exc}"
        return "stale", str(exc)
    if max_age_ns is not None:
        for link, gap in buf.nearest_gaps(target, frame, stamp):
            if gap > max_age_ns:
                return "stale", f"'{link}' has no transform within {gap / 1e6:.1f} ms of the stamp"
    return "ok", ""
