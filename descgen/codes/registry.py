"""The registry machinery of the finding-code catalogue: what a code is, how it is declared, raised and retired.

Each stage declares its codes in its own module (descgen/codes/<group>.py), one module-level
constant per code, named as the code::

    declare = Stage("generate")
    GEN005 = declare("GEN005", "generated-file-stale", "error", "summary", '''rationale''')

and raises them through the entry, so a raise names the code once and mypy checks it exists::

    from descgen.codes.generate import GEN005
    found.append(GEN005.finding(message, hint, subject, where))

A code has one severity (:class:`Code`) or a severity that "varies" (:class:`VaryingCode`,
whose ``finding`` requires ``severity=``). A code is stable unless it is retired
(:class:`Retired`: it stays in the catalogue, ``descgen rules`` explains it, it cannot be
raised, and its number is never registered again) or redirected (:class:`Redirected`: what it
reported is now another code's). Declare a retired code with ``declare.retired(...)``: it gets no
module constant, so nothing can import it to raise it.
"""

from __future__ import annotations

import re
from typing import Literal, overload

from descgen.core.findings import Finding, Severity, Where
from descgen.core.record import record

SeverityOrVaries = Severity | Literal["varies"]
StatusName = Literal["stable", "retired", "redirected"]

# Where a code comes from; ``descgen rules --group`` filters by it, and each non-rule group is
# a module of descgen/codes/ of that name.
GROUPS: dict[str, str] = {
    "spec": "reading a spec (YAML, schema, units)",
    "rule": "whole-model rules (validate, audit)",
    "read": "reading third-party descriptions (URDF, Xacro, SRDF, controllers YAML)",
    "generate": "generate and check (the proofs of the written package)",
    "control": "descgen control (trajectory, options, the ros2_control model)",
    "recording": "recordings (tf-audit, tf-scenario)",
    "simulate": "descgen simulate (MuJoCo as a consumer)",
    "import": "descgen import (a URDF or Xacro becomes a spec)",
    "command": "the command line",
    "sweep": "descgen sweep (each joint through its range: directions and self-collisions)",
    "graph": "many robots in one ROS graph (audit --together)",
}

CODE_PATTERN = re.compile(r"[A-Z]{3,6}\d{3}")
_NOWHERE = Where("<unknown>")  # Finding's default location (descgen.core.model.NOWHERE)


@record
class Retired:
    """A code no longer raised: the issue that retired it and why. Its number is never reused."""

    issue: int
    why: str


@record
class Redirected:
    """A code no longer raised because what it reported is now reported as ``to``."""

    to: str  # the code that reports it now
    issue: int  # the issue that moved it


Status = Retired | Redirected | None  # None: stable


class _Declared:
    """What :class:`Code` and :class:`VaryingCode` share (their fields are declared by each record)."""

    code: str
    name: str
    severity: SeverityOrVaries
    group: str
    summary: str
    rationale: str
    status: Status

    def _raisable(self) -> None:
        if self.status is not None:
            raise ValueError(f"finding code {self.code} is {status_note(self.status)}: it cannot be raised")


@record
class Code(_Declared):
    """A finding code that is not an audit rule, with one severity."""

    code: str
    name: str  # short kebab-case name
    severity: Severity
    group: str  # a key of GROUPS
    summary: str  # one line: what it reports
    rationale: str  # why it matters and what to do
    status: Status = None

    def finding(self, message: str, hint: str = "", subject: str = "", where: Where = _NOWHERE) -> Finding:
        """A finding of this code, with its severity (refused for a retired or redirected code)."""
        self._raisable()
        return Finding(self.code, self.severity, message, hint, subject, where)


@record
class VaryingCode(_Declared):
    """A finding code whose severity is chosen where it is raised (``descgen rules`` says "varies")."""

    code: str
    name: str
    severity: Literal["varies"]
    group: str
    summary: str
    rationale: str
    status: Status = None

    def finding(
        self, message: str, hint: str = "", subject: str = "", where: Where = _NOWHERE, *, severity: Severity
    ) -> Finding:
        """A finding of this code with the severity this raise gives it."""
        self._raisable()
        return Finding(self.code, severity, message, hint, subject, where)


AnyCode = Code | VaryingCode


@record
class Entry:
    """What the catalogue knows about one code, rule or not."""

    code: str
    name: str
    severity: SeverityOrVaries
    group: str
    summary: str
    doc: str  # markdown: a rule's docstring, or the summary and rationale
    status: StatusName = "stable"
    note: str = ""  # a non-stable code: "retired by issue 41: ..." or "redirected to GEN006 by issue 41"

    @property
    def is_rule(self) -> bool:
        return self.group == "rule"


CODES: dict[str, AnyCode] = {}
NAMES: set[str] = set()  # the names in CODES: a duplicate is found without scanning CODES


def status_name(status: Status) -> StatusName:
    if isinstance(status, Retired):
        return "retired"
    if isinstance(status, Redirected):
        return "redirected"
    return "stable"


def status_note(status: Status) -> str:
    """The status of a non-stable code in words ("" for a stable one)."""
    if isinstance(status, Retired):
        return f"retired by issue {status.issue}: {status.why}"
    if isinstance(status, Redirected):
        return f"redirected to {status.to} by issue {status.issue}"
    return ""


def register(*codes: AnyCode) -> None:
    """Add codes to the catalogue; a code or name registered twice is a bug, raised now.

    A retired code keeps its number: registering it again, with any meaning, is refused."""
    for c in codes:
        if not CODE_PATTERN.fullmatch(c.code):
            raise ValueError(f"finding code {c.code!r} is not 3 to 6 capitals and 3 digits")
        old = CODES.get(c.code)
        if old is not None and old.status is not None:
            raise ValueError(f"finding code {c.code} is {status_note(old.status)}; a retired code is never reused")
        if old is not None:
            raise ValueError(f"duplicate finding code {c.code}")
        if c.name in NAMES:
            raise ValueError(f"duplicate code name {c.name} ({c.code})")
        # a retired audit rule has no @rule function left: its entry lives here, in group "rule"
        if c.group not in GROUPS or (c.group == "rule" and c.status is None):
            raise ValueError(f"code {c.code}: unknown group {c.group!r}")
        if not c.summary.strip() or not c.rationale.strip():
            raise ValueError(f"code {c.code} needs a summary and a rationale")
        if isinstance(c.status, Redirected) and (c.status.to == c.code or not CODE_PATTERN.fullmatch(c.status.to)):
            raise ValueError(f"code {c.code}: redirected to {c.status.to!r}, not another code")
        CODES[c.code] = c
        NAMES.add(c.name)


def raisable(code: str) -> Code:
    """The registered entry of ``code`` (a KeyError if there is none), for a code that arrives as
    text (a pydantic error type, a core QuantityError); code that names its code imports the
    constant instead. Such a code has one severity: a varying one is refused."""
    entry = CODES[code]
    if not isinstance(entry, Code):
        raise TypeError(f"finding code {code} has no one severity: raise it through its constant")
    return entry


def doc_of(c: AnyCode) -> str:
    note = status_note(c.status)
    status = f"## Status\n{note[:1].upper()}{note[1:]}.\n\n" if note else ""
    return f"{status}## What it reports\n{c.summary}\n\n## Why it matters\n{c.rationale}\n"


class Stage:
    """Declares the codes of one group: ``declare = Stage("generate")`` in descgen/codes/generate.py."""

    def __init__(self, group: str) -> None:
        if group not in GROUPS or group == "rule":
            raise ValueError(f"unknown group {group!r}")
        self.group = group

    @overload
    def __call__(self, code: str, name: str, severity: Severity, summary: str, rationale: str) -> Code: ...

    @overload
    def __call__(
        self, code: str, name: str, severity: Literal["varies"], summary: str, rationale: str
    ) -> VaryingCode: ...

    def __call__(self, code: str, name: str, severity: SeverityOrVaries, summary: str, rationale: str) -> AnyCode:
        """Declare and register a stable code; the module assigns it to a constant named as the code."""
        entry = _build(code, name, severity, self.group, summary, rationale, None)
        register(entry)
        return entry

    def retired(
        self,
        code: str,
        name: str,
        severity: SeverityOrVaries,
        summary: str,
        rationale: str,
        *,
        issue: int,
        why: str,
    ) -> None:
        """Keep a retired code in the catalogue (what it reported, and why it is gone): no constant."""
        register(_build(code, name, severity, self.group, summary, rationale, Retired(issue, why)))

    def redirected(
        self,
        code: str,
        name: str,
        severity: SeverityOrVaries,
        summary: str,
        rationale: str,
        *,
        to: str,
        issue: int,
    ) -> None:
        """Keep a code whose findings are now ``to``'s: explained, never raised, never reused."""
        register(_build(code, name, severity, self.group, summary, rationale, Redirected(to, issue)))


def _build(
    code: str, name: str, severity: SeverityOrVaries, group: str, summary: str, rationale: str, status: Status
) -> AnyCode:
    why = " ".join(rationale.split())
    if severity == "varies":
        return VaryingCode(code, name, severity, group, summary, why, status)
    return Code(code, name, severity, group, summary, why, status)
