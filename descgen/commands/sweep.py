"""``descgen sweep``: the description read as the other commands read it, then swept
(descgen/physics/sweep/)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from descgen.commands.generate import plan
from descgen.core.findings import Finding, InputError
from descgen.infra.safeio import check_file
from descgen.physics.sweep import Settings, Sweep, compute, findings
from descgen.read.description import Options, kind_of, load_description, with_given_files


def sweep_description(
    path: Path, options: Options, settings: Settings, progress: Callable[[str], None] | None = None
) -> tuple[Sweep, list[Finding]]:
    """``descgen sweep``: a spec as generate sees it (with its sampled matrix), or a URDF or
    Xacro (``options``: read.description.Options, its SRDF for the disabled pairs)."""
    check_file(path, "description", display=str(path))
    read: list[Finding] = []
    if kind_of(path) == "spec":
        # an --srdf or --controllers given with a spec stands in for the spec's own, as in audit
        robot, read = with_given_files(plan(path, package_paths=options.package_paths).robot, options)
    else:
        robot, read = load_description(path, options)
    sw = compute(robot, settings, progress)
    if sw.too_large:  # nothing to show: unusable input for this command (exit 2), as a file too large
        raise InputError([*read, *findings(sw)])
    return sw, [*read, *findings(sw)]
