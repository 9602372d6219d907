"""Codes of the command line itself: options and arguments.

One constant per code, named as the code, in code order; raise one as ``CODE.finding(...)``
(descgen/codes/registry.py)."""

from __future__ import annotations

from descgen.codes.registry import Stage

declare = Stage("command")


BASE001 = declare(
    "BASE001",
    "baseline-unreadable",
    "error",
    "The --baseline file cannot be read as a descgen baseline (missing, too large, not JSON, or not the "
    "shape --write-baseline writes).",
    """A baseline that is silently ignored would fail CI on every old finding, or worse, one read wrongly
      could hide new ones. Write it with descgen audit ... --write-baseline FILE.""",
)

BASE002 = declare(
    "BASE002",
    "baseline-entry-unused",
    "warning",
    "An entry of the --baseline file matches no finding of this audit: the finding was fixed (or renamed).",
    """Remove the entry (write the baseline again with --write-baseline): left in, it would accept the
      finding silently if it came back.""",
)

BASE003 = declare(
    "BASE003",
    "baseline-unwritable",
    "error",
    "The --write-baseline file cannot be written (a missing folder, no permission, a folder in the way).",
    """Nothing is written; the audit's findings are printed as usual. Name a writable file.""",
)

CAL010 = declare(
    "CAL010",
    "calibration-file-unreadable",
    "error",
    "A calibration file given to import-calibration cannot be read in the format named (missing, too large, not "
    "YAML or CSV, or a key, column or number the format requires is missing or not finite).",
    """A calibration read partly, or with a value guessed, would be applied to the robot as if measured. The
      message names the key, column or row; the formats are described in docs/calibration.md.""",
)

CAL011 = declare(
    "CAL011",
    "calibration-target-missing",
    "error",
    "A calibration file names a joint, sensor or frame the spec does not have (after the prefix), or a hand-eye "
    "result's frames are joined by a joint that moves.",
    """Each value is applied to the spec's own element; one that matches nothing would be lost, and a hand-eye
      transform is turned into the sensor's mount only through fixed joints. Give --prefix, --sensor, or fix the
      spec's names.""",
)

CAL012 = declare(
    "CAL012",
    "drift-input-unusable",
    "error",
    "descgen drift cannot use its input: the recording or CSV is unreadable, lacks a topic, column or joint the "
    "frame's chain needs, or has too few samples to fit.",
    """The residual and the identification need, for each sample, every moving joint between the base and the
      frame, and the frame's measured position. The message names what is missing.""",
)


CAL013 = declare(
    "CAL013",
    "calibration-entry-conflict",
    "error",
    "An imported calibration would replace a joint's or sensor's calibration that cites another source.",
    """An entry cites one source for all its values; merging values of two sources into it would credit one
      with the other's measurement, and replacing it silently would lose a calibration. Import under the same
      --source name to update it, or pass --replace to replace the entry whole.""",
)


FIX001 = declare(
    "FIX001",
    "fix-not-safe",
    "error",
    "descgen fix would change more than the findings it fixes (a link or joint, another finding), or the "
    "fixed spec does not read: nothing is written.",
    """A safe fix only renames what Jazzy renamed one to one or drops what Jazzy does not read; the spec is
      read again after the edit and held to that. Report the spec; fix it by hand as the hints say.""",
)

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
