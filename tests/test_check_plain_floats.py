"""``check`` without numpy (issue 17): the known poses (POSE010, evidence/known_poses.md, the pose
images' record) in plain floats, proof 2's comparison without numpy on the common path, the
collision matrix and the sweep table importing numpy only when they compute. Oracles: pinocchio
(the known poses' rows, from a URDF written out here, and relative frames), the numpy kinematics the
pose images' scene replaced (descgen.physics.kinematics, itself held to pinocchio), numpy's
``linalg.inv`` and ``array2string``, a fresh interpreter's ``sys.modules``. Nothing is timed."""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from descgen.audit.spec import load_spec, load_spec_text
from descgen.core.model import FrameMeasurement, Joint, KnownPose, Limit, Link, Mimic, Pose, Robot
from descgen.physics import kinematics, poses, rigid, zero_pose
from descgen.write import pose_images
from tests.conftest import EXAMPLE, ROOT
from tests.helpers import cli
from tests.test_kinematics import pin_frames, random_robot

angle = st.floats(-7.0, 7.0, allow_nan=False)
coord = st.floats(-1.0, 1.0, allow_nan=False)
unit_axis = st.tuples(coord, coord, coord).filter(lambda a: math.hypot(*a) > 1e-3)


# -- the reference: pinocchio's frames ------------------------------------------------------------


def _urdf(robot: Robot) -> str:
    """The robot as URDF text, written out here for pinocchio (not by descgen's renderer)."""

    def vec(v: tuple[float, ...]) -> str:
        return " ".join(repr(float(x)) for x in v)

    out = [f'<robot name="{robot.name}">', *(f'<link name="{lk.name}"/>' for lk in robot.links)]
    for j in robot.joints:
        out.append(f'<joint name="{j.name}" type="{j.type}"><parent link="{j.parent}"/><child link="{j.child}"/>')
        out.append(f'<origin xyz="{vec(j.origin.xyz)}" rpy="{vec(j.origin.rpy)}"/>')
        if j.axis is not None:
            out.append(f'<axis xyz="{vec(j.axis)}"/>')
        if j.limit is not None:
            given = {k: getattr(j.limit, k) for k in ("lower", "upper", "effort", "velocity")}
            out.append("<limit " + " ".join(f'{k}="{v!r}"' for k, v in given.items() if v is not None) + "/>")
        out.append("</joint>")
    return "".join([*out, "</robot>"])


def _pinocchio_rows(pin: Any, robot: Robot) -> list[poses.Row]:
    """What the known poses should say, from pinocchio's frames: each measured frame's position
    in the frame it is measured from (the root when none), minus the measured position. Mimic
    followers are set from their leaders first (pinocchio's URDF model leaves them free)."""
    from descgen.physics import mimic

    urdf = _urdf(robot)
    rows: list[poses.Row] = []
    root = robot.root() or ""
    for kp in robot.known_poses:
        frames = pin_frames(pin, urdf, mimic.resolve(robot, dict(kp.joints)))
        for fm in kp.frames:
            base = np.eye(4) if fm.relative_to is None else frames[fm.relative_to]
            t = np.linalg.solve(base, frames[fm.frame])  # base^-1 frame
            model = (float(t[0, 3]) + 0.0, float(t[1, 3]) + 0.0, float(t[2, 3]) + 0.0)  # + 0.0: no -0.0 to print
            error = tuple(m - x for m, x in zip(model, fm.xyz, strict=True))
            rows.append(poses.Row(kp, fm, model, (error[0], error[1], error[2]), fm.relative_to or root))
    return rows


@st.composite
def posed_trees(draw: st.DrawFn) -> Robot:
    """A random tree of revolute, prismatic, continuous and fixed joints (some mimic followers of
    j0, with multipliers and offsets), and known poses measuring random frames, some relative to
    another link, with tolerances that let some pass and some fail."""
    n = draw(st.integers(1, 6))
    joints = []
    for k in range(n):
        kind = draw(st.sampled_from(["revolute", "prismatic", "continuous", "fixed"]))
        parent = draw(st.integers(0, k))
        mimic = Mimic("j0", draw(coord), draw(coord)) if k > 0 and kind != "fixed" and draw(st.booleans()) else None
        limit = Limit(-3.0, 3.0, 1.0, 1.0) if kind in ("revolute", "prismatic") else None
        origin = Pose(draw(st.tuples(coord, coord, coord)), draw(st.tuples(angle, angle, angle)))
        joints.append(Joint(f"j{k}", kind, f"l{parent}", f"l{k + 1}", origin, draw(unit_axis), limit, mimic=mimic))
    links = tuple(Link(f"l{k}") for k in range(n + 1))
    known = []
    for p in range(draw(st.integers(1, 3))):
        values = tuple((f"j{k}", draw(st.floats(-3.0, 3.0, allow_nan=False))) for k in range(n) if draw(st.booleans()))
        frames = tuple(
            FrameMeasurement(
                f"l{draw(st.integers(0, n))}",
                draw(st.tuples(coord, coord, coord)),
                draw(st.floats(0.0005, 2.0)),
                draw(st.one_of(st.none(), st.builds(lambda i: f"l{i}", st.integers(0, n)))),
            )
            for _ in range(draw(st.integers(1, 3)))
        )
        known.append(KnownPose(f"p{p}", values, frames))
    return Robot("r", links=links, joints=tuple(joints), known_poses=tuple(known))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(posed_trees())
def test_known_poses_in_plain_floats_are_pinocchios_rows_and_messages(pin, robot: Robot) -> None:  # type: ignore[no-untyped-def]
    got, want = poses.evaluate(robot), _pinocchio_rows(pin, robot)
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert (g.pose, g.measurement, g.relative_to) == (w.pose, w.measurement, w.relative_to)
        assert g.model is not None and w.model is not None
        np.testing.assert_allclose(g.model, w.model, rtol=0, atol=1e-12)
        assert g.ok == w.ok
        assert g.distance == pytest.approx(float(np.linalg.norm(w.error)), abs=1e-12)
    # what POSE010 says and evidence/known_poses.md shows: the same words and numbers
    assert [f.message for f in poses.findings(robot, got)] == [f.message for f in poses.findings(robot, want)]


def test_the_example_s_known_poses_are_pinocchios_rows_to_the_printed_digit(pin) -> None:  # type: ignore[no-untyped-def]
    from descgen.core import display

    for spec in (EXAMPLE, ROOT / "tests" / "data" / "mimic" / "gripper.yaml"):
        robot = load_spec(spec).robot
        got, want = poses.evaluate(robot), _pinocchio_rows(pin, robot)
        assert [(display.mm(g.model or ()), g.ok) for g in got] == [(display.mm(w.model or ()), w.ok) for w in want]
        assert [f"{g.worst * 1000:.2f}" for g in got] == [f"{w.worst * 1000:.2f}" for w in want]


def test_a_frame_outside_the_tree_has_no_model_position() -> None:
    text = (ROOT / "specs" / "warehouse_arm.yaml").read_text()
    robot = load_spec_text(text, "spec.yaml").robot
    kp = KnownPose(
        "k",
        (),
        (
            FrameMeasurement("nowhere", (0.0, 0.0, 0.0), 0.001),
            FrameMeasurement("tool_link", (0.0, 0.0, 0.0), 0.001, "nowhere"),
        ),
    )
    rows = poses.evaluate(Robot(robot.name, robot.links, robot.joints, known_poses=(kp,)))
    assert [(r.model, r.error, r.ok) for r in rows] == [(None, None, False), (None, None, False)]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_relative_frames_agree_with_pinocchio(pin, data: st.DataObject) -> None:  # type: ignore[no-untyped-def]
    from descgen.render import render_package

    text, values = data.draw(random_robot())
    robot = load_spec_text(text, "random.yaml", rules=False).robot
    urdf = render_package(robot, "specs/x.yaml")[f"urdf/{robot.name}.urdf"]
    theirs = pin_frames(pin, urdf, values)
    ours = zero_pose.forward(robot, values)
    frame = data.draw(st.sampled_from(sorted(theirs)))
    base = data.draw(st.sampled_from(sorted(theirs)))
    rel = zero_pose.relative(ours, frame, base)
    assert rel is not None
    want = np.linalg.inv(theirs[base]) @ theirs[frame]
    np.testing.assert_allclose(np.array(rel[0]), want[:3, :3], atol=1e-9)
    np.testing.assert_allclose(np.array(rel[1]), want[:3, 3], atol=1e-9)


@given(st.tuples(coord, coord, coord), st.tuples(angle, angle, angle))
def test_inverse_is_numpy_s_inverse_of_the_4x4(
    xyz: tuple[float, float, float], rpy: tuple[float, float, float]
) -> None:
    from descgen.physics.transforms import pose_matrix

    r, t = rigid.inverse(rigid.frame(xyz, rpy))
    want = np.linalg.inv(pose_matrix(xyz, rpy))
    np.testing.assert_allclose(np.array(r), want[:3, :3], atol=1e-12)
    np.testing.assert_allclose(np.array(t), want[:3, 3], atol=1e-12)


# -- the pose images' record: the same bytes as from the numpy scene -----------------------------


def _numpy_scene(robot: Robot, kp: KnownPose) -> pose_images.Scene:
    """pose_images.scene as it was (numpy kinematics)."""

    def point(m: Any) -> tuple[float, float, float]:
        return (float(m[0]) + 0.0, float(m[1]) + 0.0, float(m[2]) + 0.0)

    frames = kinematics.forward(robot, dict(kp.joints))
    links = {name: point(t[:3, 3]) for name, t in frames.items()}
    bones = [(j.parent, j.child) for j in robot.joints if j.child in frames and j.parent in frames]
    markers = []
    for fm in kp.frames:
        t = kinematics.relative(frames, fm.frame, fm.relative_to)
        base = frames.get(fm.relative_to) if fm.relative_to is not None else np.eye(4)
        measured = None if base is None else point((base @ np.array([*fm.xyz, 1.0]))[:3])
        markers.append(
            pose_images.Marker(
                fm.frame,
                fm.relative_to,
                None if t is None else point(t[:3, 3]),
                fm.xyz,
                links.get(fm.frame),
                measured,
                fm.tolerance,
            )
        )
    return pose_images.Scene(kp, links, bones, markers)


def test_the_pose_record_is_the_numpy_scene_s(monkeypatch: pytest.MonkeyPatch) -> None:
    for spec in (EXAMPLE, ROOT / "tests" / "data" / "mimic" / "gripper.yaml"):
        robot = load_spec(spec).robot
        plain = pose_images.record(robot)
        for kp in robot.known_poses:
            got, want = pose_images.scene(robot, kp), _numpy_scene(robot, kp)
            assert got.bones == want.bones and got.links.keys() == want.links.keys()
            for name, p in got.links.items():
                np.testing.assert_allclose(p, want.links[name], rtol=0, atol=1e-12)
            for a, b in zip(got.markers, want.markers, strict=True):
                np.testing.assert_allclose(a.measured_in_root or (), b.measured_in_root or (), rtol=0, atol=1e-12)
                np.testing.assert_allclose(a.model or (), b.model or (), rtol=0, atol=1e-12)
                assert a.verdict == b.verdict
        monkeypatch.setattr(pose_images, "scene", _numpy_scene)
        assert pose_images.record(robot) == plain  # the committed record's bytes, so check passes
        monkeypatch.undo()
    committed = ROOT / "generated" / "warehouse_arm_description" / pose_images.SIDECAR
    assert pose_images.record(load_spec(EXAMPLE).robot) == committed.read_text()


# -- proof 2's messages: numpy's array text, numpy imported only to print one ---------------------

_ROUNDTRIP = """
import json, sys
from descgen.prove.urdf_roundtrip import compare_readback
from descgen.render import render_package
from descgen.audit.spec import load_spec
robot = load_spec(sys.argv[1]).robot
urdf = render_package(robot, "specs/x.yaml")[f"urdf/{robot.name}.urdf"]
same = compare_readback(robot, urdf, "x.urdf")
before = "numpy" in sys.modules
edited = urdf.replace('<origin xyz="0.3 0 0"', '<origin xyz="0.31 0 0"', 1)
assert edited != urdf
found = compare_readback(robot, edited, "x.urdf")
print("PROBE" + json.dumps({"same": len(same), "numpy_before": before, "messages": [f.message for f in found]}))
"""


@pytest.mark.e2e
def test_proof_2_imports_numpy_only_to_print_a_difference() -> None:
    from descgen.physics.transforms import pose_matrix
    from descgen.read import urdf_readback as rb

    done = subprocess.run(
        [sys.executable, "-c", _ROUNDTRIP, str(EXAMPLE)], capture_output=True, text=True, cwd=ROOT, timeout=120
    )
    line = next((x for x in done.stdout.splitlines() if x.startswith("PROBE")), None)
    assert line is not None, done.stderr
    got = json.loads(line[len("PROBE") :])
    assert got["same"] == 0 and got["numpy_before"] is False
    robot = load_spec(EXAMPLE).robot
    [elbow] = [j for j in robot.joints if j.origin.xyz == (0.3, 0.0, 0.0)]
    model = pose_matrix(elbow.origin.xyz, elbow.origin.rpy)  # the oracle: numpy's matrix and its text
    urdf_rows = (
        rb.read(
            f'<robot name="r"><joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
            f'<origin xyz="0.31 0 0" rpy="{" ".join(map(repr, elbow.origin.rpy))}"/></joint></robot>'
        )
        .joints[0]
        .origin
    )
    shown = np.array2string(model, precision=12, separator=", ").replace("\n", "")
    assert got["messages"] == [
        f"URDF read back by the lxml read-back reader differs at joint:{elbow.name}/origin: "
        f"model {shown}, URDF {urdf_rows!r}"
    ]


# -- a warm check in a fresh process: no numpy ------------------------------------------------------

_PROBE = """
import json, sys
from descgen.cli import main
code = main(["check", sys.argv[1]])
print("PROBE" + json.dumps({"code": code, "modules": sorted({m.split(".")[0] for m in sys.modules})}))
"""


@pytest.mark.e2e
def test_a_warm_check_of_the_example_imports_no_numpy(tmp_path: Path) -> None:
    """A copy of the example made current by ``report`` (descgen's own source is among the
    evidence's inputs), checked twice with a result cache: the second, fresh process (a
    pre-commit hook's) imports no numpy, nor xacro, catkin_pkg or the heavy libraries. With the
    cache off the sweep table is computed (in plain floats: no numpy either) and xacro and
    catkin_pkg run: the probe does see them when they are there."""
    project = tmp_path / "project"
    for rel in ("specs/warehouse_arm.yaml", "specs/trajectories/ready.yaml"):
        (project / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / rel, project / rel)
    for pkg in ("warehouse_arm_description", "warehouse_arm_moveit_config"):
        shutil.copytree(ROOT / "generated" / pkg, project / "generated" / pkg)
    cache = tmp_path / "cache"

    def probe(cache_dir: str) -> dict[str, Any]:
        env = {**os.environ, "DESCGEN_CACHE_DIR": cache_dir}
        done = subprocess.run(
            [sys.executable, "-c", _PROBE, "specs/warehouse_arm.yaml"],
            capture_output=True,
            text=True,
            cwd=project,
            env=env,
            timeout=120,
        )
        line = next((x for x in done.stdout.splitlines() if x.startswith("PROBE")), None)
        assert line is not None, done.stderr
        result: dict[str, Any] = json.loads(line[len("PROBE") :])
        return result

    env_before = os.environ.get("DESCGEN_CACHE_DIR")
    os.environ["DESCGEN_CACHE_DIR"] = str(cache)
    try:
        assert cli("report", "specs/warehouse_arm.yaml", cwd=project).returncode == 0
    finally:
        if env_before is None:
            del os.environ["DESCGEN_CACHE_DIR"]
        else:
            os.environ["DESCGEN_CACHE_DIR"] = env_before
    first = probe(str(cache))
    assert first["code"] == 0
    warm = probe(str(cache))
    assert warm["code"] == 0  # current: every proof ran and passed
    loaded = set(warm["modules"])
    assert {"lxml", "yaml", "jinja2"} <= loaded  # it did read and render
    heavy = {"trimesh", "scipy", "matplotlib", "pinocchio", "coal", "mujoco", "yourdfpy", "rosbags"}
    assert loaded & (heavy | {"numpy", "xacro", "catkin_pkg", "pyparsing"}) == set()
    off = probe("")
    # caching off: the expansions (xacro) and the manifest (catkin_pkg) computed; the sweep table
    # too, without numpy
    assert off["code"] == 0 and {"xacro", "catkin_pkg"} <= set(off["modules"])
    assert "numpy" not in off["modules"]


# -- the equal-tree pass of the XML comparison: layout is not a difference --------------------------


@settings(max_examples=100, deadline=None)
@given(
    st.lists(st.sampled_from(["", " ", "\n  ", "\n    \n"]), min_size=6, max_size=6),
    st.sampled_from(["1", " 1 ", "1.0", "2", "", "x"]),
)
def test_whitespace_texts_compare_as_the_walk_does(spaces: list[str], text: str) -> None:
    from descgen.core.xmlcompare import first_difference, parse
    from tests.test_render_readback_fast import _reference

    a = parse('<r><j name="a">1<o xyz="0 0 1"/></j><k/></r>')
    s = spaces  # indentation the URDF has and xacro's output has not, around and inside elements
    b = parse(f'<r>{s[0]}<j name="a">{s[1]}{text}{s[2]}<o xyz="0 0 1"/>{s[3]}</j><k>{s[4]}</k>{s[5]}</r>')
    assert first_difference(a, b) == _reference(a, b)
    assert first_difference(b, a, "/x") == _reference(b, a, "/x")
