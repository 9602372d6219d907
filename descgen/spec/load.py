"""Spec file -> SI robot model, or every problem found on the way."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, replace
from pathlib import Path

from pydantic import ValidationError

from ..audit import run as run_rules
from ..findings import Finding, InputError, errors
from ..model import Robot
from ..yamlsource import Document, load, loads
from .build import Builder, missing_sources, ranges_from
from .errors import findings_from
from .models import RobotSpec


@dataclass(frozen=True)
class Loaded:
    robot: Robot
    spec: RobotSpec
    doc: Document
    findings: tuple[Finding, ...]  # warnings and infos from the whole-model rules


def load_spec(path: str | Path, display: str | None = None, rules: bool = True) -> Loaded:
    """Read, validate and build one spec. Raises :class:`InputError` with every error.

    With ``rules=False`` the whole-model rules are not run (the audit runs them itself
    and reports their errors as findings, not as unusable input)."""
    p = Path(path)
    doc = load(p, display or str(path))
    return from_document(doc, rules)


def load_spec_text(text: str, file: str = "<string>", rules: bool = True) -> Loaded:
    return from_document(loads(text, file), rules)


def from_document(doc: Document, rules: bool = True) -> Loaded:
    if not isinstance(doc.data, dict):
        raise InputError(
            [
                Finding(
                    "SPEC003",
                    "error",
                    "a spec is a YAML mapping (name:, links:, joints:, ...)",
                    "see specs/warehouse_arm.yaml",
                    "spec",
                    doc.where(()),
                )
            ]
        )
    ranges, problems = ranges_from(doc)
    try:
        spec = RobotSpec.model_validate(doc.data, context={"ranges": ranges})
    except ValidationError as exc:
        raise InputError([*problems, *findings_from(exc, doc, RobotSpec)]) from None
    builder = Builder(doc, spec, ranges)
    robot = builder.build()
    problems += builder.findings
    if spec.require_sources:
        problems += missing_sources(doc, spec)
    digest = hashlib.sha256(doc.text.encode("utf-8")).hexdigest()
    robot = replace(robot, spec_hash=digest, extras={"ranges": ranges})
    findings = run_rules(robot, stage="input") if rules else []
    problems += errors(findings)
    if problems:
        raise InputError(_ordered(problems))
    return Loaded(robot, spec, doc, tuple(f for f in findings if f.severity != "error"))


def _ordered(findings: list[Finding]) -> list[Finding]:
    return sorted(findings, key=lambda f: (f.where.file, f.where.line, f.where.col, f.code))
