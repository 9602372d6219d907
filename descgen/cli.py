"""The ``descgen`` command: parse arguments, call the library, print, choose the exit code.

Exit codes: 0 ok, 1 a check failed (or findings with errors), 2 unusable input.
Only this module maps :class:`InputError` to 2; any other exception is a bug.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__, report
from .findings import Finding, InputError, Where, summary

EXIT_OK, EXIT_FAILED, EXIT_INPUT = 0, 1, 2


def exit_code(findings: Sequence[Finding], input_error: bool = False, strict: bool = False) -> int:
    """0 clean, 1 errors (or warnings with ``strict``), 2 unusable input."""
    if input_error:
        return EXIT_INPUT
    bad = {"error", "warning"} if strict else {"error"}
    return EXIT_FAILED if any(f.severity in bad for f in findings) else EXIT_OK


def _cmd_validate(args: argparse.Namespace) -> int:
    from .spec import load_spec

    all_findings: list[Finding] = []
    failed = False
    for path in expand_specs(args.spec):
        try:
            loaded = load_spec(path)
        except InputError as exc:
            all_findings.extend(exc.findings)
            failed = True
            continue
        all_findings.extend(loaded.findings)
        if args.format == "text":
            sys.stderr.write(report.text(loaded.findings))
            r = loaded.robot
            print(
                f"{report.printable(path)}: valid: robot '{report.printable(r.name)}', {len(r.links)} links, "
                f"{len(r.joints)} joints, "
                f"{len(r.known_poses)} known poses"
            )
    if args.format == "json":
        sys.stdout.write(report.as_json(all_findings))
    elif failed:
        sys.stderr.write(report.text(f for f in all_findings if f.severity == "error"))
    return EXIT_INPUT if failed else EXIT_OK


def expand_specs(paths: Sequence[str]) -> list[str]:
    """Spec files, with a folder standing for the *.yaml files in it."""
    out: list[str] = []
    for p in paths:
        path = Path(p)
        if path.is_dir():
            found = sorted(str(x) for x in (*path.glob("*.yaml"), *path.glob("*.yml")))
            if not found:
                raise InputError(
                    [
                        Finding(
                            "YAML002",
                            "error",
                            f"{p} holds no .yaml spec",
                            "name a spec file or a folder of specs",
                            "file",
                            Where(p),
                        )
                    ]
                )
            out += found
        else:
            out.append(p)
    return out


def _out_paths(args: argparse.Namespace) -> tuple[Path | None, Path | None]:
    out = Path(args.out) if args.out else None
    templates = Path(args.templates) if args.templates else None
    if templates is not None and not templates.is_dir():
        raise InputError(
            [
                Finding(
                    "GEN010",
                    "error",
                    f"--templates {templates} is not a folder",
                    "name a folder of template overrides",
                    "option",
                    Where(str(templates)),
                )
            ]
        )
    return out, templates


def _cmd_generate(args: argparse.Namespace) -> int:
    from .generate import generate

    out, templates = _out_paths(args)
    worst = EXIT_OK
    for spec in expand_specs(args.spec):
        outcome = generate(Path(spec), out, templates, force=args.force)
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
    from .generate import check

    out, templates = _out_paths(args)
    worst = EXIT_OK
    for spec in expand_specs(args.spec):
        outcome = check(Path(spec), out, templates)
        if outcome.diff:
            sys.stdout.write(outcome.diff)
        sys.stderr.write(report.text(outcome.findings))
        if outcome.failed:
            worst = max(worst, EXIT_FAILED)
        else:
            print(f"{spec}: generated files are up to date and every check passed")
    return worst


def _cmd_poses(args: argparse.Namespace) -> int:
    from .poses import evaluate, findings
    from .spec import load_spec

    loaded = load_spec(args.spec)
    rows = evaluate(loaded.robot)
    found = findings(loaded.robot, rows)
    if args.format == "json":
        doc = [
            {
                "pose": r.pose.name,
                "frame": r.measurement.frame,
                "relative_to": r.relative_to,
                "measured_m": list(r.measurement.xyz),
                "model_m": None if r.model is None else list(r.model),
                "error_m": None if r.error is None else list(r.error),
                "worst_axis_error_m": None if r.error is None else r.worst,
                "tolerance_m": r.measurement.tolerance,
                "ok": r.ok,
                "source": r.measurement.source,
            }
            for r in rows
        ]
        sys.stdout.write(report.as_json(found, poses=doc))
    else:
        print(f"{'pose':<16} {'frame':<22} {'measured (mm)':<24} {'model (mm)':<24} {'worst':>7} {'tol':>5}  verdict")
        for r in rows:

            def mm(v: object) -> str:
                return "n/a" if v is None else ", ".join(f"{c * 1000:.1f}" for c in v)  # type: ignore[attr-defined]

            worst = "n/a" if r.error is None else f"{r.worst * 1000:.2f}"
            print(
                f"{report.printable(r.pose.name):<16} {report.printable(r.measurement.frame):<22} "
                f"{mm(r.measurement.xyz):<24} {mm(r.model):<24} "
                f"{worst:>7} {r.measurement.tolerance * 1000:>5g}  {'pass' if r.ok else 'FAIL'}"
            )
        sys.stderr.write(report.text(found))
    return exit_code(found)


def _audit_options(args: argparse.Namespace) -> object:
    from .audit.inputs import Options

    mappings = {}
    for item in args.xacro_arg or []:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            raise InputError(
                [
                    Finding(
                        "READ005",
                        "error",
                        f"--xacro-arg '{item}' is not name:=value",
                        "write e.g. --xacro-arg use_gripper:=true",
                        "option",
                        Where("<command line>"),
                    )
                ]
            )
        mappings[name] = value
    return Options(
        Path(args.srdf) if args.srdf else None,
        Path(args.controllers) if args.controllers else None,
        mappings,
        tuple(Path(p) for p in args.package_path or []),
        args.trust_xacro,
    )


def _cmd_audit(args: argparse.Namespace) -> int:
    from .audit.inputs import audit

    options = _audit_options(args)
    found: list[Finding] = []
    unusable = False
    for path in args.path:
        try:
            found += audit(Path(path), options)  # type: ignore[arg-type]
        except InputError as exc:
            found += exc.findings
            unusable = True
    if args.format == "json":
        sys.stdout.write(report.as_json(found))
    elif args.format == "sarif":
        sys.stdout.write(report.sarif(found, base=str(Path.cwd())))
    else:
        sys.stderr.write(report.text(found))
        counts = ", ".join(f"{n} {k}" for k, n in summary(found).items())
        print(f"audited {len(args.path)} description(s): {counts}")
    return exit_code(found, input_error=unusable, strict=args.strict)


def _cmd_faults(args: argparse.Namespace) -> int:
    from .audit.inputs import load_description
    from .faults import plant_all

    robot, _ = load_description(Path(args.path), _audit_options(args))  # type: ignore[arg-type]
    results = plant_all(robot)
    if args.format == "json":
        doc = {
            "path": args.path,
            "faults": [
                {
                    "fault": r.fault.name,
                    "planted": r.planted,
                    "applicable": r.applicable,
                    "caught": r.caught,
                    "by": None if r.by is None else r.by.as_dict(),
                }
                for r in results
            ],
            "caught": sum(r.caught for r in results),
            "missed": sum(r.applicable and not r.caught for r in results),
        }
        sys.stdout.write(json.dumps(doc, indent=2) + "\n")
    else:
        for r in results:
            verdict = "caught" if r.caught else "n/a" if not r.applicable else "MISSED"
            by = f" by {r.by.code}: {r.by.message}" if r.by else ""
            print(f"{verdict:<7} {r.fault.name:<28} {report.printable(r.planted + by)}")
        caught = sum(r.caught for r in results)
        applicable = sum(r.applicable for r in results)
        print(f"{caught} of {applicable} planted faults caught ({len(results) - applicable} not applicable)")
    return EXIT_FAILED if any(r.applicable and not r.caught for r in results) else EXIT_OK


def _cmd_frames(args: argparse.Namespace) -> int:
    from .audit import run
    from .audit.inputs import load_description
    from .frames import edges

    robot, _ = load_description(Path(args.path), _audit_options(args))  # type: ignore[arg-type]
    es = edges(robot)
    found = [f for f in run(robot) if f.code.startswith("FRAME")]
    if args.format == "json":
        doc = [
            {
                "parent": e.parent,
                "child": e.child,
                "owner": e.owner,
                "topic": e.topic,
                "static": e.static,
                "joint": e.joint,
                "fed_by": e.via,
            }
            for e in es
        ]
        sys.stdout.write(report.as_json(found, frames=doc))
        return exit_code(found)
    children: dict[str, list[object]] = {}
    for e in es:
        children.setdefault(e.parent, []).append(e)
    roots = [p for p in children if p not in {e.child for e in es}]

    def show(frame: str, depth: int, seen: set[str]) -> None:
        for e in children.get(frame, []):
            kind = "static" if e.static else "dynamic"  # type: ignore[attr-defined]
            line = f"{e.child}  <- {e.owner} on {e.topic} ({kind}; {e.via})"  # type: ignore[attr-defined]
            print(f"{'  ' * depth}{report.printable(line)}")
            if e.child not in seen:  # type: ignore[attr-defined]
                show(e.child, depth + 1, seen | {e.child})  # type: ignore[attr-defined]

    for r in roots:
        print(report.printable(r))
        show(r, 1, {r})
    sys.stderr.write(report.text(found))
    return exit_code(found)


def _seconds(text: str, what: str, low: float, high: float, bare_seconds: bool = True) -> float:
    """An option's time in seconds, bounded; a bare number is seconds where the option was
    documented in seconds before it took units."""
    from . import units

    try:
        return units.duration(text, low, high, bare_seconds=bare_seconds)
    except units.QuantityError as exc:
        raise InputError(
            [Finding(exc.code, "error", f"{what}: {exc.message}", exc.hint, "option", Where("<command line>"))]
        ) from None


def _ns(text: str, what: str) -> int:
    from .tf.bagaudit import MAX_WAIT_S

    return round(_seconds(text, what, 0.0, MAX_WAIT_S, bare_seconds=False) * 1e9)


def _cmd_tf_audit(args: argparse.Namespace) -> int:
    from .tf.bagaudit import audit, shown

    max_age = _ns(args.max_age, "--max-age") if args.max_age is not None else None
    rep = audit(Path(args.bag), args.target, tuple(args.topic or ()), _ns(args.wait, "--wait"), max_age)
    failed = rep.lookups - rep.counts["ok"]
    if args.format == "json":
        sys.stdout.write(json.dumps(rep.as_dict(), indent=2) + "\n")
    else:
        print(
            f"{rep.lookups} lookups into '{args.target}': {rep.counts['ok']} ok, {rep.counts['disconnected']} "
            f"disconnected, {rep.counts['stale']} stale, {rep.counts['future']} future-dated"
        )
        for topic, c in sorted(rep.per_topic.items()):
            print(f"  {shown(topic)}: " + ", ".join(f"{k} {c[k]}" for k in ("ok", "disconnected", "stale", "future")))
        print("latency (log time - stamp): " + ", ".join(f"{k} ms: {v}" for k, v in sorted(rep.latency.items())))
        for e in rep.examples:
            print(
                f"  {e['outcome']}: {shown(e['topic'])} logged {e['log_time_ns'] / 1e9:.6f} stamped "
                f"{e['stamp_ns'] / 1e9:.6f} in '{shown(e['frame_id'])}': {shown(e['detail'], 300)}"
            )
    return EXIT_FAILED if failed else EXIT_OK


def _cmd_tf_scenario(args: argparse.Namespace) -> int:
    from .spec import load_spec
    from .tf.scenario import MAX_DURATION_S, MIN_DURATION_S, write

    duration = _seconds(args.duration, "--duration", MIN_DURATION_S, MAX_DURATION_S)
    out = Path(args.out)
    robot = load_spec(args.spec).robot
    counts = write(robot, out, tuple(args.fault or ()), duration, args.storage)
    print(f"wrote {out} ({args.storage}): " + ", ".join(f"{t} {n}" for t, n in counts.items()))
    return EXIT_OK


def _cmd_control(args: argparse.Namespace) -> int:
    from .control.run import MAX_DURATION_S, MIN_DURATION_S, find_package, read_trajectory, run, write_evidence
    from .control.system import Plant, plant_faults
    from .spec import load_spec

    spec = Path(args.spec)
    robot = load_spec(spec).robot
    package = find_package(spec, robot, Path(args.package) if args.package else None)
    duration = (
        _seconds(args.duration, "--duration", MIN_DURATION_S, MAX_DURATION_S) if args.duration is not None else None
    )
    faults = plant_faults(args.plant_fault or [], args.plant, robot)
    trajectory = read_trajectory(Path(args.trajectory), robot)
    plant = Plant(args.plant, faults=faults, noise=0.0)
    out = run(package, robot, trajectory, duration, plant)
    folder = Path(args.out) if args.out else package / "evidence"
    written = write_evidence(out, folder, robot)
    verdict = out.verdict()
    print(f"wrote {', '.join(written)} to {folder}")
    for joint, err in verdict["tracking"].items():
        tol = verdict["tolerance"][joint]
        print(
            f"  {joint:<22} max |desired - measured| {err:.6g} (tolerance {tol:.6g}) {'ok' if err <= tol else 'FAILED'}"
        )
    for e in verdict["rejected"]:
        print(
            f"  rejected {e['joint']}/{e['interface']} = {e['value']:.6g} beyond {e['limit']:.6g} at {e['time']:.2f} s"
        )
    sys.stderr.write(report.text(out.findings()))
    return EXIT_OK if verdict["ok"] else EXIT_FAILED


def _cmd_schema(args: argparse.Namespace) -> int:
    from .spec.schema import json_schema

    sys.stdout.write(json.dumps(json_schema(), indent=2) + "\n")
    return EXIT_OK


def _cmd_rules(args: argparse.Namespace) -> int:
    """Every code any command prints (audit rules and the rest), or one code's explanation."""
    from .codes import GROUPS, entries, explain

    if args.code:
        entry = explain(args.code.strip().upper())
        if entry is None:
            raise InputError(
                [
                    Finding(
                        "RULE001",
                        "error",
                        f"no code {report.printable(args.code, 80)} in the catalogue",
                        "run descgen rules for the list",
                        "option",
                        Where("<command line>"),
                    )
                ]
            )
        print(f"{entry.code} {entry.name} ({entry.severity}; {GROUPS[entry.group]})\n{entry.doc}", end="")
        return EXIT_OK
    for e in entries():
        if args.group and e.group != args.group:
            continue
        print(f"{e.code}  {e.severity:<7}  {e.group:<9}  {e.name}: {e.summary}")
    return EXIT_OK


def description_options(p: argparse.ArgumentParser) -> None:
    """The options that say how to read a description someone else wrote."""
    p.add_argument("--srdf", help="SRDF of the robot")
    p.add_argument("--controllers", help="controller_manager YAML of the robot")
    p.add_argument("--xacro-arg", action="append", metavar="NAME:=VALUE", help="argument for a Xacro (repeatable)")
    p.add_argument(
        "--package-path",
        action="append",
        metavar="DIR",
        help="folder holding ROS packages, for $(find) and package:// (repeatable)",
    )
    p.add_argument(
        "--trust-xacro",
        action="store_true",
        help="expand Xacro with xacro's own evaluator, which runs the file's Python and reads any file and "
        "environment variable; only for files you trust (default: a restricted evaluator, see docs/security.md)",
    )


def _code_groups() -> list[str]:
    from .codes import GROUPS

    return list(GROUPS)


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="descgen", description="Robot descriptions from measured specs, proven.")
    p.add_argument("--version", action="version", version=f"descgen {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    v = sub.add_parser("validate", help="check specs (schema, units, whole-model rules); write nothing")
    v.add_argument("spec", nargs="+")
    v.add_argument("--format", choices=("text", "json"), default="text")
    v.set_defaults(fn=_cmd_validate)

    g = sub.add_parser("generate", help="write generated/<robot>_description/ if every check passes")
    g.add_argument("spec", nargs="+")
    g.add_argument("--out", help="output root (default: generated/ beside specs/)")
    g.add_argument("--templates", help="folder of templates that override the defaults by file name")
    g.add_argument("--force", action="store_true", help="overwrite files that were edited by hand")
    g.set_defaults(fn=_cmd_generate)

    c = sub.add_parser("check", help="regenerate in memory, compare with the files on disk, run the checks")
    c.add_argument("spec", nargs="+")
    c.add_argument("--out", help="output root (default: generated/ beside specs/)")
    c.add_argument("--templates", help="folder of template overrides")
    c.set_defaults(fn=_cmd_check)

    a = sub.add_parser("audit", help="audit specs, URDFs or Xacros (with an SRDF and controllers YAML)")
    a.add_argument("path", nargs="+")
    description_options(a)
    a.add_argument("--format", choices=("text", "json", "sarif"), default="text")
    a.add_argument("--strict", action="store_true", help="warnings count as errors")
    a.set_defaults(fn=_cmd_audit)

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
    ta.add_argument("bag", help="rosbag2 folder (MCAP or sqlite3)")
    ta.add_argument("--target", required=True, help="frame to look every message up in (e.g. odom)")
    ta.add_argument("--topic", action="append", help="sensor topic (repeatable; default: every topic with a header)")
    ta.add_argument(
        "--wait", default="0 ms", help="how long a consumer waits for transforms (e.g. '50 ms'; at most 1 h)"
    )
    ta.add_argument(
        "--max-age", help="flag interpolation across samples farther than this (e.g. '100 ms'; at most 1 h)"
    )
    ta.add_argument("--format", choices=("text", "json"), default="text")
    ta.set_defaults(fn=_cmd_tf_audit)

    sc = sub.add_parser("tf-scenario", help="write a short recording of the robot, optionally with planted faults")
    sc.add_argument("spec")
    sc.add_argument("--out", required=True, help="new rosbag2 folder to write")
    sc.add_argument("--fault", action="append", choices=("camera-future", "odom-gap", "unknown-frame"))
    sc.add_argument(
        "--duration",
        default="10 s",
        help="length of the recording, e.g. '10 s' (a bare number is seconds; at most 10 min)",
    )
    sc.add_argument("--storage", choices=("mcap", "sqlite3"), default="mcap")
    sc.set_defaults(fn=_cmd_tf_scenario)

    co = sub.add_parser("control", help="run a trajectory through a model of ros2_control (lifecycle, claims, loop)")
    co.add_argument("spec")
    co.add_argument("--trajectory", required=True)
    co.add_argument(
        "--duration",
        help="simulated time, e.g. '8 s' (a bare number is seconds; at most 10 min; default: the trajectory plus 1 s)",
    )
    co.add_argument("--plant", choices=("mock", "sim"), default="mock")
    co.add_argument(
        "--plant-fault",
        action="append",
        metavar="JOINT:=stuck|offset|reversed",
        help="plant a fault in a joint of the simulated plant (repeatable; needs --plant sim)",
    )
    co.add_argument(
        "--package",
        help="the generated package, or the output root that `generate --out` wrote it under "
        "(default: generated/ beside specs/)",
    )
    co.add_argument("--out", help="folder for the evidence (default: the package's evidence/)")
    co.set_defaults(fn=_cmd_control)

    k = sub.add_parser("poses", help="measured known poses against forward kinematics")
    k.add_argument("spec")
    k.add_argument("--format", choices=("text", "json"), default="text")
    k.set_defaults(fn=_cmd_poses)

    s = sub.add_parser("schema", help="print the JSON Schema of the spec")
    s.set_defaults(fn=_cmd_schema)

    r = sub.add_parser("rules", help="list every finding code (audit rules and the rest), or explain one")
    r.add_argument("code", nargs="?", help="a code to explain, e.g. UNIT004")
    r.add_argument("--group", choices=_code_groups(), help="list only the codes of one group")
    r.set_defaults(fn=_cmd_rules)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
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


def _reader_went_away() -> int:
    """The reader of our output closed it (``descgen rules | head``): stop quietly. Python
    flushes stdout again at exit; pointing it at devnull keeps that flush from raising a
    second BrokenPipeError (https://docs.python.org/3/library/signal.html#note-on-sigpipe)."""
    import contextlib
    import os

    # not a real file (captured in tests): then nothing is flushed to a pipe at exit
    with contextlib.suppress(OSError, ValueError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 141  # 128 + SIGPIPE, what a shell reports for a writer killed by the closed pipe


if __name__ == "__main__":
    raise SystemExit(main())
