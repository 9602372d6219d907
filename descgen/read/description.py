"""``descgen audit``: read any description (spec, URDF, Xacro; plus SRDF and controllers
YAML) into the model, resolve its mesh files, and run every rule."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import MeshState, Robot, Ros2Control, Waiver
from descgen.infra.safeio import check_file, read_bounded, read_head
from descgen.meshes import paths as mesh_paths

if TYPE_CHECKING:
    from descgen.audit import findings_cache
    from descgen.infra.progress import Step

# The readers (lxml) and the rules are imported where they are used: an audit answered from the
# findings cache (descgen/audit/findings_cache.py) needs neither.


@dataclass(frozen=True)
class Options:
    srdf: Path | None = None
    controllers: Path | None = None
    xacro_args: Mapping[str, str] = field(default_factory=dict)
    package_paths: Sequence[Path] = ()
    trust_xacro: bool = False  # expand with xacro's own evaluator (runs the file's Python)
    moveit_config: Path | None = None  # a MoveIt config package (MOVEIT rules; descgen/read/moveit_package.py)
    launch_args: Mapping[str, str] = field(default_factory=dict)  # $(var NAME) in the controllers YAML
    package_waivers: bool = True  # the waivers a generated package carries (descgen/read/package_waivers.py)


def kind_of(path: Path) -> str:
    name = path.name.lower()
    if name.endswith((".yaml", ".yml")):
        return "spec"
    if name.endswith(".xacro"):
        return "xacro"
    if name.endswith(".urdf"):
        return "urdf"
    head = read_head(path, 4096)  # not read_bytes()[:4096]: that reads all of a 1 GB file (or /dev/zero)
    return "xacro" if b"xmlns:xacro" in head else "urdf"


def mesh_status(robot: Robot, description: Path, package_paths: Sequence[Path]) -> dict[str, MeshState]:
    """ok | missing | escapes | unresolved, for every mesh filename (descgen/meshes/paths.py)."""
    return mesh_paths.mesh_status(robot, description, package_paths)[0]


def load_description(
    path: Path, options: Options = Options(), given: Mapping[Path, bytes] | None = None
) -> tuple[Robot, list[Finding]]:
    """The model of one description and what its readers reported. InputError when unusable.
    ``given`` holds bytes already read of the URDF, SRDF or controllers YAML: those are read,
    not the files again (the findings cache keys an audit by exactly the bytes it audited)."""
    given = given or {}
    shown = str(path)
    check_file(path, "description", display=shown)  # missing, a FIFO, a device, too large: before any read
    kind = kind_of(path)
    found: list[Finding] = []
    if kind == "spec":
        from descgen.audit.spec import load_spec

        robot = load_spec(path, shown, rules=False, package_paths=options.package_paths).robot
    else:
        sources = None  # a Xacro's: where each expanded element was written, so findings point there
        if kind == "xacro":
            from descgen.read.xacro_file import expand_located  # not for a plain URDF

            expansion = expand_located(path, shown, options.xacro_args, options.package_paths, options.trust_xacro)
            data, sources = expansion.xml, expansion.sources
        else:
            data = given[path] if path in given else read_bounded(path, "URDF", display=shown)
        display = f"{shown} (expanded)" if kind == "xacro" else shown
        from descgen.read.urdf import read_urdf_text

        robot, found = read_urdf_text(data, display, sources)
        if kind == "xacro":
            from descgen.read.xacro_prefix import declared

            robot = dataclasses.replace(robot, prefix=declared(path, shown, options.xacro_args))
    robot, more = with_given_files(robot, options, given)
    found += more
    if kind == "spec":  # the spec loader resolved its meshes (and refused any it could not find)
        return robot, found
    status, files = mesh_paths.mesh_status(robot, path, options.package_paths)
    resolved = tuple((name, str(p)) for name, p in files.items())
    return dataclasses.replace(robot, mesh_status=tuple(status.items()), mesh_files=resolved), found


def with_given_files(
    robot: Robot, options: Options, given: Mapping[Path, bytes] | None = None
) -> tuple[Robot, list[Finding]]:
    """``robot`` with the SRDF, controllers YAML and MoveIt config named on the command line in
    place of its own, and what their readers reported (``given``: as load_description)."""
    found: list[Finding] = []
    given = given or {}
    if options.srdf is not None:
        from descgen.read.srdf import read_srdf_text

        data, shown, sources = srdf_bytes(options, given)
        semantic, srdf_name, more = read_srdf_text(data, shown, sources)
        found += more
        robot = dataclasses.replace(robot, semantic=dataclasses.replace(semantic, robot_name=srdf_name))
    if options.controllers is not None:
        from descgen.read.controllers import read_controllers_file  # PyYAML only when a YAML is given

        cf = read_controllers_file(
            _read(options.controllers, "controllers YAML", given).decode("utf-8", "replace"),
            str(options.controllers),
            options.launch_args,
        )
        found += cf.found
        rc = robot.ros2_control or Ros2Control("", where=Where(str(options.controllers)))
        robot = dataclasses.replace(
            robot,
            ros2_control=dataclasses.replace(
                rc, controllers=cf.controllers, update_rate=cf.update_rate, update_rate_where=cf.update_rate_where
            ),
        )
    if options.moveit_config is not None:  # its SRDF and ros2_controllers.yaml only when not given
        from descgen.read.moveit_package import attach

        robot, more = attach(
            robot, options.moveit_config, read_srdf=options.srdf is None, read_controllers=options.controllers is None
        )
        found += more
    return robot, found


def srdf_bytes(
    options: Options, given: Mapping[Path, bytes] | None = None
) -> tuple[bytes, str, Sequence[Where | None] | None]:
    """The SRDF's bytes, how findings name it, and (for an ``.srdf.xacro``, which MoveIt packages
    ship) where each expanded element was written: it is expanded in the same sandbox, with the
    same --xacro-arg values, as a URDF Xacro."""
    assert options.srdf is not None
    shown = str(options.srdf)
    if not options.srdf.name.endswith(".xacro"):
        return _read(options.srdf, "SRDF", given or {}), shown, None
    from descgen.read.xacro_file import expand_located

    expansion = expand_located(options.srdf, shown, options.xacro_args, options.package_paths, options.trust_xacro)
    return expansion.xml, shown, expansion.sources


def _read(path: Path, what: str, given: Mapping[Path, bytes]) -> bytes:
    return given[path] if path in given else read_bounded(path, what)


def audit(path: Path, options: Options = Options()) -> list[Finding]:
    """Every finding for one description: what its readers reported, then every rule; for a
    plain URDF audited again unchanged, last run's (descgen/audit/findings_cache.py)."""
    from descgen.audit import findings_cache
    from descgen.audit.registry import run

    kept = _cache_inputs(path, options)
    hit = findings_cache.get(kept) if kept is not None else None
    if hit is not None:
        found = hit
    else:
        robot, found = load_description(path, options, kept.data if kept is not None else None)
        found += run(robot)
        if robot.waivers:  # a spec's: its rules' findings waived as validate and generate waive them
            from descgen.audit.waivers import applied

            found = applied(found, _rule_waivers(robot.waivers), lambda code: True)
        if kept is not None:
            findings_cache.put(kept, robot, found)
    if options.package_waivers and kind_of(path) != "spec":
        # the file generate wrote beside the description (the spec's waivers): the audit of the
        # generated files gives check's verdict. Not cached with the findings: it may change alone
        from descgen.audit.waivers import waive
        from descgen.read.package_waivers import waivers_for

        waivers = waivers_for(path)
        if waivers:  # the rules are imported only to apply some (a cache hit imports none)
            found = waive(found, _rule_waivers(waivers))
    return found


def _rule_waivers(waivers: Sequence[Waiver]) -> tuple[Waiver, ...]:
    """Only a rule's finding can be waived: a proof or an input error is fixed, not waived."""
    from descgen.audit.registry import RULES, load

    load()
    return tuple(w for w in waivers if w.code in RULES)


def audit_paths(
    paths: Sequence[Path], options: Options = Options(), jobs: int = 1, step: Step | None = None
) -> tuple[list[Finding], bool]:
    """Every finding of every description in ``paths``, in their order, and whether any was
    unusable (its input errors are among the findings, so one unreadable file does not hide
    the others'). ``jobs`` > 1 audits that many at once in separate processes (an audit is
    CPU-bound Python; descgen/infra/workers.py: a worker that dies is replaced by this process; a
    worker ends without atexit, and keeps the mesh facts it measured because descgen/meshes/load.py
    saves the index as it measures); ``step(1)`` is called as each one is done."""
    from functools import partial

    from descgen.infra.workers import map_in_processes

    if jobs > 1 and len(paths) > 1:
        from descgen.audit.registry import load
        from descgen.read import urdf  # noqa: F401  (imported once here: forked workers start with it)

        load()
    outcomes = map_in_processes(partial(_audit_one, options=options), paths, jobs, step)
    found = [f for fs, _ in outcomes for f in fs]
    return found, any(unusable for _, unusable in outcomes)


def audit_together(
    paths: Sequence[Path],
    options: Options,
    controllers: Sequence[Path],
    srdfs: Sequence[Path],
    step: Step | None = None,
) -> tuple[list[Finding], bool]:
    """``audit_paths`` for robots of one ROS graph, then what they get wrong beside each other
    (descgen/audit/together.py). Each URDF or Xacro is one robot: the i-th of ``controllers`` and
    ``srdfs`` (when given) is the i-th URDF's or Xacro's; a spec brings its own."""
    from descgen.audit import together
    from descgen.codes.graph import GRAPH010

    if options.moveit_config is not None:
        raise InputError(
            [
                GRAPH010.finding(
                    "--moveit-config is given with --together; a MoveIt config package is one robot's",
                    "audit the robot with its MoveIt config on its own, and the robots together without it",
                    "option",
                    Where("<command line>"),
                )
            ]
        )
    described = [p for p in paths if kind_of(p) != "spec"]
    for option, files in (("--controllers", controllers), ("--srdf", srdfs)):
        if files and len(files) != len(described):
            raise InputError(
                [
                    GRAPH010.finding(
                        f"{option} is given {len(files)} time(s) for {len(described)} URDF or Xacro file(s)",
                        f"with --together, give {option} once per URDF or Xacro, in their order (a spec brings its "
                        "own), or not at all",
                        "option",
                        Where("<command line>"),
                    )
                ]
            )
    per_path: list[Options] = []
    k = 0
    for p in paths:
        if kind_of(p) == "spec":
            per_path.append(options)
            continue
        per_path.append(
            dataclasses.replace(
                options,
                controllers=controllers[k] if controllers else None,
                srdf=srdfs[k] if srdfs else None,
            )
        )
        k += 1
    found: list[Finding] = []
    unusable = False
    robots: list[together.Labelled] = []
    for p, opts in zip(paths, per_path, strict=True):
        fs, bad = _audit_one(p, opts)
        found += fs
        unusable = unusable or bad
        if not bad:
            # the models again: the audit above may have been answered from the findings cache
            robots.append((str(p), load_description(p, opts)[0]))
        if step is not None:
            step(1)
    return found + together.findings(robots), unusable


def _audit_one(path: Path, options: Options) -> tuple[list[Finding], bool]:
    """One description's findings and whether it was unusable (its input errors returned, not
    raised: they cross a process boundary as data)."""
    try:
        return audit(path, options), False
    except InputError as exc:
        return list(exc.findings), True


def _cache_inputs(path: Path, options: Options) -> findings_cache.Inputs | None:
    """The findings cache's key for this audit; None for what it does not keep."""
    from descgen.audit import findings_cache

    if options.moveit_config is not None or kind_of(path) != "urdf":
        return None
    return findings_cache.inputs(path, options.srdf, options.controllers, options.launch_args, options.package_paths)
