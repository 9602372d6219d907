"""Findings (what every check reports) and the input error that ends a command with exit 2."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import field
from typing import Literal

from descgen.core.record import record

Severity = Literal["error", "warning", "info"]
SEVERITIES: tuple[Severity, ...] = ("error", "warning", "info")


@record
class Where:
    """Where an element or value came from: a file and a 1-based line and column (0 = unknown).

    ``via`` is how an element of an expanded Xacro got there: the macro calls that produced
    it, innermost first (the element itself is written in the macro body at file:line)."""

    file: str
    line: int = 0
    col: int = 0
    via: tuple[Where, ...] = ()

    def bare(self) -> Where:
        """This location without its call chain."""
        return Where(self.file, self.line, self.col) if self.via else self

    def __str__(self) -> str:
        if self.line:
            return f"{self.file}:{self.line}:{self.col or 1}"
        return self.file


@record
class Finding:
    code: str
    severity: Severity
    message: str
    hint: str = ""
    subject: str = ""
    where: Where = field(default_factory=lambda: Where("<unknown>"))
    # the reason of the spec's waiver that matched this finding (code and subject): still
    # reported, everywhere, but it fails nothing (descgen/audit/waivers.py)
    waived: str | None = None

    @property
    def blocks(self) -> bool:
        """An error that fails the command: not waived."""
        return self.severity == "error" and self.waived is None

    @property
    def related(self) -> tuple[Where, ...]:
        """Further locations of the same finding: the macro calls that produced the element."""
        return self.where.via

    def as_dict(self) -> dict[str, object]:
        out: dict[str, object] = {
            "code": self.code,
            "severity": self.severity,
            "subject": self.subject,
            "file": self.where.file,
            "line": self.where.line,
            "col": self.where.col,
            "message": self.message,
            "hint": self.hint,
        }
        if self.waived is not None:  # only then: documents without waivers keep their shape
            out["waived"] = self.waived
        if self.related:  # only then: documents written before the call chain keep their shape
            out["related"] = [
                {"file": w.file, "line": w.line, "col": w.col, "message": "macro called here"} for w in self.related
            ]
        return out


class InputError(Exception):
    """Input that cannot be used at all. The CLI turns it into exit code 2.

    It carries every problem found, not only the first.
    """

    def __init__(self, findings: Iterable[Finding]) -> None:
        self.findings = tuple(findings)
        super().__init__("; ".join(f"{f.where}: {f.message}" for f in self.findings))


def errors(findings: Iterable[Finding]) -> list[Finding]:
    """The errors that fail a command (a waived one does not)."""
    return [f for f in findings if f.blocks]


def summary(findings: Iterable[Finding]) -> dict[str, int]:
    """Findings by severity; waived ones on their own (the key only when there are some)."""
    out: dict[str, int] = dict.fromkeys(SEVERITIES, 0)
    for f in findings:
        if f.waived is not None:
            out["waived"] = out.get("waived", 0) + 1
        else:
            out[f.severity] += 1
    return out
