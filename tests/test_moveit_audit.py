"""``descgen audit --moveit-config DIR`` and ``audit_moveit_config``: real published MoveIt configs
(moveit_resources, tests/data/moveit_audit/README.md), defects planted in a copy of one, and
hostile files. The per-rule bad/good cases are in tests/rules/MOVEIT*/.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest
import yaml

from descgen.core.findings import InputError
from descgen.read.description import Options, load_description
from descgen.read.moveit_package import audit_moveit_config, moveit_codes

from .helpers import cli, run_cli

DATA = Path(__file__).with_name("data") / "moveit_audit"


def _robot(name: str, folder: Path | None = None):  # type: ignore[no-untyped-def]
    robot, _ = load_description(DATA / name / f"{name}.urdf")
    return robot


def _planted(tmp_path: Path, edits: list[tuple[str, str, str]]) -> Path:
    """A copy of the published panda config with text edits (file, old, new), each made exactly once."""
    dest = tmp_path / "panda"
    shutil.copytree(DATA / "panda", dest)
    for name, old, new in edits:
        path = dest / "config" / name
        text = path.read_text()
        assert text.count(old) == 1, (name, old)
        path.write_text(text.replace(old, new))
    return dest


def _moveit(found: list) -> list[tuple[str, str, int, str]]:  # type: ignore[type-arg]
    return [(f.code, Path(f.where.file).name, f.where.line, f.subject) for f in found if f.code.startswith("MOVEIT")]


@pytest.mark.parametrize("name", ["panda", "fanuc"])
def test_published_configs_have_no_moveit_finding(name: str) -> None:
    # Hand reading of the copied files: every planned joint (panda_joint1..7 and panda_finger_joint1;
    # panda_finger_joint2 is a passive mimic; fanuc joint_1..6) has has_acceleration_limits: true with a
    # positive float max_acceleration, and a max_velocity at or under the URDF's (2.175 < 2.3925, 2.61 <
    # 2.871, 0.1 < 0.2; fanuc equal); every value is written as a float; the one controller has action_ns
    # follow_joint_trajectory, type FollowJointTrajectory, the group's joints, and is a JTC with the same
    # joints in ros2_controllers.yaml; kinematics.yaml names the SRDF's single chain group with KDL; the
    # initial positions are inside the URDF limits (panda_joint4 -2.356 in [-3.1416, 0.0873]).
    # So no MOVEIT finding at all.
    assert audit_moveit_config(_robot(name), DATA / name) == []


def test_the_folder_srdf_and_ros2_controllers_are_read(tmp_path: Path) -> None:
    # without them MOVEIT010/011 would have nothing to compare; the published SRDF has 3 groups
    robot, _ = load_description(DATA / "panda" / "panda.urdf", Options(moveit_config=DATA / "panda"))
    assert robot.semantic is not None
    assert [g.name for g in robot.semantic.groups] == ["panda_arm", "hand", "panda_arm_hand"]
    assert robot.ros2_control is not None
    assert [c.name for c in robot.ros2_control.controllers] == [
        "panda_arm_controller",
        "panda_hand_controller",
        "joint_state_broadcaster",
    ]
    assert robot.moveit_config is not None
    assert robot.moveit_config.srdf_file == str(DATA / "panda" / "config" / "panda.srdf")


def test_planted_setup_assistant_defects_in_the_panda_config(tmp_path: Path) -> None:
    # what a fresh Setup Assistant package looks like: the double 2.0 written as `2`, no acceleration
    # limit on panda_joint7, and a controller added by "Auto Add" without action_ns
    folder = _planted(
        tmp_path,
        [
            (
                "joint_limits.yaml",
                "    max_velocity: 2.1750\n    has_acceleration_limits: true\n    max_acceleration: 3.75\n",
                "    max_velocity: 2\n    has_acceleration_limits: true\n    max_acceleration: 3.75\n",
            ),
            (
                "joint_limits.yaml",
                "  panda_joint7:\n    has_velocity_limits: true\n    max_velocity: 2.6100\n"
                "    has_acceleration_limits: true\n",
                "  panda_joint7:\n    has_velocity_limits: true\n    max_velocity: 2.6100\n"
                "    has_acceleration_limits: false\n",
            ),
            ("moveit_controllers.yaml", "    action_ns: follow_joint_trajectory\n", ""),
        ],
    )
    found = audit_moveit_config(_robot("panda"), folder)
    # lines counted in the published files: panda_joint1's max_velocity is line 8, panda_joint7 starts
    # at line 48 so its has_acceleration_limits is line 51; panda_arm_controller's key is line 14
    assert _moveit(found) == [
        ("MOVEIT001", "joint_limits.yaml", 51, "joint:panda_joint7"),
        ("MOVEIT003", "joint_limits.yaml", 8, "param:joint_limits.panda_joint1.max_velocity"),
        ("MOVEIT007", "moveit_controllers.yaml", 14, "controller:panda_arm_controller"),
    ]
    by_code = {f.code: f for f in found}
    assert by_code["MOVEIT003"].hint == "write 2.0"
    assert "action_ns: follow_joint_trajectory" in by_code["MOVEIT007"].hint
    assert by_code["MOVEIT001"].where.col == 30  # the value `false`, after "    has_acceleration_limits: "


def test_an_integer_moveit_never_reads_is_not_reported(tmp_path: Path) -> None:
    # the Setup Assistant writes `max_acceleration: 0` under has_acceleration_limits: false; MoveIt
    # reads max_acceleration only when the flag is true. Under `true` (panda_joint2) the same integer
    # is read: MOVEIT003 (and MOVEIT001, since 0 is no limit); under `false` only MOVEIT001.
    folder = _planted(
        tmp_path,
        [
            ("joint_limits.yaml", "    max_acceleration: 1.875\n", "    max_acceleration: 0\n"),
            (
                "joint_limits.yaml",
                "    has_acceleration_limits: true\n    max_acceleration: 2.5\n",
                "    has_acceleration_limits: false\n    max_acceleration: 0\n",
            ),
        ],
    )
    # panda_joint2's block is lines 13-19 (max_acceleration line 17), panda_joint3's lines 20-26
    assert _moveit(audit_moveit_config(_robot("panda"), folder)) == [
        ("MOVEIT001", "joint_limits.yaml", 17, "joint:panda_joint2"),
        ("MOVEIT001", "joint_limits.yaml", 23, "joint:panda_joint3"),
        ("MOVEIT003", "joint_limits.yaml", 17, "param:joint_limits.panda_joint2.max_acceleration"),
    ]


def test_cli_json_and_exit_codes(tmp_path: Path) -> None:
    folder = _planted(tmp_path, [("moveit_controllers.yaml", "    action_ns: follow_joint_trajectory\n", "")])
    ran = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder, "--format", "json")
    assert ran.returncode == 1
    moveit = [f for f in json.loads(ran.stdout)["findings"] if f["code"].startswith("MOVEIT")]
    assert [(f["code"], f["line"], f["col"]) for f in moveit] == [("MOVEIT007", 14, 3)]
    assert moveit[0]["file"] == str(folder / "config" / "moveit_controllers.yaml")


def test_cli_text_end_to_end(tmp_path: Path) -> None:
    folder = _planted(tmp_path, [("kinematics.yaml", "panda_arm:", "panda_manipulator:")])
    ran = run_cli("audit", str(DATA / "panda" / "panda.urdf"), "--moveit-config", str(folder))
    line = next(x for x in ran.stderr.splitlines() if "MOVEIT016" in x)
    assert line.startswith(f"{folder}/config/kinematics.yaml:1:1: warning[MOVEIT016]: ")
    assert "Traceback" not in ran.stderr


# --------------------------------------------------------------------------- hostile and unusable input


def _exit2(tmp_path: Path, name: str, content: bytes | None, code: str) -> str:
    folder = _planted(tmp_path, [])
    if content is not None:
        (folder / "config" / name).write_bytes(content)
    ran = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder)
    assert ran.returncode == 2, ran.stderr
    assert f"[{code}]" in ran.stderr and "Traceback" not in ran.stderr
    return ran.stderr


def test_yaml_bomb_is_refused(tmp_path: Path) -> None:
    bomb = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    bomb += [
        f"a{i}: &a{i} [*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}]"
        for i in range(1, 10)
    ]
    _exit2(tmp_path, "joint_limits.yaml", "\n".join(bomb).encode(), "YAML003")


def test_huge_file_is_refused_before_reading(tmp_path: Path) -> None:
    folder = _planted(tmp_path, [])
    with open(folder / "config" / "kinematics.yaml", "wb") as fh:
        fh.truncate(200 * 1024 * 1024)  # sparse: no disk used, and never read
    ran = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder)
    assert ran.returncode == 2 and "[READ041]" in ran.stderr and "Traceback" not in ran.stderr


@pytest.mark.parametrize(
    ("name", "content"),
    [
        ("moveit_controllers.yaml", b"- a\n- b\n"),
        ("initial_positions.yaml", b"3.5\n"),
        ("kinematics.yaml", b"# only\n"),
    ],
)
def test_non_mapping_root_is_refused(tmp_path: Path, name: str, content: bytes) -> None:
    err = _exit2(tmp_path, name, content, "MOVEIT020")
    assert f"{name}:1:1: error[MOVEIT020]" in err


def test_malformed_yaml_points_at_the_position(tmp_path: Path) -> None:
    err = _exit2(tmp_path, "joint_limits.yaml", b"joint_limits:\n  j1: [1, 2\n", "YAML001")
    assert "joint_limits.yaml:3:" in err or "joint_limits.yaml:2:" in err


def test_fifo_is_refused_without_blocking(tmp_path: Path) -> None:
    folder = _planted(tmp_path, [])
    target = folder / "config" / "initial_positions.yaml"
    target.unlink()
    os.mkfifo(target)
    ran = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", folder, timeout=20)
    assert ran.returncode == 2 and "[READ040]" in ran.stderr


def test_a_folder_without_moveit_files_is_exit_2(tmp_path: Path) -> None:
    with pytest.raises(InputError) as exc:
        audit_moveit_config(_robot("panda"), tmp_path)
    assert [f.code for f in exc.value.findings] == ["MOVEIT021"]
    ran = cli("audit", DATA / "panda" / "panda.urdf", "--moveit-config", tmp_path / "nope")
    assert ran.returncode == 2 and "Traceback" not in ran.stderr


def test_every_moveit_rule_is_registered_and_documented() -> None:
    codes = moveit_codes()
    assert codes == [f"MOVEIT{n:03d}" for n in range(1, 20)]
    # the published files parse as the YAML the rules assume (an oracle for the reader's input)
    assert yaml.safe_load((DATA / "panda" / "config" / "joint_limits.yaml").read_text())["joint_limits"]


def test_an_integer_pilz_limit_and_a_missing_pilz_file(tmp_path: Path) -> None:
    # the published panda file writes max_trans_vel on line 3 ("# Cartesian limits..." is line 1);
    # Pilz reads it as a double, and MoveItConfigsBuilder loads the file by default
    folder = _planted(tmp_path, [("pilz_cartesian_limits.yaml", "  max_trans_vel: 1.0\n", "  max_trans_vel: 1\n")])
    found = audit_moveit_config(_robot("panda"), folder)
    assert _moveit(found) == [
        ("MOVEIT003", "pilz_cartesian_limits.yaml", 3, "param:cartesian_limits.max_trans_vel"),
    ]
    (folder / "config" / "pilz_cartesian_limits.yaml").unlink()
    assert [f.code for f in audit_moveit_config(_robot("panda"), folder) if f.code.startswith("MOVEIT")] == [
        "MOVEIT019"
    ]
