"""Check 4: forward kinematics at each measured pose matches the measurement."""

from __future__ import annotations

from pathlib import Path

from descgen.audit import run
from descgen.core.findings import Finding
from descgen.core.model import Robot


def known_poses(files: dict[str, str], robot: Robot, where: Path) -> list[Finding]:
    """The check-stage rules (POSE010: measured poses against forward kinematics)."""
    return run(robot, stage="check")
