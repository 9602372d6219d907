"""The ``descgen`` command: parse arguments, call the library, print, choose the exit code.

Exit codes: 0 ok, 1 a check failed (or findings with errors), 2 unusable input.
Only this module maps :class:`InputError` to 2; any other exception is a bug.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

from . import __version__, report
from .findings import Finding, InputError

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
    for path in args.spec:
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
                f"{path}: valid: robot '{r.name}', {len(r.links)} links, {len(r.joints)} joints, "
                f"{len(r.known_poses)} known poses"
            )
    if args.format == "json":
        sys.stdout.write(report.as_json(all_findings))
    elif failed:
        sys.stderr.write(report.text(f for f in all_findings if f.severity == "error"))
    return EXIT_INPUT if failed else EXIT_OK


def _cmd_schema(args: argparse.Namespace) -> int:
    from .spec.schema import json_schema

    sys.stdout.write(json.dumps(json_schema(), indent=2) + "\n")
    return EXIT_OK


def _cmd_rules(args: argparse.Namespace) -> int:
    from .audit import iter_rules

    for info in iter_rules():
        if args.code and info.code != args.code:
            continue
        if args.code:
            print(f"{info.code} {info.name} ({info.severity})\n{info.doc}")
        else:
            print(f"{info.code}  {info.severity:<7}  {info.name}: {info.summary}")
    return EXIT_OK


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="descgen", description="Robot descriptions from measured specs, proven.")
    p.add_argument("--version", action="version", version=f"descgen {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    v = sub.add_parser("validate", help="check specs (schema, units, whole-model rules); write nothing")
    v.add_argument("spec", nargs="+")
    v.add_argument("--format", choices=("text", "json"), default="text")
    v.set_defaults(fn=_cmd_validate)

    s = sub.add_parser("schema", help="print the JSON Schema of the spec")
    s.set_defaults(fn=_cmd_schema)

    r = sub.add_parser("rules", help="list the rules, or show one")
    r.add_argument("code", nargs="?")
    r.set_defaults(fn=_cmd_rules)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    args = parser().parse_args(argv)
    try:
        return int(args.fn(args))
    except InputError as exc:
        sys.stderr.write(report.text(exc.findings))
        return EXIT_INPUT
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    raise SystemExit(main())
