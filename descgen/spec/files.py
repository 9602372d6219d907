"""Which spec files a command was given (a folder stands for the ``*.yaml`` specs in it), and
where a spec's generated packages go by default."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from descgen.codes.spec import YAML002
from descgen.core.findings import InputError, Where


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
                        YAML002.finding(
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


def default_out(spec: Path) -> Path:
    """``generated/`` beside ``specs/`` (or beside the spec when it is not in a specs folder)."""
    parent = spec.resolve().parent
    return parent.parent / "generated" if parent.name == "specs" else parent / "generated"
