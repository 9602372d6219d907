"""The speed work of issue 17 changed how answers are computed, not the answers.

Each test compares a faster path with an oracle: a hand count, xacro itself, lxml, or a
fresh interpreter's ``sys.modules``. No test times anything.
"""

from __future__ import annotations

import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from lxml import etree

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

from synthetic import chain_spec

from descgen.audit.spec import load_spec_text
from descgen.meshes import load as meshes
from descgen.physics import kinematics
from descgen.render import render_package

ROOT = Path(__file__).resolve().parents[1]


# -- open edges: one int64 key per edge instead of np.unique over rows -------------------------


def _open_edges_by_hand(faces: np.ndarray) -> int:
    edges: Counter[tuple[int, int]] = Counter()
    for a, b, c in faces.tolist():
        for u, v in ((a, b), (b, c), (c, a)):
            edges[(min(u, v), max(u, v))] += 1
    return sum(1 for n in edges.values() if n == 1)


@pytest.mark.parametrize("seed", range(6))
def test_open_edges_equal_a_hand_count(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 400))
    # few vertices: many shared edges; an offset: keys must not assume the indices start at 0
    faces = rng.integers(0, max(3, n // 3), size=(n, 3)) + int(rng.integers(0, 50))
    assert meshes._open_edges(faces) == _open_edges_by_hand(faces)


def test_open_edges_of_closed_and_open_solids() -> None:
    tetra = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
    assert meshes._open_edges(tetra) == 0  # closed: every edge in two triangles
    assert meshes._open_edges(tetra[:3]) == 3  # a face removed: its three edges are open
    assert meshes._open_edges(np.zeros((0, 3), dtype=np.int64)) == 0


# -- forward kinematics at zero, once per robot ----------------------------------------------------


def test_zero_pose_memo_is_per_robot_and_read_only() -> None:
    short = load_spec_text(chain_spec(3, "short"), "short.yaml").robot
    long_ = load_spec_text(chain_spec(5, "long"), "long.yaml").robot
    a, b = kinematics.at_zero(short), kinematics.at_zero(long_)
    assert set(a) == {"link0", "link1", "link2"} and len(b) == 5  # not the other robot's poses
    assert kinematics.at_zero(short) is a  # computed once
    fresh = kinematics.forward(short)
    for name, pose in a.items():
        np.testing.assert_array_equal(pose, fresh[name])
    # hand computation: each joint lifts 100 mm and turns 15 deg about z; link2 is 200 mm up
    np.testing.assert_allclose(a["link2"][:3, 3], [0.0, 0.0, 0.2], atol=1e-12)
    with pytest.raises(ValueError):
        a["link1"][0, 3] = 1.0  # a caller cannot change what the next rule sees


# -- the Xacro: properties only for values with a source; xacro expands it to the URDF -----------


def _same_tree(a: etree._Element, b: etree._Element) -> None:
    """Tags, attribute names and values equal (numbers as floats, exactly), comments ignored."""
    assert a.tag == b.tag
    assert sorted(a.attrib) == sorted(b.attrib), a.tag
    for key, va in a.attrib.items():
        vb = b.attrib[key]
        try:
            assert [float(t) for t in va.split()] == [float(t) for t in vb.split()], (a.tag, key)
        except ValueError:
            assert va == vb, (a.tag, key)
    ka = [c for c in a if isinstance(c.tag, str)]
    kb = [c for c in b if isinstance(c.tag, str)]
    assert len(ka) == len(kb), a.tag
    for x, y in zip(ka, kb, strict=True):
        _same_tree(x, y)


def _xacro_expands_to_urdf(tmp_path: Path, files: dict[str, str], name: str) -> etree._Element:
    xacro = pytest.importorskip("xacro")
    for rel, text in files.items():  # the Xacro includes its ros2_control file beside it
        if rel.startswith("urdf/"):
            (tmp_path / rel[len("urdf/") :]).write_text(text)
    source = tmp_path / f"{name}.urdf.xacro"
    expanded = etree.fromstring(xacro.process_file(str(source)).toxml().encode())
    _same_tree(expanded, etree.fromstring(files[f"urdf/{name}.urdf"].encode()))
    return etree.fromstring(files[f"urdf/{name}.urdf.xacro"].encode())


XACRO_NS = "{http://www.ros.org/wiki/xacro}"


def test_chain_without_sources_has_no_properties(tmp_path: Path) -> None:
    robot = load_spec_text(chain_spec(30, "chain30"), "chain30.yaml").robot
    tree = _xacro_expands_to_urdf(tmp_path, render_package(robot, "specs/chain30.yaml"), "chain30")
    assert tree.findall(f"{XACRO_NS}property") == []  # nothing cites a source: every value inline
    assert "${" not in etree.tostring(tree).decode()


def test_example_keeps_a_property_for_every_sourced_value(tmp_path: Path) -> None:
    from descgen.audit.spec import load_spec

    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    tree = _xacro_expands_to_urdf(tmp_path, render_package(robot, "specs/warehouse_arm.yaml"), "warehouse_arm")
    props = tree.findall(f"{XACRO_NS}property")
    # the example cites a source for every value (require_sources: true): they stay properties,
    # each followed by its source comment
    assert len(props) > 20
    for p in props:
        comment = p.getnext()
        assert isinstance(comment, etree._Comment) and comment.text.strip(), p.get("name")


def test_mixed_sources_only_sourced_values_become_properties(tmp_path: Path) -> None:
    spec = chain_spec(4, "mixed").replace("  - name: joint2\n", "  - name: joint2\n    source: datasheet p.3\n")
    robot = load_spec_text(spec, "mixed.yaml").robot
    tree = _xacro_expands_to_urdf(tmp_path, render_package(robot, "specs/mixed.yaml"), "mixed")
    names = {p.get("name") for p in tree.findall(f"{XACRO_NS}property")}
    # joint2 alone cites a source: its origin and four limits (by hand from chain_spec)
    assert names == {"joint2_xyz", "joint2_rpy", "joint2_lower", "joint2_upper", "joint2_effort", "joint2_velocity"}


# -- descgen control: matplotlib only for plots ----------------------------------------------------

NO_PLOTS = """
import sys, tempfile
from pathlib import Path
from descgen.commands.control.evidence import write_evidence
from descgen.commands.control.manager import Point
from descgen.commands.control.run import run
from descgen.commands.control.system import Plant
from descgen.commands.control.trajectory import Trajectory
from descgen.audit.spec import load_spec
robot = load_spec("specs/warehouse_arm.yaml").robot
joints = ["lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"]
traj = Trajectory("arm_controller", joints, [Point(1.0, (0.1, 0.2, 0.2, -0.5))])
out = run(Path("generated/warehouse_arm_description"), robot, traj, 1.5, Plant("mock"))
assert "matplotlib" not in sys.modules, "the loop imported matplotlib"
with tempfile.TemporaryDirectory() as d:
    written = write_evidence(out, Path(d), robot, plots=False)
    assert "matplotlib" not in sys.modules, "evidence without plots imported matplotlib"
    assert not any(w.endswith(".png") for w in written)
    written = write_evidence(out, Path(d), robot, plots=True)
    assert "matplotlib" in sys.modules and any(w.endswith(".png") for w in written)
print("ok")
"""


def test_control_loop_and_plotless_evidence_do_not_import_matplotlib() -> None:
    pytest.importorskip("matplotlib")
    done = subprocess.run([sys.executable, "-c", NO_PLOTS], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr[-2000:]
