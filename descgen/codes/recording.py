"""Codes of the recordings: ``tf-audit`` (rosbag2) and ``tf-scenario``.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("recording")


BAG001 = declare(
    "BAG001",
    "recording-unreadable",
    "error",
    "The rosbag2 recording cannot be read.",
    """A corrupt recording gives no lookups to check. Give a rosbag2 folder (metadata.yaml with
      .mcap or .db3 files).""",
)

BAG002 = declare(
    "BAG002",
    "topic-not-recorded",
    "error",
    "A --topic is not in the recording.",
    """Nothing can be looked up for a topic that was not recorded. List the topics with
      `ros2 bag info`.""",
)

BAG003 = declare(
    "BAG003",
    "recording-exists",
    "error",
    "The output recording folder already exists.",
    """A recording is written to a new folder so that an existing one is never overwritten. Choose
      another --out.""",
)

BAG010 = declare(
    "BAG010",
    "nothing-to-look-up",
    "error",
    "The recording has no sensor messages with a header, so tf-audit made no lookup.",
    """An audit that looked nothing up would pass without proving anything. Name a recorded sensor
      topic with --topic.""",
)

BAG011 = declare(
    "BAG011",
    "recording-unwritable",
    "error",
    "The recording cannot be written there.",
    """The parent folder is missing or not writable. Choose another --out.""",
)

BAG012 = declare(
    "BAG012",
    "target-frame-unknown",
    "error",
    "The --target frame appears nowhere in the recording.",
    """Every lookup would fail for the same reason, hiding real problems. Name a frame of the
      transform tree, e.g. odom or base_link.""",
)

BAG013 = declare(
    "BAG013",
    "topic-without-header",
    "error",
    "A --topic carries messages with no header.",
    """Without a header stamp and frame there is nothing to look up. Name a sensor topic whose
      messages have a std_msgs/Header.""",
)

BAG014 = declare(
    "BAG014",
    "not-a-recording",
    "error",
    "The path is not a rosbag2 folder (missing, a file, no metadata.yaml, or metadata too large).",
    """Only rosbag2 folders can be read. Give the recording's folder.""",
)

BAG015 = declare(
    "BAG015",
    "findings-table-unwritable",
    "error",
    "The findings table (--out) cannot be written there.",
    """The table is written whole or not at all, as a regular file: an existing one is replaced only
      with --force, and never a link, folder or device. Choose another --out.""",
)

BAG016 = declare(
    "BAG016",
    "engine-unavailable",
    "error",
    "The engine asked for cannot run the audit (not installed, or its cluster cannot be reached).",
    """`--engine ray` needs the fleet extra (`pip install 'descgen[fleet]'`) here and on every node of
      the cluster, at the same descgen version. Install it, or check --address.""",
)

BAG017 = declare(
    "BAG017",
    "recording-audit-crashed",
    "error",
    "The audit of a recording crashed its worker, so the recording has no result.",
    """The other recordings are reported; this one is not audited. A worker killed for memory or a
      crash in a library reading the recording ends here: audit it alone to see why.""",
)

BAG020 = declare(
    "BAG020",
    "findings-table-unreadable",
    "error",
    "A findings table given to fleet-report cannot be read, or is not a tf-audit findings table.",
    """fleet-report reads the Parquet files `tf-audit --out` writes, with their columns. Give such a
      file.""",
)

BAG021 = declare(
    "BAG021",
    "fleet-report-unwritable",
    "error",
    "The fleet report's folder cannot be written.",
    """The page and its plots are written to a new or empty folder (or one fleet-report wrote before).
      Choose another --out.""",
)
