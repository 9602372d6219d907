"""``descgen fleet-report``: findings tables rolled up by robot x description version x day, and
which robots and description versions regressed, since when.

The counts come from the summary rows (every lookup is in one), the failing lookups from the
lookup rows. A day is the UTC date of a summary row's first lookup. A robot-day is failing when
its share of failed lookups is above ``threshold`` (default 0: any failed lookup). A robot has
regressed when it is failing on its last day and on every day back to ``since``, and had a
passing day before that; one failing on every day of the table is "failing since it was first
seen"; a recording of no known robot is a robot of its own. A description version has
regressed when a robot passed on its last recording on the version before it and failed on its
first recording on the new one, even when the version
changed in the middle of a day; since the earliest such recording's day. A recording given in
two tables counts once.
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
    by_version: dict[str, dict[str, int]]  # version -> failed lookups of each class
    repeated: list[str]  # recordings in more than one table, counted once
    models: list[str]  # robots named by their URDF alone: every unit of that model is one robot here

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
            "repeated": self.repeated,
            "named_by_model": self.models,
        }


def _bad(path: Path, message: str) -> InputError:
    return InputError(
        [BAG020.finding(message, "give the Parquet files `descgen tf-audit --out` wrote", "file", Where(str(path)))]
    )


SUMMARY_COLUMNS = [
    *("kind", "recording", "robot", "description", "identity", "topic", "time", "lookups"),
    *CLASSES,
    "detail",
]
LOOKUP_COLUMNS = ["recording", "robot", "description", "topic", "frame", "outcome", "time"]


def _read(path: Path, columns: list[str], kinds: tuple[str, ...]) -> Any:
    """The columns of one findings table (rows of those ``kinds`` only), or BAG020."""
    from descgen.commands.fleet.table import FORMAT
    from descgen.write.findings_table import pyarrow_modules

    _, pq = pyarrow_modules()
    try:
        meta = pq.read_schema(path).metadata or {}
        if meta.get(b"format") != FORMAT.encode():
            raise _bad(path, f"is not a tf-audit findings table (its format is not {FORMAT})")
        tbl = pq.read_table(path, columns=columns, filters=[("kind", "in", list(kinds))])
        # nanosecond times as integers: Python's datetime holds microseconds
        return tbl.cast(_with_int_times(tbl.schema))
    except InputError:
        raise
    except Exception as exc:  # ArrowInvalid, OSError: not Parquet, truncated, unreadable
        raise _bad(path, f"cannot be read as Parquet: {' '.join(str(exc).split())[:300]}") from None


def _with_int_times(schema: Any) -> Any:
    import pyarrow as pa

    return pa.schema([(f.name, pa.int64() if pa.types.is_timestamp(f.type) else f.type) for f in schema])


@dataclass
class _Row:
    """One summary row, as the roll-up needs it."""

    robot: str
    version: str
    time: int | None
    lookups: int
    failed: dict[str, int]
    recording: str

    @property
    def rate(self) -> float:
        return sum(self.failed.values()) / self.lookups if self.lookups else 0.0


def roll_up(paths: list[Path], threshold: float = 0.0) -> RollUp:
    days: dict[tuple[str, str], Day] = {}
    rows: list[_Row] = []
    unidentified: set[str] = set()
    models: set[str] = set()
    # a recording is taken from the first table that audited it (a re-run's table beats the run
    # that could not audit it, in any order), and a row given twice counts once
    tables = [_read(path, SUMMARY_COLUMNS, ("summary", "unaudited")).to_pylist() for path in paths]
    seen: dict[str, int] = {}  # recording -> the table it is taken from (its place in the list)
    for k, table in enumerate(tables):
        for row in table:
            if row["kind"] == "summary":
                seen.setdefault(row["recording"] or "", k)
    repeated = {
        rec for k, table in enumerate(tables) for row in table if seen.get(rec := row["recording"] or "", k) != k
    }
    unaudited: dict[str, str] = {}
    taken: set[tuple[Any, ...]] = set()
    for k, table in enumerate(tables):
        for row in table:
            rec = row["recording"] or ""
            if row["kind"] == "unaudited":
                if rec not in seen:  # audited in no table
                    unaudited.setdefault(rec, row["detail"] or "")
                    if row["identity"] == "none":
                        unidentified.add(rec)
                continue
            key = (rec, row["topic"], row["description"], row["time"], row["lookups"])
            if seen[rec] != k or key in taken:
                continue
            taken.add(key)
            if row["identity"] == "none":
                unidentified.add(rec)
            if row["identity"] == "/robot_description":
                models.add(row["robot"] or UNKNOWN)
            # a recording of an unknown robot is a robot of its own: unknown units are not one unit
            robot = row["robot"] or f"{UNKNOWN} {rec}"
            r = _Row(robot, row["description"] or UNKNOWN, _time(row["time"]), int(row["lookups"] or 0),
                     {c: int(row[c] or 0) for c in CLASSES}, rec)  # fmt: skip
            rows.append(r)
            day = _day(r.time)
            d = days.get((robot, day))
            if d is None:
                d = days[(robot, day)] = Day(robot, day, [])
            if r.version not in d.versions:
                d.versions.append(r.version)
            d.lookups += r.lookups
            for c in CLASSES:
                d.failed[c] += r.failed[c]
            d.recordings.add(rec)
    rows.sort(key=lambda r: (r.robot, r.time if r.time is not None else 2**63))
    ordered = sorted(days.values(), key=lambda d: (d.robot, d.day))
    robots = _robots(ordered, rows, threshold)
    versions = _versions(rows, threshold)
    if robots:
        _failing_lookups(paths, robots, seen)
    by_version: dict[str, dict[str, int]] = {}
    for r in rows:
        bucket = by_version.setdefault(r.version, dict.fromkeys(CLASSES, 0))
        for c in CLASSES:
            bucket[c] += r.failed[c]
    return RollUp(
        ordered,
        len(seen) + len(unaudited),
        sorted(unaudited.items()),
        sorted(unidentified),
        robots,
        versions,
        threshold,
        by_version,
        sorted(repeated),
        sorted(models),
    )


NO_DAY = "(no time)"


def _time(value: Any) -> int | None:
    return None if value is None else int(value)


def _day(ns: int | None) -> str:
    """The UTC date of a time, or NO_DAY for none or one no calendar holds."""
    if ns is None:
        return NO_DAY
    try:
        return datetime.fromtimestamp(ns / 1e9, UTC).strftime("%Y-%m-%d")
    except (OverflowError, OSError, ValueError):
        return NO_DAY


def _robots(days: list[Day], rows: list[_Row], threshold: float) -> list[Regression]:
    out = []
    by_robot: dict[str, list[Day]] = defaultdict(list)
    for d in days:
        by_robot[d.robot].append(d)
    rows_of: dict[str, list[_Row]] = defaultdict(list)
    for r in rows:
        rows_of[r.robot].append(r)
    for robot, seq in by_robot.items():
        if seq[-1].rate <= threshold:
            continue
        k = len(seq) - 1
        while k > 0 and seq[k - 1].rate > threshold:
            k -= 1
        healthy = seq[k - 1] if k > 0 else None
        since = seq[k].day
        later = [r for r in rows_of[robot] if _day(r.time) >= since]
        failing = [r.version for r in later if r.rate > threshold] or [r.version for r in later]
        out.append(
            Regression(
                robot,
                since,
                healthy.day if healthy else None,
                list(dict.fromkeys(failing)),
                list(healthy.versions) if healthy else [],
            )
        )
    return out


def _versions(rows: list[_Row], threshold: float) -> list[Regression]:
    """A version whose robot passed on its last recording on the version before it and failed on
    its first recording on the new one: each robot's summary rows in time order, consecutive rows of one version taken
    together (a version changed in the middle of a day is compared too). A robot that passed on
    the new version first and failed later has regressed, but not with the version."""
    found: dict[str, Regression] = {}
    runs: list[tuple[str, str, list[_Row]]] = []  # (robot, version, rows)
    for r in rows:
        if runs and runs[-1][0] == r.robot and runs[-1][1] == r.version:
            runs[-1][2].append(r)
        else:
            runs.append((r.robot, r.version, [r]))
    for (robot_a, old, before), (robot_b, new, after) in itertools.pairwise(runs):
        if robot_a != robot_b or UNKNOWN in (old, new):
            continue
        # the last recording on the old version and the first on the new: the change between them
        last = [r for r in before if r.recording == before[-1].recording]
        first = [r for r in after if r.recording == after[0].recording]
        if _rate(last) <= threshold < _rate(first):
            since, until = _day(after[0].time), _day(before[-1].time)
            reg = found.get(new)
            if reg is None or since < reg.since:  # the earliest transition names the dates
                keep = (reg.versions, reg.before) if reg else ([], [])
                found[new] = reg = Regression(new, since, until, *keep)
            if robot_b not in reg.versions:
                reg.versions.append(robot_b)
            if old not in reg.before:
                reg.before.append(old)
    return sorted(found.values(), key=lambda r: (r.since, r.subject))


def _rate(rows: list[_Row]) -> float:
    n = sum(r.lookups for r in rows)
    return sum(sum(r.failed.values()) for r in rows) / n if n else 0.0


def _failing_lookups(paths: list[Path], robots: list[Regression], seen: dict[str, int]) -> None:
    """For each regressed robot, the lookups that fail since the day it started: topic, frame,
    class, how many and the first. One group-by per table, by Arrow (a fleet's tables hold
    millions of lookup rows), by robot (or recording, for a robot of no name) and day."""
    import pyarrow.compute as pc

    since = {r.subject: r.since for r in robots}
    counts: dict[tuple[str, str, str, str], list[int]] = {}
    for k, path in enumerate(paths):
        tbl = _read(path, LOOKUP_COLUMNS, ("lookup",))
        tbl = tbl.filter(pc.is_in(tbl["recording"], value_set=_strings([r for r, at in seen.items() if at == k])))
        tbl = tbl.append_column("day", pc.divide(tbl["time"], 86400 * 1_000_000_000))  # whole days (ints)
        keys = ["robot", "recording", "topic", "frame", "outcome", "day"]
        for g in tbl.group_by(keys).aggregate([("time", "count"), ("time", "min")]).to_pylist():
            subject = g["robot"] or f"{UNKNOWN} {g['recording']}"
            if subject not in since or g["day"] is None or _day(int(g["day"] * 86400) * 1_000_000_000) < since[subject]:
                continue
            key = (subject, g["topic"] or "", g["frame"] or "", g["outcome"] or "")
            c = counts.setdefault(key, [0, int(g["time_min"])])
            c[0] += int(g["time_count"])
            c[1] = min(c[1], int(g["time_min"]))
    for r in robots:
        rows = [(k[1], k[2], k[3], v[0], v[1]) for k, v in counts.items() if k[0] == r.subject]
        rows.sort(key=lambda x: (-x[3], x[4]))
        r.lookups = [(t, f, o, n, _moment(first)) for t, f, o, n, first in rows[:TOP_LOOKUPS]]


def _strings(values: list[str]) -> Any:
    import pyarrow as pa

    return pa.array(values, type=pa.string())


def _moment(ns: int) -> str:
    try:
        return datetime.fromtimestamp(ns / 1e9, UTC).strftime("%Y-%m-%d %H:%M:%S")
    except (OverflowError, OSError, ValueError):
        return NO_DAY
