"""Spec file -> SI robot model, or every problem found on the way."""

from __future__ import annotations

import bisect
import copy
import hashlib
import re
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from descgen.codes.spec import SPEC003, SPEC142
from descgen.core.findings import Finding, InputError, errors
from descgen.core.model import Robot
from descgen.core.naming import GLOBAL_FRAMES
from descgen.core.record import record
from descgen.core.units import Range
from descgen.infra import collector
from descgen.infra.yamlsource import Document, Path_, load, loads
from descgen.meshes.paths import resolve_spec, spec_file
from descgen.spec import calibration
from descgen.spec.build import Builder
from descgen.spec.compose import mounted
from descgen.spec.errors import data_path, findings_from
from descgen.spec.geometry import pose
from descgen.spec.models import RobotSpec
from descgen.spec.plausibility import ranges_from
from descgen.spec.quantity import MEMO, Measured
from descgen.spec.rules import derived_package_name, missing_sources


@record
class Loaded:
    robot: Robot
    spec: RobotSpec
    doc: Document
    findings: tuple[Finding, ...]  # warnings and infos from the whole-model rules


# The whole-model rules judge the built robot (descgen/audit/); the caller passes them, since a
# spec is read below the audit (descgen/audit/spec.py: load_spec, what the commands call).
Rules = Callable[[Robot], list[Finding]]


def read_spec(
    path: str | Path,
    display: str | None = None,
    rules: Rules | None = None,
    package_paths: Sequence[Path] = (),
    composing: tuple[Path, ...] = (),
) -> Loaded:
    """Read, validate and build one spec. Raises :class:`InputError` with every error.

    Without ``rules`` the whole-model rules are not run (the audit runs them itself
    and reports their errors as findings, not as unusable input). Mesh files are resolved
    beside the spec and in its ``package_paths:`` (then ``package_paths``), see
    descgen/meshes/paths.py; a spec given as text has no folder, so its meshes are not."""
    p = Path(path)
    with collector.paused():
        doc = load(p, display or str(path))
        return from_document(doc, rules, _Place(p, tuple(package_paths), composing))


def read_spec_text(text: str, file: str = "<string>", rules: Rules | None = None) -> Loaded:
    with collector.paused():
        return from_document(loads(text, file), rules)


@record
class _Place:
    """Where a spec file lies, for resolving the files it names (meshes)."""

    spec: Path
    package_paths: tuple[Path, ...] = ()
    composing: tuple[Path, ...] = ()  # the specs whose compose: led here, outermost first (cycles)


def from_document(doc: Document, rules: Rules | None = None, place: _Place | None = None) -> Loaded:
    if not isinstance(doc.data, dict):
        raise InputError(
            [
                SPEC003.finding(
                    "a spec is a YAML mapping (name:, links:, joints:, ...)",
                    "see specs/warehouse_arm.yaml",
                    "spec",
                    doc.where(()),
                )
            ]
        )
    ranges, problems = ranges_from(doc)
    try:
        spec = RobotSpec.model_validate(doc.data, context={"ranges": ranges, MEMO: {}})
    except ValidationError as exc:
        problems += findings_from(exc, doc, RobotSpec)
        # report the rest of the spec too, in the same run, if the model can still be built
        problems += _rules_despite(exc, doc, ranges, rules, place) if rules is not None else []
        raise InputError(_ordered(_unique(problems))) from None
    robot, built = _build(doc, spec, ranges, place)
    problems += errors(built)
    named = derived_package_name(doc, spec)
    problems += errors(named)
    findings = [f for f in named if f.severity != "error"]
    findings += [f for f in built if f.severity != "error"]  # the builder's warnings (SPEC114)
    findings += rules(robot) if rules is not None else []
    bad = _bad_paths(doc, built)
    if bad:  # a value the builder could not convert: rules judged a stand-in there
        inside = _inside(doc, bad)
        findings = [f for f in findings if not inside(f)]
    problems += errors(findings)
    if problems:
        # the warnings, infos and waived findings too: a spec refused for one error still shows
        # everything else its rules found, as a valid one would (issue 29)
        raise InputError(_ordered(_unique([*problems, *(f for f in findings if not f.blocks)])))
    return Loaded(robot, spec, doc, tuple(f for f in findings if not f.blocks))  # a waived error stays reported


def _build(
    doc: Document, spec: RobotSpec, ranges: dict[str, Range], place: _Place | None = None, stand_ins: bool = False
) -> tuple[Robot, list[Finding]]:
    builder = Builder(doc, spec, ranges, place.package_paths if place is not None else (), stand_ins)
    robot = builder.build()
    problems = list(builder.findings)
    if place is not None:  # before the rules, so they see the files (and a missing one is an input error)
        robot, unresolved = resolve_spec(robot, spec, doc.where, place.spec, place.package_paths)
        problems += unresolved
        if spec.calibration is not None and spec.calibration.drift is not None:
            check, refused = calibration.drift_check(
                place.spec, spec.calibration.drift, doc.where(("calibration", "drift", "samples"))
            )
            robot, problems = replace(robot, drift_check=check), problems + refused
    if spec.require_sources:
        problems += missing_sources(doc, spec)
    text = doc.text
    if spec.compose:
        robot, more, hashes = _composed(robot, spec, doc, place)
        problems += more
        text += "".join(f"\ncompose {h}" for h in hashes)  # a mounted robot's change is this spec's
    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
    rho = ranges.get("density")  # UNIT010 judges masses against the spec's plausibility
    density = None if rho is None else (rho.low, rho.high)
    return replace(robot, spec_hash=digest, density_range=density), problems


MAX_COMPOSE_DEPTH = 8  # specs composing specs: deeper is a mistake, not a robot


def _composed(
    robot: Robot, spec: RobotSpec, doc: Document, place: _Place | None
) -> tuple[Robot, list[Finding], list[str]]:
    """``robot`` with every ``compose:`` entry's robot mounted (descgen/spec/compose.py), the
    errors on the way (each mounted spec's own, located in it), and their spec hashes."""
    problems: list[Finding] = []
    hashes: list[str] = []
    for i, c in enumerate(spec.compose):
        where = doc.where(("compose", i, "spec"))

        def refused(why: str, hint: str) -> Finding:
            return SPEC142.finding(f"compose: {c.spec!r} {why}", hint, f"compose:{c.prefix}", where)  # noqa: B023

        if place is None:
            problems.append(refused("cannot be read: a spec given as text has no folder", "give the spec as a file"))
            continue
        target, why = spec_file(place.spec, c.spec)
        if target is None:
            problems.append(refused(why, "name a spec file relative to this one, inside the project"))
            continue
        chain = (*place.composing, place.spec.resolve())
        if target in chain:
            problems.append(refused("composes this spec again (a cycle)", "mount each robot once, not in a loop"))
            continue
        if len(chain) > MAX_COMPOSE_DEPTH:
            problems.append(refused(f"is nested deeper than {MAX_COMPOSE_DEPTH} specs", "flatten the composition"))
            continue
        shown = str(Path(doc.file).parent / c.spec)
        try:
            sub = read_spec(target, shown, None, place.package_paths, chain)
        except InputError as exc:
            blocking = [f for f in exc.findings if f.blocks]
            problems += [*blocking, refused(f"is refused ({len(blocking)} error(s) above)", "fix that spec first")]
            continue
        # behind this spec's own prefix too, when it has one: the composing robot's names carry it
        # already (spec/build.py applies it first), and the spec names its parent unprefixed
        own = robot.prefix.value if robot.prefix is not None else ""
        parent = c.parent if c.parent in GLOBAL_FRAMES else own + c.parent
        robot, more = mounted(
            robot, sub.robot, c.spec, own + c.prefix, parent, pose(c.origin), c.joint, where, c.source
        )
        problems += more
        hashes.append(sub.robot.spec_hash or "")
    return robot, problems, hashes


# -- every problem in one run --------------------------------------------------------------
#
# A schema error used to end the run before the model was built, so a spec with a wrong unit
# and a bad group reference needed two runs. When every schema error is a quantity that could
# not be read (or an unknown key), the model can still be built: each bad quantity is replaced
# by a stand-in and the key is dropped. The rules then judge a model that is partly made up,
# so a finding is kept only when it cannot come from a stand-in:
# - it is not located in an element (a link, a joint, a part, ...) that holds a bad value,
#   which is where a wrong value cascades ("3 kg" as a length must not also be "zero size");
# - it is the same with two different stand-ins, which drops the findings that a bad value
#   causes in another element (a wrong wheel offset changes the diff-drive separation).

_STAND_INS = (0.0, 0.123)  # SI magnitudes: zero, and a small value plausible for every kind


def _rules_despite(
    exc: ValidationError, doc: Document, ranges: dict[str, Range], rules: Rules, place: _Place | None = None
) -> list[Finding]:
    bad: list[Path_] = []
    drop: list[Path_] = []
    for err in exc.errors(include_url=False):
        path = data_path(doc.data, tuple(err["loc"]))
        if _QUANTITY.fullmatch(err["type"]):
            bad.append(path)
        elif err["type"] == "extra_forbidden":
            drop.append(path)
        else:
            return []  # a missing key, a bad name, a wrong shape: no model to judge
    runs: list[list[Finding]] = []
    for si in _STAND_INS:
        data = _patched(doc.data, bad, drop, Measured(si, "(stand-in)", "stand-in", "(stand-in)"))
        try:
            spec = RobotSpec.model_validate(data, context={"ranges": ranges})
        except ValidationError:
            return []
        robot, built = _build(doc, spec, ranges, place, stand_ins=True)
        inside = _inside(doc, [*bad, *drop, *_bad_paths(doc, built)])
        judged = [f for f in rules(robot) if not inside(f)]
        runs.append([*built, *judged])  # every severity: the warnings of the rest of the spec too
    again = {_key(f) for f in runs[1]}
    return [f for f in runs[0] if _key(f) in again]


_QUANTITY = re.compile(r"UNIT\d{3}")


def _key(f: Finding) -> tuple[str, str, int, int, str]:
    return (f.code, f.where.file, f.where.line, f.where.col, f.message)


def _patched(data: Any, bad: list[Path_], drop: list[Path_], stand_in: Measured) -> Any:
    out = copy.deepcopy(data)
    for path, remove in [*((p, False) for p in bad), *((p, True) for p in drop)]:
        if not path:
            continue
        parent = out
        try:
            for key in path[:-1]:
                parent = parent[key]
            if remove:
                del parent[path[-1]]
            else:
                parent[path[-1]] = stand_in
        except (KeyError, IndexError, TypeError):
            continue  # the path is not in the data (pydantic's loc named a validator)
    return out


def _bad_paths(doc: Document, built: list[Finding]) -> list[Path_]:
    """YAML paths of the values the builder could not convert (its UNIT findings)."""
    unconverted = [f for f in built if _QUANTITY.fullmatch(f.code)]
    if not unconverted:  # the usual case: no table of every mark (~40 ms at 1000 links)
        return []
    by_mark = {v: p for p, v in doc.value_marks.items()}
    out: list[Path_] = []
    for f in unconverted:
        path = by_mark.get((f.where.line, f.where.col))
        if path is not None:
            out.append(path)
    return out


def _element(path: Path_) -> Path_:
    """The element that holds the value at ``path``: up to its first list index
    (``links.3``, ``ros2_control.joints.2``), or its top-level section."""
    for i, key in enumerate(path):
        if isinstance(key, int):
            return path[: i + 1]
    return path[:1]


def _inside(doc: Document, bad: Sequence[Path_]) -> Callable[[Finding], bool]:
    """A test of whether a finding is located in the YAML lines of an element that holds a
    bad value (one of ``bad``).

    The line span of every element with a bad value comes from one pass over the marks, and
    each finding is then looked up in the merged spans (bisect): linear in the spec, whatever
    the number of findings and bad values (a rescan per finding and bad value was quadratic:
    300 unit errors took 100 s)."""
    elements = {_element(p) for p in bad}
    spans: dict[Path_, list[int]] = {}
    if elements:
        for table in (doc.value_marks, doc.key_marks):
            for p, (line, _) in table.items():
                # the elements that can hold p: the root, its section, up to its first index
                for e in ((), p[:1], _element(p)):
                    if e in elements:
                        span = spans.get(e)
                        if span is None:
                            spans[e] = [line, line]
                        elif line < span[0]:
                            span[0] = line
                        elif line > span[1]:
                            span[1] = line
    merged: list[list[int]] = []
    for lo, hi in sorted(spans.values()):
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    starts = [lo for lo, _ in merged]

    def inside(f: Finding) -> bool:
        if f.where.file != doc.file or not f.where.line:
            return False
        k = bisect.bisect_right(starts, f.where.line) - 1
        return k >= 0 and f.where.line <= merged[k][1]

    return inside


def _unique(findings: list[Finding]) -> list[Finding]:
    return list(dict.fromkeys(findings))


def _ordered(findings: list[Finding]) -> list[Finding]:
    return sorted(findings, key=lambda f: (f.where.file, f.where.line, f.where.col, f.code))
