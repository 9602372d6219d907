"""One key scheme for every cache descgen keeps and every piece of evidence it commits.

A key is the sha256 of one canonical JSON document (keys sorted, no spaces, ASCII;
:func:`descgen.infra.evidence_hash.digest`) holding

- ``what`` and ``version``: the name of the computation and a constant kept beside the code
  that computes it, bumped by hand when that code gives other results (``collision.ALGORITHM``,
  ``sweep.ALGORITHM``, ``evidence_page.FORMAT``, ``control.record.FORMAT``, ...);
- ``inputs``: what the result is a function of (content hashes of files, model values,
  settings), JSON-able;
- ``descgen``: descgen's identity as it applies to the result (``scope``, below);
- ``libraries``: the installed version of each distribution that computes the result, read
  from its metadata without importing it (``"absent"`` when it is not installed), or the
  versions a record says computed it.

Scopes, from strict to loose:

- :data:`LOCAL`: results kept in the user cache folder (descgen/core/cache_dir.py) and read back on
  the same machine. The release, a hash of every byte of descgen's source and the interpreter to
  its patch release: any edit to descgen computes again. A local cache only costs time, and a
  developer who edits a rule must see the edit at once.
- :data:`EVIDENCE`: evidence committed beside a package and reused on other machines (the
  evidence page, the control run). The release and the interpreter's minor version; the code
  that computes the result is named by ``version``, not by its bytes, so an edit that changes
  no result (a comment, a docstring, a refactoring, another command) leaves the evidence
  current. A behaviour change without a bump of ``version`` is caught by
  tests/test_evidence_recompute.py, which computes every piece of evidence again with reuse
  refused (``DESCGEN_RECOMPUTE=1``) and compares it with the committed files.
- :data:`RELEASE`: committed results that the named libraries compute and that are recorded in
  a compared file (the collision matrix's key in the SRDF, the sweep's in evidence/sweep.md).
  The release only: the interpreter computes nothing of them, and a key that named it would
  make the SRDF read stale on a machine with another Python.
- :data:`NOTHING`: results no code of descgen shapes beyond ``version`` (compiled templates
  named by jinja2's version and the code generator's bytes, mesh facts named by their schema),
  or records rebuilt and compared by every ``check`` (the pose images' inputs).

Nothing here imports a library it names: versions come from the installed metadata
(descgen/infra/dist_version.py).
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Mapping
from typing import Any

from descgen.infra import evidence_hash

SCHEME = 1  # bump when the document below changes its layout: every key changes with it

LOCAL = ("release", "source", "python-patch")
EVIDENCE = ("release", "python")
RELEASE = ("release",)
NOTHING: tuple[str, ...] = ()
_PARTS = frozenset(LOCAL + EVIDENCE)


def identity(scope: tuple[str, ...]) -> dict[str, Any]:
    """descgen's identity as ``scope`` takes it (module doc)."""
    unknown = set(scope) - _PARTS
    if unknown:
        raise ValueError(f"unknown identity parts: {sorted(unknown)}")
    out: dict[str, Any] = {}
    if "release" in scope:
        from descgen import __version__

        out["descgen"] = __version__
    if "source" in scope:
        out["source"] = evidence_hash.source_digest()
    if "python" in scope:
        out["python"] = list(sys.version_info[:2])
    if "python-patch" in scope:
        out["python"] = list(sys.version_info[:3])
    return out


def libraries(names: Iterable[str] | Mapping[str, str]) -> dict[str, str]:
    """Distribution name -> version: the installed ones for names, a mapping as it is given
    (the versions a record says computed a result)."""
    if isinstance(names, Mapping):
        return {str(k): str(v) for k, v in names.items()}
    return evidence_hash.versions(*names)


def document(
    what: str,
    version: int | str,
    inputs: object,
    libraries_used: Iterable[str] | Mapping[str, str] = (),
    scope: tuple[str, ...] = LOCAL,
) -> dict[str, Any]:
    """What :func:`key` hashes (for a reader, and for the tests)."""
    if not what:
        raise ValueError("a key names what it computes")
    return {
        "scheme": SCHEME,
        "what": what,
        "version": version,
        "descgen": identity(scope),
        "libraries": libraries(libraries_used),
        "inputs": inputs,
    }


def key(
    what: str,
    version: int | str,
    inputs: object,
    libraries_used: Iterable[str] | Mapping[str, str] = (),
    scope: tuple[str, ...] = LOCAL,
) -> str:
    """The sha256 (64 hex digits) of :func:`document`: the one key of every cache and record."""
    return evidence_hash.digest(document(what, version, inputs, libraries_used, scope))
