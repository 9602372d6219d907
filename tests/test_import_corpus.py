"""docs/import-corpus.md stays true: each row is re-computed by importing the robot again.

A fixed subset runs in every run; the whole corpus (69 robots, about a minute) is marked slow.
``python -m tests.test_import_corpus`` prints the table's rows to paste into the doc.
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen.audit.spec import load_spec_text
from descgen.commands.importer.run import ImportOptions, import_description
from descgen.core.findings import InputError
from descgen.physics.poses import evaluate
from descgen.read.description import Options
from tests.corpus import descriptions, imported
from tests.helpers import ROOT

DOC = ROOT / "docs" / "import-corpus.md"
ROW = re.compile(r"^\| `([^`]+)` \|.*\|$")
SUBSET = (
    "panda_description/urdf/panda.urdf",  # an arm with an SRDF: group states -> known poses
    "talos_data/robots/talos_reduced.urdf",  # a humanoid with transmissions in pass-through
    "double_pendulum_description/urdf/double_pendulum.urdf",  # a defect: the spec fails validate
    "solo_description/robots/solo12.urdf",  # a quadruped
    "tiago_description/robots/tiago.urdf",  # a mobile manipulator with Gazebo tags
    "ur_description/urdf/ur3.urdf",  # an unusable description (no links)
)


def _verdict(outcome: object) -> str:
    if outcome.proven:  # type: ignore[attr-defined]
        return "proven"
    if outcome.invalid:  # type: ignore[attr-defined]
        codes = Counter(f.code for f in outcome.invalid)  # type: ignore[attr-defined]
        return "fails validate: " + ", ".join(f"{c}×{n}" for c, n in sorted(codes.items()))
    return f"differs at {len(outcome.imported.differences)}"  # type: ignore[attr-defined]


def row(ident: str, urdf: Path, srdf: Path | None) -> str:
    """One table row: counts taken from the written spec's YAML, so the doc says what a reviewer
    finds in the file."""
    outcome = imported(urdf, srdf)
    data = yaml.safe_load(outcome.imported.spec_text)
    kept = Counter(re.match(r"<([\w:.-]+)", p["xml"]).group(1) for p in data.get("passthrough", []))  # type: ignore[union-attr]
    passthrough = ", ".join(f"{t}×{n}" for t, n in sorted(kept.items())) or "—"
    parts = sum(len(p["instances"]) for p in data.get("parts", []))
    cells = [
        f"`{ident}`",
        str(len(outcome.imported.robot.links)),
        str(len(outcome.imported.robot.joints)),
        f"{len(data.get('parts', []))} ({parts} links)" if parts else "—",
        str(len(data.get("sensors", []))),
        str(len(data.get("known_poses", []))),
        passthrough,
        _verdict(outcome),
    ]
    return "| " + " | ".join(cells) + " |"


def _documented() -> dict[str, str]:
    rows = {}
    for line in DOC.read_text().splitlines():
        m = ROW.match(line)
        if m:
            rows[m.group(1)] = line
    return rows


CORPUS = descriptions()
pytestmark = pytest.mark.skipif(not CORPUS, reason="example-robot-data is not installed")


def test_the_table_lists_every_corpus_robot_once() -> None:
    rows = _documented()
    assert sorted(rows) == sorted(ident for ident, _, _ in CORPUS)
    text = DOC.read_text()
    assert len(re.findall(r"^\| `", text, re.M)) == len(CORPUS)  # no robot twice


def _check(ident: str, urdf: Path, srdf: Path | None) -> None:
    try:
        got = row(ident, urdf, srdf)
    except InputError as exc:
        got = f"| `{ident}` | unusable: {', '.join(sorted({f.code for f in exc.findings}))} |"
    assert got == _documented()[ident]


@pytest.mark.parametrize(("ident", "urdf", "srdf"), [d for d in CORPUS if d[0] in SUBSET], ids=lambda v: str(v))
def test_subset_rows_are_true(ident: str, urdf: Path, srdf: Path | None) -> None:
    _check(ident, urdf, srdf)


@pytest.mark.slow
@pytest.mark.parametrize(("ident", "urdf", "srdf"), [d for d in CORPUS if d[0] not in SUBSET], ids=lambda v: str(v))
def test_every_row_is_true(ident: str, urdf: Path, srdf: Path | None) -> None:
    _check(ident, urdf, srdf)


@pytest.mark.parametrize("ident", ["panda_description/urdf/panda.urdf", "tiago_description/robots/tiago.urdf"])
def test_imported_known_poses_hold_on_the_loaded_spec(ident: str) -> None:
    """The known poses import adds are checked by descgen's own pose evaluation on the loaded
    spec (every frame within its 0.001 mm), and their tips are where pinocchio puts them."""
    import numpy as np
    import pinocchio as pin

    ((_, urdf, srdf),) = [d for d in CORPUS if d[0] == ident]
    outcome = import_description(urdf, ImportOptions(Options(srdf=srdf)))
    assert outcome.proven
    robot = load_spec_text(outcome.imported.spec_text, "r.yaml", rules=False).robot
    rows = evaluate(robot)
    assert rows and all(r.error is not None and max(map(abs, r.error)) <= 1e-6 for r in rows)
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    # mimic followers, read from the URDF itself (pinocchio's URDF model treats them as free)
    mimics = {
        j.get("name"): (m.get("joint"), float(m.get("multiplier", "1")), float(m.get("offset", "0")))
        for j in etree.parse(str(urdf)).getroot().iterfind("joint")
        if (m := j.find("mimic")) is not None
    }
    for kp in robot.known_poses:
        q = pin.neutral(model)
        values = dict(kp.joints)
        values |= {f: k * values.get(lead, 0.0) + off for f, (lead, k, off) in mimics.items()}
        for name, value in values.items():
            j = model.joints[model.getJointId(name)]
            if j.nq == 2:  # a continuous joint: cos, sin
                q[j.idx_q : j.idx_q + 2] = [np.cos(value), np.sin(value)]
            else:
                q[j.idx_q] = value
        pin.framesForwardKinematics(model, data, q)
        for fm in kp.frames:
            placed = data.oMf[model.getFrameId(fm.frame)].translation
            assert np.allclose(placed, fm.xyz, rtol=0, atol=1e-9), (kp.name, fm.frame)


if __name__ == "__main__":
    for ident, urdf, srdf in CORPUS:
        try:
            print(row(ident, urdf, srdf))
        except InputError as exc:
            print(f"| `{ident}` | unusable: {', '.join(sorted({f.code for f in exc.findings}))} |")
