"""The one catalogue of finding codes: every code any command can print, with its rationale.

Audit rules register themselves with ``@rule`` (descgen/audit/registry.py) and their
docstring is their documentation. Every other code (the spec loader, the readers,
``generate``/``check``, ``control``, the recording commands, the command line) is declared in
the module of its stage, descgen/codes/<group>.py (``import`` is importer.py), as a constant
named as the code, and raised through it: ``GEN005.finding(message, hint, subject, where)``.
descgen/codes/registry.py holds the machinery. :func:`descgen.audit.catalogue.explain` and
``entries`` read both, so ``descgen rules CODE`` and SARIF rule help cover every code.

Codes are stable: a code keeps its meaning, and a retired code is never reused (its entry
stays, marked retired, and cannot be raised). A code registered twice fails at import time,
here or in ``@rule``. Importing this package registers every stage's codes.
"""

from __future__ import annotations

from descgen.codes import (  # noqa: F401 - each stage registers its codes when imported
    command,
    control,
    generate,
    graph,
    importer,
    read,
    recording,
    simulate,
    spec,
    sweep,
)
from descgen.codes.registry import (
    CODE_PATTERN,
    CODES,
    GROUPS,
    NAMES,
    AnyCode,
    Code,
    Entry,
    Redirected,
    Retired,
    SeverityOrVaries,
    Stage,
    Status,
    StatusName,
    VaryingCode,
    doc_of,
    raisable,
    register,
    status_name,
    status_note,
)

__all__ = [
    "CODES",
    "CODE_PATTERN",
    "GROUPS",
    "NAMES",
    "AnyCode",
    "Code",
    "Entry",
    "Redirected",
    "Retired",
    "SeverityOrVaries",
    "Stage",
    "Status",
    "StatusName",
    "VaryingCode",
    "doc_of",
    "raisable",
    "register",
    "status_name",
    "status_note",
]
