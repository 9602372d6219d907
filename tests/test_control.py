"""The command/state boundary: lifecycle and claims as Jazzy documents them, limits, and
tracking that tells an echo from verified motion."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import pytest

from descgen.audit.spec import load_spec
from descgen.commands.control.load import load_system
from descgen.commands.control.run import run
from descgen.commands.control.system import Plant
from descgen.commands.control.trajectory import read_trajectory
from descgen.commands.generate import generate

from .conftest import EXAMPLE, ROOT
from .helpers import cli, plant

ROBOT = load_spec(EXAMPLE).robot
PACKAGE = ROOT / "generated" / "warehouse_arm_description"
READY = ROOT / "specs" / "trajectories" / "ready.yaml"


def transitions(cm):  # type: ignore[no-untyped-def]
    return [(e["name"], e["callback"], e["state"]) for e in cm.trace.events if e["event"] == "transition"]


def test_lifecycle_order_and_claims_follow_jazzy() -> None:
    cm = load_system(PACKAGE, ROBOT, Plant())
    # hardware_components_initial_state unset: the component is initialised, configured and
    # activated at startup; then the spawner loads (on_init), configures and activates each
    # controller in turn (docs/reference/ros2_control.md, spawner.py)
    expected = [
        ("WarehouseArmSystem", "on_init", "unconfigured"),
        ("WarehouseArmSystem", "on_configure", "inactive"),
        ("WarehouseArmSystem", "on_activate", "active"),
    ]
    for c in ("joint_state_broadcaster", "diff_drive_controller", "arm_controller"):
        expected += [(c, "on_init", "unconfigured"), (c, "on_configure", "inactive"), (c, "on_activate", "active")]
    assert transitions(cm) == expected
    claims = [(e["controller"], e["interface"]) for e in cm.trace.events if e["event"] == "claim"]
    assert claims == [
        ("diff_drive_controller", "left_wheel_joint/velocity"),
        ("diff_drive_controller", "right_wheel_joint/velocity"),
        ("arm_controller", "lift_joint/position"),
        ("arm_controller", "shoulder_pan_joint/position"),
        ("arm_controller", "shoulder_lift_joint/position"),
        ("arm_controller", "elbow_joint/position"),
    ]
    # a second controller claiming the same interfaces fails with tf2-like reasons, and gets nothing
    arm = cm.controllers["arm_controller"]
    second = cm.spawn("arm_controller_2", arm.type, dict(arm.params))
    assert second.state == "inactive"
    failure = [e for e in cm.trace.events if e.get("controller") == "arm_controller_2"]
    assert "Command interface with key 'lift_joint/position' is already claimed" in failure[0]["detail"]
    assert any("Resource conflict for controller 'arm_controller_2'" in e.get("detail", "") for e in failure)
    assert all(owner != "arm_controller_2" for owner in cm.resources.owner.values())
    # deactivating releases, and then the other controller can activate
    cm.deactivate("arm_controller")
    assert cm.activate("arm_controller_2") and cm.controllers["arm_controller_2"].state == "active"


def test_loop_reads_before_update_before_write() -> None:
    cm = load_system(PACKAGE, ROBOT, Plant())
    traj = read_trajectory(READY, ROBOT)
    out = run(PACKAGE, ROBOT, traj, 0.5, Plant())
    rows = [r for r in out.rows if r[1] == "elbow_joint"]
    # mock hardware mirrors in read(): the state seen in a cycle is the command of the one before
    for (_, _, _, c_prev, _), (_, _, _, _, m_next) in itertools.pairwise(rows):
        assert m_next == pytest.approx(c_prev)
    assert cm.update_rate == 100


def test_mock_is_labelled_an_echo_and_sim_is_not() -> None:
    traj = read_trajectory(READY, ROBOT)
    mock = run(PACKAGE, ROBOT, traj, None, Plant("mock"))
    assert mock.echo and mock.verdict()["state_echoes_command"] and "not verified motion" in mock.verdict()["note"]
    sim = run(PACKAGE, ROBOT, traj, None, Plant("sim"))
    assert not sim.echo and sim.verdict()["ok"]
    # the sim plant tracks through the ready pose: elbow at -90 deg after 3 s
    at_ready = next(r for r in sim.rows if r[1] == "elbow_joint" and abs(r[0] - 3.0) < 1e-9)
    assert at_ready[4] == pytest.approx(-math.pi / 2, abs=0.01)


@pytest.mark.parametrize("fault", ["reversed", "stuck"])
def test_plant_faults_fail_the_tracking_verdict(fault: str) -> None:
    traj = read_trajectory(READY, ROBOT)
    out = run(PACKAGE, ROBOT, traj, None, Plant("sim", faults={"elbow_joint": fault}))
    v = out.verdict()
    assert not v["ok"] and v["tracking_failed"] == ["elbow_joint"]
    assert v["tracking"]["elbow_joint"] > math.radians(80)


def _variant(tmp: Path, policy: str) -> Path:
    """The example with the elbow limited to [-1 rad, 1 rad] and ``on_limit: policy``, generated."""
    text = plant("lower: -150 deg, upper: 150 deg", "lower: -1 rad, upper: 1 rad")
    text = plant(
        "{name: elbow_joint, command: [position], state: [position, velocity], on_limit: reject",
        f"{{name: elbow_joint, command: [position], state: [position, velocity], on_limit: {policy}",
        text,
    )
    # the known pose at -90 deg no longer fits a 1 rad limit: drop the poses that use the elbow
    text = text.split("known_poses:")[0] + "known_poses: []\n"
    text = text.replace(
        "    - {name: zero, group: arm, pose: zero}\n    - {name: ready, group: arm, pose: ready}\n",
        "    - {name: zero, group: arm, joints: {lift_joint: {value: 0 mm, source: test}}}\n",
    )
    # the collision matrix's default state was 'ready'; the remaining state is 'zero'
    text = text.replace("collision_matrix: {default_state: ready,", "collision_matrix: {default_state: zero,")
    (tmp / "specs").mkdir()
    spec = tmp / "specs" / "warehouse_arm.yaml"
    spec.write_text(text)
    outcome = generate(spec)
    assert not outcome.failed, outcome.findings
    return spec


@pytest.fixture(scope="module")
def limited(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """One generated variant per policy, shared by the four limit tests (generating takes a second)."""
    return {policy: _variant(tmp_path_factory.mktemp(policy), policy) for policy in ("reject", "clip")}


# Hand values: the elbow's limits are -1 and +1 rad; the trajectory asks for 1.2 rad beyond
# either side in 1 s, so the controller's desired position crosses the limit before 1 s.
@pytest.mark.parametrize("side", [1.0, -1.0], ids=["above_upper", "below_lower"])
@pytest.mark.parametrize("policy", ["reject", "clip"])
def test_command_beyond_limit_rejected_or_clipped(
    limited: dict[str, Path], tmp_path: Path, policy: str, side: float
) -> None:
    spec = limited[policy]
    traj = tmp_path / "t.yaml"
    traj.write_text(
        "controller: arm_controller\njoints: [elbow_joint]\n"
        f'points:\n  - {{time_from_start: "1 s", positions: ["{1.2 * side:g} rad"]}}\n'
    )
    robot = load_spec(spec).robot
    package = spec.parent.parent / "generated" / "warehouse_arm_description"
    out = run(package, robot, read_trajectory(traj, robot), 1.5, Plant("mock"))
    v = out.verdict()
    commands = [r[3] for r in out.rows if r[1] == "elbow_joint"]
    if policy == "reject":
        assert v["rejected"] and not v["clipped"] and not v["ok"]
        first = v["rejected"][0]
        assert first["joint"] == "elbow_joint" and first["limit"] == pytest.approx(side)
        assert first["value"] * side > 1.0  # beyond the limit on the commanded side
        # the hardware never took a command beyond the limit: it kept the last accepted one
        assert all(-1.0 - 1e-12 <= c <= 1.0 + 1e-12 for c in commands)
        assert abs(commands[-1]) < 1.0
    else:
        assert v["clipped"] and not v["rejected"]
        last = v["clipped"][-1]
        assert last["proposed"] == pytest.approx(1.2 * side) and last["applied"] == pytest.approx(side)
        assert last["limit"] == pytest.approx(side)
        assert commands[-1] == pytest.approx(side)


def test_control_cli_writes_every_file(tmp_path: Path) -> None:
    out = tmp_path / "evidence"
    r = cli("control", "specs/warehouse_arm.yaml", "--trajectory", READY, "--out", out)
    assert r.returncode == 0, r.stderr
    for name in (
        "lifecycle.jsonl",
        "lifecycle.md",
        "interfaces.md",
        "desired_vs_measured.csv",
        "verdict.json",
        "elbow_joint.png",
    ):
        assert (out / name).is_file(), name
    assert next((out / "control_run").glob("*.mcap")).stat().st_size > 0
    verdict = json.loads((out / "verdict.json").read_text())
    assert {"rejected", "clipped", "tracking", "state_echoes_command"} <= set(verdict)
    assert verdict["state_echoes_command"] is True
    header = (out / "desired_vs_measured.csv").read_text().splitlines()[0]
    assert header == "time_s,joint,desired,commanded,measured,error"
    assert "\tlift_joint/position [available] [claimed]" in (out / "interfaces.md").read_text()


def test_infinite_command_takes_the_error_path() -> None:
    # GenericSystem: an infinite command makes read() return ERROR -> on_error -> unconfigured
    cm = load_system(PACKAGE, ROBOT, Plant())
    cm.by_name["elbow_joint"].commands["position"] = math.inf
    cm.step(0.01)
    assert cm.hardware.state == "unconfigured"
    errors = [e for e in cm.trace.events if e["event"] == "error"]
    assert errors and "infinite command on elbow_joint" in errors[0]["detail"]
    assert transitions(cm)[-1] == ("WarehouseArmSystem", "on_error", "unconfigured")


def test_an_oversized_or_binary_trajectory_is_named_a_trajectory(tmp_path: Path) -> None:
    from descgen.core.findings import InputError
    from descgen.infra.yamlsource import MAX_BYTES

    big = tmp_path / "big.yaml"
    big.write_bytes(b"#" * (MAX_BYTES + 1))
    binary = tmp_path / "bin.yaml"
    binary.write_bytes(b"points: [\0]\n")
    for path, words in ((big, "a trajectory file is at most"), (binary, "name a .yaml trajectory")):
        with pytest.raises(InputError) as err:
            read_trajectory(path, ROBOT)
        shown = f"{err.value.findings[0].message} {err.value.findings[0].hint}"
        assert words in shown and "spec" not in shown, shown
