"""Reusing committed evidence when nothing it depends on changed.

Some evidence is slow to compute and cheap to verify: the self-collision matrix, the sweep,
the control run, the evidence page. Each records, beside its result, two hashes:

- ``input-sha256``: everything the result is a function of (the spec, the generated files,
  descgen's version and a hash of descgen's own source files, the versions of the tools used),
  so a change in any of them makes ``check`` compute again exactly as without the record;
- ``content-sha256``: the result itself as written, so a result edited by hand with the old
  input hash kept is not taken on trust (``check`` computes again and reports the file).

Only when both match does ``check`` take the committed result without computing it.
This module sits below its users (generate, the control evidence, the evidence page) and
imports nothing heavy.
"""

from __future__ import annotations

import functools
import hashlib
import json
import re
import sys
from pathlib import Path

STAMP = re.compile(r"descgen input-sha256=([0-9a-f]{64}) content-sha256=([0-9a-f]{64})")


def sha256(data: bytes | str) -> str:
    return hashlib.sha256(data.encode("utf-8") if isinstance(data, str) else data).hexdigest()


def digest(value: object) -> str:
    """The hash of a JSON-able value (keys sorted: the same value, the same hash)."""
    return sha256(json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=True))


@functools.cache
def source_digest() -> str:
    """descgen's own code: every file of the installed package (modules, templates, data),
    by path and bytes. Any edit to descgen, not only to the module that computes a result,
    counts: a result depends on the loader, the renderers and the checks too, and telling
    which files matter would be a guess that could go stale."""
    root = Path(__file__).resolve().parent
    h = hashlib.sha256()
    for path in sorted(p for p in root.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        h.update(path.relative_to(root).as_posix().encode("utf-8") + b"\0")
        h.update(hashlib.sha256(path.read_bytes()).digest())
    return h.hexdigest()


def versions(*distributions: str) -> dict[str, str]:
    """The installed version of each distribution ("absent" when it is not installed)."""
    from importlib import metadata

    out = {}
    for name in distributions:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "absent"
    return out


def descgen_identity() -> dict[str, object]:
    """What every input hash holds about descgen itself and the interpreter it runs on."""
    from . import __version__

    return {"descgen": __version__, "source": source_digest(), "python": sys.version_info[:3]}


def package_files(package: Path, skip: tuple[str, ...] = ()) -> dict[str, str]:
    """Relative path -> sha256 of every regular file under ``package`` (links are named but
    not followed), leaving out paths that start with one of ``skip``."""
    out: dict[str, str] = {}
    if not package.is_dir():
        return out
    for path in sorted(package.rglob("*")):
        rel = path.relative_to(package).as_posix()
        if rel.startswith(skip) or (path.is_dir() and not path.is_symlink()):
            continue
        out[rel] = "link" if path.is_symlink() or not path.is_file() else sha256(path.read_bytes())
    return out


def stamp(key: str, content: str) -> str:
    """The record to write beside a result: its input hash and the hash of ``content``."""
    return f"descgen input-sha256={key} content-sha256={sha256(content)}"


def recorded(text: str) -> tuple[str, str] | None:
    """(input hash, content hash) of the first stamp in ``text``; None when there is none."""
    found = STAMP.search(text)
    return (found.group(1), found.group(2)) if found else None


def reusable(record: tuple[str, str] | None, key: str, content: str) -> bool:
    """True when ``record`` holds this input hash and ``content`` is what was written."""
    return record is not None and record[0] == key and record[1] == sha256(content)
