"""descgen/infra/dist_version.py reads an installed distribution's version as importlib.metadata
does (the oracle), for every distribution installed here, and evidence_hash.version answers
exactly what importlib.metadata answers."""

from __future__ import annotations

import subprocess
import sys
from importlib import metadata
from pathlib import Path

import pytest

from descgen.infra import evidence_hash
from descgen.infra.dist_version import installed_version
from tests.conftest import ROOT


def _installed() -> list[str]:
    return sorted({d.metadata["Name"] for d in metadata.distributions() if d.metadata["Name"]})


def test_every_installed_distribution_reads_as_importlib_metadata() -> None:
    names = _installed()
    assert len(names) > 50  # the venv: a real population, not an empty loop
    answered = 0
    for name in names:
        ours = installed_version(name)
        if ours is not None:  # None: the caller asks importlib.metadata
            assert ours == metadata.version(name), name
            answered += 1
    assert answered > len(names) * 0.9  # the fast path is the common case


@pytest.mark.parametrize("name", ["PyYAML", "pyyaml", "Jinja2", "jinja2", "pydantic", "lxml", "xacro", "numpy"])
def test_names_are_compared_normalised(name: str) -> None:
    assert installed_version(name) == metadata.version(name)
    assert evidence_hash.version.__wrapped__(name) == metadata.version(name)


def test_absent_and_ambiguous_fall_back(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert installed_version("surely-not-installed-dist-xyz") is None
    assert evidence_hash.version.__wrapped__("surely-not-installed-dist-xyz") == "absent"
    for folder in ("twin-1.0.dist-info", "twin-2.0.dist-info"):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "METADATA").write_text(f"Metadata-Version: 2.1\nName: twin\nVersion: {folder[5:8]}\n\n")
    (tmp_path / "lone-3.1.dist-info").mkdir()
    (tmp_path / "lone-3.1.dist-info" / "METADATA").write_text("Metadata-Version: 2.1\nName: lone\nVersion: 3.1\n\nbody")
    (tmp_path / "nover-1.0.dist-info").mkdir()
    (tmp_path / "nover-1.0.dist-info" / "METADATA").write_text("Metadata-Version: 2.1\nName: nover\n\nVersion: 9\n")
    (tmp_path / "old.egg-info").mkdir()
    monkeypatch.syspath_prepend(str(tmp_path))
    assert installed_version("twin") is None  # two in one folder: importlib.metadata decides
    assert installed_version("lone") == "3.1" == metadata.version("lone")
    assert installed_version("nover") is None  # no Version in the header
    assert installed_version("old") is None  # an egg-info


def test_validate_and_the_tool_versions_do_not_import_importlib_metadata() -> None:
    """Fresh process: validate needs no importlib.metadata (pydantic's plugin lookup imported it),
    nor do the tool versions check's result cache and evidence records ask for; check's
    pydantic plugin loader was descgen's stand-in, gone once main returns."""
    probe = (
        "import sys\n"
        "from descgen.cli import main\n"
        "main(['validate', sys.argv[1]])\n"
        "print('validate', 'importlib.metadata' in sys.modules)\n"
        "from descgen.infra import evidence_hash\n"
        "evidence_hash.versions('xacro', 'lxml', 'catkin_pkg', 'pyparsing', 'numpy', 'pint', 'pydantic', 'PyYAML',"
        " 'Jinja2', 'rosbags', 'trimesh')\n"
        "print('versions', 'importlib.metadata' in sys.modules)\n"
        "main(['check', sys.argv[1]])\n"
        "print('check', 'pydantic.plugin._loader' in sys.modules)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe, str(ROOT / "specs" / "warehouse_arm.yaml")],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    seen = [line for line in done.stdout.splitlines() if line.startswith(("validate ", "versions ", "check "))]
    # main took its stand-in loader away again, and pydantic's own was never imported
    assert seen == ["validate False", "versions False", "check False"], done.stdout
