"""Is the committed control evidence what its recorded run gives today? (part of ``descgen check``)

``descgen control`` records in ``verdict.json`` (key ``run``) what produced the evidence: the
trajectory file (relative to the project, as generated headers name the spec), the duration
and the plant. ``check`` runs that again in memory against the package on disk and compares
the data: CSV and JSON values (numbers to a relative 1e-9, so a last-digit difference of
another libm is not "stale"), the lifecycle and interface tables as text, and the messages of
the MCAP recording decoded. PNG bytes are not compared: they depend on matplotlib's version
and fonts, and what each plot draws is its joint's columns of desired_vs_measured.csv, which
are compared; every plot the run makes must exist.

The run imports rosbags and takes about half a second, so ``verdict.json`` also records (key
``reuse``, see descgen/infra/evidence_hash.py) the hash of the run's inputs (the record, the
trajectory file, the package's files outside evidence/, the libraries it uses, descgen's release
and ``record.FORMAT``: descgen/infra/keys.py) and the hash of what was written (every data
file, the recording's bytes, the plot names). When both match, ``check`` takes the evidence as
current without running it; else it runs and compares as described above.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import tempfile
from pathlib import Path
from typing import Any

from descgen.commands.control.evidence import plot_name, plot_names
from descgen.commands.control.record import RECORD_KEY, REUSE_KEY, input_key, project, reuse_record, written_content
from descgen.commands.control.system import FAULT_KINDS, Plant
from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import Robot
from descgen.infra import evidence_hash
from descgen.infra.safeio import MAX_DESCRIPTION_BYTES, read_bounded
from descgen.output.report import printable

_TEXT = ("lifecycle.md", "interfaces.md")  # renderings: compared as text
_REL, _ABS = 1e-9, 1e-12


def _reusable(folder: Path, package: Path, robot: Robot, committed: dict[str, Any], record: dict[str, Any]) -> bool:
    """True when the committed evidence records the inputs it has today and is what was
    written with them, and every plot the run draws is there (as the full check requires)."""
    reuse = committed.get(REUSE_KEY)
    tracking = committed.get("tracking")
    if not isinstance(reuse, dict) or not isinstance(tracking, dict):
        return False
    if sorted(p.name for p in folder.glob("*.png")) != sorted(plot_name(joint) for joint in tracking):
        return False  # a missing plot, or one of a joint the run does not track: the full check says which
    try:
        key, content = input_key(package, robot, record), written_content(folder, committed)
    except (InputError, OSError, ValueError):
        return False
    found = (str(reuse.get("input-sha256")), str(reuse.get("content-sha256")))
    return evidence_hash.reusable(found, key, content)


def check_evidence(package: Path, robot: Robot, spec_shown: str, refresh: bool = False) -> list[Finding]:
    """Findings for committed control evidence that its recorded run no longer reproduces.
    A package without ``evidence/verdict.json`` has no control evidence: nothing to check.
    ``refresh`` (``descgen report``): evidence the run was repeated for and found current gets
    its reuse record rewritten for today's inputs (its data is left as it is)."""
    folder = package / "evidence"
    verdict = folder / "verdict.json"
    if not verdict.is_file():
        return []
    stale = _Stale(folder, spec_shown)
    try:
        committed = json.loads(read_bounded(verdict, "verdict.json", MAX_DESCRIPTION_BYTES))
    except (InputError, ValueError):
        return [stale("verdict.json", "cannot be read as JSON")]
    record = committed.get(RECORD_KEY) if isinstance(committed, dict) else None
    plant = _plant(record)
    if plant is None or not isinstance(record, dict):
        return [stale("verdict.json", "does not record the run that produced it (trajectory, duration, plant)")]
    stale.record = record
    if _reusable(folder, package, robot, committed, record):
        return []  # run from these very inputs, and unchanged since
    with tempfile.TemporaryDirectory(prefix="descgen-evidence-") as tmp:
        try:
            fresh, expected = _rerun(package, robot, record, plant, Path(tmp))
        except InputError as exc:
            first = exc.findings[0].message if exc.findings else "the run failed"
            return [stale("verdict.json", f"cannot be reproduced: {first}")]
        found = _compare(folder, Path(tmp), fresh, expected, stale)
    if refresh and not found:
        record = reuse_record(folder, package, robot, committed)
        verdict.write_text(
            json.dumps({**{k: v for k, v in committed.items() if k != REUSE_KEY}, REUSE_KEY: record}, indent=2) + "\n",
            encoding="utf-8",
        )
    return found


def _plant(record: object) -> Plant | None:
    """The recorded plant, or None when the record is not one descgen writes."""
    if not isinstance(record, dict) or not isinstance(record.get("trajectory"), str):
        return None
    duration = record.get("duration_s")
    if duration is not None and (not isinstance(duration, int | float) or not math.isfinite(duration)):
        return None
    raw = record.get("plant")
    if not isinstance(raw, dict):
        return None
    try:
        plant = Plant(**raw)
    except TypeError:  # unknown or missing fields
        return None
    faults = plant.faults
    if plant.kind not in ("mock", "sim") or not isinstance(faults, dict):
        return None
    if any(not isinstance(j, str) or k not in FAULT_KINDS for j, k in faults.items()):
        return None
    return plant


def _rerun(
    package: Path, robot: Robot, record: dict[str, Any], plant: Plant, into: Path
) -> tuple[list[str], list[str]]:
    """Run the recorded trajectory again; write its evidence (without plots) into ``into``.
    Returns the files written and the plots the run would draw."""
    from descgen.commands.control.evidence import write_evidence
    from descgen.commands.control.run import run
    from descgen.commands.control.trajectory import read_trajectory

    path = Path(record["trajectory"])
    if not path.is_absolute():
        path = project(package) / path
    out = run(package, robot, read_trajectory(path, robot), record["duration_s"], plant)
    written = write_evidence(out, into, robot, plots=False)
    return written, plot_names(out)  # the names evidence._plots gives


class _Stale:
    """Builds the findings, each with the command that brings the evidence up to date."""

    def __init__(self, folder: Path, spec_shown: str) -> None:
        self.folder = folder
        self.spec = spec_shown
        self.record: dict[str, Any] = {}

    def hint(self) -> str:
        r = self.record
        if not r:
            return f"re-run descgen control {self.spec} --trajectory FILE (as before) and commit the result"
        cmd = f"descgen control {self.spec} --trajectory {printable(r['trajectory'], 200)}"
        if r.get("duration_s") is not None:
            cmd += f" --duration '{r['duration_s']:g} s'"
        plant = r.get("plant") or {}
        if plant.get("kind") == "sim":
            cmd += " --plant sim" + "".join(f" --plant-fault {j}:={k}" for j, k in plant.get("faults", {}).items())
        return f"re-run {cmd} and commit the result"

    def __call__(self, name: str, what: str, code: str = "GEN005") -> Finding:
        return Finding(
            code,
            "error",
            f"evidence/{name} {what}",
            self.hint(),
            f"file:evidence/{name}",
            Where(str(self.folder / name)),
        )


def _compare(folder: Path, fresh_dir: Path, written: list[str], plots: list[str], stale: _Stale) -> list[Finding]:
    found: list[Finding] = []
    for name in written:
        mine, theirs = folder / name.rstrip("/"), fresh_dir / name.rstrip("/")
        if not mine.exists():
            found.append(stale(name, "is missing", "GEN006"))
            continue
        same = _same_recording if name.endswith("/") else _same_file
        try:
            ok = same(mine, theirs, name)
        except (InputError, ValueError, OSError):
            ok = False
        if not ok:
            found.append(stale(name, "is stale: the recorded run gives different data today"))
    for name in plots:
        if not (folder / name).is_file():
            found.append(stale(name, "is missing", "GEN006"))
    # a plot of a joint the run no longer tracks
    for extra in sorted(p.name for p in folder.glob("*.png") if p.name not in plots):
        found.append(stale(extra, "is no longer produced by the recorded run", "GEN007"))
    return found


def _same_file(mine: Path, theirs: Path, name: str) -> bool:
    a = read_bounded(mine, name, MAX_DESCRIPTION_BYTES).decode("utf-8")
    b = theirs.read_text(encoding="utf-8")
    if name in _TEXT:
        return a == b
    if name.endswith(".csv"):
        return _same_rows(list(csv.reader(io.StringIO(a))), list(csv.reader(io.StringIO(b))))
    if name.endswith(".jsonl"):
        return _same_rows([json.loads(x) for x in a.splitlines()], [json.loads(x) for x in b.splitlines()])
    return _same(_data(json.loads(a)), _data(json.loads(b)))


def _data(verdict: object) -> object:
    """verdict.json without its reuse record (hashes of this machine's bytes, not data)."""
    return {k: v for k, v in verdict.items() if k != REUSE_KEY} if isinstance(verdict, dict) else verdict


def _same_rows(a: list[Any], b: list[Any]) -> bool:
    return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))


def _same(a: object, b: object) -> bool:
    """Equal data: numbers (also numbers written as text, as in a CSV) to a relative 1e-9."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return _same_rows(a, b)
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        return (math.isnan(x) and math.isnan(y)) or math.isclose(x, y, rel_tol=_REL, abs_tol=_ABS)
    return a == b


def _number(v: object) -> float | None:
    if isinstance(v, bool):
        return None
    if isinstance(v, int | float):
        return float(v)
    if isinstance(v, str):
        try:
            return float(v)
        except ValueError:
            return None
    return None


def _same_recording(mine: Path, theirs: Path, name: str) -> bool:
    return _same_rows(_messages(mine), _messages(theirs))


def _messages(bag: Path) -> list[Any]:
    """Every message of a rosbag2 folder, decoded: [topic, log time, stamp, names, positions]."""
    from rosbags.typesys import Stores, get_typestore

    from descgen.infra.bag_decompress import open_reader  # the recording on disk is data: it inflates to a bound

    ts = get_typestore(Stores.ROS2_JAZZY)
    out: list[Any] = []
    try:
        with contextlib.closing(open_reader(bag)) as reader:
            for conn, t, raw in reader.messages():
                msg: Any = ts.deserialize_cdr(raw, conn.msgtype)
                stamp = int(msg.header.stamp.sec) * 1_000_000_000 + int(msg.header.stamp.nanosec)
                out.append([conn.topic, t, stamp, list(msg.name), [float(x) for x in msg.position]])
    except Exception as exc:  # rosbags raises its own errors, YAML and OS errors on a broken recording
        raise ValueError(str(exc)) from None
    return out
