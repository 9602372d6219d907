"""``descgen fleet-report``: findings tables rolled up by robot x description version x day, and
which robots and description versions regressed, since when.

The counts come from the summary rows (every lookup is in one), the failing lookups from the
lookup rows. A day is the UTC date of a summary row's first lookup. A robot-day is failing when
its share of failed lookups is above ``threshold`` (default 0: any failed lookup). A robot has
regressed when it is failing on its last day and on every day back to ``since``, and had a
passing day before that; one failing on every day of the table is "failing since it was first
seen". A description version has regressed when a robot ran the version before it on a
passing day and fails on it; it is failing since its first failing robot-day.
"""

from __future__ import annotations

import itertools
from collections import defaultdict
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from descgen.codes.recording import BAG020
from descgen.core.findings import InputError, Where

UNKNOWN = "(unknown)"
CLASSES = ("disconnected", "stale", "future")
TOP_LOOKUPS = 10


@dataclass
class Day:
    """One robot's lookups on one day."""

    robot: str
    day: str
    versions: list[str]
    lookups: int = 0
    failed: dict[str, int] = field(default_factory=lambda: dict.fromkeys(CLASSES, 0))
    recordings: set[str] = field(default_factory=set)

    @property
    def failures(self) -> int:
        return sum(self.failed.values())

    @property
    def rate(self) -> float:
        return self.failures / self.lookups if self.lookups else 0.0


@dataclass
class Regression:
    subject: str  # robot or description version
    since: str  # day
    healthy_until: str | None  # the last passing day before it, None: never passing
    versions: list[str]  # the description versions on the day it started (robots), or robots (versions)
    before: list[str]  # the versions on the last passing day (robots), or the versions before (versions)
    lookups: list[tuple[str, str, str, int, str]] = field(default_factory=list)  # topic, frame, class, count, first


@dataclass
class RollUp:
    days: list[Day]
    recordings: int
    unaudited: list[tuple[str, str]]  # recording, why
    unidentified: list[str]  # recordings with neither /robot_description nor --robot
    robots: list[Regression]
    versions: list[Regression]
    threshold: float

    @property
    def lookups(self) -> int:
        return sum(d.lookups for d in self.days)

    @property
    def failures(self) -> int:
        return sum(d.failures for d in self.days)

    def as_dict(self) -> dict[str, Any]:
        def reg(r: Regression) -> dict[str, Any]:
            return {
                "subject": r.subject,
                "since": r.since,
                "healthy_until": r.healthy_until,
                "versions": r.versions,
                "before": r.before,
                "lookups": [
                    {"topic": t, "frame": f, "outcome": o, "count": n, "first": first}
                    for t, f, o, n, first in r.lookups
                ],
            }

        return {
            "recordings": self.recordings,
            "lookups": self.lookups,
            "failed": self.failures,
            "threshold": self.threshold,
            "days": [
                {
                    "robot": d.robot,
                    "day": d.day,
                    "descriptions": d.versions,
                    "lookups": d.lookups,
                    **d.failed,
                    "recordings": len(d.recordings),
                }
                for d in self.days
            ],
            "regressed_robots": [reg(r) for r in self.robots],
            "regressed_descriptions": [reg(r) for r in self.versions],
            "unaudited": [{"recording": r, "why": w} for r, w in self.unaudited],
            "unidentified": self.unidentified,
        }


def _day(ns: int) -> str:
    return datetime.fromtimestamp(ns / 1e9, UTC).strftime("%Y-%m-%d")


def _bad(path: Path, message: str) -> InputError:
    return InputError(
        [BAG020.finding(message, "give the Parquet files `descgen tf-audit --out` wrote", "file", Where(str(path)))]
    )


SUMMARY_COLUMNS = ["kind", "recording", "robot", "description", "identity", "time", "lookups", *CLASSES, "detail"]
LOOKUP_COLUMNS = ["robot", "description", "topic", "frame", "outcome", "time"]


def _read(path: Path, columns: list[str], kind: str | None) -> Any:
    """The columns of one findings table (rows of ``kind`` only), or BAG020."""
    from descgen.commands.fleet.table import FORMAT
    from descgen.write.findings_table import pyarrow_modules

    _, pq = pyarrow_modules()
    try:
        meta = pq.read_schema(path).metadata or {}
        if meta.get(b"format") != FORMAT.encode():
            raise _bad(path, f"is not a tf-audit findings table (its format is not {FORMAT})")
        filters = [("kind", "=", kind)] if kind else None
        tbl = pq.read_table(path, columns=columns, filters=filters)
        # nanosecond times as integers: Python's datetime holds microseconds
        return tbl.cast(_with_int_times(tbl.schema))
    except InputError:
        raise
    except Exception as exc:  # ArrowInvalid, OSError: not Parquet, truncated, unreadable
        raise _bad(path, f"cannot be read as Parquet: {' '.join(str(exc).split())[:300]}") from None


def _with_int_times(schema: Any) -> Any:
    import pyarrow as pa

    return pa.schema([(f.name, pa.int64() if pa.types.is_timestamp(f.type) else f.type) for f in schema])


def roll_up(paths: list[Path], threshold: float = 0.0) -> RollUp:
    days: dict[tuple[str, str], Day] = {}
    recordings: set[str] = set()
    unaudited: list[tuple[str, str]] = []
    unidentified: set[str] = set()
    for path in paths:
        for row in _read(path, SUMMARY_COLUMNS, None).to_pylist():
            recordings.add(row["recording"])
            if row["identity"] == "none":
                unidentified.add(row["recording"])
            if row["kind"] == "unaudited":
                unaudited.append((row["recording"], row["detail"] or ""))
                continue
            if row["kind"] != "summary":
                continue
            robot = row["robot"] or UNKNOWN
            day = _day(_ns(row["time"]))
            d = days.get((robot, day))
            if d is None:
                d = days[(robot, day)] = Day(robot, day, [])
            version = row["description"] or UNKNOWN
            if version not in d.versions:
                d.versions.append(version)
            d.lookups += int(row["lookups"] or 0)
            for c in CLASSES:
                d.failed[c] += int(row[c] or 0)
            d.recordings.add(row["recording"])
    ordered = sorted(days.values(), key=lambda d: (d.robot, d.day))
    robots = _robots(ordered, threshold)
    versions = _versions(ordered, threshold)
    if robots:
        _failing_lookups(paths, robots)
    return RollUp(ordered, len(recordings), sorted(unaudited), sorted(unidentified), robots, versions, threshold)


def _ns(value: Any) -> int:
    """A time column's value (ns since the epoch, as ``_read`` casts it)."""
    return int(value)


def _robots(days: list[Day], threshold: float) -> list[Regression]:
    out = []
    by_robot: dict[str, list[Day]] = defaultdict(list)
    for d in days:
        by_robot[d.robot].append(d)
    for robot, seq in by_robot.items():
        if seq[-1].rate <= threshold:
            continue
        k = len(seq) - 1
        while k > 0 and seq[k - 1].rate > threshold:
            k -= 1
        healthy = seq[k - 1] if k > 0 else None
        out.append(
            Regression(
                robot,
                seq[k].day,
                healthy.day if healthy else None,
                list(seq[k].versions),
                list(healthy.versions) if healthy else [],
            )
        )
    return out


def _versions(days: list[Day], threshold: float) -> list[Regression]:
    """A version whose robot passed on the version before it and fails on it."""
    found: dict[str, Regression] = {}
    by_robot: dict[str, list[Day]] = defaultdict(list)
    for d in days:
        by_robot[d.robot].append(d)
    for robot, seq in by_robot.items():
        for before, after in itertools.pairwise(seq):
            if len(before.versions) != 1 or len(after.versions) != 1 or before.versions == after.versions:
                continue  # a version change between two days, each on one version
            old, new = before.versions[0], after.versions[0]
            if before.rate <= threshold < after.rate and new != UNKNOWN:
                r = found.setdefault(new, Regression(new, after.day, before.day, [], []))
                r.since = min(r.since, after.day)
                if robot not in r.versions:
                    r.versions.append(robot)
                if old not in r.before:
                    r.before.append(old)
    return sorted(found.values(), key=lambda r: (r.since, r.subject))


def _failing_lookups(paths: list[Path], robots: list[Regression]) -> None:
    """For each regressed robot, the lookups that fail since the day it started: topic, frame,
    class, how many and the first. Counted by Arrow over the lookup rows (a fleet's tables hold
    millions), never as Python rows."""
    import pyarrow.compute as pc

    counts: dict[tuple[str, str, str, str], list[int]] = {}
    for path in paths:
        tbl = _read(path, LOOKUP_COLUMNS, "lookup")
        for r in robots:
            start = int(datetime.strptime(r.since, "%Y-%m-%d").replace(tzinfo=UTC).timestamp()) * 1_000_000_000
            mine = pc.is_null(tbl["robot"]) if r.subject == UNKNOWN else pc.equal(tbl["robot"], r.subject)
            picked = tbl.filter(pc.and_(mine, pc.greater_equal(tbl["time"], start)))
            if not picked.num_rows:
                continue
            grouped = picked.group_by(["topic", "frame", "outcome"]).aggregate([("time", "count"), ("time", "min")])
            for row in grouped.to_pylist():
                key = (r.subject, row["topic"] or "", row["frame"] or "", row["outcome"] or "")
                c = counts.setdefault(key, [0, _ns(row["time_min"])])
                c[0] += int(row["time_count"])
                c[1] = min(c[1], _ns(row["time_min"]))
    for r in robots:
        rows = [(k[1], k[2], k[3], v[0], v[1]) for k, v in counts.items() if k[0] == r.subject]
        rows.sort(key=lambda x: (-x[3], x[4]))
        r.lookups = [
            (t, f, o, n, datetime.fromtimestamp(first / 1e9, UTC).strftime("%Y-%m-%d %H:%M:%S"))
            for t, f, o, n, first in rows[:TOP_LOOKUPS]
        ]
