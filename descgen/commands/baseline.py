"""``audit --baseline FILE`` / ``--write-baseline FILE``: for descriptions descgen did not
write, CI fails only on new findings. A baseline is the audit's findings as (code, subject,
file, message) entries; a finding a baseline lists is reported, as waived ("in the baseline"), and fails
nothing, as a spec's waiver does (descgen/audit/waivers.py); an entry that matches nothing is
BASE002. Files are named as the audit prints them, so write and read the baseline from the
same folder with the same paths."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

from descgen.codes.command import BASE001, BASE002, BASE003
from descgen.core.findings import Finding, InputError, Where
from descgen.infra.safeio import MIB, read_bounded

FORMAT = 1
MAX_BASELINE_BYTES = 16 * MIB


def _key(f: Finding) -> tuple[str, str, str, str]:
    # the message too: a subject can hold several findings of one code (a controller's two wheel
    # parameters), and a changed value is a new finding; lines are left out (an edit shifts them)
    return f.code, f.subject, f.where.file, f.message


def write(findings: list[Finding], path: Path) -> int:
    """Write every finding (warnings and infos too) of ``findings`` to ``path``; the count."""
    entries = sorted({_key(f) for f in findings if f.waived is None})
    doc = {
        "descgen_baseline": FORMAT,
        "findings": [{"code": c, "subject": s, "file": f, "message": m} for c, s, f, m in entries],
    }
    try:
        path.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    except OSError as exc:
        raise InputError(
            [
                BASE003.finding(
                    f"cannot write {path}: {exc.strerror or exc}", "name a writable file", "option", Where(str(path))
                )
            ]
        ) from None
    return len(entries)


def read(path: Path) -> set[tuple[str, str, str, str]]:
    """The entries of a baseline file; InputError BASE001 when it is not one."""
    data = read_bounded(path, "baseline", MAX_BASELINE_BYTES, display=str(path))
    try:
        doc = json.loads(data)
        if doc.get("descgen_baseline") != FORMAT:
            raise ValueError("no descgen_baseline: 1")
        return {(str(e["code"]), str(e["subject"]), str(e["file"]), str(e["message"])) for e in doc["findings"]}
    except (ValueError, TypeError, KeyError, AttributeError) as exc:
        raise InputError(
            [
                BASE001.finding(
                    f"{path} is not a descgen baseline ({exc})",
                    "write it with: descgen audit ... --write-baseline FILE",
                    "option",
                    Where(str(path)),
                )
            ]
        ) from None


def apply(findings: list[Finding], path: Path) -> list[Finding]:
    """``findings`` with those the baseline lists marked waived, then BASE002 per unused entry."""
    entries = read(path)
    reason = f"in the baseline {path}"
    out = [replace(f, waived=reason) if _key(f) in entries and f.waived is None else f for f in findings]
    seen = {_key(f) for f in findings}
    out += [
        BASE002.finding(
            f"baseline entry {code} for '{subject}' in {file} matches no finding: fixed, or changed ({message})",
            "write the baseline again with --write-baseline",
            "option",
            Where(str(path)),
        )
        for code, subject, file, message in sorted(entries - seen)
    ]
    return out
