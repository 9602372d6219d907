"""Every finding code descgen can report, as ``descgen rules`` and SARIF list them: the audit
rules (registered by ``@rule`` in descgen/audit/rules/) beside the codes the other stages
declare in descgen/codes/. The audit layer is the lowest that sees both."""

from __future__ import annotations

from collections.abc import Iterator

from descgen.audit.registry import iter_rules
from descgen.codes import CODES, Entry, doc_of, status_name, status_note


def _rules() -> dict[str, Entry]:
    return {
        r.code: Entry(r.code, r.name, r.severity, "rule", r.summary or r.name, r.doc.strip() + "\n")
        for r in iter_rules()
    }


def explain(code: str) -> Entry | None:
    """The catalogue entry for ``code`` (an audit rule or a registered code, retired ones too), or None."""
    return next((e for e in entries() if e.code == code), None)


def entries() -> Iterator[Entry]:
    """Every code, rules and the rest, retired and redirected ones too, sorted by code."""
    both = dict(_rules())
    for code, c in CODES.items():
        both[code] = Entry(
            c.code, c.name, c.severity, c.group, c.summary, doc_of(c), status_name(c.status), status_note(c.status)
        )
    yield from sorted(both.values(), key=lambda e: e.code)
