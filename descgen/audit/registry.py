"""The rule catalogue: ``@rule`` registers a pure function ``Robot -> Iterator[Finding]``.

A rule's docstring is its documentation (``descgen rules CODE``, SARIF rule help). Codes
are stable: a retired code is never reused.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Callable, Iterable, Iterator
from typing import Literal

from descgen.codes import CODES, NAMES, status_note
from descgen.core.findings import Finding, Severity, Where
from descgen.core.model import Robot
from descgen.core.record import record

CATEGORIES = ("TOPO", "NAME", "UNIT", "INER", "GEOM", "JOINT", "POSE", "SRDF", "CTRL", "FRAME", "TIME", "MOVEIT")
_CODE = re.compile(rf"^({'|'.join(CATEGORIES)})\d{{3}}$")
_HEADINGS = ("## What it does", "## Why is this bad?")

RuleFn = Callable[[Robot], Iterable[Finding]]


Stage = Literal["input", "check"]


@record
class RuleInfo:
    code: str
    name: str
    severity: Severity
    doc: str
    fn: RuleFn
    stage: Stage = "input"  # "input": its errors make a spec invalid; "check": a claim failed

    @property
    def summary(self) -> str:
        text = self.doc.split("## What it does", 1)[-1].split("##", 1)[0]
        return " ".join(text.split())


RULES: dict[str, RuleInfo] = {}


def rule(code: str, name: str, severity: Severity, stage: Stage = "input") -> Callable[[RuleFn], RuleFn]:
    def register(fn: RuleFn) -> RuleFn:
        if not _CODE.match(code):
            raise ValueError(f"rule code {code!r} is not a category prefix plus 3 digits")
        if code in RULES or any(r.name == name for r in RULES.values()):
            raise ValueError(f"duplicate rule {code} {name}")
        if code in CODES or name in NAMES:
            # one catalogue (descgen/codes/): a rule may not reuse a loader/reader code, nor a retired one
            old = CODES.get(code)
            retired = f" ({old.code} is {status_note(old.status)})" if old is not None and old.status else ""
            raise ValueError(f"rule {code} {name} duplicates a catalogue code{retired}")
        doc = inspect.cleandoc(fn.__doc__ or "")
        missing = [h for h in _HEADINGS if h not in doc]
        if missing:
            raise ValueError(f"rule {code} doc lacks {missing}")
        RULES[code] = RuleInfo(code, name, severity, doc, fn, stage)
        return fn

    return register


def at(
    code: str,
    elem: object,
    message: str,
    hint: str,
    severity: Severity | None = None,
    subject: str | None = None,
) -> Finding:
    """A finding located at a model element (its subject and file:line)."""
    info = RULES.get(code)
    sev: Severity = severity or (info.severity if info else "error")
    subj = subject or getattr(elem, "subject", "") or ""
    where = getattr(elem, "where", None) or Where("<unknown>")
    return Finding(code, sev, message, hint, subj, where)


def run(robot: Robot, codes: Iterable[str] | None = None, stage: Stage | None = None) -> list[Finding]:
    """All registered rules (or the given codes, or one stage) over one robot, in code order."""
    load()

    wanted = set(codes) if codes is not None else None
    out: list[Finding] = []
    for code in sorted(RULES):
        info = RULES[code]
        if (wanted is not None and code not in wanted) or (stage is not None and info.stage != stage):
            continue
        out.extend(info.fn(robot))
    return out


def load() -> None:
    """Register every rule module (imported once; a process that forks workers calls it first)."""
    from descgen.audit import rules  # noqa: F401


def iter_rules() -> Iterator[RuleInfo]:
    load()

    yield from (RULES[c] for c in sorted(RULES))
