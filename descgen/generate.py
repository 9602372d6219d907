"""``generate`` and ``check``: render the package, prove it, then write it (all or nothing)
or compare it with what is committed.

This module is where generated files are written (:func:`write_package`).
"""

from __future__ import annotations

import difflib
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from . import checks
from .findings import Finding, Where, errors
from .model import Robot
from .render import header, render_package
from .render.context import package_name
from .spec import load_spec


@dataclass(frozen=True)
class Plan:
    robot: Robot
    files: dict[str, str]
    package_dir: Path
    findings: tuple[Finding, ...]  # warnings from the spec, errors and warnings from the checks


@dataclass
class Outcome:
    findings: list[Finding] = field(default_factory=list)
    written: list[str] = field(default_factory=list)
    unchanged: list[str] = field(default_factory=list)
    removed: list[str] = field(default_factory=list)
    diff: str = ""

    @property
    def failed(self) -> bool:
        return bool(errors(self.findings))


def default_out(spec: Path) -> Path:
    """``generated/`` beside ``specs/`` (or beside the spec when it is not in a specs folder)."""
    parent = spec.resolve().parent
    return parent.parent / "generated" if parent.name == "specs" else parent / "generated"


def spec_display(spec: Path, out_root: Path) -> str:
    """How the header names the spec: relative to the project (the folder holding the
    output root), so it is the same from any working directory and on any machine."""
    try:
        return spec.resolve().relative_to(out_root.resolve().parent).as_posix()
    except ValueError:
        return spec.name


def plan(spec: Path, out_root: Path | None = None, templates: Path | None = None) -> Plan:
    """Load, render and prove one spec. Raises InputError for invalid input."""
    root = out_root or default_out(spec)
    loaded = load_spec(spec)
    robot = loaded.robot
    files = render_package(robot, spec_display(spec, root), templates)
    package_dir = root / package_name(robot)
    found = [*loaded.findings, *checks.run_all(files, robot, package_dir)]
    return Plan(robot, files, package_dir, tuple(found))


def _hand_edited(package_dir: Path, files: dict[str, str]) -> list[str]:
    """Files we would overwrite that are not as descgen wrote them."""
    edited = []
    for rel in files:
        target = package_dir / rel
        if not target.is_file():
            continue
        stamp = header.read(target.read_text(encoding="utf-8", errors="replace"))
        if stamp is None or stamp.hand_edited:
            edited.append(rel)
    return edited


# What generate owns; other commands may add their own evidence to the package.
_OWN_DIRS = {"urdf", "srdf", "config", "launch", "rviz", "package.xml", "CMakeLists.txt"}
_OWN_FILES: set[str] = {"evidence/known_poses.md", "evidence/frames.md", "evidence/frames.dot"}


def _ours(package_dir: Path) -> list[str]:
    """Files of the package that ``generate`` wrote earlier (they carry its header)."""
    found: list[str] = []
    if not package_dir.is_dir():
        return found
    for p in sorted(package_dir.rglob("*")):
        if p.is_file():
            try:
                head = p.read_text(encoding="utf-8")[:600]
            except (UnicodeDecodeError, OSError):
                continue
            rel = p.relative_to(package_dir).as_posix()
            if header.MARK in head and (rel.split("/")[0] in _OWN_DIRS or rel in _OWN_FILES):
                found.append(rel)
    return found


def write_package(package_dir: Path, files: dict[str, str]) -> Outcome:
    """Write every file into a scratch folder beside the package, then move each into
    place. Nothing is moved unless everything was written; files descgen wrote earlier
    and no longer produces are removed; other files are left alone."""
    out = Outcome()
    package_dir.parent.mkdir(parents=True, exist_ok=True)
    stale = [rel for rel in _ours(package_dir) if rel not in files]
    scratch = Path(tempfile.mkdtemp(prefix=".descgen-", dir=package_dir.parent))
    try:
        for rel, text in files.items():
            target = package_dir / rel
            if target.is_file() and target.read_text(encoding="utf-8", errors="replace") == text:
                out.unchanged.append(rel)
                continue
            tmp = scratch / rel
            tmp.parent.mkdir(parents=True, exist_ok=True)
            with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
            out.written.append(rel)
        for rel in out.written:
            target = package_dir / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            os.replace(scratch / rel, target)
        for rel in stale:
            (package_dir / rel).unlink()
            out.removed.append(rel)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return out


def generate(spec: Path, out_root: Path | None = None, templates: Path | None = None, force: bool = False) -> Outcome:
    p = plan(spec, out_root, templates)
    outcome = Outcome(findings=list(p.findings))
    if outcome.failed:
        return outcome
    edited = [] if force else _hand_edited(p.package_dir, p.files)
    if edited:
        for rel in edited:
            outcome.findings.append(
                Finding(
                    "GEN004",
                    "error",
                    f"{rel} was edited by hand (its content no longer matches its header); not overwritten",
                    "move the change into the spec or a template, or run with --force to discard it",
                    f"file:{rel}",
                    Where(str(p.package_dir / rel)),
                )
            )
        return outcome
    written = write_package(p.package_dir, p.files)
    written.findings = outcome.findings
    draw_frames(p.package_dir)
    return written


def draw_frames(package_dir: Path) -> None:
    """evidence/frames.svg from frames.dot when Graphviz's dot is installed. Its bytes depend
    on the Graphviz version, so it is not part of what check compares (and not committed)."""
    dot = shutil.which("dot")
    source = package_dir / "evidence" / "frames.dot"
    if dot is None or not source.is_file():
        return
    import subprocess

    subprocess.run(
        [dot, "-Tsvg", str(source), "-o", str(source.with_suffix(".svg"))], check=False, capture_output=True, timeout=60
    )


def check(spec: Path, out_root: Path | None = None, templates: Path | None = None) -> Outcome:
    """Regenerate in memory and compare with the files on disk; run every check."""
    p = plan(spec, out_root, templates)
    outcome = Outcome(findings=list(p.findings))
    diffs: list[str] = []
    for rel, fresh in p.files.items():
        target = p.package_dir / rel
        where = Where(str(target))
        if not target.is_file():
            outcome.findings.append(
                Finding("GEN006", "error", f"{rel} is missing", "run descgen generate", f"file:{rel}", where)
            )
            continue
        current = target.read_text(encoding="utf-8", errors="replace")
        if current == fresh:
            continue
        stamp = header.read(current)
        if stamp is not None and stamp.hand_edited:
            what, hint, code = "was edited by hand", "move the change into the spec or a template", "GEN004"
        elif stamp is not None and stamp.spec_hash != p.robot.spec_hash:
            what, hint, code = "is stale: the spec changed", "run descgen generate and commit the result", "GEN005"
        else:
            what, hint, code = (
                "is stale: templates or descgen changed",
                "run descgen generate and commit the result",
                "GEN005",
            )
        outcome.findings.append(Finding(code, "error", f"{rel} {what}", hint, f"file:{rel}", where))
        diffs.append(
            "".join(
                difflib.unified_diff(
                    current.splitlines(keepends=True),
                    fresh.splitlines(keepends=True),
                    fromfile=f"a/{rel}",
                    tofile=f"b/{rel}",
                )
            )
        )
    for rel in _ours(p.package_dir):
        if rel not in p.files:
            outcome.findings.append(
                Finding(
                    "GEN007",
                    "error",
                    f"{rel} is no longer generated",
                    "run descgen generate",
                    f"file:{rel}",
                    Where(str(p.package_dir / rel)),
                )
            )
    outcome.diff = "".join(diffs)
    return outcome
