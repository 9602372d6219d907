"""What users install is what is tested: the wheel, built from its sdist as ``python -m build``
does, installed without ``-e`` (dependencies resolved by pip from the registry, as a user's
``pip install`` does) into a fresh venv outside the checkout, runs every command from a project
folder that is not this repository, on the example and on an example-robot-data robot.

A hand-kept package list once left four packages out of the wheel and every command died with
ModuleNotFoundError while the editable install the rest of the suite uses hid it. Expected exit
codes are those the README states for each command on these inputs."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from tests.corpus import share
from tests.helpers import ROOT, user_project

pytestmark = [pytest.mark.slow, pytest.mark.e2e]


def _build(work: Path) -> Path:
    """The wheel, built from a copy of what the sdist is made of (the repository stays clean)."""
    src = work / "src"
    shutil.copytree(ROOT / "descgen", src / "descgen", ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src / name)
    dist = work / "dist"
    # no isolation: the build backend is the test venv's setuptools (pyproject's test extra)
    done = subprocess.run(
        [sys.executable, "-m", "build", "--no-isolation", "--outdir", str(dist), str(src)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    (built,) = dist.glob("descgen-*.whl")
    return built


def _install(wheel: Path, folder: Path) -> Path:
    """A fresh venv with the wheel and its declared dependencies; its bin folder."""
    base = getattr(sys, "_base_executable", sys.executable)
    subprocess.run([base, "-m", "venv", str(folder)], check=True, timeout=300)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    done = subprocess.run(
        # --no-compile: no .pyc for all of numpy, scipy and matplotlib up front (half of the install's
        # time); the commands compile what they import, as any interpreter does
        [
            str(folder / "bin" / "python"),
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            "--no-compile",
            str(wheel),
        ],
        capture_output=True,
        text=True,
        timeout=1200,
        env=env,
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    return folder / "bin"


def _holds_every_package_and_the_templates(wheel: Path) -> None:
    names = set(zipfile.ZipFile(wheel).namelist())
    packages = sorted(p.parent.relative_to(ROOT).as_posix() for p in (ROOT / "descgen").rglob("__init__.py"))
    assert [p for p in packages if f"{p}/__init__.py" not in names] == []
    templates = sorted(p.name for p in (ROOT / "descgen" / "templates").glob("*.j2"))
    assert templates and [t for t in templates if f"descgen/templates/{t}" not in names] == []
    modules = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "descgen").rglob("*.py"))
    assert [m for m in modules if m not in names] == []


def _run(bin_dir: Path, cwd: Path, *args: str | Path) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    return subprocess.run(
        [str(bin_dir / "descgen"), *map(str, args)], capture_output=True, text=True, cwd=cwd, env=env, timeout=600
    )


def _installed_descgen_is_the_wheel(venv: Path, tmp_path: Path) -> None:
    code = "import descgen, sys; print(descgen.__file__)"
    where = subprocess.run([str(venv / "python"), "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert where.returncode == 0, where.stderr
    assert Path(where.stdout.strip()).is_relative_to(venv.parent)
    assert subprocess.run([str(venv / "python"), "-m", "pip", "check"], capture_output=True).returncode == 0


# command line -> the exit code the README gives for it on these inputs
EXAMPLE = "specs/warehouse_arm.yaml"
URDF = "generated/warehouse_arm_description/urdf/warehouse_arm.urdf"
COMMANDS: list[tuple[list[str], int]] = [
    (["--version"], 0),
    (["--help"], 0),
    (["validate", EXAMPLE], 0),
    (["validate", EXAMPLE, "--format", "junit"], 0),
    (["generate", EXAMPLE], 0),
    (["check", EXAMPLE], 0),
    (["check", EXAMPLE, "--format", "junit"], 0),
    (["poses", EXAMPLE], 0),
    (["frames", EXAMPLE], 0),
    (["audit", URDF], 0),
    (["audit", URDF, "--format", "sarif"], 0),
    (["audit", URDF, "--format", "junit"], 0),
    (["faults", URDF], 0),
    (["tf-scenario", EXAMPLE, "--out", "bag", "--duration", "2 s"], 0),
    (["tf-audit", "bag", "--target", "base_link"], 0),
    (["control", EXAMPLE, "--trajectory", "specs/trajectories/ready.yaml", "--out", "control"], 0),
    (["report", EXAMPLE], 0),
    (["sweep", EXAMPLE], 0),
    # the optional extras are not installed: a located error saying how to get them
    (["simulate", EXAMPLE], 2),
    (["view", EXAMPLE], 2),
    (["schema"], 0),
    (["rules"], 0),
    (["rules", "GEN001"], 0),
    (["validate", "specs/missing.yaml"], 2),
]


def _every_command_runs_on_the_example(venv: Path, tmp_path: Path) -> None:
    project = user_project(tmp_path)
    for args, expected in COMMANDS:
        done = _run(venv, project, *args)
        assert "Traceback" not in done.stderr + done.stdout, (args, done.stderr[-3000:])
        assert done.returncode == expected, (args, done.returncode, done.stderr[-3000:])
    assert _run(venv, project, "--version").stdout.strip() == "descgen 0.1.0"
    assert "SIM009" in _run(venv, project, "simulate", EXAMPLE).stderr


def _import_and_audit_a_real_robot(venv: Path, tmp_path: Path) -> None:
    corpus = share()
    assert corpus is not None, "example-robot-data is in the test extra"
    robots = corpus / "example-robot-data" / "robots" / "ur_description"
    urdf, srdf = robots / "urdf" / "ur5_robot.urdf", robots / "srdf" / "ur5.srdf"
    project = tmp_path / "ur_ws"
    (project / "specs").mkdir(parents=True)
    pkg = ["--package-path", str(corpus)]
    steps: list[tuple[list[str | Path], int]] = [
        (["audit", urdf, "--srdf", srdf, *pkg], 0),
        (["import", urdf, "--srdf", srdf, *pkg, "-o", "specs/ur5.yaml"], 0),
        (["validate", "specs/ur5.yaml", *pkg], 0),
        (["generate", "specs/ur5.yaml", *pkg], 0),
        (["check", "specs/ur5.yaml", *pkg], 0),
        (["audit", "generated/ur5_description/urdf/ur5.urdf", *pkg], 0),
    ]
    for args, expected in steps:
        done = _run(venv, project, *args)
        assert "Traceback" not in done.stderr, (args, done.stderr[-3000:])
        assert done.returncode == expected, (args, done.returncode, done.stderr[-3000:])
    assert (project / "generated" / "ur5_description" / "package.xml").is_file()


def test_the_wheel_installs_and_runs_every_command(tmp_path: Path) -> None:
    """One test, so one process builds and installs the wheel once (about a minute)."""
    wheel = _build(tmp_path / "build")
    _holds_every_package_and_the_templates(wheel)
    venv = _install(wheel, tmp_path / "venv" / "venv")
    for step, check in enumerate(
        (_installed_descgen_is_the_wheel, _every_command_runs_on_the_example, _import_and_audit_a_real_robot)
    ):
        (tmp_path / f"step{step}").mkdir()
        check(venv, tmp_path / f"step{step}")
