"""A long recording cut into time windows audited apart (``tf-audit --window``), and joined
back into the report one pass gives.

A window looks up the sensor messages logged in its slice, in a buffer filled with every
static transform before it and the dynamic ones from one horizon (the buffer's depth plus the
wait) before it. That is the one pass's buffer unless a transform older than the horizon was
still held (a link that stopped publishing keeps its last samples in tf2, however old), so it
is not assumed: each window keeps a digest of its buffer where it starts and where it ends,
and the windows are joined only where the digests of each boundary agree. Where one differs,
the recording is audited again in one pass (``join`` returns None).
"""

from __future__ import annotations

import itertools
from collections import Counter

from descgen.commands.tf.bagaudit import Report, Window

MIN_WINDOW_NS = 1_000_000_000  # a window shorter than a second is all horizon
MAX_WINDOWS = 10_000  # a recording's metadata may claim any span: the windows widen instead


MIN_WINDOW_BYTES = 2_000  # a window of less holds a handful of messages: metadata that says otherwise is wrong


def plan(start_ns: int, end_ns: int, length_ns: int, horizon_ns: int, size: int | None = None) -> list[Window | None]:
    """The windows of a recording whose metadata says it was logged from ``start_ns`` to
    ``end_ns``: [None] (one pass) when it is no longer than one window. The first window is open
    to the left and the last to the right, so a message outside what the metadata says is still
    looked up, once. ``size`` (bytes on disk) bounds the count as well: a span the metadata gets
    wrong (decades of a few seconds' data) gives few windows, not thousands of empty ones."""
    span = end_ns - start_ns
    most = MAX_WINDOWS if size is None else max(1, min(MAX_WINDOWS, size // MIN_WINDOW_BYTES))
    if span <= length_ns or most == 1:
        return [None]
    length = max(length_ns, -(-span // most))
    cuts: list[int | None] = list(range(start_ns + length, end_ns, length))
    return [Window(a, b, horizon_ns) for a, b in itertools.pairwise([None, *cuts, None])]


def join(parts: list[Report], examples: int) -> Report | None:
    """The windows' reports as one, in time order; None when a boundary's digests differ (the
    windows did not see what one pass sees)."""
    for a, b in itertools.pairwise(parts):
        if a.boundary[1] != b.boundary[0]:
            return None
    out = Report()
    shown: Counter[str] = Counter()
    for p in parts:
        out.lookups += p.lookups
        out.counts.update(p.counts)
        out.latency.update(p.latency)
        for topic, counts in p.per_topic.items():
            out.per_topic.setdefault(topic, Counter()).update(counts)
        for key, span in p.spans.items():
            if key in out.spans:
                out.spans[key].merge(span)
            else:
                out.spans[key] = span
        for e in p.examples:  # each window kept its first few of each kind: the first few of all
            if shown[e["outcome"]] < examples:
                shown[e["outcome"]] += 1
                out.examples.append(e)
        out.results.extend(p.results)
        out.failures.extend(p.failures)
        out.frames |= p.frames
    out.descriptions = parts[0].descriptions if parts else []
    return out
