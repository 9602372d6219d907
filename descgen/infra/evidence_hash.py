"""Reusing committed evidence when nothing it depends on changed.

Some evidence is slow to compute and cheap to verify: the self-collision matrix, the sweep,
the control run, the evidence page. Each records, beside its result, two hashes:

- ``input-sha256``: the key (descgen/infra/keys.py) of everything the result is a function of:
  the spec, the generated files, the versions of the libraries used, and descgen's part in it,
  named by the computation's format version and descgen's release (not by the bytes of its
  source: a comment or a refactoring leaves evidence current), so a change in any of them makes
  ``check`` compute again exactly as without the record;
- ``content-sha256``: the result itself as written, so a result edited by hand with the old
  input hash kept is not taken on trust (``check`` computes again and reports the file).

Only when both match does ``check`` take the committed result without computing it, and never
with ``DESCGEN_RECOMPUTE=1`` (:func:`recompute`): then every piece of evidence is computed again
and compared with the committed files, which is how tests/test_evidence_recompute.py catches a
behaviour change whose format version was not bumped. This module also holds the hashing
primitives the keys are made of. It sits below its users and imports nothing heavy.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import re
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
    by path and bytes: the identity of the local caches (descgen/infra/keys.py ``LOCAL``). Any
    edit to descgen, not only to the module that computes a result, counts: a cached result
    depends on the loader, the renderers and the checks too, and a local cache can afford to
    compute again. Committed evidence is named by format versions instead (keys.py)."""
    import descgen

    root = os.path.dirname(os.path.realpath(descgen.__file__))  # the package, not this folder
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
    """True when ``record`` holds this input hash and ``content`` is what was written (never
    while :func:`recompute`)."""
    return record is not None and record[0] == key and record[1] == sha256(content) and not recompute()


RECOMPUTE_ENV = "DESCGEN_RECOMPUTE"


def recompute() -> bool:
    """True when ``DESCGEN_RECOMPUTE`` is set to anything but "" or "0": committed evidence is
    then never reused (the collision matrix is sampled, the sweep, the control run and the
    evidence page are computed again) and ``check`` compares what it computed with the
    committed files. Read each time: a test may set it."""
    return os.environ.get(RECOMPUTE_ENV, "") not in ("", "0")
