"""What ``verdict.json`` records of a control run: the run itself (``run``), so that ``check``
can repeat it, and the hashes of its inputs and of what it wrote (``reuse``), so that ``check``
can take unchanged evidence as current without repeating it (descgen/commands/control/evidence_check.py)."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

from descgen.commands.control.system import Plant
from descgen.core.model import Robot
from descgen.infra import evidence_hash, keys
from descgen.infra.safeio import MAX_DESCRIPTION_BYTES, read_bounded

RECORD_KEY = "run"
REUSE_KEY = "reuse"  # the input and content hashes (descgen/infra/evidence_hash.py); never compared
_DATA = ("lifecycle.jsonl", "lifecycle.md", "interfaces.md", "desired_vs_measured.csv")
# what the run's results depend on besides descgen: the recording's writer and its arrays, the
# YAML and XML readers and xacro (the package's ros2_control block is expanded and read)
_TOOLS = ("rosbags", "numpy", "PyYAML", "lxml", "xacro")
# descgen's part in the evidence (descgen/infra/keys.py EVIDENCE): bump when the run, the plant or
# what the evidence files hold changes; committed evidence then reads as computed with another
# descgen and check runs it again. tests/test_evidence_recompute.py runs it again regardless and
# fails when the committed files differ, so a forgotten bump does not pass CI.
FORMAT = 1


def run_record(package: Path, trajectory: str, duration: float | None, plant: Plant) -> dict[str, Any]:
    """What ``verdict.json`` records so that ``check`` can run the same again."""
    return {
        "trajectory": _shown(Path(trajectory), project(package)),
        "duration_s": duration,
        "plant": dataclasses.asdict(plant),
    }


def project(package: Path) -> Path:
    """The folder holding the output root (``generated/``), as ``generate.spec_display`` uses."""
    return package.resolve().parent.parent


def _shown(path: Path, project: Path) -> str:
    try:
        return path.resolve().relative_to(project).as_posix()
    except ValueError:
        return str(path.resolve())


def input_key(package: Path, robot: Robot, record: dict[str, Any]) -> str:
    """The key (descgen/infra/keys.py) of everything the run and its files are a function of:
    the spec (the model's limits and tolerances), the generated package on disk (the run loads
    its ros2_control block and controllers YAML), the record and the trajectory, with
    :data:`FORMAT`, descgen's release and the libraries' versions."""
    path = Path(str(record.get("trajectory")))
    if not path.is_absolute():
        path = project(package) / path
    trajectory = evidence_hash.sha256(path.read_bytes()) if path.is_file() else "missing"
    inputs = {
        "spec": robot.spec_hash,
        "record": record,
        "trajectory": trajectory,
        "package": evidence_hash.package_files(package, ("evidence/",)),
    }
    return keys.key("control evidence", FORMAT, inputs, _TOOLS, keys.EVIDENCE)


def written_content(folder: Path, verdict: dict[str, Any]) -> str:
    """The evidence as written, as one text to hash: each data file's bytes, verdict.json's
    data (its reuse record aside), the recording's files and the names of the plots."""
    parts: dict[str, Any] = {
        name: evidence_hash.sha256(read_bounded(folder / name, name, MAX_DESCRIPTION_BYTES)) for name in _DATA
    }
    parts["verdict.json"] = evidence_hash.digest({k: v for k, v in verdict.items() if k != REUSE_KEY})
    parts["control_run/"] = evidence_hash.package_files(folder / "control_run")
    parts["plots"] = sorted(p.name for p in folder.glob("*.png"))
    return json.dumps(parts, sort_keys=True)


def reuse_record(folder: Path, package: Path, robot: Robot, verdict: dict[str, Any]) -> dict[str, str] | None:
    """What verdict.json records for reuse after a run wrote ``folder`` (None: no record)."""
    record = verdict.get(RECORD_KEY)
    if not isinstance(record, dict):
        return None
    content = evidence_hash.sha256(written_content(folder, verdict))
    return {"input-sha256": input_key(package, robot, record), "content-sha256": content}
