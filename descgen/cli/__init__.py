"""The ``descgen`` command: parse arguments, call the library, print, choose the exit code.

Exit codes: 0 ok, 1 a check failed (or findings with errors), 2 unusable input.
Only this module maps :class:`InputError` to 2; any other exception is a bug.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, NoReturn

from descgen import __version__
from descgen.cli import arguments as types
from descgen.codes.graph import GRAPH010
from descgen.codes.importer import IMP007
from descgen.codes.read import CTRL055
from descgen.codes.recording import BAG016
from descgen.commands import text as cli_format
from descgen.core.findings import Finding, InputError, Where, summary
from descgen.infra import collector
from descgen.output import report

if TYPE_CHECKING:
    from descgen.read.description import Options

EXIT_OK, EXIT_FAILED, EXIT_INPUT = 0, 1, 2


def exit_code(findings: Sequence[Finding], input_error: bool = False, strict: bool = False) -> int:
    """0 clean, 1 errors (or warnings with ``strict``), 2 unusable input."""
    if input_error:
        return EXIT_INPUT
    bad = {"error", "warning"} if strict else {"error"}
    return EXIT_FAILED if any(f.severity in bad and f.waived is None for f in findings) else EXIT_OK


def _cmd_validate(args: argparse.Namespace) -> int:
    _settled_import("descgen.audit.spec")
    from descgen.audit.spec import validate_spec
    from descgen.spec.files import expand_specs

    all_findings: list[Finding] = []
    unusable: list[Finding] = []  # the specs that could not be loaded: their errors, printed last
    per_spec: list[tuple[str, list[Finding], str]] = []
    failed = False
    for path in expand_specs(args.spec):
        try:
            loaded = validate_spec(path, package_paths=_packages(args))
        except InputError as exc:
            all_findings.extend(exc.findings)
            unusable.extend(exc.findings)
            per_spec.append((str(path), list(exc.findings), ""))
            failed = True
            continue
        found = list(loaded.findings)
        all_findings.extend(found)
        per_spec.append((str(path), found, ""))
        if args.format == "text":
            sys.stderr.write(report.text(found))
            print(cli_format.validated(path, loaded.robot))
    if args.format == "json":
        sys.stdout.write(report.as_json(all_findings))
    elif args.format == "junit":
        sys.stdout.write(report.junit("validate", per_spec))
    elif unusable:  # every finding of a refused spec: its warnings and waived errors beside what blocks
        sys.stderr.write(report.text(unusable))
    return EXIT_INPUT if failed else EXIT_OK


def _cmd_generate(args: argparse.Namespace) -> int:
    _settled_import("descgen.commands.generate")
    from descgen.commands.generate import generate
    from descgen.infra.progress import wanted
    from descgen.spec.files import expand_specs

    worst = EXIT_OK
    for spec in expand_specs(args.spec):
        outcome = generate(Path(spec), args.out, args.templates, args.force, _packages(args), wanted())
        sys.stderr.write(report.text(outcome.findings))
        if outcome.failed:
            print(f"{spec}: nothing written: a check failed", file=sys.stderr)
            worst = max(worst, EXIT_FAILED)
            continue
        print(
            f"{spec}: wrote {len(outcome.written)} files, {len(outcome.unchanged)} unchanged"
            + (f", removed {len(outcome.removed)}" if outcome.removed else "")
        )
        for rel in outcome.written:
            print(f"  wrote {rel}")
    return worst


def _cmd_check(args: argparse.Namespace) -> int:
    _settled_import("descgen.commands.generate")
    from descgen.commands.generate import check
    from descgen.spec.files import expand_specs

    worst = EXIT_OK
    junit = args.format == "junit"
    per_spec: list[tuple[str, list[Finding], str]] = []
    for spec in expand_specs(args.spec):
        try:
            outcome = check(
                Path(spec),
                args.out,
                args.templates,
                package_paths=_packages(args),
                thorough=args.thorough,
            )
        except InputError as exc:
            if not junit:
                raise
            per_spec.append((str(spec), list(exc.findings), ""))
            worst = EXIT_INPUT
            continue
        if junit:
            per_spec.append((str(spec), list(outcome.findings), outcome.diff))
        elif outcome.diff:
            sys.stdout.write(report.lines_text(outcome.diff))
        if not junit:
            sys.stderr.write(report.text(outcome.findings))
        if outcome.failed:
            worst = max(worst, EXIT_FAILED)
        elif not junit:
            print(f"{spec}: generated files are up to date and every check passed")
    if junit:
        sys.stdout.write(report.junit("check", per_spec))
    return worst


def _cmd_report(args: argparse.Namespace) -> int:
    from descgen.commands.generate import check

    outcome = check(Path(args.spec), args.out, write_page=True, package_paths=_packages(args))
    sys.stderr.write(report.text(outcome.findings))
    if outcome.failed:
        print(f"{args.spec}: evidence page not written", file=sys.stderr)
        return EXIT_FAILED
    for rel in outcome.written:
        print(f"wrote {rel}")
    return EXIT_OK


def _cmd_view(args: argparse.Namespace) -> int:
    import threading

    from descgen.commands.view import load, require_viser
    from descgen.commands.view.server import start

    robot, urdf = load(Path(args.path), _packages(args))  # bad input first: exit 2 at the file
    require_viser()
    viewer = start(robot, urdf, args.host, args.port, Path(args.path).resolve().parent)
    try:  # from here on Ctrl-C stops the server and exits 0
        if args.host not in ("127.0.0.1", "::1"):
            print(f"warning: bound to {args.host}: anyone who can reach it can see the robot", file=sys.stderr)
        print(f"descgen view: {robot.name} at {viewer.url} (Ctrl-C to stop)", flush=True)
        threading.Event().wait()  # viser serves from its own thread
    except KeyboardInterrupt:
        print("descgen view: stopped", file=sys.stderr)
    finally:
        viewer.close()
    return EXIT_OK


def _cmd_poses(args: argparse.Namespace) -> int:
    from descgen.audit.spec import load_spec
    from descgen.audit.waivers import waive
    from descgen.physics.poses import evaluate, findings

    loaded = load_spec(args.spec, package_paths=_packages(args))
    rows = evaluate(loaded.robot)
    found = waive(findings(loaded.robot, rows), loaded.robot.waivers)
    if args.format == "json":
        sys.stdout.write(report.as_json(found, poses=cli_format.poses_json(rows)))
    else:
        sys.stdout.write(cli_format.poses_table(rows))
        sys.stderr.write(report.text(found))
    return exit_code(found)


def _once(args: argparse.Namespace, option: str) -> Path | None:
    """The one file given with ``--srdf`` or ``--controllers`` (repeated only with audit --together)."""
    given: list[Path] = getattr(args, option) or []
    if len(given) > 1:
        raise InputError(
            [
                GRAPH010.finding(
                    f"--{option} is given {len(given)} times; it names the one robot's file",
                    f"give --{option} once (audit --together takes it once per URDF or Xacro, in their order)",
                    "option",
                    types.COMMAND_LINE,
                )
            ]
        )
    return given[0] if given else None


def _description_options(args: argparse.Namespace) -> Options:
    from descgen.read.description import Options

    if args.launch_arg and not args.controllers:
        # only a controllers YAML named with --controllers is read with launch arguments; a value
        # that changes nothing would let a user believe a $(var) was checked
        raise InputError(
            [
                CTRL055.finding(
                    "--launch-arg is given without --controllers; launch arguments are used only for the "
                    "$(var NAME) substitutions of the controllers YAML named by --controllers",
                    "add --controllers FILE, or drop --launch-arg",
                    "option",
                    types.COMMAND_LINE,
                )
            ]
        )
    return Options(
        _once(args, "srdf") if not getattr(args, "together", False) else None,
        _once(args, "controllers") if not getattr(args, "together", False) else None,
        dict(args.xacro_arg or []),
        _packages(args),
        args.trust_xacro,
        launch_args=dict(args.launch_arg or []),
    )


def _cmd_audit(args: argparse.Namespace) -> int:
    from descgen.infra.progress import counting, wanted
    from descgen.read.description import audit_paths

    options = dataclasses.replace(
        _description_options(args), moveit_config=args.moveit_config, package_waivers=not args.no_waivers
    )
    paths = [Path(p) for p in args.path]
    show = wanted(args.format == "text") and len(paths) > 1
    with counting(len(paths), "audit", "file", show) as step:
        if args.together:
            from descgen.read.description import audit_together

            found, unusable = audit_together(paths, options, args.controllers or [], args.srdf or [], step)
        else:
            found, unusable = audit_paths(paths, options, args.jobs, step)
    if args.baseline is not None or args.write_baseline is not None:
        from descgen.commands import baseline

        if args.baseline is not None:
            found = baseline.apply(found, args.baseline)
        if args.write_baseline is not None:
            n = baseline.write(found, args.write_baseline)
            print(f"wrote {args.write_baseline}: {n} finding(s)", file=sys.stderr)
    if args.format == "json":
        sys.stdout.write(report.as_json(found))
    elif args.format == "sarif":
        sys.stdout.write(report.sarif(found, base=str(Path.cwd())))
    elif args.format == "junit":
        sys.stdout.write(report.junit("audit", _by_input(args.path, found), strict=args.strict))
    else:
        sys.stderr.write(report.text(found))
        counts = ", ".join(f"{n} {k}" for k, n in summary(found).items())
        print(f"audited {len(args.path)} description(s): {counts}")
    return exit_code(found, input_error=unusable, strict=args.strict)


def _by_input(paths: Sequence[str], found: Sequence[Finding]) -> list[tuple[str, list[Finding], str]]:
    """Findings grouped by the file they are in: one group per input named (a clean input has
    one too), then one per other file a finding points at (an SRDF, an included Xacro)."""
    groups: dict[str, list[Finding]] = {p: [] for p in paths}
    for f in found:
        file = f.where.file.removesuffix(" (expanded)")
        if file == "<unknown>" and paths:
            file = paths[0]
        groups.setdefault(file, []).append(f)
    return [(name, fs, "") for name, fs in groups.items()]


def _cmd_import(args: argparse.Namespace) -> int:
    from descgen.commands.importer.run import ImportOptions, import_description

    out: Path | None = args.output
    if out is not None:
        from descgen.write.spec_file import refuse_unsafe_output

        refuse_unsafe_output(out)  # a link, FIFO or device: never replaced, --force or not
    if out is not None and out.exists() and not args.force:
        raise InputError(
            [
                IMP007.finding(
                    f"{out} exists; import does not overwrite a spec",
                    "choose another -o file, or pass --force to replace it",
                    "option",
                    Where(str(out)),
                )
            ]
        )
    from descgen.commands.importer.variants import Variant

    variants = tuple(Variant(n, a) for n, a in args.variant or [])
    opts = ImportOptions(
        _description_options(args),
        args.units,
        str(out) if out else "imported.yaml",
        variants,
        not args.no_waivers,
        args.fix,
    )
    result = import_description(Path(args.path), opts)
    imp = result.imported
    sys.stderr.write(report.text(imp.audit + imp.report + result.invalid + imp.differences))
    if imp.differences:
        print(f"import: round trip differs at {len(imp.differences)} place(s); nothing written", file=sys.stderr)
        return EXIT_FAILED
    if out is None:
        sys.stdout.write(imp.spec_text)
    else:
        from descgen.write.spec_file import write_spec

        write_spec(out, imp.spec_text)
    print(cli_format.import_summary(result, str(out) if out else "stdout"), file=sys.stderr)
    return EXIT_OK


def _cmd_faults(args: argparse.Namespace) -> int:
    from descgen.commands.faults import plant_all
    from descgen.read.description import load_description

    robot, _ = load_description(Path(args.path), _description_options(args))
    results = plant_all(robot)
    if args.format == "json":
        sys.stdout.write(json.dumps(cli_format.faults_json(args.path, results), indent=2) + "\n")
    else:
        sys.stdout.write(cli_format.faults_text(results))
    return EXIT_FAILED if any(r.applicable and not r.caught for r in results) else EXIT_OK


def _cmd_frames(args: argparse.Namespace) -> int:
    from descgen.audit import run
    from descgen.physics.frames import edges
    from descgen.read.description import load_description

    robot, _ = load_description(Path(args.path), _description_options(args))
    es = edges(robot)
    found = [f for f in run(robot) if f.code.startswith("FRAME")]
    if args.format == "json":
        sys.stdout.write(report.as_json(found, frames=cli_format.frames_json(es)))
    else:
        sys.stdout.write(cli_format.frames_tree(es))
        sys.stderr.write(report.text(found))
    return exit_code(found)


def _cmd_tf_audit(args: argparse.Namespace) -> int:
    from descgen.commands.fleet.audit import tf_audit
    from descgen.infra.progress import wanted

    if args.address is not None and args.engine != "ray":
        raise InputError(
            [
                BAG016.finding(
                    "--address is the Ray cluster's: it needs --engine ray",
                    "add --engine ray, or leave --address out",
                    "option",
                    types.COMMAND_LINE,
                )
            ]
        )
    mappings = tuple(args.robot or ())
    outcomes = tf_audit(
        args.bag,
        args.target,
        out=args.out,
        force=args.force,
        mappings=mappings,
        show_progress=wanted(args.format == "text"),
        engine=args.engine,
        jobs=args.jobs,
        address=args.address,
        window_ns=args.window,
        topics=tuple(args.topic or ()),
        wait_ns=args.wait,
        max_age_ns=args.max_age,
    )
    errors = [f for o in outcomes for f in o.findings]
    if errors and not any(o.report is not None for o in outcomes):
        raise InputError(errors)  # nothing to report: exit 2, as for one recording
    if args.format == "json":
        sys.stdout.write(json.dumps(cli_format.tf_audit_json(outcomes, args.target, mappings), indent=2) + "\n")
    else:
        sys.stdout.write(cli_format.tf_audit_texts(outcomes, args.target, mappings))
    if errors:  # the readable recordings are reported above; the unreadable one is exit 2
        raise InputError(errors)
    reps = [o.report for o in outcomes if o.report is not None]
    return EXIT_FAILED if any(rep.lookups - rep.counts["ok"] for rep in reps) else EXIT_OK


def _cmd_fleet_report(args: argparse.Namespace) -> int:
    from descgen.commands.fleet.page import text
    from descgen.commands.fleet.report import fleet_report

    rollup, page = fleet_report(args.findings, args.out, args.threshold / 100)
    if args.format == "json":
        sys.stdout.write(json.dumps(rollup.as_dict() | {"page": str(page)}, indent=2) + "\n")
    else:
        sys.stdout.write(text(rollup, str(page)))
    # a regression, a recording not audited, or nothing audited at all: not a fleet that passed
    return EXIT_FAILED if rollup.robots or rollup.versions or rollup.unaudited or not rollup.lookups else EXIT_OK


def _cmd_tf_scenario(args: argparse.Namespace) -> int:
    from descgen.audit.spec import load_spec
    from descgen.commands.tf.scenario import write

    robot = load_spec(args.spec, package_paths=_packages(args)).robot
    urdf = None
    if args.description:  # the URDF generate writes, as robot_state_publisher would publish it
        from descgen.render import render_package

        urdf = render_package(robot, args.spec, only=[f"urdf/{robot.name}.urdf"])[f"urdf/{robot.name}.urdf"]
    start = {} if args.start is None else {"start_ns": args.start}
    counts = write(robot, args.out, tuple(args.fault or ()), args.duration, args.storage, description=urdf, **start)
    print(f"wrote {args.out} ({args.storage}): " + ", ".join(f"{t} {n}" for t, n in counts.items()))
    return EXIT_OK


def _cmd_control(args: argparse.Namespace) -> int:
    from descgen.audit.spec import load_spec
    from descgen.commands.control.evidence import evidence_folder, write_evidence
    from descgen.commands.control.load import find_package
    from descgen.commands.control.run import run
    from descgen.commands.control.system import Plant, plant_faults
    from descgen.commands.control.trajectory import read_trajectory

    robot = load_spec(args.spec, package_paths=_packages(args)).robot
    package = find_package(Path(args.spec), robot, args.package)
    faults = plant_faults(args.plant_fault or [], args.plant, robot)
    trajectory = read_trajectory(args.trajectory, robot)
    out = run(package, robot, trajectory, args.duration, Plant(args.plant, faults=faults, noise=0.0))
    folder = args.out or evidence_folder(package, args.plant, faults)
    written = write_evidence(out, folder, robot, package=package)
    verdict = out.verdict()
    sys.stdout.write(cli_format.control_text(written, folder, verdict))
    sys.stderr.write(report.text(out.findings()))
    return EXIT_OK if verdict["ok"] else EXIT_FAILED


def _cmd_simulate(args: argparse.Namespace) -> int:
    from descgen.commands.simulate import Settings, simulate_description

    settings = Settings(seconds=args.seconds, pose=args.pose, base=args.base)
    outcome = simulate_description(Path(args.path), _description_options(args), settings)
    if args.format == "json":
        sys.stdout.write(report.as_json(outcome.findings, simulate=outcome.report))
    else:
        sys.stdout.write(cli_format.simulate_text(args.path, outcome.report))
        sys.stderr.write(report.text(outcome.findings))
    return exit_code(outcome.findings)


def _cmd_sweep(args: argparse.Namespace) -> int:
    from descgen.commands.sweep import sweep_description
    from descgen.infra.progress import wanted
    from descgen.physics.sweep import Settings, as_dict, text

    tty = wanted(args.format == "text")  # progress on a terminal only: not in a log, a pipe, CI or JSON

    def progress(line: str) -> None:
        sys.stderr.write(f"\r\x1b[K{line}")
        sys.stderr.flush()

    result, found = sweep_description(
        Path(args.path), _description_options(args), Settings(args.state, args.steps), progress if tty else None
    )
    if tty:
        sys.stderr.write("\r\x1b[K")
    if args.format == "json":
        sys.stdout.write(report.as_json(found, sweep=as_dict(result)))
    else:
        sys.stdout.write(text(result))
        sys.stderr.write(report.text(found))
    return exit_code(found, strict=args.strict)


def _cmd_import_calibration(args: argparse.Namespace) -> int:
    """A calibration file merged into the spec's calibration: (descgen/commands/calibration_import.py),
    as a diff on stdout; written unless --dry-run."""
    from descgen.commands.calibration_import import import_file

    done = import_file(
        Path(args.spec),
        Path(args.file),
        args.format,
        write=not args.dry_run,
        source=args.source,
        prefix=args.prefix,
        sensor=args.sensor,
        date=args.date,
        replace=args.replace,
    )
    sys.stdout.write(done.diff(args.spec))
    for line in done.entries:
        print(f"{args.spec}: {line}", file=sys.stderr)
    state = "would be imported (--dry-run: nothing written)" if args.dry_run else "imported"
    print(f"{args.spec}: {len(done.entries)} calibration value(s) {state} from {args.file}", file=sys.stderr)
    return EXIT_OK


def _cmd_drift(args: argparse.Namespace) -> int:
    """The model against a recording of the running robot (descgen/commands/drift.py)."""
    from descgen.audit.spec import load_spec
    from descgen.commands.drift import drift, text

    loaded = load_spec(args.spec, package_paths=_packages(args))
    result = drift(
        loaded.robot,
        args.frame,
        base=args.base,
        recording=args.recording,
        pose_topic=args.pose_topic,
        samples=args.samples,
        parameters=tuple(p.strip() for p in (args.parameters or "").split(",") if p.strip()),
        tolerance_m=args.tolerance,
    )
    if args.format == "json":
        sys.stdout.write(json.dumps(result, indent=2) + "\n")
    else:
        sys.stdout.write(text(result))
    return 1 if result["drifted"] else EXIT_OK


def _cmd_fix(args: argparse.Namespace) -> int:
    """The safe fixes of each spec (descgen/commands/fix.py), as a diff on stdout; written
    unless --dry-run."""
    from descgen.commands.fix import fix_file
    from descgen.spec.files import expand_specs

    for spec in expand_specs(args.spec):
        fixed = fix_file(Path(spec), write=not args.dry_run)
        sys.stdout.write(fixed.diff(str(spec)))
        for x in fixed.fixes:
            print(f"{spec}: {x.code} {x.subject}: {x.what}", file=sys.stderr)
        done = "would be fixed (--dry-run: nothing written)" if args.dry_run else "fixed"
        print(
            f"{spec}: {len(fixed.fixes)} finding(s) {done}; what is left changes the robot: "
            "descgen validate shows it, each hint with the value that would pass"
            if fixed.fixes
            else f"{spec}: nothing to fix safely",
            file=sys.stderr,
        )
    return EXIT_OK


def _cmd_schema(args: argparse.Namespace) -> int:
    from descgen.spec.schema import json_schema

    sys.stdout.write(json.dumps(json_schema(), indent=2) + "\n")
    return EXIT_OK


def _cmd_rules(args: argparse.Namespace) -> int:
    """Every code any command prints (audit rules and the rest), or one code's explanation."""
    from descgen.audit.catalogue import entries, explain
    from descgen.codes import GROUPS

    if args.code:
        entry = explain(args.code)
        assert entry is not None  # cli_types.rule_code refused unknown codes
        status = f"; {entry.note}" if entry.note else ""  # a retired or redirected code says so
        print(f"{entry.code} {entry.name} ({entry.severity}; {GROUPS[entry.group]}{status})\n{entry.doc}", end="")
        return EXIT_OK
    for e in entries():  # sorted by code
        if args.group and e.group != args.group:
            continue
        status = f"[{e.status}] " if e.status != "stable" else ""
        print(f"{e.code}  {e.severity:<7}  {e.group:<9}  {e.name}: {status}{e.summary}")
    return EXIT_OK


# -- bounds of the time options, looked up only when the option is given -----------------------


def _scenario_bounds() -> tuple[float, float]:
    from descgen.commands.tf.scenario import MAX_DURATION_S, MIN_DURATION_S

    return MIN_DURATION_S, MAX_DURATION_S


def _control_bounds() -> tuple[float, float]:
    from descgen.commands.control.trajectory import MAX_DURATION_S, MIN_DURATION_S

    return MIN_DURATION_S, MAX_DURATION_S


def _simulate_bounds() -> tuple[float, float]:
    from descgen.commands.simulate import MAX_SECONDS, MIN_SECONDS

    return MIN_SECONDS, MAX_SECONDS


def _window_bounds() -> tuple[float, float]:
    return 1.0, 7 * 24 * 3600.0  # a second (all else is horizon) to a week


def _wait_bounds() -> tuple[float, float]:
    from descgen.commands.tf.bagaudit import MAX_WAIT_S

    return 0.0, MAX_WAIT_S


def description_options(p: argparse.ArgumentParser) -> None:
    """The options that say how to read a description someone else wrote."""
    p.add_argument(
        "--srdf",
        action="append",
        type=types.path,
        help="SRDF of the robot (audit --together: once per URDF or Xacro, in their order)",
    )
    p.add_argument(
        "--controllers",
        action="append",
        type=types.path,
        help="controller_manager YAML of the robot (audit --together: once per URDF or Xacro, in their order)",
    )
    p.add_argument(
        "--xacro-arg",
        action="append",
        type=types.xacro_arg,
        metavar="NAME:=VALUE",
        help="argument for a Xacro (repeatable)",
    )
    p.add_argument(
        "--launch-arg",
        action="append",
        type=types.launch_arg,
        metavar="NAME:=VALUE",
        help="value of a $(var NAME) launch substitution in the controllers YAML (repeatable)",
    )
    package_path(p)
    p.add_argument(
        "--trust-xacro",
        action="store_true",
        help="expand Xacro with xacro's own evaluator, which runs the file's Python and reads any file and "
        "environment variable; only for files you trust (default: a restricted evaluator, see docs/security.md)",
    )


def package_path(p: argparse.ArgumentParser) -> None:
    """--package-path, the same for every command that reads a spec or a description: where the
    packages that package:// and $(find) name are, after a spec's package_paths: and before the
    sourced environment (descgen/meshes/packages.py, docs/packages.md)."""
    p.add_argument(
        "--package-path",
        action="append",
        type=types.folder,
        metavar="DIR",
        help="folder holding ROS packages (a workspace's src/ or install/, a share/), for package:// and "
        "$(find) (repeatable; searched after a spec's package_paths:, before AMENT_PREFIX_PATH and ROS_PACKAGE_PATH)",
    )


def _packages(args: argparse.Namespace) -> tuple[Path, ...]:
    """The folders searched for packages, in the one order (descgen/meshes/packages.py)."""
    import os

    from descgen.meshes.packages import search

    return search(tuple(getattr(args, "package_path", None) or ()), os.environ)


def _code_groups() -> list[str]:
    from descgen.codes import GROUPS

    return list(GROUPS)


class Parser(argparse.ArgumentParser):
    """argparse, printing a bad option value that has a finding code as findings are printed.

    argparse turns the :class:`~descgen.cli.arguments.OptionError` a ``type=`` callable raised into
    an ``ArgumentError`` and calls :meth:`error` while handling it, so the finding is the
    handled exception's context. Anything else (an unknown option, a bad choice, a value
    without a code) keeps argparse's usage message. Both exit 2."""

    def error(self, message: str) -> NoReturn:
        handled = sys.exc_info()[1]
        bad = handled.__context__ if handled is not None else None
        if not isinstance(bad, types.OptionError):
            super().error(message)
        sys.stderr.write(report.text([bad.finding]))
        self.exit(EXIT_INPUT)


def parser() -> argparse.ArgumentParser:
    p = Parser(prog="descgen", description="Robot descriptions from measured specs, proven.")
    p.add_argument("--version", action="version", version=f"descgen {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    v = sub.add_parser("validate", help="check specs (schema, units, whole-model rules); write nothing")
    v.add_argument("spec", nargs="+")
    v.add_argument("--format", choices=("text", "json", "junit"), default="text")
    package_path(v)
    v.set_defaults(fn=_cmd_validate)

    g = sub.add_parser("generate", help="write generated/<robot>_description/ if every check passes")
    g.add_argument("spec", nargs="+")
    g.add_argument("--out", type=types.path, help="output root (default: generated/ beside specs/)")
    g.add_argument(
        "--templates", type=types.templates_folder, help="folder of templates that override the defaults by file name"
    )
    g.add_argument("--force", action="store_true", help="overwrite files that were edited by hand")
    package_path(g)
    g.set_defaults(fn=_cmd_generate)

    c = sub.add_parser("check", help="regenerate in memory, compare with the files on disk, run the checks")
    c.add_argument("spec", nargs="+")
    c.add_argument("--out", type=types.path, help="output root (default: generated/ beside specs/)")
    c.add_argument("--templates", type=types.templates_folder, help="folder of template overrides")
    c.add_argument(
        "--format",
        choices=("text", "junit"),
        default="text",
        help="junit: JUnit XML on stdout (a test suite per spec; the diff of stale files in its failure)",
    )
    package_path(c)
    c.add_argument(
        "--thorough",
        action="store_true",
        help="also read the URDF back with yourdfpy (slower to start: it imports trimesh and scipy)",
    )
    c.set_defaults(fn=_cmd_check)

    a = sub.add_parser("audit", help="audit specs, URDFs or Xacros (with an SRDF and controllers YAML)")
    a.add_argument("path", nargs="+")
    description_options(a)
    a.add_argument(
        "--moveit-config",
        type=types.folder,
        metavar="DIR",
        help="a MoveIt config package to audit with the robot (its SRDF and ros2_controllers.yaml unless given)",
    )
    a.add_argument("--format", choices=("text", "json", "sarif", "junit"), default="text")
    a.add_argument("--strict", action="store_true", help="warnings count as errors")
    a.add_argument(
        "--baseline",
        type=types.path,
        metavar="FILE",
        help="findings listed in FILE (written by --write-baseline) are reported as waived and fail nothing: "
        "CI fails only on new findings",
    )
    a.add_argument(
        "--write-baseline",
        type=types.path,
        metavar="FILE",
        help="write this audit's findings to FILE as the baseline (the exit code is still this audit's)",
    )
    a.add_argument(
        "--no-waivers",
        action="store_true",
        help="ignore the descgen-waivers.yaml of the package a description is in (generate writes it from the "
        "spec's waivers:)",
    )
    a.add_argument(
        "--jobs", type=types.jobs, default=1, help="audit this many descriptions at once, in separate processes"
    )
    a.add_argument(
        "--together",
        action="store_true",
        help="the descriptions are robots of one ROS graph: also report frames and joints two of them would both "
        "publish, and controllers of one that name the other's joints (GRAPH codes; docs/multi-robot.md)",
    )
    a.set_defaults(fn=_cmd_audit)

    im = sub.add_parser("import", help="a URDF or Xacro (+ SRDF) -> a spec with sources, proven by a round trip")
    im.add_argument("path")
    description_options(im)
    im.add_argument("-o", "--output", type=types.path, help="spec file to write (default: print the spec)")
    im.add_argument(
        "--units", type=types.import_units, default=types.import_units("mm,deg,kg"), help="mm,deg,kg (default) or si"
    )
    im.add_argument("--force", action="store_true", help="replace an existing -o file")
    im.add_argument(
        "--no-waivers",
        action="store_true",
        help="do not write a waiver for each defect of the description (then validate fails at them)",
    )
    im.add_argument(
        "--fix",
        action="store_true",
        help="apply the fixes that cannot change the robot (as descgen fix does) to the imported spec",
    )
    im.add_argument(
        "--variant",
        action="append",
        type=types.variant,
        metavar="NAME:[ARG:=VALUE,...]",
        help="a hardware variant (mock, gazebo, real) and the Xacro args that select it; repeat per variant",
    )
    im.set_defaults(fn=_cmd_import)

    f = sub.add_parser("faults", help="plant each fault of the catalogue in a copy and audit it")
    f.add_argument("path")
    description_options(f)
    f.add_argument("--format", choices=("text", "json"), default="text")
    f.set_defaults(fn=_cmd_faults)

    fr = sub.add_parser("frames", help="the transform tree with the publisher of every edge")
    fr.add_argument("path")
    description_options(fr)
    fr.add_argument("--format", choices=("text", "json"), default="text")
    fr.set_defaults(fn=_cmd_frames)

    ta = sub.add_parser("tf-audit", help="look up every sensor message of a rosbag2 recording at its stamp")
    ta.add_argument("bag", nargs="+", help="rosbag2 folder (MCAP or sqlite3); several are audited one by one")
    ta.add_argument(
        "--jobs", type=types.jobs, default=1, help="audit this many recordings at once, in separate processes"
    )
    ta.add_argument("--target", required=True, help="frame to look every message up in (e.g. odom)")
    ta.add_argument("--topic", action="append", help="sensor topic (repeatable; default: every topic with a header)")
    ta.add_argument(
        "--wait",
        default="0 ms",
        type=types.Nanoseconds("--wait", _wait_bounds),
        help="how long a consumer waits for transforms (e.g. '50 ms'; at most 1 h)",
    )
    ta.add_argument(
        "--max-age",
        type=types.Nanoseconds("--max-age", _wait_bounds),
        help="flag interpolation across samples farther than this (e.g. '100 ms'; at most 1 h)",
    )
    ta.add_argument(
        "--engine",
        choices=("local", "ray"),
        default="local",
        help="where the recordings are audited: this machine's processes (--jobs), or a Ray cluster",
    )
    ta.add_argument(
        "--address", type=types.address, help="the Ray cluster's head (host:port or auto); default: start a local one"
    )
    ta.add_argument(
        "--window",
        type=types.Nanoseconds("--window", _window_bounds),
        help="audit recordings longer than this in time windows of this length, in parallel (e.g. '10 min')",
    )
    ta.add_argument("--out", type=types.path, help="write every failed lookup and a summary per topic as Parquet")
    ta.add_argument("--force", action="store_true", help="replace an existing --out file")
    ta.add_argument(
        "--robot",
        action="append",
        type=types.robot_mapping,
        metavar="GLOB=ROBOT[@VERSION]",
        help="recordings whose path matches GLOB are of ROBOT (at VERSION); default: from /robot_description",
    )
    ta.add_argument("--format", choices=("text", "json"), default="text")
    ta.set_defaults(fn=_cmd_tf_audit)

    fl = sub.add_parser("fleet-report", help="roll tf-audit findings tables up by robot, description version and day")
    fl.add_argument("findings", nargs="+", type=types.path, help="Parquet files written by tf-audit --out")
    fl.add_argument("--out", type=types.path, default=Path("fleet-report"), help="folder for the page and its plots")
    fl.add_argument(
        "--threshold",
        type=types.percent,
        default=0.0,
        help="a robot-day fails when more than this share of its lookups failed (percent; default 0)",
    )
    fl.add_argument("--format", choices=("text", "json"), default="text")
    fl.set_defaults(fn=_cmd_fleet_report)

    sc = sub.add_parser("tf-scenario", help="write a short recording of the robot, optionally with planted faults")
    sc.add_argument("spec")
    sc.add_argument("--out", required=True, type=types.path, help="new rosbag2 folder to write")
    sc.add_argument("--fault", action="append", choices=("camera-future", "odom-gap", "unknown-frame"))
    sc.add_argument(
        "--duration",
        default="10 s",
        type=types.Duration("--duration", _scenario_bounds),
        help="length of the recording, e.g. '10 s' (a bare number is seconds; at most 10 min)",
    )
    sc.add_argument("--storage", choices=("mcap", "sqlite3"), default="mcap")
    sc.add_argument(
        "--start",
        type=types.start_time,
        help="when the recording starts (ISO 8601, UTC by default; default 2023-11-14T22:13:20)",
    )
    sc.add_argument(
        "--description",
        action="store_true",
        help="record /robot_description (the URDF), as robot_state_publisher latches it",
    )
    package_path(sc)
    sc.set_defaults(fn=_cmd_tf_scenario)

    co = sub.add_parser("control", help="run a trajectory through a model of ros2_control (lifecycle, claims, loop)")
    co.add_argument("spec")
    co.add_argument("--trajectory", required=True, type=types.path)
    co.add_argument(
        "--duration",
        type=types.Duration("--duration", _control_bounds),
        help="simulated time, e.g. '8 s' (a bare number is seconds; at most 10 min; default: the trajectory plus 1 s)",
    )
    co.add_argument("--plant", choices=("mock", "sim"), default="mock")
    co.add_argument(
        "--plant-fault",
        action="append",
        type=types.plant_fault,
        metavar="JOINT:=stuck|offset|reversed",
        help="plant a fault in a joint of the simulated plant (repeatable; needs --plant sim)",
    )
    co.add_argument(
        "--package",
        type=types.path,
        help="the generated package, or the output root that `generate --out` wrote it under "
        "(default: generated/ beside specs/)",
    )
    co.add_argument(
        "--out",
        type=types.path,
        help="folder for the evidence (default: the package's evidence/ for a mock run; "
        "a new scratch folder for an experiment with --plant sim or --plant-fault)",
    )
    package_path(co)
    co.set_defaults(fn=_cmd_control)

    si = sub.add_parser("simulate", help="compile the robot with MuJoCo and hold it at a pose under gravity")
    si.add_argument("path", help="spec, URDF or Xacro")
    si.add_argument(
        "--seconds",
        default="2 s",
        type=types.Duration("--seconds", _simulate_bounds),
        help="simulated time of the gravity run, e.g. '2 s' (a bare number is seconds; at most 10 s)",
    )
    si.add_argument(
        "--pose",
        help="known pose or SRDF group state to hold (default: the SRDF's first state; every joint a state does not "
        "name at MoveIt's default position: zero, or the middle of limits that exclude it)",
    )
    si.add_argument(
        "--base",
        choices=("fixed", "floor"),
        help="fixed to the world, or free on a ground plane (default: floor for a robot whose SRDF virtual "
        "joint is planar or floating, whose root link is base_footprint, or that has a drive controller)",
    )
    description_options(si)
    si.add_argument("--format", choices=("text", "json"), default="text")
    si.set_defaults(fn=_cmd_simulate)

    sw = sub.add_parser("sweep", help="each joint through its range: which way it moves the robot, what collides")
    sw.add_argument("path", help="spec, URDF or Xacro")
    sw.add_argument(
        "--state",
        help="group state or known pose the other joints hold (default: the collision matrix's state, else the "
        "SRDF's first state; every other joint at MoveIt's default position: zero, or the middle of limits that "
        "exclude it)",
    )
    sw.add_argument(
        "--steps", type=types.sweep_steps, default=36, help="steps per joint, both limits included (default 36)"
    )
    description_options(sw)
    sw.add_argument("--format", choices=("text", "json"), default="text")
    sw.add_argument("--strict", action="store_true", help="exit 1 on warnings too (a collision on the way)")
    sw.set_defaults(fn=_cmd_sweep)

    rp = sub.add_parser("report", help="write evidence/README.md: every proof of the package on one page")
    rp.add_argument("spec")
    rp.add_argument("--out", type=types.path, help="output root (default: generated/ beside specs/)")
    package_path(rp)
    rp.set_defaults(fn=_cmd_report)

    vw = sub.add_parser("view", help="the robot in the browser: joint sliders, known poses and their measurements")
    vw.add_argument("path", help="spec, URDF or Xacro")
    vw.add_argument("--port", type=types.port, default=8080, help="TCP port (default 8080; 0: any free port)")
    vw.add_argument(
        "--host", type=types.host, default="127.0.0.1", help="address to bind (default 127.0.0.1: this machine only)"
    )
    package_path(vw)
    vw.set_defaults(fn=_cmd_view)

    k = sub.add_parser("poses", help="measured known poses against forward kinematics")
    k.add_argument("spec")
    k.add_argument("--format", choices=("text", "json"), default="text")
    package_path(k)
    k.set_defaults(fn=_cmd_poses)

    fx = sub.add_parser(
        "fix",
        help="apply the fixes that cannot change the robot (Jazzy's one-to-one renames, parameters Jazzy "
        "removed) to specs, and print them as a diff",
    )
    fx.add_argument("spec", nargs="+")
    fx.add_argument("--dry-run", action="store_true", help="print the diff, write nothing")
    fx.set_defaults(fn=_cmd_fix)

    dr = sub.add_parser(
        "drift",
        help="the model against what the running robot reports: residuals of a frame's measured pose, when they "
        "changed, and the calibration parameters that explain them",
    )
    dr.add_argument("spec")
    src = dr.add_mutually_exclusive_group(required=True)
    src.add_argument("--recording", type=types.path, help="a rosbag2 recording with /joint_states and --pose-topic")
    src.add_argument("--samples", type=types.path, help="a CSV: time, one column per joint, x,y,z[,qx,qy,qz,qw]")
    dr.add_argument("--pose-topic", help="the measured pose (PoseStamped or TransformStamped) in the recording")
    dr.add_argument("--frame", required=True, help="the link whose pose was measured")
    dr.add_argument("--base", help="the link the pose is measured in (default: the pose's frame_id, else the root)")
    dr.add_argument("--parameters", help="comma-separated patterns of the parameters to fit, e.g. 'joint:*:offset'")
    dr.add_argument(
        "--tolerance",
        type=types.Length("--tolerance"),
        default=0.001,
        help="the 95th percentile of the residual that counts as drift (default 1 mm; exit 1 beyond it)",
    )
    dr.add_argument("--format", choices=("text", "json"), default="text")
    package_path(dr)
    dr.set_defaults(fn=_cmd_drift)

    ic = sub.add_parser(
        "import-calibration",
        help="merge a calibration file (UR kinematics YAML, easy_handeye2 result, CSV of joint offsets) into a "
        "spec's calibration:, with its provenance, and print the change as a diff",
    )
    ic.add_argument("spec")
    ic.add_argument("file")
    ic.add_argument("--format", choices=("ur", "handeye", "csv"), required=True, help="the file's format")
    ic.add_argument("--source", type=types.name, help="the name the entries cite in calibration.sources")
    ic.add_argument("--prefix", default="", type=types.prefix, help="prefix of the spec's joint and frame names")
    ic.add_argument("--sensor", type=types.name, help="handeye: the spec's sensor the result mounts")
    ic.add_argument("--date", type=types.date, help="when the calibration was measured (YYYY-MM-DD)")
    ic.add_argument(
        "--replace", action="store_true", help="replace an entry that cites another source whole (else CAL013)"
    )
    ic.add_argument("--dry-run", action="store_true", help="print the diff, write nothing")
    ic.set_defaults(fn=_cmd_import_calibration)

    s = sub.add_parser("schema", help="print the JSON Schema of the spec")
    s.set_defaults(fn=_cmd_schema)

    r = sub.add_parser("rules", help="list every finding code (audit rules and the rest), or explain one")
    r.add_argument("code", nargs="?", type=types.rule_code, help="a code to explain, e.g. UNIT004")
    r.add_argument("--group", choices=_code_groups(), help="list only the codes of one group")
    r.set_defaults(fn=_cmd_rules)
    return p


def main(argv: Sequence[str] | None = None, ending: bool = False) -> int:
    """Run one command; its exit code. ``ending``: the process ends after it (see :func:`entry`)."""
    _one_blas_thread()
    _fewer_collections()
    from descgen.infra.pydantic_plugins import no_plugin_lookup

    with no_plugin_lookup():
        return _run(argv, ending)


def entry() -> NoReturn:
    """The console script and ``python -m descgen``: :func:`main` in a process that ends with it,
    so the objects the command made are left to the exit (descgen/infra/collector.py), not collected."""
    raise SystemExit(main(ending=True))


def _run(argv: Sequence[str] | None, ending: bool = False) -> int:
    try:
        args = parser().parse_args(argv)
    except SystemExit as exc:  # argparse: --help, --version, or a bad option value (exit 2)
        return exc.code if isinstance(exc.code, int) else EXIT_INPUT if exc.code else EXIT_OK
    try:
        # validate, generate and check: every object lives to the end (descgen/infra/collector.py), and
        # their input is bounded (a spec is at most 16 MiB); tf-audit and control keep the collector
        with collector.paused(args.fn in (_cmd_validate, _cmd_generate, _cmd_check), ending):
            code = int(args.fn(args))
        sys.stdout.flush()  # a closed pipe shows here, inside the handler, not at exit
        return code
    except InputError as exc:
        sys.stderr.write(report.text(exc.findings))
        return EXIT_INPUT
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return _reader_went_away()


def _one_blas_thread() -> None:
    """numpy's OpenBLAS starts a thread per core when numpy is imported, ~60 ms of CPU in every
    process that imports numpy; descgen multiplies 4x4 matrices and small vertex arrays, where
    BLAS threads gain nothing. Only before numpy is loaded (a fresh process), and a user's own
    setting wins."""
    import os

    if "numpy" not in sys.modules:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def _fewer_collections() -> None:
    """Python's cyclic collector runs after every 700 new container objects; a 1000-link robot
    makes millions (YAML nodes, DOM nodes, model records), nearly all alive, and collecting
    took a third of ``generate`` (3.2 s -> 2.3 s with it off, the same peak memory). Every
    10,000 still collects, so garbage cycles stay bounded. Only over Python's default."""
    import gc

    gen0, gen1, gen2 = gc.get_threshold()
    if gen0 == 700:
        gc.set_threshold(10_000, gen1, gen2)


def _settled_import(module: str) -> None:
    """Import a command's modules with the cyclic collector paused, then freeze what they made.
    Importing pydantic, numpy, jinja2 and the spec models creates hundreds of thousands of
    objects that live as long as the process; collecting while they are made, and traversing
    them in every later collection, was ~35 ms of a cold ``check`` (8 ms after). Only on the
    first import (a process that imports again, like the test suite, freezes nothing more), and
    the collector is left as it was found."""
    import gc
    import importlib

    if module in sys.modules:
        return
    was = gc.isenabled()
    gc.disable()
    try:
        importlib.import_module(module)
    finally:
        gc.freeze()  # long-lived objects out of every later collection's traversal
        if was:
            gc.enable()


def _reader_went_away() -> int:
    """The reader of our output closed it (``descgen rules | head``): stop quietly. Python
    flushes stdout again at exit; pointing it at devnull keeps that flush from raising a
    second BrokenPipeError (https://docs.python.org/3/library/signal.html#note-on-sigpipe)."""
    import os

    # not a real file (captured in tests): then nothing is flushed to a pipe at exit
    with contextlib.suppress(OSError, ValueError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 141  # 128 + SIGPIPE, what a shell reports for a writer killed by the closed pipe


if __name__ == "__main__":
    raise SystemExit(main())
