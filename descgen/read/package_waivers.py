"""The waivers a generated package carries (``descgen-waivers.yaml`` at its root, written by
``generate`` from the spec's ``waivers:``), for ``descgen audit`` of a description inside that
package: the audit of the generated files then gives check's verdict, each waived finding
still reported, as waived, with the file named in its reason.

The file is someone else's data like any audited file (docs/security.md): YAML read safely
and bounded (descgen/infra/yamlsource.py), the file exactly as generate wrote it (its header's
content hash), each entry exactly a code, a subject and a reason, all strings; anything else is
READ049 at its line, never a guess at what it meant. Only the
package that holds the audited description is searched: the nearest folder above it with a
package.xml, at most a few levels up.
"""

from __future__ import annotations

import hashlib
import re
from pathlib import Path

from descgen.codes.read import READ049
from descgen.core.findings import InputError, Where
from descgen.core.model import WAIVERS_FILE, Waiver

_LEVELS = 4  # urdf/robot.urdf, urdf/sub/robot.urdf.xacro ... : a package's files sit a few folders down
_FIELDS = ("code", "subject", "reason")


def package_of(description: Path) -> Path | None:
    """The package folder holding ``description``: the nearest ancestor with a package.xml."""
    folder = description.absolute().parent
    for _ in range(_LEVELS):
        if (folder / "package.xml").is_file():
            return folder
        if folder.parent == folder:
            break
        folder = folder.parent
    return None


def waivers_for(description: Path) -> tuple[Waiver, ...]:
    """The waivers of the package that holds ``description``; none when it has no such file."""
    package = package_of(description)
    if package is None:
        return ()
    path = package / WAIVERS_FILE
    if not path.exists() and not path.is_symlink():
        return ()
    from descgen.infra import yamlsource  # only for a package that has the file: a URDF audit needs no YAML

    doc = yamlsource.load(path, str(path), what="waivers file")
    _generated(doc.text, Where(str(path), 1, 1))
    entries = doc.data.get("waivers") if isinstance(doc.data, dict) else None
    if not isinstance(doc.data, dict) or set(doc.data) != {"waivers"} or not isinstance(entries, list):
        raise _invalid(doc.where(()), "the file is not a mapping with one key, waivers:, holding a list")
    out = []
    for i, entry in enumerate(entries):
        where = doc.where(("waivers", i))
        if not isinstance(entry, dict) or set(entry) != set(_FIELDS):
            raise _invalid(where, "a waiver has exactly code, subject and reason")
        if not all(isinstance(entry[k], str) and entry[k] for k in _FIELDS):
            raise _invalid(where, "a waiver's code, subject and reason are non-empty strings")
        out.append(Waiver(entry["code"], entry["subject"], f"{entry['reason']} ({path.name})", where))
    return tuple(out)


_STAMP = re.compile(r"# descgen spec-sha256=[0-9a-f]{64} content-sha256=(?P<content>[0-9a-f]{64})")


def _generated(text: str, where: Where) -> None:
    """The file is one ``generate`` wrote and nobody edited since: its header's content hash
    (descgen/render/header.py) is the hash of the rest. A file that only looks like waivers (a
    third party's, or one in a folder above that is no package of this robot) is refused."""
    lines = text.split("\n", 2)
    stamp = _STAMP.fullmatch(lines[1]) if len(lines) == 3 else None
    if stamp is None or hashlib.sha256(lines[2].encode("utf-8")).hexdigest() != stamp["content"]:
        raise _invalid(where, "the file is not the one descgen generate wrote (no header, or edited since)")


def _invalid(where: Where, message: str) -> InputError:
    return InputError(
        [
            READ049.finding(
                message,
                "regenerate the package (descgen generate), or audit with --no-waivers to ignore the file",
                "file",
                where,
            )
        ]
    )
