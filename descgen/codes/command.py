"""Codes of the command line itself: options and arguments.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("command")


IMP008 = declare(
    "IMP008",
    "import-bad-units",
    "error",
    "--units of import names a unit that import does not write.",
    """Lengths are written in mm, cm or m, angles in deg or rad, masses in kg or g (or si for all SI).""",
)

RULE001 = declare(
    "RULE001",
    "unknown-code",
    "error",
    "`descgen rules CODE` names a code that is not in the catalogue.",
    """Every code descgen prints is in the catalogue, so an unknown one is a typo. Run descgen rules
      for the list.""",
)

UNIT021 = declare(
    "UNIT021",
    "option-time-out-of-range",
    "error",
    "A duration or wait option is outside its allowed range.",
    """Absurd durations would run for hours or prove nothing; option values are bounded like spec
      values (docs/security.md). Give a time in the range the message states.""",
)

VIEW001 = declare(
    "VIEW001",
    "viewer-not-installed",
    "error",
    "descgen view needs the optional viewer (viser with URDF support), which is not installed.",
    """The viewer is an optional extra so that descgen's proofs need no web stack. Install it with
      pip install 'descgen[view]'; its wheel ships the web client, so it works offline.""",
)
