"""Calibration (issue 31): the spec's calibration layer, the importers and ``descgen drift``.

Oracles: the UR description's own Xacro expanded with a UR calibration file; yourdfpy's forward
kinematics of the generated URDF; pinocchio on a URDF with planted errors (tests/drift_data.py)
for the recordings drift reads; hand-computed transforms for the hand-eye mount."""

from __future__ import annotations

import dataclasses
import json
import math
import random
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml

from . import drift_data as dd
from .conftest import EXAMPLE, ROOT
from .helpers import cli

UR = ROOT / "tests" / "data" / "xacro_corpus"
EXAMPLE_URDF = ROOT / "generated" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf"
ARM = ("lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint")
CAL_BLOCK = """
calibration:
  sources:
    tracker: {method: laser tracker, date: 2026-11-20}
  joints:
    elbow_joint:
      source: tracker
      offset: 0.05 deg
      origin: {xyz: [0.3 mm, 0, 0]}
  sensors:
    camera:
      source: tracker
      origin: {xyz: [25.5 mm, 0, 40 mm], rpy: [0, 0, 0.2 deg]}
"""


def _no_poses(text: str) -> str:
    """The example with its known poses' tolerance at 20 mm: they hold the nominal model to 2 mm
    and one sits at exactly 2.0 mm, so any calibration of the arm would fail them (rightly)."""
    return text.replace("tolerance: 2 mm", "tolerance: 20 mm")


def _spec(tmp_path: Path, block: str = CAL_BLOCK) -> Path:
    spec = tmp_path / "wa.yaml"
    spec.write_text(EXAMPLE.read_text() + block)
    return spec


def _urdf_model(path: Path) -> object:
    import yourdfpy

    return yourdfpy.URDF.load(str(path), load_meshes=False, build_scene_graph=True)


def _transform(model: object, cfg: dict[str, float], frame: str, base: str) -> np.ndarray:
    model.update_cfg(cfg)  # type: ignore[attr-defined]
    return np.array(model.get_transform(frame, base))  # type: ignore[attr-defined]


# --------------------------------------------------------------------------- the spec layer


def test_calibrated_urdf_is_the_nominal_robot_at_q_plus_offset(tmp_path: Path) -> None:
    """yourdfpy: the generated URDF at q equals the committed (nominal) URDF at q + offset for the
    elbow, with the origin shifted 0.3 mm along the upper arm's x; the camera sits where it was
    measured. ``xacro calibration:=nominal.yaml`` (the real xacro CLI) gives the nominal origins."""
    spec = _spec(tmp_path)
    ran = cli("generate", spec, "--out", tmp_path / "gen", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-3000:]
    pkg = tmp_path / "gen" / "warehouse_arm_description"
    cal, nom = _urdf_model(pkg / "urdf" / "warehouse_arm.urdf"), _urdf_model(EXAMPLE_URDF)
    rng = random.Random(4)
    for _ in range(5):
        q = {
            "lift_joint": rng.uniform(0, 0.3),
            "shoulder_lift_joint": rng.uniform(-1, 1),
            "elbow_joint": rng.uniform(-1, 1),
        }
        got = _transform(cal, q, "forearm_link", "upper_link")
        want = _transform(
            nom, {**q, "elbow_joint": q["elbow_joint"] + math.radians(0.05)}, "forearm_link", "upper_link"
        )
        want[0, 3] += 0.0003
        assert np.allclose(got, want, atol=1e-12)
    cam = _transform(cal, {}, "camera_link", "tool_link")
    assert np.allclose(cam[:3, 3], [0.0255, 0.0, 0.04], atol=1e-12)
    assert math.isclose(math.atan2(cam[1, 0], cam[0, 0]), math.radians(0.2), abs_tol=1e-12)
    nominal = yaml.safe_load((pkg / "config" / "calibration" / "nominal.yaml").read_text())
    assert nominal["joints"]["elbow_joint"]["x"] == 0.3 and nominal["joints"]["camera_joint"]["x"] == 0.025
    xacro = shutil.which("xacro", path=str(ROOT / ".venv" / "bin")) or shutil.which("xacro")
    assert xacro is not None
    import subprocess

    out = subprocess.run(
        [xacro, str(pkg / "urdf" / "warehouse_arm.urdf.xacro"), f"calibration:={pkg}/config/calibration/nominal.yaml"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    elbow = re.search(r'<joint name="elbow_joint".*?<origin ([^/]*)/>', out, re.S)
    assert elbow is not None
    xyz = re.search(r'xyz="([^"]*)"', elbow.group(1))
    rpy = re.search(r'rpy="([^"]*)"', elbow.group(1))
    assert xyz and rpy and [float(v) for v in xyz.group(1).split()] == [0.3, 0.0, 0.0]
    assert [float(v) for v in rpy.group(1).split()] == [0.0, 0.0, 0.0]


@pytest.mark.parametrize(
    ("block", "code"),
    [
        (CAL_BLOCK.replace("source: tracker\n      offset", "source: tape\n      offset"), "CAL001"),
        (CAL_BLOCK.replace("    elbow_joint:", "    elbow_jiont:"), "CAL002"),
        (CAL_BLOCK.replace("    camera:", "    kamera:"), "CAL002"),
        (CAL_BLOCK.replace("    elbow_joint:", "    tool_joint:"), "CAL003"),
        (CAL_BLOCK.replace("offset: 0.05 deg", "offset: 8 deg"), "CAL004"),
        (CAL_BLOCK.replace("[0.3 mm, 0, 0]", "[30 mm, 0, 0]"), "CAL004"),
    ],
)
def test_calibration_rules_bad(tmp_path: Path, block: str, code: str) -> None:
    ran = cli("validate", _spec(tmp_path, block), cwd=tmp_path)
    assert f"[{code}]" in ran.stderr, ran.stderr[-2000:]


def test_calibration_rules_good(tmp_path: Path) -> None:
    ran = cli("validate", _spec(tmp_path), cwd=tmp_path)
    assert ran.returncode == 0 and "CAL0" not in ran.stderr, ran.stderr[-2000:]


def test_nominal_proof_catches_a_wrong_layer(tmp_path: Path) -> None:
    """The check that takes the layer off fails when the nominal file disagrees with the spec."""
    from descgen.audit.spec import load_spec
    from descgen.prove.xacro_expand import xacro_calibration_nominal
    from descgen.render import render_package

    robot = load_spec(_spec(tmp_path), rules=False).robot
    files = render_package(robot, "wa.yaml", only=None, sweep=lambda r: {"rows": []})
    assert xacro_calibration_nominal(files, robot, tmp_path) == []
    path = "config/calibration/nominal.yaml"
    files[path] = files[path].replace("x: 0.3\n", "x: 0.31\n")
    found = xacro_calibration_nominal(files, robot, tmp_path)
    assert [f.code for f in found] == ["GEN001"] and "elbow_joint" in found[0].message


# --------------------------------------------------------------------------- importers


def test_ur_calibration_generates_the_ur_xacro_with_that_file(tmp_path: Path) -> None:
    """A UR calibration file imported into a spec generates a URDF whose joint origins equal the UR
    Xacro expanded with that file (kinematics_params:=), to 1e-9."""
    from lxml import etree

    from descgen.read.xacro_file import expand

    spec = tmp_path / "specs" / "ur.yaml"
    args = ("--xacro-arg", "ur_type:=ur5e", "--xacro-arg", "name:=ur5e", "--package-path", UR)
    ran = cli("import", UR / "ur_description/urdf/ur.urdf.xacro", *args, "-o", spec, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    # import's known pose is the nominal model's forward kinematics (nominal: true): it pins the
    # nominal model, which the calibration leaves as it is
    assert yaml.safe_load(spec.read_text())["known_poses"][0]["nominal"] is True
    doc = yaml.safe_load((UR / "ur_description/config/ur5e/default_kinematics.yaml").read_text())
    rng = random.Random(7)
    for entry in doc["kinematics"].values():
        if isinstance(entry, dict):
            for k in entry:
                entry[k] = (
                    float(entry[k]) + rng.uniform(-5e-4, 5e-4)
                    if k in "xyz"
                    else float(entry[k]) + rng.uniform(-2e-3, 2e-3)
                )
    doc["kinematics"]["hash"] = "calib_4242"
    cal = tmp_path / "cal" / "robot_calibration.yaml"
    cal.parent.mkdir()
    cal.write_text(yaml.safe_dump(doc))
    ran = cli("import-calibration", spec, cal, "--format", "ur", "--date", "2026-11-02", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    assert "shoulder_pan_joint" in ran.stdout and "6 calibration value(s) imported" in ran.stderr
    saved = yaml.safe_load(spec.read_text())["calibration"]
    assert saved["sources"]["ur_calibration"]["hash"] == "calib_4242"
    ran = cli("generate", spec, "--out", tmp_path / "gen", "--package-path", UR, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-3000:]
    ours = etree.parse(str(tmp_path / "gen" / "ur5e_description" / "urdf" / "ur5e.urdf")).getroot()
    theirs = etree.fromstring(
        expand(
            UR / "ur_description/urdf/ur.urdf.xacro",
            "ur.urdf.xacro",
            {"ur_type": "ur5e", "name": "ur5e", "kinematics_params": str(cal)},
            [UR, cal.parent],
        )
    )

    def origins(root: etree._Element) -> dict[str, list[float]]:
        out = {}
        for j in root.findall("joint"):
            o = j.find("origin")
            out[j.get("name")] = [float(v) for v in f"{o.get('xyz', '0 0 0')} {o.get('rpy', '0 0 0')}".split()]
        return out

    a, b = origins(ours), origins(theirs)
    assert sorted(a) == sorted(b)
    assert max(abs(x - y) for n in a for x, y in zip(a[n], b[n], strict=True)) <= 1e-9
    moved = max(abs(x - y) for x, y in zip(a["elbow_joint"], [-0.425, 0, 0, 0, 0, 0], strict=True))
    assert moved > 1e-5  # the file's values, not the defaults


def test_csv_offsets_and_handeye_mount(tmp_path: Path) -> None:
    """CSV offsets land on their joints; an eye-in-hand result for the camera's optical frame in
    tool_link becomes the camera mount whose optical frame yourdfpy then finds at exactly that pose."""
    spec = tmp_path / "wa.yaml"
    spec.write_text(_no_poses(EXAMPLE.read_text()))
    offsets = tmp_path / "offsets.csv"
    offsets.write_text("joint,offset,unit\nelbow_joint,0.25,deg\nlift_joint,0.0004,\n")
    ran = cli("import-calibration", spec, offsets, "--format", "csv", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    joints = yaml.safe_load(spec.read_text())["calibration"]["joints"]
    assert joints["elbow_joint"]["offset"] == "0.25 deg" and joints["lift_joint"]["offset"] == "0.0004 m"
    he = tmp_path / "wrist.calib"
    q = np.array([-0.5, 0.5, -0.5, 0.5]) + np.array([0.001, -0.002, 0.0015, 0.0])  # REP 103 optical, turned
    q /= np.linalg.norm(q)
    he.write_text(
        yaml.safe_dump(
            {
                "parameters": {
                    "name": "wrist",
                    "calibration_type": "eye_in_hand",
                    "robot_base_frame": "base_link",
                    "robot_effector_frame": "/tool_link",
                    "tracking_base_frame": "camera_optical_frame",
                    "tracking_marker_frame": "marker",
                },
                "transform": {
                    "translation": {"x": 0.0254, "y": 0.0003, "z": 0.0402},
                    "rotation": dict(zip("xyzw", map(float, q), strict=True)),
                },
            }
        )
    )
    ran = cli("import-calibration", spec, he, "--format", "handeye", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    ran = cli("generate", spec, "--out", tmp_path / "gen", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-3000:]
    model = _urdf_model(tmp_path / "gen" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf")
    got = _transform(model, {}, "camera_optical_frame", "tool_link")
    from scipy.spatial.transform import Rotation

    rot = Rotation.from_quat(q).as_matrix()  # scipy: x, y, z, w
    assert np.allclose(got[:3, 3], [0.0254, 0.0003, 0.0402], atol=1e-12)
    assert np.allclose(got[:3, :3], rot, atol=1e-12)


def test_import_calibration_refuses_what_it_cannot_place(tmp_path: Path) -> None:
    spec = tmp_path / "wa.yaml"
    spec.write_text(EXAMPLE.read_text())
    bad = tmp_path / "offsets.csv"
    bad.write_text("joint,offset\nno_such_joint,0.1\n")
    ran = cli("import-calibration", spec, bad, "--format", "csv", cwd=tmp_path)
    assert ran.returncode == 2 and "error[CAL011]" in ran.stderr and "offsets.csv:2" in ran.stderr
    assert spec.read_text() == EXAMPLE.read_text()
    ur = tmp_path / "ur.yaml"
    ur.write_text("kinematics: {shoulder: {x: 0}}\n")
    ran = cli("import-calibration", spec, ur, "--format", "ur", cwd=tmp_path)
    assert ran.returncode == 2 and "error[CAL010]" in ran.stderr and "kinematics.shoulder.y" in ran.stderr


# --------------------------------------------------------------------------- drift


def _drift_json(tmp_path: Path, *args: str | Path) -> dict:
    ran = cli("drift", EXAMPLE, "--frame", "tool_link", "--format", "json", *args, cwd=tmp_path)
    assert ran.returncode in (0, 1), ran.stderr[-2000:]
    return json.loads(ran.stdout)


def _by_name(report: dict) -> dict[str, dict]:
    return {p["parameter"]: p for p in report["identified"]}


@pytest.mark.parametrize("source", ["csv", "bag"])
def test_drift_recovers_planted_errors(tmp_path: Path, source: str) -> None:
    """0.5 deg on the elbow's zero and 3 mm on the shoulder-lift origin, 0.2 mm tracker noise
    (pinocchio's truth): both recovered within three standard errors; the tool frame's own
    roll/pitch/yaw (which move no position) are unidentifiable."""
    urdf = EXAMPLE_URDF.read_text()
    rec = dd.samples(
        urdf,
        "tool_link",
        base="arm_base_link",
        offsets={"elbow_joint": math.radians(0.5)},
        origins={("shoulder_lift_joint", "x"): 0.003},
        joints=ARM,
        n=600,
        noise_m=0.0002,
        seed=11,
    )
    if source == "csv":
        dd.write_csv(tmp_path / "s.csv", rec)
        report = _drift_json(tmp_path, "--samples", tmp_path / "s.csv", "--base", "arm_base_link")
    else:
        dd.write_bag(tmp_path / "bag", rec, joint_rate_hz=97)
        report = _drift_json(tmp_path, "--recording", tmp_path / "bag", "--pose-topic", "/tracker/pose")
        assert report["base"] == "arm_base_link"  # from the poses' frame_id
    assert report["residual"]["samples"] == 600 and report["drifted"]
    assert report["residual"]["p95_m"] > 0.003
    got = _by_name(report)
    offset, origin = got["joint:elbow_joint:offset"], got["joint:shoulder_lift_joint:origin.x"]
    assert abs(offset["value"] - math.radians(0.5)) <= 3 * offset["stderr"], offset
    assert abs(origin["value"] - 0.003) <= 3 * origin["stderr"], origin
    assert offset["stderr"] < math.radians(0.05) and origin["stderr"] < 0.0003
    assert report["after_fit"]["median_m"] < 0.0004  # what is left is the noise
    assert {f"joint:tool_joint:origin.{c}" for c in ("roll", "pitch", "yaw")} <= set(report["unidentifiable"])
    assert report["change_point"] is None


def test_drift_unexcited_parameter_is_unidentifiable(tmp_path: Path) -> None:
    """The elbow never moves (it stays at 0): the tool flange's place on the forearm cannot be told
    from the elbow's place on the upper arm, so of the four asked for, the elbow's two carry the sums
    and the tool's two are unidentifiable; with the elbow moving, all four are identified."""
    urdf = EXAMPLE_URDF.read_text()
    asked = ",".join(f"joint:{j}:origin.{c}" for j in ("elbow_joint", "tool_joint") for c in "xz")
    still = dd.samples(
        urdf,
        "tool_link",
        base="arm_base_link",
        joints=ARM,
        n=200,
        noise_m=0.0002,
        moving=("lift_joint", "shoulder_pan_joint", "shoulder_lift_joint"),
    )
    dd.write_csv(tmp_path / "still.csv", still)
    report = _drift_json(
        tmp_path, "--samples", tmp_path / "still.csv", "--base", "arm_base_link", "--parameters", asked
    )
    assert report["unidentifiable"] == ["joint:tool_joint:origin.x", "joint:tool_joint:origin.z"]
    assert _by_name(report)["joint:elbow_joint:origin.x"]["stands_for"] == ["joint:tool_joint:origin.x"]
    moving = dd.samples(urdf, "tool_link", base="arm_base_link", joints=ARM, n=200, noise_m=0.0002)
    dd.write_csv(tmp_path / "moving.csv", moving)
    report = _drift_json(
        tmp_path, "--samples", tmp_path / "moving.csv", "--base", "arm_base_link", "--parameters", asked
    )
    assert report["unidentifiable"] == [] and len(report["identified"]) == 4
    assert all("stands_for" not in p for p in report["identified"])


def test_drift_finds_the_moment_of_a_motor_swap(tmp_path: Path) -> None:
    """A recording that spans a motor swap (the elbow's zero moves by 1 deg at 24 s): the change
    is found near 24 s and the fit after it recovers the new offset."""
    urdf = EXAMPLE_URDF.read_text()
    rec = dd.samples(
        urdf,
        "tool_link",
        base="arm_base_link",
        joints=ARM,
        n=600,
        noise_m=0.0002,
        seed=3,
        switch=(24.0, {"elbow_joint": math.radians(1.0)}, None),
    )
    dd.write_csv(tmp_path / "swap.csv", rec)
    report = _drift_json(
        tmp_path, "--samples", tmp_path / "swap.csv", "--base", "arm_base_link", "--parameters", "joint:*:offset"
    )
    change = report["change_point"]
    assert change is not None and abs(change["after_s"] - 24.0) < 2.0, change
    got = _by_name(report)["joint:elbow_joint:offset"]
    assert abs(got["value"] - math.radians(1.0)) <= max(3 * got["stderr"], math.radians(0.02)), got


def test_drift_clean_robot_passes(tmp_path: Path) -> None:
    urdf = EXAMPLE_URDF.read_text()
    rec = dd.samples(urdf, "tool_link", base="arm_base_link", joints=ARM, n=100, noise_m=0.0001)
    dd.write_csv(tmp_path / "ok.csv", rec)
    ran = cli(
        "drift",
        EXAMPLE,
        "--frame",
        "tool_link",
        "--base",
        "arm_base_link",
        "--samples",
        tmp_path / "ok.csv",
        cwd=tmp_path,
    )
    assert ran.returncode == 0 and "no change of the residual" in ran.stdout, ran.stdout + ran.stderr


def test_suggested_block_validates(tmp_path: Path) -> None:
    """The block drift suggests, pasted into the spec, is accepted by validate."""
    urdf = EXAMPLE_URDF.read_text()
    rec = dd.samples(
        urdf,
        "tool_link",
        base="arm_base_link",
        offsets={"elbow_joint": math.radians(0.3)},
        joints=ARM,
        n=200,
        noise_m=0.0001,
    )
    dd.write_csv(tmp_path / "s.csv", rec)
    report = _drift_json(
        tmp_path, "--samples", tmp_path / "s.csv", "--base", "arm_base_link", "--parameters", "joint:*:offset"
    )
    spec = tmp_path / "wa.yaml"
    spec.write_text(_no_poses(EXAMPLE.read_text()) + "\n" + report["suggested"])
    ran = cli("validate", spec, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]


def test_evidence_page_shows_nominal_beside_calibrated(tmp_path: Path) -> None:
    """report's section 11: each calibrated joint's nominal and calibrated origin and the size of
    the correction (0.3 mm and 0.05 deg for the elbow, by hand: x + 0.3 mm, pitch = the offset)."""
    (tmp_path / "specs").mkdir()
    spec = tmp_path / "specs" / "wa.yaml"
    spec.write_text(EXAMPLE.read_text() + CAL_BLOCK)
    assert cli("generate", spec, cwd=tmp_path).returncode == 0
    ran = cli("report", spec, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    page = (tmp_path / "generated" / "warehouse_arm_description" / "evidence" / "README.md").read_text()
    section = page[page.index("## 11. Calibration") :]
    elbow = next(ln for ln in section.splitlines() if ln.startswith("| `elbow_joint`"))
    assert "(300.000, 0.000, 0.000)" in elbow and "(300.300, 0.000, 0.000), (0.0000, 0.0500, 0.0000)" in elbow
    assert "| 0.300 mm | 0.0500 deg |" in elbow and "tracker: laser tracker, 2026-11-20" in elbow
    assert "**Verdict: PASS**: 2 calibrated joint(s)" in section
    assert "| xacro calibration:=nominal.yaml expands to the nominal model | passed |" in page
    example = (ROOT / "generated" / "warehouse_arm_description" / "evidence" / "README.md").read_text()
    assert "## 11." not in example and "calibration:=" not in example


def _drift_project(
    tmp_path: Path, offsets: dict[str, float] | None = None, samples: str = "../data/tracker.csv"
) -> Path:
    """The example with CAL_BLOCK and a drift check of 300 tracker samples (0.2 mm noise) made by
    pinocchio from the calibrated URDF, with ``offsets`` planted on top."""
    (tmp_path / "specs").mkdir()
    spec = tmp_path / "specs" / "wa.yaml"
    spec.write_text(EXAMPLE.read_text() + CAL_BLOCK)
    assert cli("generate", spec, "--out", tmp_path / "first", cwd=tmp_path).returncode == 0
    urdf = (tmp_path / "first" / "warehouse_arm_description" / "urdf" / "warehouse_arm.urdf").read_text()
    rec = dd.samples(urdf, "tool_link", base="arm_base_link", offsets=offsets, joints=ARM, n=300, noise_m=0.0002)
    (tmp_path / "data").mkdir()
    dd.write_csv(tmp_path / "data" / "tracker.csv", rec)
    check = f"  drift:\n    samples: {samples}\n    frame: tool_link\n    base: arm_base_link\n"
    spec.write_text(spec.read_text() + check)
    return spec


def test_evidence_page_plots_the_drift_samples(tmp_path: Path) -> None:
    """report: section 11 gives the samples' residual (within the 1 mm tolerance: 0.2 mm noise) and
    writes evidence/drift.svg, a polyline of one point per sample; check then passes, and a changed
    sample makes both the page and the plot stale."""
    from lxml import etree

    spec = _drift_project(tmp_path)
    assert cli("generate", spec, cwd=tmp_path).returncode == 0
    ran = cli("report", spec, cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-2000:]
    evidence = tmp_path / "generated" / "warehouse_arm_description" / "evidence"
    page = (evidence / "README.md").read_text()
    section = page[page.index("## 11. Calibration and drift") :]
    assert "`tracker.csv` (300 samples)" in section and "![residual over time](drift.svg)" in section
    median = float(re.search(r"residual: median ([0-9.]+) mm", section).group(1))  # type: ignore[union-attr]
    assert 0.15 < median < 0.45  # 0.2 mm per axis: the norm's median is ~0.31 mm
    assert "the drift samples are within tolerance" in section
    plot = etree.fromstring((evidence / "drift.svg").read_bytes())
    points = plot.find("{http://www.w3.org/2000/svg}polyline").get("points").split()
    assert len(points) == 300
    assert cli("check", spec, cwd=tmp_path).returncode == 0
    csv = tmp_path / "data" / "tracker.csv"
    lines = csv.read_text().splitlines()
    row = lines[5].split(",")
    row[5] = repr(float(row[5]) + 0.01)  # one tracker position 10 mm off
    lines[5] = ",".join(row)
    csv.write_text("\n".join(lines) + "\n")
    ran = cli("check", spec, cwd=tmp_path)
    assert ran.returncode == 1 and "evidence/drift.svg" in ran.stderr and "evidence/README.md is stale" in ran.stderr


def test_evidence_page_refuses_a_drifted_robot(tmp_path: Path) -> None:
    """A 1 deg elbow offset the spec does not have: the page's verdict fails and report writes nothing."""
    spec = _drift_project(tmp_path, offsets={"elbow_joint": math.radians(1.0)})
    assert cli("generate", spec, cwd=tmp_path).returncode == 0
    ran = cli("report", spec, cwd=tmp_path)
    assert ran.returncode == 1 and "DRIFTED beyond tolerance" in ran.stderr, ran.stderr[-2000:]
    assert not (tmp_path / "generated" / "warehouse_arm_description" / "evidence" / "drift.svg").exists()


@pytest.mark.parametrize(
    ("samples", "why"),
    [
        ("/etc/passwd", "is absolute"),
        ("../../outside.csv", "leaves the project"),
        ("../data/none.csv", "does not exist"),
    ],
)
def test_drift_samples_path_bad(tmp_path: Path, samples: str, why: str) -> None:
    spec = _drift_project(tmp_path, samples=samples)
    ran = cli("validate", spec, cwd=tmp_path)
    assert ran.returncode == 2 and "error[CAL005]" in ran.stderr and why in ran.stderr, ran.stderr[-1500:]


def test_drift_samples_path_good(tmp_path: Path) -> None:
    ran = cli("validate", _drift_project(tmp_path), cwd=tmp_path)
    assert ran.returncode == 0 and "CAL005" not in ran.stderr, ran.stderr[-1500:]


def test_pairing_interpolates_each_joint_between_its_own_states() -> None:
    """Two /joint_states publishers, each with one joint, a late message, and gaps: a pose takes
    each joint's value interpolated at its stamp (by hand), and is dropped when a joint has no
    state within 0.1 s on both sides of it."""
    from descgen.read.drift_samples import _Pairing

    p = _Pairing(["a", "b"])
    p.joint_state(0.00, ["a"], [0.0])
    p.pose(0.03, (1, 2, 3, 0, 0, 0, 1))
    p.joint_state(0.01, ["b"], [10.0])
    p.joint_state(0.05, ["a"], [1.0])
    p.joint_state(0.06, ["b"], [20.0])
    p.joint_state(0.04, ["b"], [14.0])  # late: logged after the 0.06 one
    p.pose(0.30, (4, 5, 6, 0, 0, 0, 1))  # a's next state is 0.5 s later: dropped
    p.joint_state(0.80, ["a", "b"], [2.0, 30.0])
    t, q, pv = p.finish()
    assert t.tolist() == [0.03] and p.dropped == 1
    # a: 0.0 at 0.00 and 1.0 at 0.05; b: 10 at 0.01 and 14 at 0.04 (the late one, not 20 at 0.06)
    assert q[0].tolist() == pytest.approx([0.6, 10.0 + 4.0 * 2 / 3], abs=1e-12)
    assert pv[0].tolist() == [1, 2, 3, 0, 0, 0, 1]


def test_import_merges_by_source_and_keeps_the_rest_of_the_spec(tmp_path: Path) -> None:
    """A second import for a joint calibrated from another source is refused (CAL013) unless
    --replace; under the same source its fields are updated and the others kept; a comment before
    the next top-level key survives; a bare 1e-3 in the CSV is read as SI."""
    spec = tmp_path / "wa.yaml"
    spec.write_text(
        _no_poses(EXAMPLE.read_text())
        + "\ncalibration:\n  sources:\n    factory: {method: tape}\n  joints:\n"
        + "    elbow_joint: {source: factory, origin: {xyz: [0.3 mm, 0, 0]}}\n# kept: a note on what follows\n"
        + "waivers: []\n"
    )
    offsets = tmp_path / "o.csv"
    offsets.write_text("joint,offset\nelbow_joint,1e-3\n")
    ran = cli("import-calibration", spec, offsets, "--format", "csv", cwd=tmp_path)
    assert ran.returncode == 2 and "error[CAL013]" in ran.stderr and "'factory'" in ran.stderr
    ran = cli("import-calibration", spec, offsets, "--format", "csv", "--source", "factory", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-1500:]
    text = spec.read_text()
    elbow = yaml.safe_load(text)["calibration"]["joints"]["elbow_joint"]
    assert elbow["offset"] == "1e-3 rad" and elbow["origin"]["xyz"] == ["0.3 mm", 0, 0]
    assert "# kept: a note on what follows\nwaivers: []" in text
    ran = cli("import-calibration", spec, offsets, "--format", "csv", "--replace", cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr[-1500:]
    elbow = yaml.safe_load(spec.read_text())["calibration"]["joints"]["elbow_joint"]
    assert elbow == {"source": "joint_offsets", "offset": "1e-3 rad"}


def test_drift_input_refusals_and_quaternions(tmp_path: Path) -> None:
    """Quaternions are normalised within 1e-3 of unit length and refused beyond (CSV: the row); a
    recording whose poses are NaN or whose /joint_states is not JointState is handled (dropped and
    counted, CAL012); the frame as its own base is refused."""
    urdf = EXAMPLE_URDF.read_text()
    rec = dd.samples(urdf, "tool_link", base="arm_base_link", joints=ARM, n=60, noise_m=0.0001, noise_rad=0.001)
    dd.write_csv(tmp_path / "s.csv", rec)
    rows = (tmp_path / "s.csv").read_text().splitlines()
    scaled = rows[:3] + [
        ",".join([*r.split(",")[:-4], *(repr(float(c) * 1.0004) for c in r.split(",")[-4:])]) for r in rows[3:]
    ]
    (tmp_path / "near.csv").write_text("\n".join(scaled) + "\n")
    base = ("--base", "arm_base_link")
    near = _drift_json(tmp_path, "--samples", tmp_path / "near.csv", *base)
    exact = _drift_json(tmp_path, "--samples", tmp_path / "s.csv", *base)
    assert near["residual"]["rotation"]["median_rad"] == pytest.approx(
        exact["residual"]["rotation"]["median_rad"], rel=1e-9
    )
    bad = [*rows[:3], ",".join([*rows[3].split(",")[:-4], "0", "0", "0", "3"]), *rows[4:]]
    (tmp_path / "bad.csv").write_text("\n".join(bad) + "\n")
    ran = cli("drift", EXAMPLE, "--frame", "tool_link", *base, "--samples", tmp_path / "bad.csv", cwd=tmp_path)
    assert ran.returncode == 2 and "error[CAL012]" in ran.stderr and "row 4" in ran.stderr
    ran = cli(
        "drift", EXAMPLE, "--frame", "tool_link", "--base", "tool_link", "--samples", tmp_path / "s.csv", cwd=tmp_path
    )
    assert ran.returncode == 2 and "nothing to compare" in ran.stderr
    nan = dataclasses.replace(rec, xyz=np.where(np.arange(60)[:, None] % 10 == 0, np.nan, rec.xyz))
    dd.write_bag(tmp_path / "nan", nan)
    report = _drift_json(tmp_path, "--recording", tmp_path / "nan", "--pose-topic", "/tracker/pose")
    assert report["residual"]["samples"] == 54 and report["dropped"] == 6
    dd.write_bag(tmp_path / "wrong", rec)
    ran = cli(
        "drift",
        EXAMPLE,
        "--frame",
        "tool_link",
        "--recording",
        tmp_path / "wrong",
        "--pose-topic",
        "/joint_states",
        cwd=tmp_path,
    )
    assert ran.returncode == 2 and "error[CAL012]" in ran.stderr


def test_suggested_block_quotes_joint_names() -> None:
    """A joint name YAML would read as syntax (*j, true) comes back as the same key."""
    from descgen.audit.spec import load_spec
    from descgen.commands.drift import suggested_block

    robot = load_spec(EXAMPLE, rules=False).robot
    block = suggested_block(
        robot,
        [
            {"parameter": "joint:*j:offset", "value": 0.01, "stderr": 0.001},
            {"parameter": "joint:true:origin.x", "value": 0.001, "stderr": 0.0001},
        ],
    )
    joints = yaml.safe_load(block)["calibration"]["joints"]
    assert set(joints) == {"*j", "true"}


def test_identification_jacobian_matches_central_differences() -> None:
    """The closed-form Jacobian (every parameter kind: origin xyz and rpy, revolute, continuous and
    prismatic offsets, a fixed joint, unit and non-unit axes, non-zero rpy) against central
    differences of the forward kinematics, to the differences' own error."""
    from descgen.core.model import Joint, Pose
    from descgen.physics.drift import Model, parameters

    rng = random.Random(1)

    def joint(name: str, parent: str, child: str, kind: str) -> Joint:
        origin = Pose(tuple(rng.uniform(-0.3, 0.3) for _ in range(3)), tuple(rng.uniform(-3, 3) for _ in range(3)))
        return Joint(name, kind, parent, child, origin, tuple(rng.uniform(-1, 1) for _ in range(3)))

    kinds = ("revolute", "prismatic", "continuous", "fixed", "revolute")
    joints = [joint(f"j{i}", f"l{i}", f"l{i + 1}", k) for i, k in enumerate(kinds)]
    model = Model(joints, parameters(joints))
    q = {j.name: np.array([rng.uniform(-2, 2) for _ in range(9)]) for j in joints}
    theta = np.array([rng.uniform(-0.05, 0.05) for _ in model.names])
    closed, numeric = model.jacobian(q, theta, 9), model.jacobian_numeric(q, theta, 9)
    assert closed.shape == (27, 34)
    assert np.abs(closed - numeric).max() < 1e-8
    assert np.abs(closed).max() > 0.1  # not all zeros


def test_nothing_significant_suggests_an_empty_block(tmp_path: Path) -> None:
    """A robot that matches its model: no fitted value clears three standard errors, so none is
    suggested, and the (empty) block still validates."""
    urdf = EXAMPLE_URDF.read_text()
    rec = dd.samples(urdf, "tool_link", base="arm_base_link", joints=ARM, n=200, noise_m=0.0002, seed=5)
    dd.write_csv(tmp_path / "s.csv", rec)
    report = _drift_json(
        tmp_path, "--samples", tmp_path / "s.csv", "--base", "arm_base_link", "--parameters", "joint:*:offset"
    )
    assert report["identified"] and not any(p["significant"] for p in report["identified"])
    assert yaml.safe_load(report["suggested"])["calibration"]["joints"] == {}
    spec = tmp_path / "wa.yaml"
    spec.write_text(EXAMPLE.read_text() + "\n" + report["suggested"])
    assert cli("validate", spec, cwd=tmp_path).returncode == 0


def test_a_fifo_or_a_device_is_refused_not_waited_on(tmp_path: Path) -> None:
    """A FIFO would block open() forever and /dev/zero would never end: both are refused at once."""
    import os

    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    spec = tmp_path / "wa.yaml"
    spec.write_text(EXAMPLE.read_text())
    ran = cli("import-calibration", spec, fifo, "--format", "csv", cwd=tmp_path, timeout=60)
    assert ran.returncode == 2 and "error[CAL010]" in ran.stderr and "FIFO" in ran.stderr
    for bad in (fifo, Path("/dev/zero")):
        ran = cli("drift", spec, "--samples", bad, "--frame", "tool_link", cwd=tmp_path, timeout=60)
        assert ran.returncode == 2 and "error[CAL012]" in ran.stderr, ran.stderr[-800:]
    assert spec.read_text() == EXAMPLE.read_text()
