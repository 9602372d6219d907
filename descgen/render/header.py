"""The header on every generated file: where it came from, and two hashes.

``spec-sha256`` is the hash of the spec text; ``content-sha256`` the hash of the file
without its header. A file whose content no longer matches its own recorded hash was
edited by hand; one that matches but differs from a fresh render is stale.
"""

from __future__ import annotations

import hashlib
import re

from descgen.core.record import record
from descgen.render.formatting import comment, visible

MARK = "descgen spec-sha256="
_HASHES = re.compile(r"descgen spec-sha256=([0-9a-f]{64}) content-sha256=([0-9a-f]{64})")


def _style(path: str) -> tuple[str, str]:
    if path.endswith((".xml", ".urdf", ".xacro", ".srdf", ".md")):
        return "<!-- ", " -->"
    if path.endswith(".dot"):
        return "// ", ""
    return "# ", ""


def shown(path: str, spec_display: str) -> str:
    """The spec's path as the header comment of ``path`` can hold it: a file name may contain
    a line break (which would end a ``#`` or ``//`` comment and start code) or ``--`` (which
    ends an XML comment); control characters become visible escapes."""
    text = visible(spec_display)
    return comment(text) if _style(path)[0] == "<!-- " else text


def digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def add(path: str, body: str, spec_display: str, spec_hash: str) -> str:
    """``body`` with the header lines inserted (after an XML declaration, if any)."""
    open_, close = _style(path)
    lines = [
        f"{open_}generated from {shown(path, spec_display)} by descgen — do not edit{close}",
        f"{open_}{MARK}{spec_hash} content-sha256={digest(body)}{close}",
    ]
    if body.startswith("<?xml"):
        first, _, rest = body.partition("\n")
        return "\n".join([first, *lines, rest])
    return "\n".join([*lines, body])


@record
class Stamp:
    spec_hash: str
    content_hash: str
    body: str

    @property
    def hand_edited(self) -> bool:
        return digest(self.body) != self.content_hash


def read(text: str) -> Stamp | None:
    """The recorded hashes and the body of a generated file; None if it has no header."""
    lines = text.split("\n")
    for i, line in enumerate(lines[:4]):
        m = _HASHES.search(line)
        if m and i >= 1 and "generated from" in lines[i - 1]:
            body = "\n".join(lines[: i - 1] + lines[i + 1 :])
            return Stamp(m.group(1), m.group(2), body)
    return None
