"""A transform buffer with tf2's BufferCore semantics, in integer nanoseconds.

Encoded from geometry2 (reference/tf2.md; tf2/src/buffer_core.cpp, cache.cpp,
static_cache.cpp) and checked against Debian's python3-tf2 (the same C++ core) by
tests/test_tf_buffer.py:

- one cache per child frame; a dynamic cache keeps ``cache_time`` (10 s) behind its newest
  sample: inserting older data is refused (TF_OLD_DATA) and older samples are pruned;
- a static transform is one value valid at every time;
- a lookup at time t interpolates between the two samples around t (linear translation,
  slerp rotation); it never extrapolates: before the oldest sample is "past", after the
  newest "future", a lone sample at another time "nodata";
- time 0 means the latest time at which every non-static link of the chain has data;
- the walk goes from the source frame up to its root and from the target frame up, and
  fails with "lookup" for an unknown frame and "connectivity" for frames in different trees
  (or "past"/"future"/"nodata" when a cache on the way had no data at that time).
"""

from __future__ import annotations

import math
from bisect import bisect_left
from dataclasses import dataclass, field

import numpy as np

Vec = tuple[float, float, float]
Quat = tuple[float, float, float, float]  # x, y, z, w

DEFAULT_CACHE_NS = 10_000_000_000
MAX_DEPTH = 1000


class TransformError(Exception):
    """A failed lookup; ``kind`` is lookup | connectivity | past | future | nodata | invalid."""

    def __init__(self, kind: str, message: str) -> None:
        super().__init__(message)
        self.kind = kind


@dataclass(frozen=True)
class Sample:
    stamp: int
    parent: str
    translation: Vec
    rotation: Quat


@dataclass(frozen=True)
class Transform:
    """Pose of the source frame in the target frame at ``stamp``."""

    translation: Vec
    rotation: Quat
    stamp: int

    def matrix(self) -> np.ndarray:
        m = np.eye(4)
        m[:3, :3] = quat_matrix(self.rotation)
        m[:3, 3] = self.translation
        return m


def quat_matrix(q: Quat) -> np.ndarray:
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def quat_from_matrix(m: np.ndarray) -> Quat:
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s)
    if m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        return (0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s)
    if m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        return ((m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s)
    s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
    return ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s, (m[1, 0] - m[0, 1]) / s)


def slerp(a: Quat, b: Quat, t: float) -> Quat:
    """tf2::Quaternion::slerp: the shorter way round."""
    dot = sum(x * y for x, y in zip(a, b, strict=True))
    if dot < 0:
        b, dot = (-b[0], -b[1], -b[2], -b[3]), -dot
    dot = min(1.0, dot)
    theta = math.acos(dot)
    if theta == 0:
        return a
    d = 1.0 / math.sin(theta)
    s0, s1 = math.sin((1 - t) * theta), math.sin(t * theta)
    return (
        (a[0] * s0 + b[0] * s1) * d,
        (a[1] * s0 + b[1] * s1) * d,
        (a[2] * s0 + b[2] * s1) * d,
        (a[3] * s0 + b[3] * s1) * d,
    )


def _seconds(ns: int) -> str:
    return f"{ns / 1e9:.6f}"


@dataclass
class _Cache:
    static: bool
    samples: list[Sample] = field(default_factory=list)  # oldest first

    def newest(self) -> int:
        return self.samples[-1].stamp if self.samples else 0

    def get(self, time: int) -> Sample:
        s = self.samples
        if self.static:
            only = s[-1]
            return Sample(time, only.parent, only.translation, only.rotation)
        if time == 0:
            return s[-1]
        if len(s) == 1:
            if s[0].stamp == time:
                return s[0]
            raise TransformError(
                "nodata",
                f"Lookup would require extrapolation at time {_seconds(time)}, "
                f"but only time {_seconds(s[0].stamp)} is in the buffer",
            )
        if time > s[-1].stamp:
            raise TransformError(
                "future",
                f"Lookup would require extrapolation into the future.  Requested time "
                f"{_seconds(time)} but the latest data is at time {_seconds(s[-1].stamp)}",
            )
        if time < s[0].stamp:
            raise TransformError(
                "past",
                f"Lookup would require extrapolation into the past.  Requested time "
                f"{_seconds(time)} but the earliest data is at time {_seconds(s[0].stamp)}",
            )
        i = bisect_left([x.stamp for x in s], time)
        if s[i].stamp == time:
            return s[i]
        one, two = s[i - 1], s[i]
        if one.parent != two.parent:
            return one
        ratio = (time - one.stamp) / (two.stamp - one.stamp)
        k = 1 - ratio
        translation = tuple(k * a + ratio * b for a, b in zip(one.translation, two.translation, strict=True))
        return Sample(time, one.parent, translation, slerp(one.rotation, two.rotation, ratio))  # type: ignore[arg-type]


class BufferCore:
    def __init__(self, cache_ns: int = DEFAULT_CACHE_NS) -> None:
        self.cache_ns = cache_ns
        self.caches: dict[str, _Cache] = {}

    # -- inserting ---------------------------------------------------------------------

    def set_transform(
        self, parent: str, child: str, stamp: int, translation: Vec, rotation: Quat, static: bool = False
    ) -> str | None:
        """Insert one transform; returns why it was refused, or None (tf2 logs and drops)."""
        parent, child = parent.lstrip("/"), child.lstrip("/")
        if not child:
            return "TF_NO_CHILD_FRAME_ID"
        if not parent:
            return "TF_NO_FRAME_ID"
        if parent == child:
            return "TF_SELF_TRANSFORM"
        values = (*translation, *rotation)
        if any(math.isnan(v) for v in values):
            return "TF_NAN_INPUT"
        if abs(sum(q * q for q in rotation) - 1) > 10 * 1e-6 * 2:  # tf2's QUATERNION_NORMALIZATION_TOLERANCE
            return "TF_DENORMALIZED_QUATERNION"
        norm = math.sqrt(sum(q * q for q in rotation))
        sample = Sample(
            stamp, parent, translation, (rotation[0] / norm, rotation[1] / norm, rotation[2] / norm, rotation[3] / norm)
        )
        cache = self.caches.get(child)
        if cache is None or cache.static != static:
            cache = self.caches[child] = _Cache(static)
        if static:
            cache.samples = [sample]
            return None
        s = cache.samples
        if s and s[-1].stamp > stamp + self.cache_ns:
            return "TF_OLD_DATA"
        stamps = [x.stamp for x in s]
        i = bisect_left(stamps, stamp)
        if i < len(s) and s[i].stamp == stamp:
            return None  # a sample at that time is already there
        s.insert(i, sample)
        newest = s[-1].stamp
        while s and s[0].stamp + self.cache_ns < newest:
            s.pop(0)
        return None

    # -- looking up ----------------------------------------------------------------------

    def _check(self, frame: str, arg: str) -> None:
        if not frame:
            raise TransformError("invalid", f"Invalid argument passed to {arg} in tf2 frame_ids cannot be empty")
        if frame.startswith("/"):
            raise TransformError(
                "invalid",
                f"Invalid argument \"{frame}\" passed to {arg} in tf2 frame_ids cannot start with a '/' like: ",
            )

    def nearest_gaps(self, target: str, source: str, time: int) -> list[tuple[str, int]]:
        """For each dynamic link between the two frames: how far (ns) its nearest sample is
        from ``time``. A lookup interpolating across a long gap succeeds in tf2; this says so."""
        out = []
        up = {f: i for i, f in enumerate(self._chain_of(source))}
        chain_t = self._chain_of(target)
        common = next((f for f in chain_t if f in up), None)
        for chain in (self._chain_of(source), chain_t):
            for frame in chain:
                if frame == common:
                    break
                cache = self.caches.get(frame)
                if cache is None or cache.static or not cache.samples:
                    continue
                stamps = [x.stamp for x in cache.samples]
                i = bisect_left(stamps, time)
                near = [abs(stamps[k] - time) for k in (i - 1, i) if 0 <= k < len(stamps)]
                out.append((frame, min(near)))
        return out

    def _chain_of(self, frame: str) -> list[str]:
        out = [frame]
        while frame in self.caches and self.caches[frame].samples and len(out) < MAX_DEPTH:
            frame = self.caches[frame].samples[-1].parent
            out.append(frame)
        return out

    def exists(self, frame: str) -> bool:
        return frame in self.caches or any(c.samples and c.samples[-1].parent == frame for c in self.caches.values())

    def _latest(self, frame: str) -> tuple[int, str] | None:
        """(newest stamp, parent) of a frame's cache; static caches report stamp 0."""
        cache = self.caches.get(frame)
        if cache is None or not cache.samples:
            return None
        return (0 if cache.static else cache.newest(), cache.samples[-1].parent)

    def latest_common_time(self, target: str, source: str) -> int:
        """tf2 BufferCore::getLatestCommonTime, step for step."""
        if target == source:
            cache = self.caches.get(source)
            return cache.newest() if cache and not cache.static else 0
        big = 1 << 62
        lct: list[tuple[int, str]] = []
        common = big
        frame = source
        for _ in range(MAX_DEPTH):
            latest = self._latest(frame)
            if latest is None:
                break
            if latest[0]:
                common = min(common, latest[0])
            lct.append(latest)
            frame = latest[1]
            if frame == target:
                return 0 if common == big else common
        frame, common, common_parent = target, big, None
        for _ in range(MAX_DEPTH):
            latest = self._latest(frame)
            if latest is None:
                break
            if latest[0]:
                common = min(common, latest[0])
            if any(parent == latest[1] for _, parent in lct):
                common_parent = latest[1]
                break
            frame = latest[1]
            if frame == source:
                return 0 if common == big else common
        if common_parent is None:
            raise TransformError("connectivity", _disconnected(target, source))
        for stamp, parent in lct:
            if stamp:
                common = min(common, stamp)
            if parent == common_parent:
                break
        return 0 if common == big else common

    def lookup(self, target: str, source: str, time: int) -> Transform:
        """Pose of ``source`` in ``target`` at ``time`` (ns; 0 = latest common time):
        tf2 BufferCore::lookupTransform and walkToTopParent, step for step."""
        if target == source:
            cache = self.caches.get(target)
            stamp = cache.newest() if time == 0 and cache is not None and not cache.static else time
            return Transform((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), stamp)
        self._check(target, "lookupTransform argument target_frame")
        self._check(source, "lookupTransform argument source_frame")
        for frame, arg in ((target, "target_frame"), (source, "source_frame")):
            if not self.exists(frame):
                raise TransformError("lookup", f'"{frame}" passed to lookupTransform argument {arg} does not exist. ')
        if time == 0:
            time = self.latest_common_time(target, source)
        suffix = f", when looking up transform from frame [{source}] to frame [{target}]"
        # up from the source to its root, accumulating source -> root
        acc_source = np.eye(4)
        frame, top, pending = source, source, None
        for _ in range(MAX_DEPTH):
            cache = self.caches.get(frame)
            if cache is None:
                top = frame
                break
            try:
                s = cache.get(time)
            except TransformError as exc:
                top, pending = frame, exc
                break
            if frame == target:
                return _result(acc_source, time)
            acc_source = _matrix(s) @ acc_source
            top = frame
            frame = s.parent
        else:
            raise TransformError("lookup", "The tf tree is invalid because it contains a loop.")
        # up from the target to the same top, accumulating target -> top
        acc_target = np.eye(4)
        frame = target
        for _ in range(MAX_DEPTH):
            if frame == top:
                break
            cache = self.caches.get(frame)
            if cache is None:
                break
            try:
                s = cache.get(time)
            except TransformError as exc:
                raise TransformError(exc.kind, f"{exc}{suffix}") from None
            if frame == source:
                return _result(np.linalg.inv(acc_target), time)
            acc_target = _matrix(s) @ acc_target
            frame = s.parent
        if frame != top:
            if pending is not None:
                raise TransformError(pending.kind, f"{pending}{suffix}")
            raise TransformError("connectivity", _disconnected(target, source))
        return _result(np.linalg.inv(acc_target) @ acc_source, time)


def _disconnected(target: str, source: str) -> str:
    return (
        f"Could not find a connection between '{target}' and '{source}' because they are not part of the same "
        "tree.Tf has two or more unconnected trees."
    )


def _matrix(s: Sample) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = quat_matrix(s.rotation)
    m[:3, 3] = s.translation
    return m


def _result(m: np.ndarray, time: int) -> Transform:
    t = (float(m[0, 3]), float(m[1, 3]), float(m[2, 3]))
    return Transform(t, quat_from_matrix(m[:3, :3]), time)
