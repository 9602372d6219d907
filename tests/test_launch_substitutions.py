"""Launch substitutions in a controllers YAML (``$(var NAME)``, loaded by launch_ros with
``ParameterFile(..., allow_substs=True)``): ``--launch-arg`` gives values, nothing else is ever
evaluated, and the joint checks do not call the literal ``$(var ...)`` an unknown joint.

The corpus file is ros2_control_demos (jazzy) example_1's ``config/rrbot_controllers.yaml``
(vendored): its joints are on lines 11 and 12, ``      - $(var joint_prefix)1`` (the ``$`` at
column 9: six spaces, the dash and a space before it). Its launch file declares ``joint_prefix``
with ``default_value="joint"``, so launch gives the controller ``joint1`` and ``joint2``."""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

import pytest
import yaml

from descgen.read.controllers import parse_substituted, read_controllers_text
from tests.helpers import ROOT, cli

CORPUS = ROOT / "tests" / "data" / "xacro_corpus"
XACRO = CORPUS / "ros2_control_demo_example_1" / "urdf" / "rrbot.urdf.xacro"
CONTROLLERS = CORPUS / "ros2_control_demo_example_1" / "config" / "rrbot_controllers.yaml"
URDF = """<robot name="two">
  <link name="base"/><link name="l1"/>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def _audit(*extra: str | Path, controllers: Path = CONTROLLERS, path: Path = XACRO) -> tuple[int, list[dict]]:
    ran = cli("audit", path, "--package-path", CORPUS, "--controllers", controllers, "--format", "json", *extra)
    assert ran.returncode in (0, 1), ran.stderr[-2000:]
    return ran.returncode, json.loads(ran.stdout)["findings"]


def _codes(found: list[dict]) -> set[str]:
    return {f["code"] for f in found}


def test_without_a_value_each_site_warns_and_no_joint_is_called_unknown() -> None:
    code, found = _audit()
    sites = [(f["line"], f["col"]) for f in found if f["code"] == "CTRL052"]
    assert sorted(sites) == [(11, 9), (12, 9)]
    assert all(f["file"].endswith("rrbot_controllers.yaml") for f in found if f["code"] == "CTRL052")
    assert not _codes(found) & {"CTRL002", "CTRL009"}
    assert code == 0  # warnings only
    assert "--launch-arg joint_prefix:=" in next(f["hint"] for f in found if f["code"] == "CTRL052")


def test_the_launch_default_resolves_to_the_urdf_joints() -> None:
    code, found = _audit("--launch-arg", "joint_prefix:=joint")
    assert code == 0
    assert not {c for c in _codes(found) if c.startswith("CTRL")}
    controllers, _, more = read_controllers_text(CONTROLLERS.read_text(), "c.yaml", {"joint_prefix": "joint"})
    assert more == []
    forward = next(c for c in controllers if c.name == "forward_position_controller")
    assert forward.param("joints") == ("joint1", "joint2")


@pytest.mark.parametrize(("prefix", "names"), [("left_", ["left_1", "left_2"]), ("", ["1", "2"])])
def test_a_wrong_value_gives_true_unknown_joint_findings(prefix: str, names: list[str]) -> None:
    # an empty value is a value (launch joins '' and '1'), not a missing one
    code, found = _audit("--launch-arg", f"joint_prefix:={prefix}")
    assert code == 1
    unknown = sorted(f["message"].split("'")[3] for f in found if f["code"] == "CTRL009")
    assert unknown == names
    assert "CTRL052" not in _codes(found)


def _params(text: str, args: dict[str, str]) -> tuple[dict[str, Any], Any]:
    parsed = parse_substituted(text, "f.yaml", args)
    return {p.name: p for p in parsed.params.nodes[0].params}, parsed


def test_marks_point_into_the_file_as_written() -> None:
    # '    a: [$(var p), b]': b is at column 19 of the file; after substitution it would be at 21
    text = "n:\n  ros__parameters:\n    a: [$(var p), b]\n    c: $(var q)\n"
    got, parsed = _params(text, {"p": "xxxxxxxxxx"})
    assert {k: p.value for k, p in got.items()} == {"a": ("xxxxxxxxxx", "b"), "c": "$(var q)"}
    assert (got["a"].items[1].line, got["a"].items[1].col) == (3, 19)
    assert [(f.code, f.where.line, f.where.col) for f in parsed.found] == [("CTRL052", 4, 8)]
    assert [s.value for s in parsed.sites] == ["xxxxxxxxxx", None]


def test_values_are_typed_after_substitution_and_defaults_apply() -> None:
    # launch substitutes the text, then rcl types it: 'update_rate: $(var r)' is the integer 250
    text = "controller_manager:\n  ros__parameters:\n    update_rate: $(var r)\n    x: $(var s 7)\n"
    got, parsed = _params(text, {"r": "250"})
    assert {k: p.value for k, p in got.items()} == {"update_rate": 250, "x": 7}
    assert parsed.found == ()


def test_escaped_dollar_is_text_as_launch_reads_it() -> None:
    # launch's grammar: a '$' after a backslash is text, and text loses its backslashes
    got, parsed = _params('n:\n  ros__parameters:\n    a: "\\$(var p)"\n    b: $(var p)\n', {"p": "v"})
    assert {k: p.value for k, p in got.items()} == {"a": "$(var p)", "b": "v"}
    assert len(parsed.sites) == 1 and parsed.found == ()


def test_env_is_never_read(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    secret = "s3cret-home-7f3a"
    monkeypatch.setenv("HOME", f"/home/{secret}")
    ctl = tmp_path / "c.yaml"
    ctl.write_text(
        "fwd:\n  ros__parameters:\n    type: forward_command_controller/ForwardCommandController\n"
        "    joints: [$(env HOME)]\n    interface_name: position\n"
    )
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    for fmt in ("text", "json"):
        ran = cli("audit", urdf, "--controllers", ctl, "--format", fmt, "--launch-arg", "HOME:=x")
        assert secret not in ran.stdout + ran.stderr
        assert "CTRL053" in ran.stdout + ran.stderr
        assert "CTRL009" not in ran.stdout + ran.stderr  # the warning stands for the name


def test_eval_and_command_are_not_run(tmp_path: Path) -> None:
    marker = tmp_path / "ran"
    ctl = tmp_path / "c.yaml"
    ctl.write_text(
        f"a:\n  ros__parameters:\n    type: x/Y\n    p: $(eval \"__import__('os').system('touch {marker}')\")\n"
        f"    q: $(command touch {marker})\n    r: $(find-pkg-share rclpy)/x\n"
    )
    parsed = parse_substituted(ctl.read_text(), str(ctl), {})
    assert not marker.exists()
    assert [s.kind for s in parsed.sites] == ["eval", "command", "find-pkg-share"]
    assert [(f.code, f.where.line) for f in parsed.found] == [("CTRL053", 4), ("CTRL053", 5), ("CTRL053", 6)]
    assert parsed.params.nodes[0].get("r").value == "$(find-pkg-share rclpy)/x"  # left as written


@pytest.mark.parametrize(
    "text",
    [
        "a: [" + ", ".join(["$(var x)"] * 1001) + "]\n",  # more sites than any real file
        "a: " + "$(var " * 30 + "x" + ")" * 30 + "\n",  # nested deeper than the limit
        "a: '" + "$(var x " * 5000 + "'\n",  # unterminated, nested: must not recurse without bound
    ],
    ids=["many", "deep", "unterminated"],
)
def test_a_substitution_bomb_is_refused_fast(text: str, tmp_path: Path) -> None:
    ctl = tmp_path / "c.yaml"
    ctl.write_text(text)
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    start = time.perf_counter()
    ran = cli("audit", urdf, "--controllers", ctl, "--launch-arg", "x:=" + "y" * 4096)
    assert time.perf_counter() - start < 5
    assert ran.returncode == 2
    assert "error[CTRL054]" in ran.stderr
    assert "Traceback" not in ran.stderr


def test_the_result_size_is_bounded(tmp_path: Path) -> None:
    ctl = tmp_path / "c.yaml"
    ctl.write_text("# " + "z" * (5 * 1024 * 1024 - 200 * 8) + "\n" + "a: [" + ", ".join(["$(var x)"] * 200) + "]\n")
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    ran = cli("audit", urdf, "--controllers", ctl, "--launch-arg", "x:=" + "y" * 4096)
    assert ran.returncode == 2 and "error[CTRL054]" in ran.stderr and "grows past 5 MB" in ran.stderr


@pytest.mark.parametrize("arg", ["x", ":=v", "a:=line\nbreak", "a:=" + "v" * 4097, "a b:=1"])
def test_bad_launch_arg_values_exit_2(arg: str, tmp_path: Path) -> None:
    urdf = tmp_path / "r.urdf"
    urdf.write_text(URDF)
    ran = cli("audit", urdf, "--launch-arg", arg)
    assert ran.returncode == 2 and "error[CTRL054]: --launch-arg" in ran.stderr


@pytest.mark.parametrize("command", ["audit", "import"])
def test_a_launch_arg_without_controllers_is_refused_not_ignored(command: str, tmp_path: Path) -> None:
    out = tmp_path / "robot.yaml"
    extra = ["-o", out] if command == "import" else []
    ran = cli(command, XACRO, "--package-path", CORPUS, "--launch-arg", "joint_prefix:=joint", *extra, cwd=tmp_path)
    assert ran.returncode == 2
    assert "<command line>: error[CTRL055]: --launch-arg is given without --controllers" in ran.stderr
    assert "add --controllers FILE" in ran.stderr and "Traceback" not in ran.stderr
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_import_without_a_value_refuses_and_writes_nothing(tmp_path: Path) -> None:
    out = tmp_path / "robot.yaml"
    ran = cli("import", XACRO, "--package-path", CORPUS, "--controllers", CONTROLLERS, "-o", out, cwd=tmp_path)
    assert ran.returncode == 2
    assert ran.stderr.count("error[IMP032]") == 2
    assert "rrbot_controllers.yaml:11:9" in ran.stderr and "--launch-arg joint_prefix:=" in ran.stderr
    assert not out.exists()


@pytest.mark.slow
def test_import_with_the_launch_value_proves_and_the_spec_checks(tmp_path: Path) -> None:
    out = tmp_path / "robot.yaml"
    ran = cli(
        "import", XACRO, "--package-path", CORPUS, "--controllers", CONTROLLERS, "-o", out,
        "--launch-arg", "joint_prefix:=joint", cwd=tmp_path,
    )  # fmt: skip
    assert ran.returncode == 0, ran.stderr[-2000:]
    assert ran.stderr.count("info[IMP031]") == 2
    spec = yaml.safe_load(out.read_text())
    forward = next(c for c in spec["ros2_control"]["controllers"] if c["name"] == "forward_position_controller")
    assert forward["params"]["joints"] == ["joint1", "joint2"]
    for command in ("validate", "generate", "check"):
        extra = [] if command == "validate" else ["--out", tmp_path / "gen", "--package-path", CORPUS]
        done = cli(command, out, *extra, cwd=tmp_path)
        assert done.returncode == 0, (command, done.stderr[-2000:])


def test_a_spec_value_that_looks_like_a_substitution_is_just_a_name(tmp_path: Path) -> None:
    # found by tests/test_fuzz_generate.py: validate let it through as if launch would substitute
    # it, then generate's proof failed; a spec is never substituted, so it is an unknown joint
    spec = tmp_path / "specs" / "warehouse_arm.yaml"
    spec.parent.mkdir()
    text = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    assert "left_wheel_names: [left_wheel_joint]" in text
    spec.write_text(
        text.replace("left_wheel_names: [left_wheel_joint]", 'left_wheel_names: ["left_wheel_joint$(env HOME)"]')
    )
    ran = cli("validate", spec)
    assert ran.returncode == 2 and "error[CTRL009]" in ran.stderr and "left_wheel_joint$(env HOME)" in ran.stderr
