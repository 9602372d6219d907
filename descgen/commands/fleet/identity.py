"""Which robot, on which description version, a recording is of.

From the recording itself: the URDF that robot_state_publisher latched on /robot_description
(its SHA-256 is the version, its ``<robot name>`` the robot); or from the team's mapping
``--robot GLOB=ROBOT[@VERSION]`` (first match on the recording's path as given, or its folder's
name), which names the unit (a fleet has many robots of one URDF) and wins over the URDF's name.
A version from the mapping wins over the hash. A recording with neither is said to have neither.
"""

from __future__ import annotations

import fnmatch
from dataclasses import dataclass
from pathlib import PurePath

from descgen.commands.tf.bagaudit import Description

VERSION_CHARS = 12  # of the SHA-256, as a version is shown (git's short hash is 7 to 12)


@dataclass(frozen=True)
class Mapping:
    pattern: str
    robot: str
    version: str | None


@dataclass(frozen=True)
class Identity:
    robot: str | None
    version: str | None  # the mapping's version, else the description hash's first characters
    sha256: str | None  # the whole hash of the URDF on /robot_description
    source: str  # "--robot", "/robot_description", "--robot and /robot_description" or "none"

    def said(self) -> str:
        """One line for the text report."""
        if self.source == "none":
            return "robot unknown: no /robot_description in the recording and no --robot mapping matches it"
        return f"robot {self.robot or 'unnamed'}, description {self.version or 'unknown'} (from {self.source})"


def parse(text: str) -> Mapping:
    """``GLOB=ROBOT`` or ``GLOB=ROBOT@VERSION``; ValueError says what is wrong."""
    pattern, sep, rest = text.partition("=")
    if not sep or not pattern or not rest:
        raise ValueError("give GLOB=ROBOT or GLOB=ROBOT@VERSION, e.g. 'bags/r07_*=r07'")
    robot, at, version = rest.partition("@")
    if not robot or (at and not version):
        raise ValueError("give GLOB=ROBOT or GLOB=ROBOT@VERSION, e.g. 'bags/r07_*=r07@v12'")
    for name in (robot, version):
        if any(not c.isprintable() for c in name) or len(name) > 200:
            raise ValueError("a robot or version is printable text of at most 200 characters")
    return Mapping(pattern, robot, version or None)


def resolve(recording: str, descriptions: list[Description], version: int, mappings: tuple[Mapping, ...]) -> Identity:
    """The identity of the lookups made under ``descriptions[version]`` (-1: the recording has none)."""
    d = descriptions[version] if 0 <= version < len(descriptions) else None
    name = PurePath(recording.rstrip("/")).name
    m = next(
        (m for m in mappings if fnmatch.fnmatchcase(recording, m.pattern) or fnmatch.fnmatchcase(name, m.pattern)), None
    )
    sha = d.sha256 if d else None
    if m is None and d is None:
        return Identity(None, None, None, "none")
    if m is None:
        assert d is not None
        return Identity(d.robot or None, d.sha256[:VERSION_CHARS], sha, "/robot_description")
    if d is None:
        return Identity(m.robot, m.version, None, "--robot")
    return Identity(m.robot, m.version or d.sha256[:VERSION_CHARS], sha, "--robot and /robot_description")
