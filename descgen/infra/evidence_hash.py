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
    import os

    root = os.path.dirname(os.path.realpath(__file__))
    found: list[tuple[list[str], str]] = []
    # os.walk, not Path.rglob: a third of the time, and __pycache__ folders are not walked at all
    for folder, dirs, names in os.walk(root):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        rel = os.path.relpath(folder, root).replace(os.sep, "/")
        for name in names:
            path = os.path.join(folder, name)
            if os.path.isfile(path):
                found.append(((rel + "/" + name).removeprefix("./").split("/"), path))
    h = hashlib.sha256()
    for parts, path in sorted(found):  # by path components, as pathlib sorts
        with open(path, "rb") as fh:
            h.update("/".join(parts).encode("utf-8") + b"\0")
            h.update(hashlib.sha256(fh.read()).digest())
    return h.hexdigest()


def versions(*distributions: str) -> dict[str, str]:
    """The installed version of each distribution ("absent" when it is not installed)."""
    return {name: version(name) for name in distributions}


@functools.cache
def version(name: str) -> str:
    """``importlib.metadata.version(name)``, read from the metadata's header alone.

    ``metadata.version`` parses the whole METADATA file as an e-mail message, the project's long
    description included: 6-12 ms for pydantic or matplotlib, and every ``check`` asks for a
    dozen versions. The header ends at the first blank line (core metadata, RFC 822 layout);
    when it holds no Version field, ``metadata.version`` decides. A plain wheel install is read
    without importing importlib.metadata at all (descgen/infra/dist_version.py, ~25 ms of imports)."""
    from descgen.infra.dist_version import installed_version

    found = installed_version(name)
    if found is not None:
        return found
    from importlib import metadata

    try:
        dist = metadata.distribution(name)
    except metadata.PackageNotFoundError:
        return "absent"
    text = dist.read_text("METADATA") or dist.read_text("PKG-INFO") or ""
    for line in text.replace("\r\n", "\n").split("\n\n", 1)[0].split("\n"):
        if line[:8].lower() == "version:":
            return line[8:].strip()
    return str(dist.version)


def descgen_identity() -> dict[str, object]:
    """What every input hash holds about descgen itself and the interpreter it runs on. The
    interpreter by its minor version: committed evidence made with Python 3.11.7 is reused by a
    checkout on Debian 12's 3.11.2 (a patch release changes no result descgen computes; the
    libraries that compute results are named by their own versions)."""
    from descgen import __version__

    return {"descgen": __version__, "source": source_digest(), "python": sys.version_info[:2]}


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


def model_values(value: object) -> object:
    """A model value (descgen.core.model's frozen dataclasses, tuples, numbers, strings) as plain
    JSON-able data for :func:`digest`: every field by name, with each class's name, leaving out
    only ``Where`` (where a value was written changes no result, and paths differ by machine).
    A TypeError for anything else, so a value this cannot see whole is never keyed by part of it."""
    from descgen.core.findings import Where

    kind = type(value)
    if value is None or kind in (bool, int, str):
        return value
    if kind is float:
        return repr(value)  # exact, and NaN or -0.0 stay themselves
    if kind is tuple or kind is list:
        return [model_values(v) for v in value]  # type: ignore[attr-defined]
    if kind is Where:
        return None
    names = _FIELDS.get(kind, ()) or _fields(kind)
    if names is not None:
        got = [(n, getattr(value, n)) for n in names]
        return [kind.__name__, {n: model_values(v) for n, v in got if type(v) is not Where}]
    if isinstance(value, dict):
        return ["dict", [[model_values(k), model_values(v)] for k, v in value.items()]]
    if isinstance(value, (set, frozenset)):
        return ["set", sorted(json.dumps(model_values(v), sort_keys=True) for v in value)]
    from pathlib import PurePath

    if isinstance(value, PurePath):
        return ["path", str(value)]
    raise TypeError(f"no model value: {kind.__name__}")


_FIELDS: dict[type, tuple[str, ...] | None] = {}


def _fields(kind: type) -> tuple[str, ...] | None:
    """The field names of a dataclass (None for any other class), once per class."""
    import dataclasses

    names = tuple(f.name for f in dataclasses.fields(kind)) if dataclasses.is_dataclass(kind) else None
    _FIELDS[kind] = names
    return names


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
