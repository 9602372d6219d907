"""What a control run showed at the command/state boundary: the joint tracking, rejected and
clipped commands, controllers that never became active, as findings and as ``verdict.json``."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from descgen.codes.control import CTRL011, CTRL012, CTRL013, CTRL014
from descgen.commands.control.manager import ControllerManager
from descgen.core.findings import Finding


@dataclass
class Outcome:
    cm: ControllerManager
    rows: list[tuple[float, str, float, float, float]] = field(default_factory=list)  # t, joint, desired, cmd, meas
    tracking: dict[str, float] = field(default_factory=dict)
    tolerance: dict[str, float] = field(default_factory=dict)
    record: dict[str, Any] = field(default_factory=dict)  # what ran: record.run_record

    @property
    def echo(self) -> bool:
        return self.cm.hardware.echoes_commands

    def findings(self) -> list[Finding]:
        """What the run showed at the command/state boundary, as findings."""
        out = []
        for j, e in self.tracking.items():
            if e > self.tolerance[j]:
                out.append(
                    CTRL011.finding(
                        f"joint '{j}' tracking error reached {e:.4g} (tolerance "
                        f"{self.tolerance[j]:.4g}): the measured state does not follow the command",
                        "check the joint's direction, encoder offset and whether it moves at all",
                        f"joint:{j}",
                    )
                )
        for ev in self.cm.rejected[:1]:
            out.append(
                CTRL012.finding(
                    f"{len(self.cm.rejected)} command(s) rejected by limits; first: "
                    f"{ev.joint}/{ev.interface} = {ev.value:.6g} beyond {ev.limit:.6g} at {ev.time:.2f} s",
                    "keep the trajectory inside the joint limits",
                    f"joint:{ev.joint}",
                )
            )
        for n, c in self.cm.controllers.items():
            if c.state != "active":
                out.append(
                    CTRL013.finding(
                        f"controller '{n}' never became active (state {c.state})",
                        "see lifecycle.md for the failed transition or claim",
                        f"controller:{n}",
                    )
                )
        if self.echo:
            out.append(
                CTRL014.finding(
                    "the measured state is the mock hardware echoing the command",
                    "this run does not verify motion; use --plant sim or real hardware",
                    "hardware",
                )
            )
        return out

    def verdict(self) -> dict[str, Any]:
        failed = [j for j, e in self.tracking.items() if e > self.tolerance[j]]
        inactive = [n for n, c in self.cm.controllers.items() if c.state != "active"]
        return {
            "run": self.record,  # so that `descgen check` can run it again (control/evidence_check.py)
            "rejected": [
                {"joint": e.joint, "interface": e.interface, "time": e.time, "value": e.value, "limit": e.limit}
                for e in self.cm.rejected
            ],
            "clipped": [
                {
                    "joint": e.joint,
                    "interface": e.interface,
                    "time": e.time,
                    "proposed": e.value,
                    "applied": e.applied,
                    "limit": e.limit,
                }
                for e in self.cm.clipped
            ],
            "tracking": self.tracking,
            "tolerance": self.tolerance,
            "tracking_failed": failed,
            "controllers_not_active": inactive,
            "state_echoes_command": self.echo,
            "note": (
                "the 'measured' state is mock_components/GenericSystem mirroring the command: this is not "
                "verified motion"
            )
            if self.echo
            else "measured state comes from the simulated plant",
            "ok": not failed and not self.cm.rejected and not inactive,
            "findings": [f.as_dict() for f in self.findings()],
        }
