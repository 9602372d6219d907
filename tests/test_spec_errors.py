"""Each kind of mistake is reported at the YAML line where it was planted, with exit 2."""

from __future__ import annotations

from pathlib import Path

import pytest

from .helpers import EXAMPLE_TEXT, cli, errors_of, line_of, plant

CASES = [
    # (id, old, new, expected code, text marking the expected line)
    ("wrong-unit", "{xyz: [0, 0, 85 mm], source: M09}", "{xyz: [0, 0, 85 kg], source: M09}", "UNIT003", "85 kg"),
    ("bare-number", "[-240 mm, 0, -55 mm]", "[-240 mm, 0, -55]", "UNIT001", "[-240 mm, 0, -55]"),
    ("mm-as-m", "xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]", "UNIT004", "[25 m, 0, 40 mm]"),
    ("g-as-kg", "{value: 1200 g, source: M03}", "{value: 1200 kg, source: M03}", "UNIT010", "1200 kg"),
    ("g-as-kg-caster", "{mass: 300 g, from: collision}", "{mass: 300 kg, from: collision}", "UNIT010", "300 kg"),
    ("typo-key", "        material: tyre_black", "        materal: tyre_black", "SPEC001", "materal"),
    ("unknown-top-key", "require_sources: true", "require_source: true", "SPEC001", "require_source:"),
    (
        "duplicate-name",
        "  - name: caster_link\n",
        "  - name: lift_link\n",
        "NAME001",
        "name: lift_link\n    description: lift",
    ),
    ("missing-parent", "    parent: lift_link\n", "    parent: lift_lnk\n", "TOPO004", "- name: shoulder_pan_joint"),
    (
        "cycle",
        "    parent: base_link\n    child: arm_base_link",
        "    parent: tool_link\n    child: arm_base_link",
        "TOPO003",
        "- name: arm_mount_joint",
    ),
    (
        "lower-above-upper",
        "lower: -100 deg, upper: 100 deg",
        "lower: 100 deg, upper: -100 deg",
        "JOINT004",
        "lower: 100 deg, upper: -100 deg",
    ),
    (
        "non-positive-definite",
        "inertial: {mass: 0.9 kg, from: collision}",
        "inertial: {mass: 0.9 kg, inertia: {ixx: -0.001 kg*m^2, iyy: 0.001 kg*m^2, izz: 0.001 kg*m^2}}",
        "INER003",
        "ixx: -0.001",
    ),
    (
        "triangle-inequality",
        "inertial: {mass: 0.9 kg, from: collision}",
        "inertial: {mass: 0.9 kg, inertia: {ixx: 0.001 kg*m^2, iyy: 0.001 kg*m^2, izz: 0.01 kg*m^2}}",
        "INER004",
        "izz: 0.01",
    ),
    ("no-source", "{xyz: [-50 mm, 0, 175 mm], source: M13}", "{xyz: [-50 mm, 0, 175 mm]}", "SPEC010", "175 mm]}"),
    (
        "pose-unknown-joint",
        "joints: {shoulder_lift_joint: -30 deg}",
        "joints: {shoulder_lifter: -30 deg}",
        "POSE001",
        "- name: shoulder_up_30",
    ),
    (
        "pose-outside-limits",
        "joints: {lift_joint: 300 mm, shoulder_pan_joint: 90 deg}",
        "joints: {lift_joint: 350 mm, shoulder_pan_joint: 90 deg}",
        "POSE003",
        "- name: side_reach",
    ),
    ("pose-unknown-frame", "{frame: tool_link, xyz: [428 mm", "{frame: tool_lnk, xyz: [428 mm", "POSE002", "tool_lnk"),
    (
        "interface-on-unknown-joint",
        "{name: elbow_joint, command: [position]",
        "{name: elbo_joint, command: [position]",
        "CTRL001",
        "elbo_joint",
    ),
    # '-' is a name ROS accepts (flange-tool0); tf2 refuses a leading '/'
    ("bad-name", "  - name: tool_link\n", "  - name: /tool_link\n", "SPEC050", "/tool_link"),
    ("wrong-joint-type", "    type: prismatic\n", "    type: slider\n", "SPEC003", "type: slider"),
    ("missing-key", "    parent: upper_link\n", "", "SPEC002", "- name: elbow_joint"),
    (
        "geometry-two-shapes",
        "{sphere: {diameter: 60 mm}}",
        "{sphere: {diameter: 60 mm}, box: {size: [1 mm, 1 mm, 1 mm]}}",
        "SPEC004",
        "box: {size: [1 mm",
    ),
    ("torque-as-energy", "effort: 20 N*m", "effort: 20 J", "UNIT003", "effort: 20 J"),
    ("hz-as-angular-velocity", "velocity: 120 deg/s", "velocity: 2 Hz", "UNIT003", "velocity: 2 Hz"),
]


@pytest.mark.parametrize(("old", "new", "code", "marker"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_mistake_reported_at_its_line(tmp_path: Path, old: str, new: str, code: str, marker: str) -> None:
    text = plant(old, new)
    found = errors_of(text, tmp_path)
    assert found, "the planted mistake was not reported"
    expected_line = line_of(text, marker)
    hits = [f for f in found if f.code == code]
    assert hits, f"expected {code}, got {[(f.code, f.message) for f in found]}"
    assert any(f.where.line == expected_line for f in hits), [(f.where.line, f.message) for f in hits]
    assert all(f.hint for f in found)
    assert all(f.where.file.endswith("robot.yaml") for f in found)


def test_typo_suggests_the_key(tmp_path: Path) -> None:
    found = errors_of(plant("        material: tyre_black", "        materal: tyre_black"), tmp_path)
    assert any("did you mean 'material'" in f.hint for f in found)


def test_every_problem_reported_not_just_the_first(tmp_path: Path) -> None:
    text = plant("xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]")
    text = plant("[-240 mm, 0, -55 mm]", "[-240 mm, 0, -55]", text)
    text = plant("        material: tyre_black", "        materal: tyre_black", text)
    codes = sorted(f.code for f in errors_of(text, tmp_path))
    assert codes == ["SPEC001", "UNIT001", "UNIT004"]


def test_mm_as_m_message_shows_si_written_and_range(tmp_path: Path) -> None:
    [f] = errors_of(plant("xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]"), tmp_path)
    assert '"25 m"' in f.message and "= 25 m" in f.message and "10 m" in f.message
    assert '"25 mm"' in f.hint


def test_plausibility_override_accepts_a_big_robot(tmp_path: Path) -> None:
    text = plant("xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]")
    text = plant("require_sources: true\n", "require_sources: true\nplausibility:\n  offset: {max: 30 m}\n", text)
    found = errors_of(text, tmp_path)
    assert not any(f.code == "UNIT004" for f in found)
    # the range no longer objects, but the offset is 50 times the robot's typical link (UNIT011),
    # and a 95 g camera 25 m out is more than the arm can hold (JOINT008)
    assert {f.code for f in found} == {"JOINT008", "UNIT011"}
    assert any("elbow_joint" in f.message for f in found)


def test_cli_validate_example_exits_0() -> None:
    r = cli("validate", "specs/warehouse_arm.yaml")
    assert r.returncode == 0, r.stderr
    assert "valid" in r.stdout


def test_cli_reports_file_line_col_code_and_hint(tmp_path: Path) -> None:
    text = plant("{xyz: [0, 0, 85 mm], source: M09}", "{xyz: [0, 0, 85 kg], source: M09}")
    spec = tmp_path / "broken.yaml"
    spec.write_text(text)
    r = cli("validate", str(spec))
    assert r.returncode == 2
    line = line_of(text, "85 kg")
    col = text.splitlines()[line - 1].index("85 kg") + 1
    assert f"{spec}:{line}:{col}: error[UNIT003]:" in r.stderr
    assert "\n  hint: " in r.stderr
    assert "Traceback" not in r.stderr


def test_cli_json_format(tmp_path: Path) -> None:
    import json

    spec = tmp_path / "broken.yaml"
    spec.write_text(plant("lower: -100 deg, upper: 100 deg", "lower: 100 deg, upper: -100 deg"))
    r = cli("validate", "--format", "json", str(spec))
    assert r.returncode == 2
    doc = json.loads(r.stdout)
    assert doc["summary"]["error"] == len([f for f in doc["findings"] if f["severity"] == "error"]) >= 1
    assert {"code", "severity", "subject", "file", "line", "message", "hint"} <= set(doc["findings"][0])


def test_example_spec_is_unchanged_by_these_tests() -> None:
    assert (Path(__file__).resolve().parents[1] / "specs" / "warehouse_arm.yaml").read_text() == EXAMPLE_TEXT
