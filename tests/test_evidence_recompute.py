"""Committed evidence goes stale only when what determines it changes (issue 30).

Evidence is keyed (descgen/infra/keys.py) by its inputs, the libraries' versions, descgen's
release and a format version per computation (collision.ALGORITHM, sweep.ALGORITHM,
evidence_page.FORMAT, control.record.FORMAT), not by the bytes of descgen's source. So:

- a comment-only or docstring-only edit anywhere in descgen leaves ``descgen check specs/``
  passing on the committed evidence, reusing every record (nothing sampled, swept, run or built);
- a behaviour change whose format version was not bumped is caught here: ``check`` with
  ``DESCGEN_RECOMPUTE=1`` computes every piece of evidence again (caches off, no record reused)
  and compares it with the committed files, so the committed evidence must be what descgen
  computes today; a bumped version makes a plain ``check`` compute again too.

The edits are made in a copy of the repository (its tracked and untracked-but-not-ignored files,
as ``git ls-files`` lists them), run with ``PYTHONPATH=<copy>``."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from descgen.commands import evidence_page
from descgen.infra import evidence_hash
from tests.helpers import ROOT

pytest.importorskip("pinocchio")  # the matrix and the sweep are sampled again (the test extras have it)

EVERY = ["control", "matrix", "page", "sweep"]
# `descgen check` in the current folder, counting each piece of evidence it computes instead of reusing
_PROBE = """
import json, sys
from descgen.cli import main
from descgen.commands import evidence_page
from descgen.commands.control import evidence_check
from descgen.physics import collision
import descgen.physics.sweep as sweep
computed = []
def counted(module, name, label):
    real = getattr(module, name)
    def wrapper(*args, **kwargs):
        computed.append(label)
        return real(*args, **kwargs)
    setattr(module, name, wrapper)
counted(evidence_page, "build", "page")
counted(evidence_check, "_rerun", "control")
counted(collision, "_sample", "matrix")
counted(sweep, "runs", "sweep")
code = main(["check", "specs/"])
seen = {"code": code, "computed": sorted(set(computed)), "descgen": sys.modules["descgen"].__file__}
print("PROBE" + json.dumps(seen))
"""
HOW_TO_FIX = (
    "the committed evidence is not what descgen computes today: if the change is meant, bump the "
    "format version of what changed (collision.ALGORITHM, sweep.ALGORITHM, evidence_page.FORMAT, "
    "control.record.FORMAT, pose_images.RENDERER_VERSION), then run `descgen generate specs/` and "
    "`descgen report specs/warehouse_arm.yaml` and commit the evidence"
)


def _check(project: Path, recompute: bool) -> tuple[dict[str, object], str]:
    """The probe's result and what check printed (stdout and stderr)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", evidence_hash.RECOMPUTE_ENV)}
    env |= {"PYTHONPATH": str(project), "DESCGEN_CACHE_DIR": ""}
    if recompute:
        env[evidence_hash.RECOMPUTE_ENV] = "1"
    done = subprocess.run(
        [sys.executable, "-c", _PROBE], capture_output=True, text=True, cwd=project, env=env, timeout=600
    )
    line = next((x for x in done.stdout.splitlines() if x.startswith("PROBE")), None)
    assert line is not None, done.stdout[-3000:] + done.stderr[-3000:]
    result: dict[str, object] = json.loads(line[len("PROBE") :])
    assert result["descgen"] == str(project / "descgen" / "__init__.py")  # the copy's descgen ran
    return result, done.stdout + done.stderr


def _copy_repository(dest: Path) -> Path:
    """The repository's files as git sees them (tracked, and new files not ignored) under ``dest``."""
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT,
        capture_output=True,
        check=True,
    ).stdout.decode("utf-8", "surrogateescape")
    for rel in filter(None, listed.split("\0")):
        source, target = ROOT / rel, dest / rel
        if not source.is_symlink() and not source.is_file():
            continue  # deleted in the work tree, not yet in the index
        target.parent.mkdir(parents=True, exist_ok=True)
        if source.is_symlink():
            target.symlink_to(os.readlink(source))
        else:
            shutil.copyfile(source, target)
    return dest


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert text.count(old) == 1, (path, old)
    path.write_text(text.replace(old, new), encoding="utf-8")


@pytest.mark.e2e
@pytest.mark.slow
def test_the_committed_evidence_is_what_descgen_computes_today() -> None:
    """Caches off, every record refused: the matrix sampled, the sweep run, the control run
    repeated and the page built, each compared with the committed files."""
    result, printed = _check(ROOT, recompute=True)
    assert result["computed"] == EVERY  # nothing was taken from a record
    assert result["code"] == 0, HOW_TO_FIX + "\n" + printed[-4000:]


@pytest.mark.e2e
@pytest.mark.slow
def test_a_comment_only_edit_leaves_the_committed_evidence_current(tmp_path: Path) -> None:
    """The issue's acceptance test: comments and docstrings edited in the rules and in the code
    that computes the evidence; check passes on the committed evidence and recomputes none of it."""
    project = _copy_repository(tmp_path / "repo")
    descgen = project / "descgen"
    joints = descgen / "audit" / "rules" / "joints.py"
    joints.write_text(joints.read_text(encoding="utf-8") + "# a comment: no rule changed\n", encoding="utf-8")
    _edit(descgen / "commands" / "evidence_page.py", '"""``descgen report``: ', '"""``descgen report`` (edited): ')
    collision = descgen / "physics" / "collision.py"
    _edit(collision, '"""The self-collision matrix: ', '"""The self-collision matrix (a docstring edit): ')
    result, printed = _check(project, recompute=False)
    assert result["code"] == 0, printed[-4000:]
    assert "generated files are up to date and every check passed" in printed
    assert result["computed"] == []  # every piece of evidence taken from its record


@pytest.mark.e2e
@pytest.mark.slow
def test_a_behaviour_change_is_caught_by_recomputing_and_by_its_bump(tmp_path: Path) -> None:
    """What the page says changes: the recomputing check reports the committed page stale even
    before the format version is bumped (CI runs it), and after the bump a plain check does."""
    project = _copy_repository(tmp_path / "repo")
    page = project / "descgen" / "commands" / "evidence_page.py"
    _edit(page, "ends with a verdict.", "ends with its verdict.")
    stale = "error[GEN080]: evidence/README.md is stale"
    result, printed = _check(project, recompute=True)
    assert result["code"] == 1 and stale in printed, printed[-4000:]
    _edit(page, f"\nFORMAT = {evidence_page.FORMAT}\n", f"\nFORMAT = {evidence_page.FORMAT + 1}\n")
    result, printed = _check(project, recompute=False)
    assert result["code"] == 1 and stale in printed, printed[-4000:]
    assert result["computed"] == ["page"]  # the key named the new format: built again, and compared
