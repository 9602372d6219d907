"""descgen sweep: directions by hand computation, collisions at hand-computed joint values,
mimic followers, the evidence file's reuse in check, and bad input (exit 2, no traceback)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tests.helpers import ROOT, cli

pytest.importorskip("pinocchio")

EXAMPLE = ROOT / "specs" / "warehouse_arm.yaml"
GRIPPER = ROOT / "tests" / "data" / "mimic" / "gripper.yaml"


def _json(*args: str | Path) -> tuple[int, dict, str]:
    ran = cli("sweep", *args, "--format", "json")
    assert "Traceback" not in ran.stderr
    return ran.returncode, json.loads(ran.stdout), ran.stderr


def _joint(doc: dict, name: str) -> dict:
    return next(j for j in doc["sweep"]["joints"] if j["joint"] == name)


def _moved(doc: dict, joint: str, link: str) -> list[float]:
    return next(m["displacement_m"] for m in _joint(doc, joint)["moving"] if m["link"] == link)


# --- the example: directions against the measurement sheet, computed by hand ---------------------


@pytest.fixture(scope="module")
def example() -> dict:
    code, doc, _ = _json(EXAMPLE)
    assert code == 0  # warnings only (contacts at limits); exit 1 needs --strict
    return doc


def _rot_y(angle: float, length: float) -> tuple[float, float]:
    """(x, z) of a point ``length`` along +x after a rotation by ``angle`` about +y."""
    return length * math.cos(angle), -length * math.sin(angle)


def test_elbow_moves_tool_by_hand(example: dict) -> None:
    # elbow range -150..150 deg is more than half a turn, so the direction is a quarter turn from
    # the state: ready has the elbow at -90 deg; the tool is 250 mm along the forearm (M22)
    lo, hi = _rot_y(math.radians(-90), 0.25), _rot_y(0.0, 0.25)
    d = _moved(example, "elbow_joint", "tool_link")
    assert d == pytest.approx([hi[0] - lo[0], 0.0, hi[1] - lo[1]], abs=1e-9)  # (0.25, 0, -0.25)
    assert _joint(example, "elbow_joint")["direction"] == (
        "positive elbow_joint moves tool_link +x 250 mm, -z 250 mm over a quarter turn"
    )
    assert _joint(example, "elbow_joint")["axis_root"] == pytest.approx([0, 1, 0], abs=1e-12)


def test_shoulder_lift_tips_the_arm_down_by_hand(example: dict) -> None:
    # M19: positive tips the arm down; upper arm 300 mm (M20), forearm 250 mm at elbow -90 deg (ready);
    # the range -100..100 deg is more than half a turn: a quarter turn from the state (0 deg)
    def tool(phi: float) -> tuple[float, float]:
        ux, uz = _rot_y(phi, 0.3)
        fx, fz = _rot_y(phi - math.pi / 2, 0.25)
        return ux + fx, uz + fz

    lo, hi = tool(0.0), tool(math.pi / 2)
    d = _moved(example, "shoulder_lift_joint", "tool_link")
    assert d == pytest.approx([hi[0] - lo[0], 0.0, hi[1] - lo[1]], abs=1e-9)  # (-0.05, 0, -0.55)
    assert d[2] < -0.5  # down
    assert _joint(example, "shoulder_lift_joint")["direction"].startswith(
        "positive shoulder_lift_joint moves tool_link -z 550 mm, -x 50 mm"
    )


def test_lift_moves_everything_above_it_up(example: dict) -> None:
    j = _joint(example, "lift_joint")
    moving = {m["link"] for m in j["moving"]}
    assert moving == {
        "lift_link",
        "shoulder_link",
        "upper_link",
        "forearm_link",
        "tool_link",
        "camera_link",
        "camera_optical_frame",
    }
    for m in j["moving"]:
        assert m["displacement_m"] == pytest.approx([0, 0, 0.3], abs=1e-12)  # M15: 0 to 300 mm along +z
    assert example["sweep"]["state"] == "ready"  # the matrix's default state
    assert example["sweep"]["links_without_collision_geometry"] == [
        "base_footprint",
        "tool_link",
        "camera_optical_frame",
    ]


def test_evidence_file_says_the_same(example: dict) -> None:
    text = (ROOT / "generated" / "warehouse_arm_description" / "evidence" / "sweep.md").read_text()
    assert "positive elbow\\_joint moves tool\\_link +x 250 mm, -z 250 mm over a quarter turn" in text
    assert "positive lift\\_joint moves tool\\_link +z 300 mm" in text


# --- collisions at hand-computed joint values ------------------------------------------------------

# base_link: a post, box 0.2 m with centre (0, 0.5, 0): its corner nearest the arm is (0.1, 0.4).
# arm_link: a bar 0.4 x 0.02 x 0.02 from x = 0.05 to 0.45, turning about +z. Its leading face
# (0.01 ahead of the centre line) reaches the corner at atan2(0.4, 0.1) - asin(0.01 / |corner|)
# = 75.96 - 1.39 = 74.57 deg; the grid of [-75, 75] deg in 36 steps has 70.83 deg before 75.
ONSET = math.degrees(math.atan2(0.4, 0.1) - math.asin(0.01 / math.hypot(0.1, 0.4)))

URDF = """<robot name="post">
  <link name="base_link">
    <collision><origin xyz="0 0.5 0"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    {ball}
  </link>
  <link name="arm_link">
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.4 0.02 0.02"/></geometry></collision>
  </link>
  <joint name="turn" type="{type}">
    <parent link="base_link"/><child link="arm_link"/><axis xyz="{axis}"/>
    <limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>
  </joint>
</robot>
"""
SRDF = """<robot name="post">{disable}</robot>"""


def _write(tmp_path: Path, disable: str = "", **kw: object) -> tuple[Path, Path]:
    fields = {"ball": "", "type": "revolute", "axis": "0 0 1", "lower": -math.radians(75), "upper": math.radians(75)}
    fields.update(kw)
    urdf, srdf = tmp_path / "post.urdf", tmp_path / "post.srdf"
    urdf.write_text(URDF.format(**fields))
    srdf.write_text(SRDF.format(disable=disable))
    return urdf, srdf


def test_contact_only_at_the_upper_limit(tmp_path: Path) -> None:
    assert 70.84 < ONSET < 75  # the hand computation puts the contact between the last two steps
    urdf, srdf = _write(tmp_path)
    code, doc, _ = _json(urdf, "--srdf", srdf)
    assert code == 0
    (c,) = _joint(doc, "turn")["collisions"]
    assert (c["link1"], c["link2"], c["at_limit"]) == ("base_link", "arm_link", ["upper"])
    assert c["from"] == c["to"] == pytest.approx(math.radians(75))
    (f,) = [f for f in doc["findings"] if f["code"].startswith("SWEEP")]
    assert f["code"] == "SWEEP001" and f["severity"] == "warning"
    assert "upper limit of turn (75 deg)" in f["message"]
    assert cli("sweep", urdf, "--srdf", srdf, "--strict").returncode == 1


def test_same_pair_disabled_in_the_srdf_gives_nothing(tmp_path: Path) -> None:
    urdf, srdf = _write(tmp_path, '<disable_collisions link1="arm_link" link2="base_link" reason="User"/>')
    code, doc, _ = _json(urdf, "--srdf", srdf)
    assert code == 0
    assert _joint(doc, "turn")["collisions"] == []
    assert not [f for f in doc["findings"] if f["code"].startswith("SWEEP")]
    assert cli("sweep", urdf, "--srdf", srdf, "--strict").returncode == 0


def test_contact_inside_the_range(tmp_path: Path) -> None:
    # a ball of radius 0.05 at (0.3, 0, 0), on the bar's path: the bar (half thickness 0.01) is within
    # 0.05 of its centre while 0.3 sin|q| <= 0.06, |q| <= 11.54 deg; on the 5-degree grid of
    # [-90, 90] deg that is -10 to 10 deg
    ball = '<collision><origin xyz="0.3 0 0"/><geometry><sphere radius="0.05"/></geometry></collision>'
    urdf, srdf = _write(tmp_path, ball=ball, lower=-math.pi / 2, upper=math.pi / 2)
    urdf.write_text(urdf.read_text().replace('<origin xyz="0 0.5 0"/>', '<origin xyz="0 5 0"/>'))  # post out of reach
    _, doc, _ = _json(urdf, "--srdf", srdf)
    (c,) = _joint(doc, "turn")["collisions"]
    assert math.degrees(c["from"]) == pytest.approx(-10) and math.degrees(c["to"]) == pytest.approx(10)
    assert c["at_limit"] == []
    (f,) = [f for f in doc["findings"] if f["code"].startswith("SWEEP")]
    assert f["code"] == "SWEEP002" and "from -10 deg to 10 deg" in f["message"]


def test_prismatic_contact_at_the_upper_limit(tmp_path: Path) -> None:
    # the bar slides along +y; its face (y = q + 0.01) meets the post (y = 0.4) at q = 0.39 for x in
    # [0.05, 0.45] overlapping the post's [-0.1, 0.1]: limits [0, 0.395] put 0.384 before the upper
    urdf, srdf = _write(tmp_path, type="prismatic", axis="0 1 0", lower=0, upper=0.395)
    _, doc, _ = _json(urdf, "--srdf", srdf)
    (c,) = _joint(doc, "turn")["collisions"]
    assert c["at_limit"] == ["upper"] and c["from"] == pytest.approx(0.395)
    assert "(395 mm)" in next(f["message"] for f in doc["findings"] if f["code"] == "SWEEP001")


def test_without_srdf_adjacent_pairs_are_not_checked(tmp_path: Path) -> None:
    urdf, _ = _write(tmp_path)
    _, doc, _ = _json(urdf)
    assert doc["sweep"]["disabled_pairs"] == {"count": 1, "from": "adjacent pairs (no SRDF given)"}
    assert _joint(doc, "turn")["collisions"] == []


def test_without_pinocchio_directions_still_come(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import descgen.physics.sweep as sweep

    monkeypatch.setattr(sweep, "available", lambda: False)
    urdf, srdf = _write(tmp_path)
    code, doc, _ = _json(urdf, "--srdf", srdf)
    assert code == 0 and doc["sweep"]["collisions_checked"] is False
    (f,) = [f for f in doc["findings"] if f["code"].startswith("SWEEP")]
    assert f["code"] == "SWEEP005" and "pinocchio is not installed" in f["message"]
    d = _moved(doc, "turn", "arm_link")
    assert d == pytest.approx([0, 0, 0], abs=1e-12)  # its origin is on the axis
    assert "turns arm_link in place" in _joint(doc, "turn")["direction"]


# --- mimic: the follower moves with its leader and is not swept itself ---------------------------


def test_mimic_follower_moves_with_its_leader() -> None:
    code, doc, _ = _json(GRIPPER)
    assert code == 0
    swept = [j["joint"] for j in doc["sweep"]["joints"]]
    assert "finger_right_joint" not in swept  # a follower
    left = _joint(doc, "finger_left_joint")
    assert left["followers"] == ["finger_right_joint"]
    # finger_left 0 -> 40 mm along +y; finger_right = -1 * left - 10 mm: -10 -> -50 mm along +y
    assert _moved(doc, "finger_left_joint", "finger_left_tip") == pytest.approx([0, 0.04, 0], abs=1e-12)
    assert _moved(doc, "finger_left_joint", "finger_right_tip") == pytest.approx([0, -0.04, 0], abs=1e-12)


# --- the evidence file: check reuses its collision runs ---------------------------------------------


def test_committed_runs_are_reused_only_with_the_same_hash() -> None:
    from descgen.commands.generate import plan
    from descgen.physics.sweep import _RUNS
    from descgen.prove import sweep as evidence

    robot = plan(EXAMPLE).robot
    text = evidence.context(robot)["data"]
    assert text.startswith("<!-- sweep input-sha256=")
    key = text.split("=")[1].split()[0]
    saved = dict(_RUNS)
    try:
        _RUNS.clear()
        fake = text.split(" runs=")[0] + ' runs=[["elbow_joint","a","b",3,4]] -->'
        assert evidence.reuse(robot, fake)
        assert [(r.link1, r.first) for r in _RUNS[key]] == [("a", 3)]
        ctx = evidence.context(robot)  # rendered from the reused runs: no pinocchio needed
        elbow = next(j for j in ctx["joints"] if j["name"] == "elbow_joint")
        assert elbow["collisions"] == [
            {"link1": "a", "link2": "b", "span": "from -125 deg to -116.7 deg", "limit": "no"}
        ]
        _RUNS.clear()
        assert not evidence.reuse(robot, fake.replace(key, "0" * 64))  # another input: sweep again
        assert not evidence.reuse(robot, fake.replace(",3,4]", ",3,99]"))  # not a grid step: refused
        assert not _RUNS
    finally:
        _RUNS.clear()
        _RUNS.update(saved)


# --- bad input: exit 2, one clear line, no traceback -----------------------------------------------


def test_unknown_state_is_exit_2(tmp_path: Path) -> None:
    ran = cli("sweep", EXAMPLE, "--state", "nowhere")
    assert ran.returncode == 2 and "Traceback" not in ran.stderr
    assert "error[SWEEP004]" in ran.stderr and "ready" in ran.stderr and ran.stdout == ""


@pytest.mark.parametrize(
    "content",
    ["<robot name='x'><link name='a'/><joint name='j' type='revolute'>", "not xml at all", ""],
)
def test_broken_description_is_exit_2(tmp_path: Path, content: str) -> None:
    bad = tmp_path / "bad.urdf"
    bad.write_text(content)
    ran = cli("sweep", bad)
    assert ran.returncode == 2 and "Traceback" not in ran.stderr and "error[" in ran.stderr


def test_bad_options_are_exit_2(tmp_path: Path) -> None:
    urdf, _ = _write(tmp_path)
    for args in (["--steps", "0"], ["--steps", "many"], ["--srdf", str(tmp_path / "missing.srdf")]):
        ran = cli("sweep", urdf, *args)
        assert ran.returncode == 2 and "Traceback" not in ran.stderr, args
    assert cli("sweep", tmp_path / "missing.urdf").returncode == 2


def test_hostile_names_stay_data(tmp_path: Path) -> None:
    urdf, srdf = _write(tmp_path)
    urdf.write_text(urdf.read_text().replace("arm_link", "arm--link&lt;x&gt;"))
    _, doc, _ = _json(urdf, "--srdf", srdf)
    assert _joint(doc, "turn")["collisions"][0]["link2"] == "arm--link<x>"


TURN = """<robot name="turn">
  <link name="base_link"/><link name="a"/><link name="tip"/>
  <joint name="j" type="revolute">
    <parent link="base_link"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>
  </joint>
  <joint name="t" type="fixed"><parent link="a"/><child link="tip"/><origin xyz="1 0 0"/></joint>
</robot>
"""


@pytest.mark.parametrize(
    ("lower", "upper", "expected", "between"),
    [
        # UR-style -360..360 deg: both limits are one pose, so the direction is a quarter turn from
        # zero: tip (1, 0, 0) -> (0, 1, 0), by hand
        (-2 * math.pi, 2 * math.pi, [-1.0, 1.0, 0.0], [0.0, math.pi / 2]),
        # a 270 deg range starting at zero: still a quarter turn, inside the limits
        (0.0, 1.5 * math.pi, [-1.0, 1.0, 0.0], [0.0, math.pi / 2]),
        # up to half a turn the chord is the direction: -75 -> 75 deg moves the tip +y 2 sin 75
        (-math.radians(75), math.radians(75), [0.0, 2 * math.sin(math.radians(75)), 0.0], [-1.309, 1.309]),
    ],
)
def test_direction_of_a_wide_revolute_is_a_quarter_turn(
    tmp_path: Path, lower: float, upper: float, expected: list[float], between: list[float]
) -> None:
    urdf = tmp_path / "turn.urdf"
    urdf.write_text(TURN.format(lower=lower, upper=upper))
    code, doc, err = _json(urdf)
    assert code == 0, err
    assert _moved(doc, "j", "tip") == pytest.approx(expected, abs=1e-9)
    assert _joint(doc, "j")["displacement_between"] == pytest.approx(between, abs=1e-3)
    assert ("over a quarter turn" in _joint(doc, "j")["direction"]) == (between[0] == 0.0)
