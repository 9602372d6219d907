"""Re-extract the parameter facts of descgen/physics/controller_params.py from a checkout of
ros-controls/ros2_controllers (the generate_parameter_library YAML of each controller).

    python scripts/extract_controller_params.py GIT_DIR [--ref jazzy] [--write]

GIT_DIR is a clone (a bare mirror will do: files are read with ``git show REF:PATH``). Without
``--write`` the generated block is printed; with it, the block between the BEGIN/END markers of
descgen/physics/controller_params.py is replaced and the cited commit updated (then run
``ruff format`` on it, which wraps the long entries). Descriptions
are not copied: only each parameter's name, type, default, read_only flag and validators.

Not run by the tests (it needs the checkout); docs/controller_params.md says how the data was
made and what was added by hand (the tables outside the generated block).
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import yaml

MODULE = Path(__file__).resolve().parent.parent / "descgen" / "physics" / "controller_params.py"
BEGIN = "# --- BEGIN GENERATED (scripts/extract_controller_params.py) ---"
END = "# --- END GENERATED ---"

# every generate_parameter_library file of a controller plugin; the wrench transformer's is a
# separate node's (force_torque_sensor_broadcaster/src/wrench_transformer_parameters.yaml)
SKIP = ("force_torque_sensor_broadcaster/src/wrench_transformer_parameters.yaml",)
_LEAF_KEYS = {"type", "default_value", "description", "read_only", "validation", "additional_constraints"}


def _git(git_dir: str, *args: str) -> str:
    return subprocess.run(["git", "-C", git_dir, *args], check=True, capture_output=True, text=True).stdout


def parameter_files(git_dir: str, ref: str) -> list[str]:
    names = _git(git_dir, "ls-tree", "-r", ref, "--name-only").split()
    return sorted(n for n in names if re.fullmatch(r"[^/]+/src/[^/]+\.yaml", n) and n not in SKIP)


def _is_leaf(node: object) -> bool:
    return isinstance(node, dict) and isinstance(node.get("type"), str) and set(node) <= _LEAF_KEYS


def leaves(node: dict[str, Any], prefix: tuple[str, ...] = ()) -> list[tuple[str, dict[str, Any]]]:
    out: list[tuple[str, dict[str, Any]]] = []
    for key, value in node.items():
        path = (*prefix, str(key))
        if _is_leaf(value):
            out.append((".".join(path), value))
        elif isinstance(value, dict):
            out += leaves(value, path)
        else:
            raise ValueError(f"{'.'.join(path)}: neither a parameter nor a namespace")
    return out


def _args(raw: object) -> tuple[object, ...]:
    if raw is None:
        return ()
    if isinstance(raw, list):
        return tuple(tuple(a) if isinstance(a, list) else a for a in raw)
    return (raw,)


def _check_name(name: str) -> str:
    """``gt_eq<>`` and ``gt_eq`` are one check; control_filters' NaN-tolerant ones keep their name."""
    name = name.removesuffix("<>")
    return name.removeprefix("control_filters::")


def _literal(v: object) -> str:
    if isinstance(v, float) and math.isnan(v):
        return "NAN"
    if isinstance(v, float) and math.isinf(v):
        return "INF" if v > 0 else "-INF"
    if isinstance(v, list | tuple):
        items = ", ".join(_literal(x) for x in v)
        return f"({items},)" if len(v) == 1 else f"({items})"
    if isinstance(v, str):
        return json.dumps(v)  # a Python literal too, in the double quotes ruff format keeps
    return repr(v)


def entry(name: str, leaf: dict[str, Any]) -> str:
    default = _literal(leaf["default_value"]) if "default_value" in leaf else "REQUIRED"
    flags = "RO" if leaf.get("read_only") else "RW"
    checks = tuple((_check_name(str(k)), _args(v)) for k, v in (leaf.get("validation") or {}).items())
    return f"({_literal(name)}, {_literal(leaf['type'])}, {default}, {flags}, {_literal(checks)}),"


def generate(git_dir: str, ref: str) -> tuple[str, str]:
    commit = _git(git_dir, "rev-parse", ref).strip()
    lines = [BEGIN, f"# ros-controls/ros2_controllers {ref} @ {commit}", "PARAMETER_FILES: dict[str, Defs] = {"]
    sources = ["# namespace -> (package, file under its src/)", "SOURCES: dict[str, tuple[str, str]] = {"]
    for path in parameter_files(git_dir, ref):
        doc = yaml.safe_load(_git(git_dir, "show", f"{ref}:{path}"))
        for namespace, body in doc.items():
            lines.append(f"    # {path}")
            lines.append(f"    {_literal(namespace)}: (")
            lines += [f"        {entry(n, leaf)}" for n, leaf in leaves(body)]
            lines.append("    ),")
            package, _, file = path.partition("/src/")
            sources.append(f"    {_literal(namespace)}: ({_literal(package)}, {_literal(file)}),")
    lines.append("}")
    sources.append("}")
    return commit, "\n".join([*lines, *sources, END])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("git_dir")
    ap.add_argument("--ref", default="jazzy")
    ap.add_argument("--write", action="store_true", help=f"replace the generated block of {MODULE.name}")
    args = ap.parse_args(argv)
    commit, block = generate(args.git_dir, args.ref)
    if not args.write:
        print(block)
        return 0
    text = MODULE.read_text(encoding="utf-8")
    start, end = text.index(BEGIN), text.index(END) + len(END)
    text = text[:start] + block + text[end:]
    text = re.sub(r'^COMMIT = "[0-9a-f]{40}"', f'COMMIT = "{commit}"', text, count=1, flags=re.M)
    MODULE.write_text(text, encoding="utf-8")
    print(f"{MODULE}: {args.ref} @ {commit}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
