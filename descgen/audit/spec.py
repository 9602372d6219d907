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


def validate_spec(path: str | Path, display: str | None = None, package_paths: Sequence[Path] = ()) -> Loaded:
    """``descgen validate``: the spec read and built, its model judged by every rule generate
    judges (the input-stage rules and the check-stage ones: a known pose off its forward
    kinematics, POSE010), each with the spec's waivers, so "valid" means generate's rules pass
    as well. Raises :class:`InputError` with every finding (warnings and infos beside the
    errors) when one blocks; else the findings are the Loaded's."""
    return read_spec(path, display, _every_rule, package_paths)


def _every_rule(robot: Robot) -> list[Finding]:
    return [*_input_rules(robot), *applied(run(robot, stage="check"), robot.waivers, check_stage)]
