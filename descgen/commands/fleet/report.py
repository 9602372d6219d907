"""``descgen fleet-report``'s work: the tables rolled up, the page and its plots written."""

from __future__ import annotations

from pathlib import Path

from descgen.commands.fleet.page import MARK, PLOTS, markdown
from descgen.commands.fleet.rollup import RollUp, roll_up
from descgen.write.fleet_report import PAGE, check_folder, write_report


def fleet_report(findings: list[Path], out: Path, threshold: float) -> tuple[RollUp, Path]:
    """The roll-up and the page written in ``out`` (``threshold``: a share, 0 to 1)."""
    check_folder(out, [PAGE, *PLOTS], MARK)  # before reading a fleet's tables
    rollup = roll_up(findings, threshold)
    rates: dict[str, list[tuple[str, float]]] = {}
    for d in rollup.days:
        rates.setdefault(d.robot, []).append((d.day, d.rate))
    return rollup, write_report(out, markdown(rollup), rates, rollup.by_version, PLOTS)
