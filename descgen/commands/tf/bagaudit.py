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
from collections import Counter, deque
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from descgen.codes import Code
from descgen.codes.recording import BAG001, BAG002, BAG010, BAG012, BAG013, BAG014
from descgen.commands.tf.buffer import BufferCore, TransformError
from descgen.core.findings import Finding, InputError, Where
from descgen.infra.progress import counting

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


def _unusable(code: Code, path: Path, message: str, hint: str) -> InputError:
    return InputError([code.finding(message, hint, "file", Where(str(path)))])


def _one_line(exc: BaseException) -> str:
    """A library's error text on one line (YAML errors span several)."""
    return shown(" ".join(str(exc).split()) or type(exc).__name__, 300)


def _bag_folder(path: Path) -> Path:
    """The rosbag2 folder ``path`` names, checked for type and size before rosbags reads it."""
    hint = "give a rosbag2 folder (metadata.yaml with .mcap or .db3)"
    if path.is_file() and (path.parent / "metadata.yaml").is_file():
        path = path.parent  # the storage file or metadata.yaml inside a recording
    if not path.exists():
        raise _unusable(BAG014, path, "no such recording", hint)
    if not path.is_dir():
        raise _unusable(BAG014, path, "is a file, not a rosbag2 folder", hint)
    meta = path / "metadata.yaml"
    if not meta.exists():
        raise _unusable(BAG014, path, "holds no metadata.yaml, so it is not a rosbag2 folder", hint)
    if not meta.is_file():
        raise _unusable(BAG014, meta, "is not a regular file", hint)
    size = meta.stat().st_size
    if size > MAX_METADATA:
        raise _unusable(
            BAG014, meta, f"is {size / 1e6:.1f} MB; a rosbag2 metadata.yaml is at most {MAX_METADATA >> 20} MB", hint
        )
    return path


def _open(path: Path) -> Any:
    from descgen.infra.bag_decompress import open_reader  # chunks, messages and files inflate to a bound

    bag = _bag_folder(path)
    try:
        reader = open_reader(bag)
    except Exception as exc:  # rosbags raises ReaderError, YAML and OS errors on unusable input
        raise _unusable(
            BAG001,
            path,
            f"cannot read the recording: {_one_line(exc)}",
            "give a rosbag2 folder (metadata.yaml with .mcap or .db3)",
        ) from None
    return reader


def _stamp(header: Any) -> int:
    return int(header.stamp.sec) * 1_000_000_000 + int(header.stamp.nanosec)


@dataclass
class _Pending:
    """A sensor message waiting for its deadline (log time + wait) before it is looked up."""

    deadline: int
    topic: str
    log_ns: int
    stamp: int
    frame: str


class _Replay:
    """The audit as a stream: transforms go into the buffer in log-time order, and each
    sensor message is looked up once every transform logged by its deadline is in. Holds
    only the buffer (cache_ns of transforms), the messages still inside their wait, and
    bounded counts: memory does not grow with the recording's length."""

    def __init__(
        self, target: str, wait_ns: int, max_age_ns: int | None, cache_ns: int, examples: int, keep_results: bool
    ) -> None:
        self.target, self.wait_ns, self.max_age_ns, self.examples = target, wait_ns, max_age_ns, examples
        self.buf = BufferCore(cache_ns)
        self.report = Report()
        self.keep_results = keep_results
        self.pending: deque[_Pending] = deque()
        self.frames: set[str] = set()  # every frame named in the recording, for BAG012
        self.shown_examples: Counter[str] = Counter()

    def sensor(self, topic: str, log_ns: int, stamp: int, frame: str) -> None:
        self.frames.add(frame)
        self.pending.append(_Pending(log_ns + self.wait_ns, topic, log_ns, stamp, frame))

    def transforms(self, log_ns: int, msg: Any, static: bool) -> None:
        self.flush(log_ns)  # messages whose deadline is before this transform arrived
        for t in msg.transforms:
            tr, ro, parent, child = t.transform.translation, t.transform.rotation, t.header.frame_id, t.child_frame_id
            self.frames.add(parent)
            self.frames.add(child)
            self.buf.set_transform(
                parent, child, _stamp(t.header), (tr.x, tr.y, tr.z), (ro.x, ro.y, ro.z, ro.w), static
            )

    def flush(self, before: int | None) -> None:
        """Look up every waiting message whose deadline is before ``before`` (None: all)."""
        pending = self.pending
        while pending and (before is None or pending[0].deadline < before):
            self._look_up(pending.popleft())

    def _look_up(self, m: _Pending) -> None:
        report = self.report
        outcome, detail = _lookup(self.buf, self.target, m.frame, m.stamp, m.deadline, self.max_age_ns)
        report.lookups += 1
        report.counts[outcome] += 1
        report.per_topic.setdefault(m.topic, Counter())[outcome] += 1
        report.latency[_bucket((m.log_ns - m.stamp) / 1e6)] += 1
        if self.keep_results:
            report.results.append((m.topic, m.log_ns, outcome))
        if outcome != "ok" and self.shown_examples[outcome] < self.examples:
            self.shown_examples[outcome] += 1
            report.examples.append(
                {
                    "topic": m.topic,
                    "outcome": outcome,
                    "log_time_ns": m.log_ns,
                    "stamp_ns": m.stamp,
                    "frame_id": m.frame,
                    "detail": detail,
                }
            )


def audit(
    path: Path,
    target: str,
    topics: tuple[str, ...] = (),
    wait_ns: int = 0,
    max_age_ns: int | None = None,
    cache_ns: int = 10_000_000_000,
    examples: int = 5,
    keep_results: bool = False,
    show_progress: bool = False,
) -> Report:
    """Replay the recording once, in log-time order (the order rosbags yields: MCAP chunks
    merged by time, sqlite3 ORDER BY timestamp). ``keep_results`` keeps every lookup's
    outcome in ``Report.results``, which grows with the recording (tests use it);
    ``show_progress`` draws the messages read on a terminal (descgen/infra/progress.py)."""
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    reader = _open(path)
    replay = _Replay(target, wait_ns, max_age_ns, cache_ns, examples, keep_results)
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
                    BAG002.finding(
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
                    BAG013,
                    path,
                    f"topic {shown(c.topic)} ({shown(c.msgtype)}) has no header to look up",
                    "name a sensor topic whose messages have a std_msgs/Header",
                )
        tf_conns = [c for c in connections if c.topic in TF_TOPICS]
        read = tf_conns + chosen
        total = sum(int(getattr(c, "msgcount", 0) or 0) for c in read) or None
        with counting(total, path.name, "msg", show_progress) as step:
            since = 0
            for conn, log_ns, raw in reader.messages(connections=read):
                topic = conn.topic
                if topic in TF_TOPICS:
                    replay.transforms(log_ns, ts.deserialize_cdr(raw, conn.msgtype), topic == "/tf_static")
                else:
                    # rosbags decodes the whole message: reading the header from the bytes by hand was
                    # 2% of a 10-minute audit (benchmarks/bench_tf.py), not worth a second CDR reader
                    header = getattr(ts.deserialize_cdr(raw, conn.msgtype), "header")  # noqa: B009
                    replay.sensor(topic, log_ns, _stamp(header), header.frame_id)
                since += 1
                if since == _PROGRESS_EVERY:
                    step(since)
                    since = 0
            step(since)
        replay.flush(None)
    except InputError:
        raise
    except Exception as exc:  # a corrupt recording
        raise _unusable(
            BAG001, path, f"cannot read the recording: {_one_line(exc)}", "check the recording's files"
        ) from None
    finally:
        reader.close()
    _check_lookups(path, target, topics, replay.report.lookups, replay.frames)
    return replay.report


def _has_header(ts: Any, topic: str, msgtype: str) -> bool:
    return (
        topic not in TF_TOPICS
        and msgtype in ts.types
        and "header" in getattr(ts.types[msgtype], "__dataclass_fields__", {})
    )


def _check_lookups(path: Path, target: str, topics: tuple[str, ...], lookups: int, frames: set[str]) -> None:
    """Refuse an audit that passed without looking anything up."""
    if not lookups:
        what = f"the topics {', '.join(shown(t) for t in topics)} hold" if topics else "the recording has"
        raise _unusable(
            BAG010,
            path,
            f"nothing to look up: {what} no sensor messages with a header",
            "name a recorded sensor topic with --topic (/tf, /tf_static and /joint_states are not looked up)",
        )
    if target not in frames:
        known = ", ".join(shown(f, 40) for f in sorted(frames)[:8]) + (", ..." if len(frames) > 8 else "")
        raise _unusable(
            BAG012,
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


MAX_JOBS = 64
_PROGRESS_EVERY = 4096  # messages between two updates of the bar: its cost stays out of the loop


def _audit_one(path: Path, kwargs: dict[str, Any]) -> tuple[Report | None, tuple[Finding, ...]]:
    """One recording's audit, its input errors returned rather than raised (they cross a
    process boundary as plain data)."""
    try:
        return audit(path, **kwargs), ()
    except InputError as exc:
        return None, exc.findings


def audit_each(
    paths: list[Path], target: str, jobs: int = 1, show_progress: bool = False, **kwargs: Any
) -> list[tuple[Report | None, tuple[Finding, ...]]]:
    """Audit several recordings, ``jobs`` of them at a time in separate processes (each is one
    CPU-bound stream): for each recording, in order, its report or the input errors that kept it
    from one, so the readable recordings are reported beside the unreadable. ``show_progress``:
    the messages of each recording on a terminal, or the recordings done with ``jobs``."""
    kwargs["target"] = target
    if jobs <= 1 or len(paths) <= 1:
        outcomes = [_audit_one(p, kwargs | {"show_progress": show_progress}) for p in paths]
    else:
        from functools import partial

        from descgen.infra.workers import map_in_processes

        with counting(len(paths), "tf-audit", "recording", show_progress) as step:
            outcomes = map_in_processes(partial(_audit_one, kwargs=kwargs), paths, jobs, step)
    return outcomes
