"""Test helpers: plant a change in the example spec and find where it went."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from descgen.findings import Finding, InputError
from descgen.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE_TEXT = (ROOT / "specs" / "warehouse_arm.yaml").read_text()


def plant(old: str, new: str, text: str = EXAMPLE_TEXT, count: int = 1) -> str:
    assert text.count(old) >= count, f"{old!r} not in the spec"
    return text.replace(old, new, count)


def line_of(text: str, needle: str) -> int:
    """1-based line of the first occurrence of ``needle`` (the oracle for locations)."""
    idx = text.index(needle)
    return text.count("\n", 0, idx) + 1


def errors_of(text: str, tmp_path: Path, name: str = "robot.yaml") -> list[Finding]:
    path = tmp_path / name
    path.write_text(text)
    try:
        load_spec(path)
    except InputError as exc:
        return list(exc.findings)
    return []


def run_cli(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    """The descgen command in a subprocess, as a user runs it."""
    return subprocess.run(
        [sys.executable, "-m", "descgen", *args], capture_output=True, text=True, cwd=cwd, timeout=300
    )
