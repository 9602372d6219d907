"""A rendered image per known pose on the evidence page: the record check compares (its model
positions against yourdfpy, its measured positions against the spec), staleness, missing
images, and that PNG bytes are never what check compares."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from descgen.commands import evidence_page
from descgen.commands.generate import check, plan
from descgen.write import pose_images

from .conftest import ROOT

SPEC = "specs/warehouse_arm.yaml"
PKG = "generated/warehouse_arm_description"


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """The committed example (package, control evidence and report) copied: check passes on it."""
    shutil.copytree(ROOT / "specs", tmp_path / "specs")
    shutil.copytree(ROOT / PKG, tmp_path / PKG, symlinks=True)
    moveit = "generated/warehouse_arm_moveit_config"
    shutil.copytree(ROOT / moveit, tmp_path / moveit, symlinks=True)
    return tmp_path


def errors(root: Path) -> list[tuple[str, str]]:
    outcome = check(root / SPEC)
    return [(f.code, f.subject) for f in outcome.findings if f.severity == "error"]


def sidecar(root: Path) -> dict:  # type: ignore[type-arg]
    return json.loads((root / PKG / pose_images.SIDECAR).read_text())


def test_recorded_model_positions_equal_yourdfpy_forward_kinematics(tmp_path: Path) -> None:
    yourdfpy = pytest.importorskip("yourdfpy")
    p = plan(ROOT / SPEC)
    urdf_rel = next(rel for rel in p.files if rel.startswith("urdf/") and rel.endswith(".urdf"))
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(p.files[urdf_rel])
    model = yourdfpy.URDF.load(str(urdf), load_meshes=False, build_collision_scene_graph=False)
    record = json.loads(pose_images.record(p.robot))["poses"]
    assert sorted(record) == sorted(kp.name for kp in p.robot.known_poses)
    checked = 0
    for kp in p.robot.known_poses:
        q = dict(kp.joints)
        model.update_cfg({name: q.get(name, 0.0) for name in model.actuated_joint_names})
        for marker in record[kp.name]["markers"]:
            base = marker["relative_to"] or model.base_link
            want = model.get_transform(marker["frame"], base)[:3, 3] * 1000
            assert np.allclose(marker["model_mm"], want, atol=1e-3), (kp.name, marker["frame"])
            checked += 1
    assert checked == 6  # the example's six measurements (hand count of the spec's known_poses)


def test_recorded_measured_positions_are_the_specs_values() -> None:
    record = json.loads(pose_images.record(plan(ROOT / SPEC).robot))["poses"]
    measured = {(name, m["frame"]): m["measured_mm"] for name, pose in record.items() for m in pose["markers"]}
    assert measured == {  # copied by hand from specs/warehouse_arm.yaml
        ("zero", "tool_link"): [501.0, 0.0, 459.0],
        ("zero", "camera_link"): [524.0, 1.0, 501.0],
        ("ready", "tool_link"): [251.0, -1.0, 861.0],
        ("ready", "camera_link"): [211.0, 0.0, 884.0],
        ("side_reach", "tool_link"): [-49.0, 552.0, 758.0],
        ("shoulder_up_30", "tool_link"): [428.0, 0.0, 733.0],
    }
    assert record["ready"]["joints"] == {"lift_joint": 0.15, "elbow_joint": pytest.approx(-np.pi / 2)}


def test_the_page_embeds_one_image_per_known_pose_and_each_exists() -> None:
    page = (ROOT / PKG / evidence_page.PAGE).read_text()
    names = ["zero", "ready", "side_reach", "shoulder_up_30"]  # the spec's known poses, in order
    embedded = [line for line in page.splitlines() if line.startswith("![") and "(poses/" in line]
    assert embedded == [f"![{n}](poses/{n}.png)" for n in names]
    for n in names:
        png = ROOT / PKG / "evidence" / "poses" / f"{n}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", n
    assert sorted(sidecar(ROOT)["poses"]) == sorted(names)


def test_a_changed_measured_value_makes_the_image_stale(project: Path) -> None:
    spec = project / SPEC
    text = spec.read_text()
    old = "{frame: tool_link, xyz: [251 mm, -1 mm, 861 mm]"
    assert text.count(old) == 1
    spec.write_text(text.replace(old, "{frame: tool_link, xyz: [251 mm, -1 mm, 862 mm]"))
    assert ("GEN080", f"file:{pose_images.SIDECAR}") in errors(project)


def test_a_deleted_image_is_reported_missing(project: Path) -> None:
    (project / PKG / "evidence" / "poses" / "side_reach.png").unlink()
    assert errors(project) == [("GEN006", "file:evidence/poses/side_reach.png")]


def test_a_deleted_record_is_reported_missing(project: Path) -> None:
    (project / PKG / pose_images.SIDECAR).unlink()
    assert errors(project) == [("GEN006", f"file:{pose_images.SIDECAR}")]


def test_png_bytes_are_not_compared(project: Path) -> None:
    import matplotlib

    before = {p.name: p.read_bytes() for p in (project / PKG / "evidence" / "poses").glob("*.png")}
    robot = plan(project / SPEC).robot
    with matplotlib.rc_context({"lines.linewidth": 6.0}):
        pose_images.write(project / PKG, robot)
    after = {p.name: p.read_bytes() for p in (project / PKG / "evidence" / "poses").glob("*.png")}
    assert sorted(after) == sorted(before) and all(after[n] != before[n] for n in before)  # really redrawn
    assert errors(project) == []


def test_a_new_renderer_version_reads_stale(project: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(pose_images, "RENDERER_VERSION", pose_images.RENDERER_VERSION + "+1")
    assert errors(project) == [("GEN080", f"file:{pose_images.SIDECAR}")]
