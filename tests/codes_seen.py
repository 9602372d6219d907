"""Every finding code descgen made during the test session must be in the catalogue.

``install()`` wraps ``Finding.__init__`` so that each finding made by descgen's own code
(not a test's hand-made one) records its code. Each process (the single pytest process,
or each pytest-xdist worker) writes its set to a file in one folder shared through the
environment; the controlling process reads them all at the end and fails the session
when a code is not in ``descgen.codes`` (see conftest.py).
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import uuid
from pathlib import Path
from typing import Any

from descgen.core.findings import Finding

ENV = "DESCGEN_CODES_SEEN_DIR"
SEEN: dict[str, str] = {}  # code -> the descgen module that made it first

_original_init = Finding.__init__
_HELPERS = {"descgen.audit.registry", "descgen.codes.registry"}  # build a finding for their caller


def _recording_init(self: Finding, *args: Any, **kwargs: Any) -> None:
    _original_init(self, *args, **kwargs)
    # who called Finding(...): descgen's code, or a test planting a finding of its own; for
    # registry.at() (a helper every rule calls) it is the rule that called it, and for
    # CODE.finding(...) (descgen/codes/registry.py) the module that raised the code
    frame = sys._getframe(1)
    caller = frame.f_globals.get("__name__", "")
    if caller in _HELPERS and frame.f_back is not None:
        caller = frame.f_back.f_globals.get("__name__", "")
    if caller.startswith("descgen") and self.code not in SEEN:
        SEEN[self.code] = caller


def install() -> None:
    Finding.__init__ = _recording_init  # type: ignore[method-assign]


def uninstall() -> None:
    Finding.__init__ = _original_init  # type: ignore[method-assign]


def shared_dir() -> Path:
    """The folder all processes of this session write to (made by the first, the controller)."""
    if ENV not in os.environ:
        os.environ[ENV] = tempfile.mkdtemp(prefix="descgen-codes-")
    return Path(os.environ[ENV])


def dump() -> None:
    path = shared_dir() / f"{os.getpid()}-{uuid.uuid4().hex}.json"
    path.write_text(json.dumps(SEEN))


def collect() -> dict[str, str]:
    seen: dict[str, str] = {}
    for f in sorted(shared_dir().glob("*.json")):
        for code, where in json.loads(f.read_text()).items():
            seen.setdefault(code, where)
    return seen


def unregistered(seen: dict[str, str]) -> dict[str, str]:
    """The codes in ``seen`` that ``descgen rules`` cannot explain, or that it explains as
    retired or redirected (such a code is no longer raised: a hand-built Finding slipped past)."""
    from descgen.audit.catalogue import entries

    stable = {e.code for e in entries() if e.status == "stable"}
    return {code: where for code, where in sorted(seen.items()) if code not in stable}
