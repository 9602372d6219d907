"""A spec validated: read (descgen/spec/) and its built model judged by the input-stage rules,
the whole of ``descgen validate``. What every command that takes a spec calls."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from descgen.audit.registry import RULES, load, run
from descgen.audit.waivers import applied
from descgen.core.findings import Finding
from descgen.core.model import Robot
from descgen.spec.load import Loaded, read_spec, read_spec_text


def input_stage(code: str) -> bool:
    """Whether ``validate`` judges ``code``: an input-stage rule (the rest is generate's)."""
    load()
    info = RULES.get(code)
    return info is not None and info.stage == "input"


def check_stage(code: str) -> bool:
    """Whether ``generate``/``check`` judge ``code``: a check-stage rule (POSE010)."""
    load()
    info = RULES.get(code)
    return info is not None and info.stage == "check"


def _validate_judges(code: str) -> bool:
    # validate also judges a waiver of a code no rule has (a proof's, an input error's): it can
    # never match, so it is reported unused at once
    return input_stage(code) or not check_stage(code)


def _input_rules(robot: Robot) -> list[Finding]:
    """The input-stage rules over ``robot``, with the spec's waivers of those codes applied."""
    return applied(run(robot, stage="input"), robot.waivers, _validate_judges)


INPUT_RULES = _input_rules


def load_spec(
    path: str | Path, display: str | None = None, rules: bool = True, package_paths: Sequence[Path] = ()
) -> Loaded:
    """Read, validate and build one spec, its model judged by the rules (``rules=False``: not,
    the audit runs them itself). Raises :class:`InputError` with every error."""
    return read_spec(path, display, INPUT_RULES if rules else None, package_paths)


def load_spec_text(text: str, file: str = "<string>", rules: bool = True) -> Loaded:
    return read_spec_text(text, file, INPUT_RULES if rules else None)


def validate_spec(
    path: str | Path, display: str | None = None, package_paths: Sequence[Path] = ()
) -> tuple[Loaded, list[Finding]]:
    """``descgen validate``: the spec loaded (:func:`load_spec`, InputError when it cannot be
    built or an input-stage rule fails), then the check-stage rules too (a known pose off its
    forward kinematics, POSE010) with the spec's waivers of them, so "valid" means generate's
    rules pass as well. Returns the loaded spec and the check-stage findings."""
    from descgen.audit.waivers import applied

    loaded = load_spec(path, display, True, package_paths)
    later = applied(run(loaded.robot, stage="check"), loaded.robot.waivers, check_stage)
    return loaded, later
