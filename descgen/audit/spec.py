"""A spec validated: read (descgen/spec/) and its built model judged by the input-stage rules,
the whole of ``descgen validate``. What every command that takes a spec calls."""

from __future__ import annotations

from collections.abc import Sequence
from functools import partial
from pathlib import Path

from descgen.audit.registry import run
from descgen.spec.load import Loaded, read_spec, read_spec_text

INPUT_RULES = partial(run, stage="input")


def load_spec(
    path: str | Path, display: str | None = None, rules: bool = True, package_paths: Sequence[Path] = ()
) -> Loaded:
    """Read, validate and build one spec, its model judged by the rules (``rules=False``: not,
    the audit runs them itself). Raises :class:`InputError` with every error."""
    return read_spec(path, display, INPUT_RULES if rules else None, package_paths)


def load_spec_text(text: str, file: str = "<string>", rules: bool = True) -> Loaded:
    return read_spec_text(text, file, INPUT_RULES if rules else None)
