"""Formatting finished findings; no checks and no I/O here."""

from __future__ import annotations

import json
import re
from collections.abc import Iterable

from descgen.core.findings import Finding, Where, summary

MAX_QUOTED = 200  # characters of one quoted value in a text message
MAX_FIELD = 2000  # characters of one printed field, whatever it holds

# C0, DEL, C1 (with NEL), the Unicode line and paragraph separators, and the bidi controls
# that reorder what a terminal shows ("Trojan Source"): a value from an audited file
# could otherwise start a new line that looks like a finding, or rewrite the terminal.
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f\u061c\u2028\u2029\u200e\u200f\u202a-\u202e\u2066-\u2069]")
# the same, but a multi-line text keeps its line breaks and tabs (a diff)
_CONTROL_IN_LINES = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u061c\u2028\u2029\u200e\u200f\u202a-\u202e\u2066-\u2069]")
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}
_QUOTED = re.compile(f"'([^']{{{MAX_QUOTED + 1},}})'")


def _escape(m: re.Match[str]) -> str:
    c = m.group()
    if c in _NAMED:
        return _NAMED[c]
    return f"\\x{ord(c):02x}" if ord(c) < 0x100 else f"\\u{ord(c):04x}"


def printable(value: object, limit: int = MAX_FIELD) -> str:
    """``value`` as one line of plain text for a terminal: control characters escaped
    (``\\n``, ``\\x1b``), quoted values longer than MAX_QUOTED and the whole beyond
    ``limit`` cut with an ellipsis. JSON and SARIF keep the full value."""
    out = _CONTROL.sub(_escape, str(value))
    out = _QUOTED.sub(lambda m: "'" + m.group(1)[:MAX_QUOTED] + "…'", out)
    return out if len(out) <= limit else out[: limit - 1] + "…"


def lines_text(value: str) -> str:
    """A multi-line text (``check``'s diff of committed files) for a terminal: its lines and tabs
    kept, every other control character escaped, so a file in a pull request cannot set the
    terminal's title, clear the screen or erase the finding lines above it."""
    return _CONTROL_IN_LINES.sub(_escape, value)


def text(findings: Iterable[Finding]) -> str:
    """One line per finding, a line per macro call that produced the element (innermost
    first), then its hint line: nothing in a value can add a line."""
    lines = []
    for f in findings:
        lines.append(f"{printable(f.where)}: {f.severity}[{f.code}]: {printable(f.message)}")
        lines.extend(f"  in macro called from {printable(w)}" for w in f.related)
        if f.waived is not None:  # still shown, with why it fails nothing
            lines.append(f"  waived: {printable(f.waived)}")
        if f.hint:
            lines.append(f"  hint: {printable(f.hint)}")
    return "\n".join(lines) + ("\n" if lines else "")


def as_json(findings: Iterable[Finding], **extra: object) -> str:
    fs = list(findings)
    doc = {"findings": [f.as_dict() for f in fs], "summary": summary(fs), **extra}
    return json.dumps(doc, indent=2, sort_keys=False) + "\n"


_LEVEL = {"error": "error", "warning": "warning", "info": "note"}


def sarif(findings: Iterable[Finding], base: str | None = None) -> str:
    """SARIF 2.1.0 (what GitHub code scanning reads): one run, the rules that fired (their
    catalogue entry, descgen/codes/, as help), one result per finding."""
    from descgen import __version__
    from descgen.audit.catalogue import entries

    fs = list(findings)
    known = {e.code: e for e in entries()}  # every code any command prints, rules or not
    codes = sorted({f.code for f in fs})
    rules = []
    for code in codes:
        info = known.get(code)
        entry: dict[str, object] = {"id": code}
        if info is not None:
            entry.update(
                {
                    "name": info.name,
                    "shortDescription": {"text": info.summary or info.name},
                    "fullDescription": {"text": " ".join(info.doc.split())},
                    "help": {"text": info.doc.strip(), "markdown": info.doc.strip()},
                }
            )
            if info.severity != "varies":
                entry["defaultConfiguration"] = {"level": _LEVEL[info.severity]}
        else:
            entry["shortDescription"] = {"text": f"descgen {code}"}
        rules.append(entry)
    index = {code: i for i, code in enumerate(codes)}
    results = []
    for f in fs:
        message = f.message + (f" (hint: {f.hint})" if f.hint else "")
        result: dict[str, object] = {
            "ruleId": f.code,
            "ruleIndex": index[f.code],
            "level": _LEVEL[f.severity],
            "message": {"text": message},
            "locations": [
                {
                    "physicalLocation": _physical(f.where, base),
                    **({"logicalLocations": [{"name": f.subject}]} if f.subject else {}),
                }
            ],
        }
        if f.waived is not None:
            # a spec's waiver (SARIF 3.35: a suppression in the source, the reason as justification):
            # code scanning shows it as dismissed, not as an open alert
            result["suppressions"] = [{"kind": "inSource", "justification": f.waived}]
        if f.related:
            # the macro calls, innermost first; ids are unique within the result (SARIF 3.28.2)
            result["relatedLocations"] = [
                {"id": i, "physicalLocation": _physical(w, base), "message": {"text": "macro called here"}}
                for i, w in enumerate(f.related, 1)
            ]
        results.append(result)
    doc = {
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [
            {
                "tool": {"driver": {"name": "descgen", "version": __version__, "rules": rules}},
                "results": results,
            }
        ],
    }
    return json.dumps(doc, indent=2) + "\n"


def _physical(where: Where, base: str | None) -> dict[str, object]:
    """A SARIF physicalLocation: the file relative to ``base`` when it lies inside, and the region."""
    from pathlib import Path

    uri = where.file.removesuffix(" (expanded)")
    if base is not None:
        try:
            uri = Path(uri).resolve().relative_to(Path(base).resolve()).as_posix()
        except ValueError:
            uri = Path(uri).as_posix()
    location: dict[str, object] = {"artifactLocation": {"uri": uri}}
    if where.line > 0:
        region: dict[str, int] = {"startLine": where.line}
        if where.col > 0:
            region["startColumn"] = where.col
        location["region"] = region
    return location


# XML 1.0 has no way to write these (not even as character references): a value from an audited
# file holding one would make the whole report unreadable, so it is written as an escape
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff\ud800-\udfff]")


def _xml_text(value: object) -> str:
    return _NOT_XML.sub(lambda m: f"\\x{ord(m.group()):02x}", str(value))


def junit(command: str, suites: Iterable[tuple[str, Iterable[Finding], str]], strict: bool = False) -> str:
    """JUnit XML, as CI servers (Jenkins, GitLab, Azure) show test results: one ``<testsuite>``
    per input (a spec or a description) with a ``<testcase>`` for the command on that input and
    one per finding. A finding fails its case when it makes the command fail (an error; a
    warning with ``strict``); others pass and keep their text in ``<system-out>``, so the
    failures a server counts are exactly what set the exit code. ``suites``: (name, findings,
    text shown with the command's own case, e.g. the diff of stale files, whose findings fail)."""
    from xml.etree import ElementTree as ET

    failing = {"error", "warning"} if strict else {"error"}
    root = ET.Element("testsuites", name=f"descgen {command}")
    total = failed_total = 0
    for name, findings, shown in suites:
        fs = list(findings)
        suite = ET.SubElement(root, "testsuite", name=_xml_text(name))
        own = ET.SubElement(suite, "testcase", name=command, classname=f"descgen.{command}", file=_xml_text(name))
        if shown:
            ET.SubElement(own, "system-out").text = _xml_text(shown)
        failed = 0
        for f in fs:
            case = ET.SubElement(
                suite,
                "testcase",
                name=_xml_text(f"{f.code} {f.subject}".strip()),
                classname=f"descgen.{command}.{f.code}",
                file=_xml_text(f.where.file),
                line=str(f.where.line),
            )
            body = _xml_text(text([f]))
            if f.severity in failing and f.waived is None:
                failure = ET.SubElement(case, "failure", type=f.severity, message=_xml_text(f.message))
                failure.text = body
                failed += 1
            else:
                ET.SubElement(case, "system-out").text = body
        suite.set("tests", str(1 + len(fs)))
        suite.set("failures", str(failed))
        suite.set("errors", "0")
        suite.set("skipped", "0")
        total += 1 + len(fs)
        failed_total += failed
    root.set("tests", str(total))
    root.set("failures", str(failed_total))
    root.set("errors", "0")
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
