"""A transform buffer with tf2's BufferCore semantics, in integer nanoseconds.

Encoded from geometry2 (docs/reference/tf2.md; tf2/src/buffer_core.cpp, cache.cpp,
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
from typing import NamedTuple

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


class Transform(NamedTuple):
    """Pose of the source frame in the target frame at ``stamp`` (a named tuple: one is
    built per lookup, and a frozen dataclass costs a microsecond more to build)."""

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


def _seconds(ns: int) -> str:
    return f"{ns / 1e9:.6f}"


# A pose as seven plain floats: translation x, y, z and rotation quaternion x, y, z, w.
# Plain floats, not numpy: a lookup composes a handful of poses, and a 4x4 array per compose
# (plus ``inv`` at the end) costs more than the arithmetic itself.
Pose = tuple[float, float, float, float, float, float, float]
IDENTITY: Pose = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
# Where a cache's value at a time is: (cache, older index, newer index, ratio); older ==
# newer means the sample itself, no interpolation.
Step = tuple["_Cache", int, int, float]


class _Cache:
    """One child frame's samples, oldest first, with the stamps in their own list so a
    lookup bisects it directly (no list rebuilt per call)."""

    __slots__ = ("parents", "poses", "reparented", "spans", "stamps", "static")

    def __init__(self, static: bool) -> None:
        self.static = static
        self.stamps: list[int] = []
        self.parents: list[str] = []
        self.poses: list[Pose] = []
        # whether the parent ever changed: if not, a walk needs no bisect to know the parent
        self.reparented = False
        # older stamp -> what slerp needs of the span that starts there (see _pose)
        self.spans: dict[int, tuple[int, float, float, float, float, float, float]] = {}

    def parent_at(self, time: int) -> str:
        """The parent the value at ``time`` hangs from, or tf2's TransformError."""
        if not self.reparented:
            s = self.stamps
            if self.static or time == 0 or (s[0] <= time <= s[-1] and len(s) > 1):
                return self.parents[-1]
        return self.parents[self.locate(time)[1]]

    def newest(self) -> int:
        return self.stamps[-1] if self.stamps else 0

    def locate(self, time: int) -> Step:
        """Where the value at ``time`` is, or the TransformError tf2's TimeCache gives."""
        s = self.stamps
        last = len(s) - 1
        if self.static or time == 0:
            return (self, last, last, 0.0)
        if last == 0:
            if s[0] == time:
                return (self, 0, 0, 0.0)
            raise TransformError(
                "nodata",
                f"Lookup would require extrapolation at time {_seconds(time)}, "
                f"but only time {_seconds(s[0])} is in the buffer",
            )
        if time > s[last]:
            raise TransformError(
                "future",
                f"Lookup would require extrapolation into the future.  Requested time "
                f"{_seconds(time)} but the latest data is at time {_seconds(s[last])}",
            )
        if time < s[0]:
            raise TransformError(
                "past",
                f"Lookup would require extrapolation into the past.  Requested time "
                f"{_seconds(time)} but the earliest data is at time {_seconds(s[0])}",
            )
        i = bisect_left(s, time)
        if s[i] == time:
            return (self, i, i, 0.0)
        if self.parents[i - 1] != self.parents[i]:
            return (self, i - 1, i - 1, 0.0)  # tf2 does not interpolate across a re-parenting
        return (self, i - 1, i, (time - s[i - 1]) / (s[i] - s[i - 1]))


def _pose(cache: _Cache, time: int) -> Pose:
    """A cache's (interpolated) pose at ``time``: linear translation, slerp rotation."""
    s = cache.stamps
    if cache.static or time == 0:
        return cache.poses[-1]
    if not s[0] < time <= s[-1]:  # at or outside the ends (or one sample): the general path
        _, i, j, ratio = cache.locate(time)
        if i == j:
            return cache.poses[i]
    else:  # locate's usual case, inline: this runs once per link of every lookup
        j = bisect_left(s, time)
        if s[j] == time:
            return cache.poses[j]
        i = j - 1
        if cache.parents[i] != cache.parents[j]:
            return cache.poses[i]  # tf2 does not interpolate across a re-parenting
        ratio = (time - s[i]) / (s[j] - s[i])
    a = cache.poses[i]
    b = cache.poses[j]
    # tf2::Quaternion::slerp: the shorter way round. What depends on the two samples alone
    # (the sign-corrected end, the angle, 1/sin) is kept per span, keyed by its older stamp
    # and checked against its newer one (a sample inserted between makes a new span).
    span = cache.spans.get(s[i])
    if span is None or span[0] != s[j]:
        bx, by, bz, bw = b[3], b[4], b[5], b[6]
        dot = a[3] * bx + a[4] * by + a[5] * bz + a[6] * bw
        if dot < 0:
            bx, by, bz, bw, dot = -bx, -by, -bz, -bw, -dot
        theta = math.acos(min(1.0, dot))
        span = (s[j], bx, by, bz, bw, theta, 1.0 / math.sin(theta) if theta != 0 else 0.0)
        if len(cache.spans) > len(s):  # never more spans than samples
            cache.spans.clear()
        cache.spans[s[i]] = span
    _, bx, by, bz, bw, theta, d = span
    k = 1.0 - ratio
    ax, ay, az, aw = a[3], a[4], a[5], a[6]
    if theta != 0:
        s0, s1 = math.sin(k * theta) * d, math.sin(ratio * theta) * d
        ax, ay, az, aw = ax * s0 + bx * s1, ay * s0 + by * s1, az * s0 + bz * s1, aw * s0 + bw * s1
    return (k * a[0] + ratio * b[0], k * a[1] + ratio * b[1], k * a[2] + ratio * b[2], ax, ay, az, aw)


def _chain(caches: list[_Cache], time: int) -> Pose:
    """The pose of the first cache's child in the last cache's parent at ``time``: each
    link's pose composed onto the accumulated one (parent_T_child applied on the left)."""
    if not caches:
        return IDENTITY
    tx, ty, tz, qx, qy, qz, qw = _pose(caches[0], time)
    for cache in caches[1:]:
        ax, ay, az, bx, by, bz, bw = _pose(cache, time)
        # t = R(b) t + a, with R(b) v = v + w c + u x c, c = 2 u x v
        cx, cy, cz = 2 * (by * tz - bz * ty), 2 * (bz * tx - bx * tz), 2 * (bx * ty - by * tx)
        tx, ty, tz = (
            tx + bw * cx + by * cz - bz * cy + ax,
            ty + bw * cy + bz * cx - bx * cz + ay,
            tz + bw * cz + bx * cy - by * cx + az,
        )
        # q = b * q
        qx, qy, qz, qw = (
            bw * qx + bx * qw + by * qz - bz * qy,
            bw * qy - bx * qz + by * qw + bz * qx,
            bw * qz + bx * qy - by * qx + bz * qw,
            bw * qw - bx * qx - by * qy - bz * qz,
        )
    return (tx, ty, tz, qx, qy, qz, qw)


def _between(target: Pose, source: Pose, time: int) -> Transform:
    """inverse(target) * source: the source's pose in the target frame, both given in one top frame."""
    ax, ay, az, bx, by, bz, bw = target
    sx, sy, sz, qx, qy, qz, qw = source
    bx, by, bz = -bx, -by, -bz  # the conjugate rotates the other way
    vx, vy, vz = sx - ax, sy - ay, sz - az
    cx, cy, cz = 2 * (by * vz - bz * vy), 2 * (bz * vx - bx * vz), 2 * (bx * vy - by * vx)
    translation = (
        vx + bw * cx + by * cz - bz * cy,
        vy + bw * cy + bz * cx - bx * cz,
        vz + bw * cz + bx * cy - by * cx,
    )
    rotation = (
        bw * qx + bx * qw + by * qz - bz * qy,
        bw * qy - bx * qz + by * qw + bz * qx,
        bw * qz + bx * qy - by * qx + bz * qw,
        bw * qw - bx * qx - by * qy - bz * qz,
    )
    return Transform(translation, rotation, time)


class BufferCore:
    def __init__(self, cache_ns: int = DEFAULT_CACHE_NS) -> None:
        self.cache_ns = cache_ns
        self.caches: dict[str, _Cache] = {}
        self.frames: set[str] = set()  # every frame named by an accepted transform (tf2 never forgets one)

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
        x, y, z = translation
        qx, qy, qz, qw = rotation
        if math.isnan(x + y + z + qx + qy + qz + qw):  # a NaN anywhere makes the sum NaN
            return "TF_NAN_INPUT"
        n2 = qx * qx + qy * qy + qz * qz + qw * qw
        if abs(n2 - 1) > 10 * 1e-6 * 2:  # tf2's QUATERNION_NORMALIZATION_TOLERANCE
            return "TF_DENORMALIZED_QUATERNION"
        self.frames.add(child)
        self.frames.add(parent)
        norm = math.sqrt(n2)
        pose = (x, y, z, qx / norm, qy / norm, qz / norm, qw / norm)
        cache = self.caches.get(child)
        if cache is None or cache.static != static:
            cache = self.caches[child] = _Cache(static)
        if static:
            cache.stamps, cache.parents, cache.poses = [stamp], [parent], [pose]
            return None
        stamps = cache.stamps
        if stamps and parent != cache.parents[-1]:
            cache.reparented = True
        if not stamps or stamp > stamps[-1]:  # the usual case: newer than everything held
            stamps.append(stamp)
            cache.parents.append(parent)
            cache.poses.append(pose)
        else:
            if stamps[-1] > stamp + self.cache_ns:
                return "TF_OLD_DATA"
            i = bisect_left(stamps, stamp)
            if stamps[i] == stamp:
                return None  # a sample at that time is already there
            stamps.insert(i, stamp)
            cache.parents.insert(i, parent)
            cache.poses.insert(i, pose)
        if stamps[0] + self.cache_ns < stamps[-1]:  # prune what fell out of the window
            k = bisect_left(stamps, stamps[-1] - self.cache_ns)
            del stamps[:k], cache.parents[:k], cache.poses[:k]
            cache.spans.clear()  # kept spans are a memo: bounded by what was looked up since
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
        chain_s, chain_t = self._chain_of(source), self._chain_of(target)
        up = set(chain_s)
        common = next((f for f in chain_t if f in up), None)
        for chain in (chain_s, chain_t):
            for frame in chain:
                if frame == common:
                    break
                cache = self.caches.get(frame)
                if cache is None or cache.static or not cache.stamps:
                    continue
                stamps = cache.stamps
                i = bisect_left(stamps, time)
                out.append((frame, min(abs(stamps[k] - time) for k in (i - 1, i) if 0 <= k < len(stamps))))
        return out

    def _chain_of(self, frame: str) -> list[str]:
        out = [frame]
        caches = self.caches
        while frame in caches and caches[frame].stamps and len(out) < MAX_DEPTH:
            frame = caches[frame].parents[-1]
            out.append(frame)
        return out

    def exists(self, frame: str) -> bool:
        return frame in self.frames

    def _latest(self, frame: str) -> tuple[int, str] | None:
        """(newest stamp, parent) of a frame's cache; static caches report stamp 0."""
        cache = self.caches.get(frame)
        if cache is None or not cache.stamps:
            return None
        return (0 if cache.static else cache.stamps[-1], cache.parents[-1])

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
        tf2 BufferCore::lookupTransform and walkToTopParent, step for step.

        The walks first only find each link's parent at that time (a range check, a
        bisect only where a frame was re-parented), which decides success or tf2's error;
        then only the links below the common ancestor are interpolated and composed (the
        shared links above it cancel out)."""
        if target == source:
            cache = self.caches.get(target)
            stamp = cache.newest() if time == 0 and cache is not None and not cache.static else time
            return Transform((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), stamp)
        if not target or target[0] == "/":
            self._check(target, "lookupTransform argument target_frame")
        if not source or source[0] == "/":
            self._check(source, "lookupTransform argument source_frame")
        if target not in self.frames:
            raise TransformError(
                "lookup", f'"{target}" passed to lookupTransform argument target_frame does not exist. '
            )
        if source not in self.frames:
            raise TransformError(
                "lookup", f'"{source}" passed to lookupTransform argument source_frame does not exist. '
            )
        if time == 0:
            time = self.latest_common_time(target, source)
        caches = self.caches
        # up from the source to its root
        up: list[_Cache] = []
        up_frames: list[str] = []
        frame, top, pending = source, source, None
        for _ in range(MAX_DEPTH):
            cache = caches.get(frame)
            if cache is None:
                top = frame
                break
            st = cache.stamps
            if not cache.reparented and (cache.static or (st[0] <= time <= st[-1] and len(st) > 1)):
                parent = cache.parents[-1]  # parent_at, inline: this is the hot loop
            else:
                try:
                    parent = cache.parent_at(time)
                except TransformError as exc:
                    top, pending = frame, exc
                    break
            if frame == target:  # the target is an ancestor of the source
                return _between(IDENTITY, _chain(up, time), time)
            up.append(cache)
            up_frames.append(frame)
            top = frame
            frame = parent
        else:
            raise TransformError("lookup", "The tf tree is invalid because it contains a loop.")
        # up from the target to the same top
        down: list[_Cache] = []
        down_frames: list[str] = []
        frame = target
        for _ in range(MAX_DEPTH):
            if frame == top:
                break
            cache = caches.get(frame)
            if cache is None:
                break
            st = cache.stamps
            if not cache.reparented and (cache.static or (st[0] <= time <= st[-1] and len(st) > 1)):
                parent = cache.parents[-1]
            else:
                try:
                    parent = cache.parent_at(time)
                except TransformError as exc:
                    raise TransformError(exc.kind, f"{exc}{_suffix(target, source)}") from None
            if frame == source:  # the source is an ancestor of the target
                return _between(_chain(down, time), IDENTITY, time)
            down.append(cache)
            down_frames.append(frame)
            frame = parent
        if frame != top:
            if pending is not None:
                raise TransformError(pending.kind, f"{pending}{_suffix(target, source)}")
            raise TransformError("connectivity", _disconnected(target, source))
        # both walks end with the links above the common ancestor: they cancel, skip them
        while up_frames and down_frames and up_frames[-1] == down_frames[-1]:
            up_frames.pop(), down_frames.pop(), up.pop(), down.pop()
        return _between(_chain(down, time), _chain(up, time), time)


def _suffix(target: str, source: str) -> str:
    return f", when looking up transform from frame [{source}] to frame [{target}]"


def _disconnected(target: str, source: str) -> str:
    return (
        f"Could not find a connection between '{target}' and '{source}' because they are not part of the same "
        "tree.Tf has two or more unconnected trees."
    )
