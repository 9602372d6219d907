"""Findings of ``descgen simulate``; the codes and their rationale are in descgen/codes/__init__.py."""

from __future__ import annotations

from descgen.codes import CODES
from descgen.core.findings import Finding, Where
from descgen.core.model import NOWHERE


def finding(code: str, message: str, hint: str, subject: str = "", where: Where = NOWHERE) -> Finding:
    """A finding with the severity the catalogue gives ``code`` (a KeyError is a missing entry)."""
    severity = CODES[code].severity
    assert severity != "varies", code
    return Finding(code, severity, message, hint, subject, where)
