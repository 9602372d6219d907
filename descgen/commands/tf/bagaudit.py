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

import hashlib
import itertools
from bisect import bisect_right
from collections import Counter, deque
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

from descgen.codes import Code
from descgen.codes.recording import BAG001, BAG002, BAG010, BAG012, BAG013, BAG014
from descgen.commands.tf.buffer import BufferCore, TransformError
from descgen.core.findings import InputError, Where
from descgen.infra.progress import counting

TF_TOPICS = ("/tf", "/tf_static")
DESCRIPTION_TOPIC = "/robot_description"  # robot_state_publisher's, std_msgs/String, transient local
HISTOGRAM_MS = (0, 10, 50, 100, 500)  # bucket edges of log time - stamp
OUTCOMES = ("ok", "disconnected", "stale", "future")


class Failure(NamedTuple):
    """One failed lookup: a row of the findings table (descgen/commands/fleet/table.py)."""

    topic: str
    log_ns: int
    stamp: int
    frame: str
    outcome: str
    detail: str
    version: int  # index into Report.descriptions of the description in effect; -1: none


class Description(NamedTuple):
    """A /robot_description message of the recording: the URDF's hash and its robot's name."""

    log_ns: int
    sha256: str
    robot: str


@dataclass
class Span:
    """The lookups of one topic under one description: counts, time range and latency."""

    counts: Counter[str] = field(default_factory=Counter)
    first_ns: int = 0
    last_ns: int = 0
    latency_sum_ns: int = 0
    latency_max_ns: int = 0

    def add(self, outcome: str, log_ns: int, latency_ns: int) -> None:
        if not self.counts:
            self.first_ns = log_ns
            self.latency_max_ns = latency_ns
        self.counts[outcome] += 1
        self.last_ns = log_ns
        self.latency_sum_ns += latency_ns
        self.latency_max_ns = max(self.latency_max_ns, latency_ns)

    def merge(self, other: Span) -> None:
        """``other`` holds later lookups than this span (the next time window)."""
        if not other.counts:
            return
        if not self.counts:
            self.first_ns, self.latency_max_ns = other.first_ns, other.latency_max_ns
        self.counts.update(other.counts)
        self.last_ns = other.last_ns
        self.latency_sum_ns += other.latency_sum_ns
        self.latency_max_ns = max(self.latency_max_ns, other.latency_max_ns)


@dataclass
class Report:
    lookups: int = 0
    counts: Counter[str] = field(default_factory=Counter)
    per_topic: dict[str, Counter[str]] = field(default_factory=dict)
    examples: list[dict[str, Any]] = field(default_factory=list)
    latency: Counter[str] = field(default_factory=Counter)
    results: list[tuple[str, int, str]] = field(default_factory=list)  # (topic, log ns, outcome) per lookup
    failures: list[Failure] = field(default_factory=list)  # every failed lookup, with keep_failures
    spans: dict[tuple[str, int], Span] = field(default_factory=dict)  # (topic, description index)
    descriptions: list[Description] = field(default_factory=list)
    frames: set[str] = field(default_factory=set)  # every frame named in what was read
    boundary: tuple[str, str] = ("", "")  # the buffer's digest at a window's start and end

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
        } | (
            {
                "descriptions": [
                    {"log_time_ns": d.log_ns, "sha256": d.sha256, "robot": d.robot} for d in self.descriptions
                ]
            }
            if self.descriptions
            else {}
        )


def _bucket(ms: float) -> str:
    if ms < 0:
        return "<0 (stamped after arrival)"
    for lo, hi in itertools.pairwise(HISTOGRAM_MS):
        if ms < hi:
            return f"{lo}-{hi}"
    return f">={HISTOGRAM_MS[-1]}"


MAX_WAIT_S = 3600.0  # --wait and --max-age: beyond an hour the answer is the same
MAX_METADATA = 4 * 1024 * 1024  # a rosbag2 metadata.yaml is kilobytes, even for long recordings


MAX_ROW_TEXT = 1000  # characters of a frame name in a failure row (tf2's words: four times that)


def _clip(text: str, limit: int) -> str:
    return text if len(text) <= limit else text[: limit - 3] + "..."


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
    try:
        return _checked_folder(path)
    except OSError as exc:  # a name too long, a folder without permission, a loop of links
        raise _unusable(
            BAG014, path, f"cannot be read: {exc.strerror or exc}", "give a rosbag2 folder you can read"
        ) from None


def _checked_folder(path: Path) -> Path:
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


@dataclass(frozen=True)
class Window:
    """A time slice of one recording, audited on its own (``tf-audit --window``): the sensor
    messages logged in [start, stop), looked up in a buffer filled from ``start - horizon``
    (static transforms from the beginning). The buffer's digest where the slice starts and
    ends is kept, so the slices of a recording are known to have given what one pass gives
    (descgen/commands/fleet/windows.py)."""

    start: int | None  # None: from the beginning of the recording (whatever its metadata says)
    stop: int | None  # None: to the end of the recording
    horizon: int


@dataclass
class _Pending:
    """A sensor message waiting for its deadline (log time + wait) before it is looked up."""

    deadline: int
    topic: str
    log_ns: int
    stamp: int
    frame: str
    version: int


class _Replay:
    """The audit as a stream: transforms go into the buffer in log-time order, and each
    sensor message is looked up once every transform logged by its deadline is in. Holds
    only the buffer (cache_ns of transforms), the messages still inside their wait, and
    bounded counts (with ``keep_failures``, the failed lookups too): memory does not grow
    with the recording's length."""

    def __init__(
        self,
        target: str,
        wait_ns: int,
        max_age_ns: int | None,
        cache_ns: int,
        examples: int,
        keep_results: bool,
        keep_failures: bool = False,
    ) -> None:
        self.target, self.wait_ns, self.max_age_ns, self.examples = target, wait_ns, max_age_ns, examples
        self.buf = BufferCore(cache_ns)
        self.report = Report()
        self.keep_results, self.keep_failures = keep_results, keep_failures
        self.pending: deque[_Pending] = deque()
        self.frames = self.report.frames  # every frame named in the recording, for BAG012
        self.shown_examples: Counter[str] = Counter()
        self.version_times: list[int] = []  # log times of the recording's descriptions

    def sensor(self, topic: str, log_ns: int, stamp: int, frame: str) -> None:
        self.frames.add(frame)
        # the description in effect when the message was logged; one logged before the first
        # description gets the first (robot_state_publisher's is latched: it was published
        # before the recording started)
        version = max(0, bisect_right(self.version_times, log_ns) - 1) if self.version_times else -1
        self.pending.append(_Pending(log_ns + self.wait_ns, topic, log_ns, stamp, frame, version))

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
        span = report.spans.get((m.topic, m.version))
        if span is None:
            span = report.spans[(m.topic, m.version)] = Span()
        span.add(outcome, m.log_ns, m.log_ns - m.stamp)
        if self.keep_results:
            report.results.append((m.topic, m.log_ns, outcome))
        if outcome == "ok":
            return
        if self.keep_failures:  # a row per failure: its frame name and tf2's words bounded
            row = Failure(
                m.topic,
                m.log_ns,
                m.stamp,
                _clip(m.frame, MAX_ROW_TEXT),
                outcome,
                _clip(detail, 4 * MAX_ROW_TEXT),
                m.version,
            )
            report.failures.append(row)
        if self.shown_examples[outcome] < self.examples:
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

    def digest(self) -> str:
        """The buffer's whole state as a digest: two replays whose buffers have one digest at
        a time give the same lookups from then on (the span memo is a cache, left out)."""
        h = hashlib.blake2b(digest_size=16)
        for child in sorted(self.buf.caches):
            c = self.buf.caches[child]
            h.update(repr((child, c.static, c.stamps, c.parents, c.poses)).encode("utf-8", "surrogatepass"))
        h.update(repr(sorted(self.buf.frames)).encode("utf-8", "surrogatepass"))
        return h.hexdigest()


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
    keep_failures: bool = False,
    window: Window | None = None,
) -> Report:
    """Replay the recording once, in log-time order (the order rosbags yields: MCAP chunks
    merged by time, sqlite3 ORDER BY timestamp). ``keep_results`` keeps every lookup's
    outcome in ``Report.results``, which grows with the recording (tests use it);
    ``keep_failures`` every failed lookup in ``Report.failures``; ``show_progress`` draws the
    messages read on a terminal (descgen/infra/progress.py). With ``window`` only that time
    slice is looked up, and the checks of the whole recording (BAG010, BAG012) are left to
    whoever joins the slices."""
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    reader = _open(path)
    replay = _Replay(target, wait_ns, max_age_ns, cache_ns, examples, keep_results, keep_failures)
    report = replay.report
    try:
        connections = list(reader.connections)
        chosen = _chosen(path, ts, connections, topics)
        report.descriptions = _descriptions(reader, ts, connections)
        replay.version_times = [d.log_ns for d in report.descriptions]
        tf_conns = [c for c in connections if c.topic in TF_TOPICS]
        read = tf_conns + chosen
        start = stop = None
        first, last = -(2**63), None  # sensor messages logged in [first, last) are looked up
        if window is not None:
            last = window.stop
            # the last message's deadline is stop - 1 + wait, and rosbags' stop is exclusive
            stop = None if window.stop is None else window.stop + wait_ns
        if window is not None and window.start is not None:
            first = window.start
            start = window.start - window.horizon
            static = [c for c in tf_conns if c.topic == "/tf_static"]
            # static transforms are timeless: all of them before the window (no connection at all
            # must read nothing: rosbags reads every connection when given none)
            for _, log_ns, raw in reader.messages(connections=static, stop=start) if static else ():
                replay.transforms(log_ns, ts.deserialize_cdr(raw, "tf2_msgs/msg/TFMessage"), True)
        total = None if window else sum(int(getattr(c, "msgcount", 0) or 0) for c in read) or None
        at_start = at_end = ""
        with counting(total, path.name, "msg", show_progress) as step:
            since = 0
            for conn, log_ns, raw in reader.messages(connections=read, start=start, stop=stop):
                if not at_start and log_ns >= first:
                    at_start = replay.digest()
                if not at_end and last is not None and log_ns >= last:
                    at_end = replay.digest()
                topic = conn.topic
                if topic in TF_TOPICS:
                    replay.transforms(log_ns, ts.deserialize_cdr(raw, conn.msgtype), topic == "/tf_static")
                elif first <= log_ns and (last is None or log_ns < last):
                    # rosbags decodes the whole message: reading the header from the bytes by hand was
                    # 2% of a 10-minute audit (benchmarks/bench_tf.py), not worth a second CDR reader
                    header = getattr(ts.deserialize_cdr(raw, conn.msgtype), "header")  # noqa: B009
                    replay.sensor(topic, log_ns, _stamp(header), header.frame_id)
                since += 1
                if since == _PROGRESS_EVERY:
                    step(since)
                    since = 0
            step(since)
        if window is not None:
            report.boundary = (at_start or replay.digest(), at_end or replay.digest())
        replay.flush(None)
    except InputError:
        raise
    except Exception as exc:  # a corrupt recording
        raise _unusable(
            BAG001, path, f"cannot read the recording: {_one_line(exc)}", "check the recording's files"
        ) from None
    finally:
        reader.close()
    if window is None:
        check_lookups(path, target, topics, report.lookups, report.frames)
    return report


def _chosen(path: Path, ts: Any, connections: list[Any], topics: tuple[str, ...]) -> list[Any]:
    """The sensor topics' connections: those named, or every one with a header."""
    chosen = (
        [c for c in connections if c.topic in topics]
        if topics
        else [
            c for c in connections if _has_header(ts, c.topic, c.msgtype) and c.msgtype != "sensor_msgs/msg/JointState"
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
    return chosen


MAX_DESCRIPTIONS = 1000  # a description is published at start and on each reload: a handful per recording


def _descriptions(reader: Any, ts: Any, connections: list[Any]) -> list[Description]:
    """The recording's /robot_description messages, oldest first: each URDF's hash and robot
    name. Read in a pass of their own (a few messages), so every time window of a recording
    knows which description was in effect, however long before the window it was published."""
    conns = [c for c in connections if c.topic == DESCRIPTION_TOPIC and c.msgtype == "std_msgs/msg/String"]
    out: list[Description] = []
    for _, log_ns, raw in reader.messages(connections=conns) if conns else ():
        text = str(ts.deserialize_cdr(raw, "std_msgs/msg/String").data)
        if out and out[-1].sha256 == hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest():
            continue  # republished unchanged
        out.append(
            Description(log_ns, hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest(), _robot_name(text))
        )
        if len(out) >= MAX_DESCRIPTIONS:
            break
    return out


MAX_URDF = 64 * 1024 * 1024


def _robot_name(urdf: str) -> str:
    """The ``<robot name>`` of a URDF from a recording (data: no entities, no network, bounded),
    or "" when it is not one."""
    from lxml import etree

    if len(urdf) > MAX_URDF:
        return ""
    try:
        parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False)
        root = etree.fromstring(urdf.encode("utf-8", "surrogatepass"), parser)
    except (etree.XMLSyntaxError, ValueError):
        return ""
    return str(root.get("name") or "") if root.tag == "robot" else ""


def _has_header(ts: Any, topic: str, msgtype: str) -> bool:
    return (
        topic not in TF_TOPICS
        and msgtype in ts.types
        and "header" in getattr(ts.types[msgtype], "__dataclass_fields__", {})
    )


def check_lookups(path: Path, target: str, topics: tuple[str, ...], lookups: int, frames: set[str]) -> None:
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


def time_range(path: Path) -> tuple[int, int]:
    """When the recording's first and last messages were logged (ns), from its metadata."""
    reader = _open(path)
    try:
        return int(reader.start_time), int(reader.end_time)
    except Exception as exc:  # a metadata.yaml without the times
        raise _unusable(
            BAG001, path, f"cannot read the recording: {_one_line(exc)}", "check the recording's files"
        ) from None
    finally:
        reader.close()
