"""The folders are the pipeline: the layers contract (pyproject.toml) holds, and no import cycle
exists, module-level or inside a function. Each checker is also shown to fail on a planted break,
so a green run is not a checker that sees nothing."""

from __future__ import annotations

import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
from check_import_cycles import cycles  # noqa: E402

LINT_IMPORTS = shutil.which("lint-imports", path=str(Path(sys.executable).parent))


def _package(tmp_path: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        path = tmp_path / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return tmp_path


def test_descgen_keeps_its_layers() -> None:
    assert LINT_IMPORTS is not None, "import-linter is in the test extra"
    done = subprocess.run([LINT_IMPORTS], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-2000:]
    assert "1 kept, 0 broken" in done.stdout


def test_an_upward_import_in_a_function_breaks_the_contract(tmp_path: Path) -> None:
    _package(
        tmp_path,
        {
            "pkg/__init__.py": "",
            "pkg/high/__init__.py": "",
            "pkg/low/__init__.py": "def f():\n    from pkg.high import x  # upward, hidden in a function\n",
            "pkg/high/x.py": "",
            ".importlinter": """
                [importlinter]
                root_package = pkg
                [importlinter:contract:layers]
                name = layers
                type = layers
                containers = pkg
                layers =
                    high
                    low
                """,
        },
    )
    assert LINT_IMPORTS is not None
    done = subprocess.run(
        [LINT_IMPORTS, "--config", ".importlinter"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
        env={"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"},
    )
    assert done.returncode == 1 and "pkg.low -> pkg.high.x" in done.stdout, done.stdout + done.stderr


def test_descgen_has_no_import_cycle() -> None:
    assert cycles("descgen") == []


def test_the_cycle_check_finds_one_closed_inside_a_function(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    _package(
        tmp_path,
        {
            "cyc/__init__.py": "",
            "cyc/a.py": "from cyc import b\n",
            "cyc/b.py": "def later():\n    from cyc import c\n",
            "cyc/c.py": "import cyc.a\n",
            "cyc/d.py": "from cyc import a\n",  # imports into the cycle, is not part of it
        },
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    assert cycles("cyc") == [["cyc.a", "cyc.b", "cyc.c"]]
