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
