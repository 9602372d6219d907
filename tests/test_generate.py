"""generate and check: determinism, all-or-nothing writes, the hand-edit guard, escaping,
template overrides, and check catching any change."""

from __future__ import annotations

import hashlib
import math
import py_compile
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml
from lxml import etree

from descgen import prove as checks
from descgen.commands.generate import check, generate
from descgen.core.findings import InputError

from .conftest import ROOT, require_tool
from .helpers import EXAMPLE_TEXT, cli, plant, run_cli

PKG = "warehouse_arm_description"


def project(tmp: Path, text: str = EXAMPLE_TEXT) -> Path:
    """A scratch project: specs/warehouse_arm.yaml (+ the schema it names)."""
    (tmp / "specs").mkdir(parents=True, exist_ok=True)
    spec = tmp / "specs" / "warehouse_arm.yaml"
    spec.write_text(text)
    return spec


def snapshot(folder: Path) -> dict[str, str]:
    """Hashes of the files check compares (frames.svg depends on the Graphviz version: not one)."""
    return {
        p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and p.suffix != ".svg"
    }


@pytest.fixture(scope="module")
def generated_once(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A scratch project with the example generated, once for the module (a generate is most of
    a second); each test gets a copy of it, as the tests edit what they get."""
    root = tmp_path_factory.mktemp("generated-once")
    outcome = generate(project(root))
    assert not outcome.failed, outcome.findings
    return root


@pytest.fixture
def generated(generated_once: Path, tmp_path: Path) -> tuple[Path, Path]:
    # nothing generate writes depends on where the project is (test_deterministic_twice_and_...)
    shutil.copytree(generated_once, tmp_path, symlinks=True, dirs_exist_ok=True)
    return tmp_path / "specs" / "warehouse_arm.yaml", tmp_path / "generated" / PKG


@pytest.mark.e2e
def test_committed_files_are_up_to_date() -> None:
    # end to end, as a user runs it: `python -m descgen check` in a fresh interpreter
    r = run_cli("check", "specs/warehouse_arm.yaml")
    assert r.returncode == 0, r.stdout + r.stderr


def test_package_layout(generated: tuple[Path, Path]) -> None:
    _, pkg = generated
    assert (pkg / "evidence" / "frames.svg").is_file() == (shutil.which("dot") is not None)
    files = set(snapshot(pkg))
    assert files == {
        "package.xml",
        "CMakeLists.txt",
        "urdf/warehouse_arm.urdf.xacro",
        "urdf/warehouse_arm.urdf",
        "urdf/warehouse_arm.ros2_control.xacro",
        "srdf/warehouse_arm.srdf",
        "config/ros2_controllers.yaml",
        "launch/display.launch.py",
        "launch/control.launch.py",
        "rviz/warehouse_arm.rviz",
        "evidence/known_poses.md",
        "evidence/collision_matrix.md",
        "evidence/sweep.md",
        "evidence/frames.md",
        "evidence/frames.dot",
    }
    for rel in files:
        text = (pkg / rel).read_text()
        head = "\n".join(text.splitlines()[:3])
        assert "generated from specs/warehouse_arm.yaml by descgen — do not edit" in head, rel
        assert "spec-sha256=" + hashlib.sha256(EXAMPLE_TEXT.encode()).hexdigest() in head, rel
        assert str(pkg.parent.parent) not in text, f"absolute path in {rel}"


def test_deterministic_twice_and_from_two_working_directories(tmp_path: Path) -> None:
    spec_a = project(tmp_path / "a")
    spec_b = project(tmp_path / "b")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    assert cli("generate", str(spec_a), cwd=tmp_path / "a").returncode == 0
    assert cli("generate", str(spec_b.resolve()), cwd=elsewhere).returncode == 0
    first = {
        k: (tmp_path / "a" / "generated" / PKG / k).read_bytes() for k in snapshot(tmp_path / "a" / "generated" / PKG)
    }
    second = {
        k: (tmp_path / "b" / "generated" / PKG / k).read_bytes() for k in snapshot(tmp_path / "b" / "generated" / PKG)
    }
    assert first == second
    # the MoveIt config package (spec moveit:) is as deterministic
    moveit = {p: snapshot(tmp_path / p / "generated" / "warehouse_arm_moveit_config") for p in ("a", "b")}
    assert moveit["a"] and moveit["a"] == moveit["b"]
    for k in moveit["a"]:
        a, b = (tmp_path / p / "generated" / "warehouse_arm_moveit_config" / k for p in ("a", "b"))
        assert a.read_bytes() == b.read_bytes(), k
    again = cli("generate", str(spec_a), cwd=tmp_path / "a")
    assert again.returncode == 0 and f"wrote 0 files, {len(first) + len(moveit['a'])} unchanged" in again.stdout
    # and what the repository has committed is the same bytes
    committed = ROOT / "generated" / PKG
    assert {k: (committed / k).read_bytes() for k in first} == first


def test_failed_check_writes_nothing(generated: tuple[Path, Path], monkeypatch: pytest.MonkeyPatch) -> None:
    spec, pkg = generated
    before = snapshot(pkg)
    spec.write_text(plant("{value: 1200 g, source: M03}", "{value: 1250 g, source: M03}"))
    calls: list[str] = []

    def broken(files: dict[str, str], robot: object, where: Path) -> list[checks.Finding]:
        calls.append("ran")
        return [checks.Finding("GEN999", "error", "planted failure", "none")]

    monkeypatch.setattr(checks, "CHECKS", [*checks.CHECKS[:1], ("planted", broken), *checks.CHECKS[1:]])
    outcome = generate(spec)
    assert calls and outcome.failed and not outcome.written
    assert snapshot(pkg) == before
    assert not list(pkg.parent.glob(".descgen-*")), "scratch folder left behind"


def test_write_failure_midway_moves_nothing(generated: tuple[Path, Path], monkeypatch: pytest.MonkeyPatch) -> None:
    spec, pkg = generated
    before = snapshot(pkg)
    spec.write_text(plant("{value: 1200 g, source: M03}", "{value: 1250 g, source: M03}"))
    import builtins

    real_open = builtins.open
    seen = {"n": 0}

    def failing_open(file, mode="r", *args, **kwargs):  # type: ignore[no-untyped-def]
        if "w" in mode and ".descgen-" in str(file):
            seen["n"] += 1
            if seen["n"] == 3:
                raise OSError(28, "No space left on device")
        return real_open(file, mode, *args, **kwargs)

    monkeypatch.setattr(builtins, "open", failing_open)
    with pytest.raises(InputError) as info:
        generate(spec)
    monkeypatch.undo()
    assert [f.code for f in info.value.findings] == ["GEN045"]
    assert "No space left on device" in info.value.findings[0].message
    assert seen["n"] == 3
    assert snapshot(pkg) == before


def test_hand_edit_guard(generated: tuple[Path, Path]) -> None:
    spec, pkg = generated
    urdf = pkg / "urdf" / "warehouse_arm.urdf"
    edited = urdf.read_text().replace('value="28"', 'value="29"')
    urdf.write_text(edited)
    spec.write_text(plant("{value: 1200 g, source: M03}", "{value: 1250 g, source: M03}"))
    r = cli("generate", str(spec))
    assert r.returncode == 1
    assert "urdf/warehouse_arm.urdf was edited by hand" in r.stderr
    assert urdf.read_text() == edited
    r = cli("generate", "--force", str(spec))
    assert r.returncode == 0, r.stderr
    assert 'value="28"' in urdf.read_text() and '<mass value="1.25"/>' in urdf.read_text()


def test_check_catches_one_character_in_every_file(generated: tuple[Path, Path]) -> None:
    spec, pkg = generated
    for rel in snapshot(pkg):
        path = pkg / rel
        original = path.read_text()
        # change one character near the end of the file (past the header)
        i = len(original) - 3
        changed = original[:i] + ("X" if original[i] != "X" else "Y") + original[i + 1 :]
        path.write_text(changed)
        outcome = check(spec)
        assert outcome.failed, rel
        assert any(f.code == "GEN004" and rel in f.message for f in outcome.findings), rel
        assert f"--- a/{rel}" in outcome.diff and f"+++ b/{rel}" in outcome.diff
        path.write_text(original)
    assert not check(spec).failed


def test_check_catches_a_stale_spec_with_a_diff(generated: tuple[Path, Path]) -> None:
    spec, _ = generated
    spec.write_text(plant("{value: 1200 g, source: M03}", "{value: 1250 g, source: M03}"))
    r = cli("check", str(spec))
    assert r.returncode == 1
    assert "is stale: the spec changed" in r.stderr
    assert '-  <xacro:property name="drive_wheel_mass" value="1.2"/>' in r.stdout
    assert '+  <xacro:property name="drive_wheel_mass" value="1.25"/>' in r.stdout


def test_check_on_a_missing_package(tmp_path: Path) -> None:
    spec = project(tmp_path)
    r = cli("check", str(spec))
    assert r.returncode == 1 and "is missing" in r.stderr


def test_invalid_spec_is_exit_2_and_writes_nothing(tmp_path: Path) -> None:
    spec = project(tmp_path, plant("xyz: [25 mm, 0, 40 mm]", "xyz: [25 m, 0, 40 mm]"))
    for cmd in ("generate", "check"):
        r = cli(cmd, str(spec))
        assert r.returncode == 2, (cmd, r.stderr)
        assert "error[UNIT004]" in r.stderr
    assert not (tmp_path / "generated").exists()


HOSTILE = "${__import__('os').system('touch PWNED')} $(env HOME) $(find x) --> <!-- <evil a=\"1\"/> & ]]> '\""


def test_hostile_text_stays_text(tmp_path: Path) -> None:
    h = HOSTILE
    text = EXAMPLE_TEXT
    text = text.replace("{name: tyre_black,", "{name: " + yaml.safe_dump(h, default_style='"').strip() + ",")
    text = text.replace("material: tyre_black", "material: " + yaml.safe_dump(h, default_style='"').strip())
    quoted = yaml.safe_dump(h, default_style='"').strip()
    text = text.replace("description: chassis, frame at the wheel-axle centre", f"description: {quoted}")
    text = text.replace("source: M09}", f"source: {quoted}}}")
    text = text.replace(
        "package: {version: 0.1.0, maintainer: WA-1 integration team,",
        f"package: {{version: 0.1.0, maintainer: {quoted},",
    )
    text = text.replace(
        "    plugin: mock_components/GenericSystem\n",
        f"    plugin: mock_components/GenericSystem\n    params: {{note: {quoted}}}\n",
    )
    text = text.replace(
        "      - geometry: {sphere: {diameter: 60 mm}}\n        material",
        f"      - name: {quoted}\n        geometry: {{sphere: {{diameter: 60 mm}}}}\n        material",
    )
    spec = project(tmp_path, text)
    outcome = generate(spec)
    assert not outcome.failed, outcome.findings  # includes: xacro expands to exactly the URDF
    pkg = tmp_path / "generated" / PKG
    assert not list(tmp_path.rglob("PWNED")) and not (ROOT / "PWNED").exists()
    parser = etree.XMLParser(resolve_entities=False)
    urdf = etree.parse(str(pkg / "urdf" / "warehouse_arm.urdf"), parser).getroot()
    names = [m.get("name") for m in urdf.iter("material")]
    assert h in names
    assert h in [v.get("name") for v in urdf.iter("visual")]
    assert [e.tag for e in urdf.iter() if e.tag == "evil"] == []
    hw = urdf.find("ros2_control/hardware/param[@name='note']")
    assert hw is not None and hw.text == h
    # every XML output still parses, and comments did not swallow elements
    for rel in snapshot(pkg):
        if rel.endswith((".xml", ".urdf", ".xacro", ".srdf")):
            etree.parse(str(pkg / rel), parser)
    from catkin_pkg.package import parse_package

    assert parse_package(str(pkg / "package.xml")).maintainers[0].name == h
    # the Xacro carries the dollar signs as an expression that yields a literal '$'
    xacro_text = (pkg / "urdf" / "warehouse_arm.urdf.xacro").read_text()
    assert "${__import__" not in xacro_text


def test_template_override_by_file_name(tmp_path: Path) -> None:
    spec = project(tmp_path)
    overrides = tmp_path / "my_templates"
    overrides.mkdir()
    original = (ROOT / "descgen" / "templates" / "robot.rviz.j2").read_text()
    (overrides / "robot.rviz.j2").write_text(original.replace("Frame Rate: 30", "Frame Rate: 60"))
    r = cli("generate", "--templates", str(overrides), str(spec))
    assert r.returncode == 0, r.stderr
    pkg = tmp_path / "generated" / PKG
    assert "Frame Rate: 60" in (pkg / "rviz" / "warehouse_arm.rviz").read_text()
    committed = ROOT / "generated" / PKG
    assert (pkg / "urdf" / "warehouse_arm.urdf").read_bytes() == (
        committed / "urdf" / "warehouse_arm.urdf"
    ).read_bytes()
    assert cli("generate", "--templates", str(tmp_path / "nope"), str(spec)).returncode == 2


def test_broken_template_override_fails_the_xacro_check(tmp_path: Path) -> None:
    spec = project(tmp_path)
    overrides = tmp_path / "t"
    overrides.mkdir()
    src = (ROOT / "descgen" / "templates" / "robot.urdf.j2").read_text()
    assert '{% include "_ros2_control.xml.j2" %}' in src
    (overrides / "robot.urdf.j2").write_text(src.replace('{% include "_ros2_control.xml.j2" %}', ""))
    outcome = generate(spec, templates=overrides)
    assert outcome.failed
    assert any(f.code == "GEN001" and "ros2_control" in f.message for f in outcome.findings)
    assert not (tmp_path / "generated").exists()


def test_derived_controller_values(generated: tuple[Path, Path]) -> None:
    _, pkg = generated
    doc = yaml.safe_load((pkg / "config" / "ros2_controllers.yaml").read_text())
    dd = doc["diff_drive_controller"]["ros__parameters"]
    assert dd["wheel_separation"] == pytest.approx(19.1 * 0.0254, abs=1e-12)  # M04
    assert dd["wheel_radius"] == pytest.approx(0.170 / 2, abs=1e-12)  # M01
    cm = doc["controller_manager"]["ros__parameters"]
    assert cm["update_rate"] == 100 and isinstance(cm["update_rate"], int)  # C02
    assert cm["arm_controller"]["type"] == "joint_trajectory_controller/JointTrajectoryController"


def test_ros2_control_limits_from_the_joint_limits(generated: tuple[Path, Path]) -> None:
    _, pkg = generated
    root = etree.parse(str(pkg / "urdf" / "warehouse_arm.urdf")).getroot()

    def params(joint: str, iface: str) -> dict[str, float]:
        e = root.find(f"ros2_control/joint[@name='{joint}']/command_interface[@name='{iface}']")
        assert e is not None
        return {p.get("name"): float(p.text) for p in e.findall("param")}

    assert params("shoulder_pan_joint", "position") == pytest.approx(
        {"min": -math.radians(170), "max": math.radians(170)}
    )
    assert params("lift_joint", "position") == pytest.approx({"min": 0.0, "max": 0.3})
    assert params("left_wheel_joint", "velocity") == pytest.approx(
        {"min": -112 * math.pi / 30, "max": 112 * math.pi / 30}
    )


def test_urdfdom_accepts_the_urdf(generated: tuple[Path, Path]) -> None:
    tool = require_tool("check_urdf")
    _, pkg = generated
    r = subprocess.run([tool, str(pkg / "urdf" / "warehouse_arm.urdf")], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "root Link: base_footprint" in r.stdout


def test_launch_files_compile(generated: tuple[Path, Path]) -> None:
    _, pkg = generated
    for name in ("display.launch.py", "control.launch.py"):
        py_compile.compile(str(pkg / "launch" / name), doraise=True)
    control = (pkg / "launch" / "control.launch.py").read_text()
    for ctrl in ("joint_state_broadcaster", "diff_drive_controller", "arm_controller"):
        assert f'"{ctrl}", "--controller-manager"' in control


def test_cmake_installs_every_folder(generated: tuple[Path, Path]) -> None:
    _, pkg = generated
    cmake = (pkg / "CMakeLists.txt").read_text()
    installed = cmake.split("DIRECTORY", 1)[1].split("DESTINATION", 1)[0].split()
    # every folder a robot needs at run time; evidence/ is for reviewers of the source tree
    assert installed == ["config", "launch", "rviz", "srdf", "urdf"]
    assert (pkg / "evidence").is_dir()


def test_stale_generated_file_is_removed(generated: tuple[Path, Path]) -> None:
    spec, pkg = generated
    text = EXAMPLE_TEXT.split("\nsemantic:\n")[0] + "\nknown_poses:\n" + EXAMPLE_TEXT.split("\nknown_poses:\n")[1]
    spec.write_text(text)
    outcome = generate(spec)
    assert not outcome.failed, outcome.findings
    assert outcome.removed == ["srdf/warehouse_arm.srdf"]
    assert not (pkg / "srdf" / "warehouse_arm.srdf").exists()


def test_other_files_in_the_package_are_left_alone(generated: tuple[Path, Path]) -> None:
    spec, pkg = generated
    mine = pkg / "evidence" / "my_notes.md"
    mine.parent.mkdir(exist_ok=True)
    mine.write_text("notes")
    spec.write_text(plant("{value: 1200 g, source: M03}", "{value: 1250 g, source: M03}"))
    assert not generate(spec).failed
    assert mine.read_text() == "notes"


def test_generated_copy_can_be_checked_elsewhere(tmp_path: Path) -> None:
    """The committed package is complete: copying the project (the spec, the trajectory its
    control evidence records, the package) elsewhere keeps check green."""
    shutil.copytree(ROOT / "generated", tmp_path / "generated")
    spec = project(tmp_path)
    shutil.copytree(ROOT / "specs" / "trajectories", tmp_path / "specs" / "trajectories")
    assert not check(spec).failed
