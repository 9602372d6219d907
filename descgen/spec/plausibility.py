"""The spec's ``plausibility:`` overrides of the default ranges, read before the rest of
the spec so that validation already uses them."""

from __future__ import annotations

from descgen.codes import raisable
from descgen.codes.spec import SPEC001
from descgen.core import units
from descgen.core.findings import Finding
from descgen.infra.yamlsource import Document, Path_


def ranges_from(doc: Document) -> tuple[dict[str, units.Range], list[Finding]]:
    """The spec's plausibility overrides, read before the rest so that validation uses them."""
    ranges = dict(units.DEFAULT_RANGES)
    findings: list[Finding] = []
    raw = doc.data.get("plausibility") if isinstance(doc.data, dict) else None
    if not isinstance(raw, dict):
        return ranges, findings
    for role, bounds in raw.items():
        p: Path_ = ("plausibility", role)
        if role not in ranges:
            findings.append(
                SPEC001.finding(
                    f"unknown plausibility role '{role}'",
                    f"roles: {', '.join(ranges)}",
                    ".".join(map(str, p)),
                    doc.where(p, key=True),
                )
            )
            continue
        if not isinstance(bounds, dict):
            continue  # the schema reports the shape
        r = ranges[role]
        low, high = r.low, r.high
        for key in ("min", "max"):
            if key in bounds:
                try:
                    v = abs(units.to_si(bounds[key], r.kind))
                except units.QuantityError as exc:
                    findings.append(
                        raisable(exc.code).finding(  # a core QuantityError carries its code as text
                            exc.message,
                            exc.hint,
                            ".".join(map(str, (*p, key))),
                            doc.where((*p, key)),
                        )
                    )
                    continue
                if key == "min":
                    low = v
                else:
                    high = v
        ranges[role] = units.Range(r.kind, low, high)
    return ranges, findings
