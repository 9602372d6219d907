"""Formatting finished findings; no checks and no I/O here."""

from __future__ import annotations

import json
from collections.abc import Iterable

from .findings import Finding, summary


def text(findings: Iterable[Finding]) -> str:
    lines = []
    for f in findings:
        lines.append(f"{f.where}: {f.severity}[{f.code}]: {f.message}")
        if f.hint:
            lines.append(f"  hint: {f.hint}")
    return "\n".join(lines) + ("\n" if lines else "")


def as_json(findings: Iterable[Finding], **extra: object) -> str:
    fs = list(findings)
    doc = {"findings": [f.as_dict() for f in fs], "summary": summary(fs), **extra}
    return json.dumps(doc, indent=2, sort_keys=False) + "\n"
