"""A spec's waivers applied to findings: a finding whose code and subject a waiver names is
marked waived with the waiver's reason (still reported in every output; it fails nothing),
and a waiver that matches nothing is SPEC130.

Each stage judges the waivers of the codes it evaluates, so no waiver is called unused by a
stage that could not have matched it: ``validate`` the input-stage rules, ``generate`` and
``check`` the rest (check-stage rules, the proofs), ``audit`` of a spec every rule.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import replace

from descgen.codes.spec import SPEC130
from descgen.core.findings import Finding
from descgen.core.model import Waiver


def waive(findings: Iterable[Finding], waivers: Sequence[Waiver]) -> list[Finding]:
    """``findings`` with every one a waiver names marked waived (the first waiver's reason)."""
    if not waivers:
        return list(findings)
    by_key: dict[tuple[str, str], Waiver] = {}
    for w in waivers:
        by_key.setdefault((w.code, w.subject), w)
    out = []
    for f in findings:
        match = by_key.get((f.code, f.subject))
        out.append(replace(f, waived=match.reason) if match is not None and f.waived is None else f)
    return out


def unused(waivers: Sequence[Waiver], findings: Iterable[Finding], judged: Callable[[str], bool]) -> list[Finding]:
    """SPEC130 for each waiver of a code ``judged`` by this stage that matched none of ``findings``."""
    from descgen.audit.registry import RULES, load

    load()
    matched = {(f.code, f.subject) for f in findings if f.waived is not None}
    return [
        SPEC130.finding(
            f"waiver of {w.code} for '{w.subject}' matches no finding"
            + (
                ""
                if w.code in RULES
                else f": {w.code} is no audit rule's code, and only a rule's finding can be waived"
            ),
            "remove it, or copy the code and subject from the finding it is meant for "
            "(descgen validate --format json prints both); a proof of descgen's output or an input error is fixed, "
            "not waived",
            "waivers",
            w.where,
        )
        for w in waivers
        if judged(w.code) and (w.code, w.subject) not in matched
    ]


def applied(findings: Iterable[Finding], waivers: Sequence[Waiver], judged: Callable[[str], bool]) -> list[Finding]:
    """:func:`waive`, then :func:`unused` for the codes this stage judges."""
    out = waive(findings, waivers)
    return out + unused(waivers, out, judged)
