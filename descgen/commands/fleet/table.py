"""The findings table: what ``tf-audit --out`` writes and ``fleet-report`` reads, one schema.

Three kinds of row, one table, so a fleet is one query away (DuckDB, pandas, Polars):

- ``lookup``: one failed lookup: its topic, frame, failure class (``outcome``), log time,
  stamp, latency (log time - stamp) and tf2's words (``detail``);
- ``summary``: one per recording, topic and description version: how many lookups, how many
  of each class, from the first to the last, mean and largest latency;
- ``unaudited``: a recording that gave no result (unreadable, crashed): why, in ``detail``.

Every row names the robot, the description version (and the URDF's SHA-256 when the recording
has one), where those came from (``identity``), the recording and the target frame. Times are
UTC nanosecond timestamps of the recording's clock. The lookups of one summary row add up:
``lookups = ok + disconnected + stale + future``, and its failures are its lookup rows.
"""

from __future__ import annotations

from typing import Any

from descgen.commands.fleet.identity import Identity, Mapping, resolve
from descgen.commands.fleet.run import Outcome
from descgen.commands.tf.bagaudit import OUTCOMES

FORMAT = "descgen-findings/1"  # in the file's metadata: fleet-report refuses other tables

COLUMNS: tuple[tuple[str, str], ...] = (
    ("kind", "string"),
    ("recording", "string"),
    ("robot", "string"),
    ("description", "string"),
    ("description_sha256", "string"),
    ("identity", "string"),
    ("target", "string"),
    ("topic", "string"),
    ("frame", "string"),
    ("outcome", "string"),
    ("time", "timestamp"),
    ("time_end", "timestamp"),
    ("stamp", "timestamp"),
    ("latency_ms", "float64"),
    ("latency_max_ms", "float64"),
    ("lookups", "int64"),
    ("ok", "int64"),
    ("disconnected", "int64"),
    ("stale", "int64"),
    ("future", "int64"),
    ("detail", "string"),
)


def schema(pa: Any) -> Any:
    types = {
        "string": pa.string(),
        "timestamp": pa.timestamp("ns", tz="UTC"),
        "float64": pa.float64(),
        "int64": pa.int64(),
    }
    return pa.schema([(name, types[kind]) for name, kind in COLUMNS], metadata={"format": FORMAT})


def rows(outcome: Outcome, target: str, mappings: tuple[Mapping, ...]) -> dict[str, list[Any]]:
    """The recording's rows as columns (lists), in the schema's order of columns."""
    cols: dict[str, list[Any]] = {name: [] for name, _ in COLUMNS}

    def add(ident: Identity, **values: Any) -> None:
        values |= {
            "recording": outcome.path,
            "robot": ident.robot,
            "description": ident.version,
            "description_sha256": ident.sha256,
            "identity": ident.source,
            "target": target,
        }
        for name, kind in COLUMNS:
            v = values.get(name)
            if isinstance(v, str):
                v = _text(v)
            elif kind == "timestamp" and v is not None and not -(2**63) <= v < 2**63:
                v = None  # a log time past 2262 (rosbag2 stores a uint64): no timestamp holds it
            cols[name].append(v)

    rep = outcome.report
    if rep is None:
        why = "; ".join(f"{f.code}: {f.message}" for f in outcome.findings) or "no result"
        add(resolve(outcome.path, [], -1, mappings), kind="unaudited", detail=why)
        return cols
    idents = {v: resolve(outcome.path, rep.descriptions, v, mappings) for _, v in rep.spans}
    for (topic, version), span in sorted(rep.spans.items()):
        n = sum(span.counts.values())
        add(
            idents[version],
            kind="summary",
            topic=topic,
            time=span.first_ns,
            time_end=span.last_ns,
            latency_ms=span.latency_sum_ns / n / 1e6,
            latency_max_ms=span.latency_max_ns / 1e6,
            lookups=n,
            **{k: span.counts[k] for k in OUTCOMES},
        )
    for f in rep.failures:
        add(
            idents[f.version],
            kind="lookup",
            topic=f.topic,
            frame=f.frame,
            outcome=f.outcome,
            time=f.log_ns,
            time_end=f.log_ns,
            stamp=f.stamp,
            latency_ms=(f.log_ns - f.stamp) / 1e6,
            detail=f.detail,
        )
    return cols


def _text(s: str) -> str:
    """Names from a recording as Parquet's UTF-8 holds them (a lone surrogate, escaped)."""
    try:
        s.encode("utf-8")
    except UnicodeEncodeError:
        return s.encode("utf-8", "backslashreplace").decode("utf-8")
    return s


def table(pa: Any, cols: dict[str, list[Any]]) -> Any:
    return pa.Table.from_pydict(cols, schema=schema(pa))
