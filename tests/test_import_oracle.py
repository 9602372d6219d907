"""The issue's oracle for ``descgen import``: every example-robot-data URDF whose round trip
is proven (docs/import-corpus.md, kept true by tests/test_import_corpus.py) is imported, its
spec's URDF is generated, and the original and the generated URDF are compared by two
independent readers, within 1e-9:

- pinocchio: every frame's pose at 5 random configurations within the limits (set by joint
  name, so a different joint order cannot hide or fake a difference), and every body's mass,
  centre of mass and rotational inertia (by joint name);
- yourdfpy: every link's pose at the same configurations (yourdfpy applies mimic joints), and
  every link's mass, inertial origin and inertia tensor.

A fixed subset (robots whose names are not identifiers: ``flange-tool0``, ``link_0.0``,
``2dof_planar``...) runs every time; the whole corpus is marked slow.
"""

from __future__ import annotations

import math
import random
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from descgen.audit.spec import load_spec_text
from descgen.render import render_package
from tests.corpus import descriptions, imported
from tests.helpers import ROOT

TOL = 1e-9
CONFIGS = 5
DOC = ROOT / "docs" / "import-corpus.md"
# names real robots use that the spec once refused
FAST = (
    "double_pendulum_description/urdf/double_pendulum.urdf",  # 2dof_planar-like robot names
    "ur_description/urdf/ur5_robot.urdf",  # flange-tool0 style names
    "allegro_hand_description/urdf/allegro_right_hand.urdf",  # link_0.0
    "z1_description/urdf/z1.urdf",
)


def _proven() -> list[tuple[str, Path, Path | None]]:
    text = DOC.read_text() if DOC.is_file() else ""
    proven = set(re.findall(r"^\| `([^`]+)` \|.*\| proven \|$", text, re.M))
    return [d for d in descriptions() if d[0] in proven]


PROVEN = _proven()
pytestmark = pytest.mark.skipif(not PROVEN, reason="example-robot-data is not installed")


def _generated_urdf(tmp_path: Path, urdf: Path, srdf: Path | None) -> Path:
    outcome = imported(urdf, srdf)
    assert outcome.proven, outcome.imported.differences[:5]
    robot = load_spec_text(outcome.imported.spec_text, "r.yaml", rules=False).robot
    out = tmp_path / "generated.urdf"
    out.write_text(render_package(robot, "r.yaml")[f"urdf/{robot.name}.urdf"])
    return out


def _random_configs(model: Any, seed: str) -> list[dict[str, np.ndarray]]:
    """``CONFIGS`` configurations within the limits (±pi where a joint has none), per joint name."""
    import pinocchio as pin

    lo = np.where(np.isfinite(model.lowerPositionLimit), model.lowerPositionLimit, -math.pi)
    hi = np.where(np.isfinite(model.upperPositionLimit), model.upperPositionLimit, math.pi)
    rng = random.Random(seed)
    out = []
    for _ in range(CONFIGS):
        np.random.seed(rng.randrange(2**31))  # pinocchio draws from numpy's generator
        q = pin.randomConfiguration(model, lo, hi)
        # joint 0 is the universe
        out.append({model.names[i]: q[j.idx_q : j.idx_q + j.nq].copy() for i, j in enumerate(model.joints) if i > 0})
    return out


def _q_of(model: Any, named: dict[str, np.ndarray]) -> np.ndarray:
    import pinocchio as pin

    q = pin.neutral(model)
    for i, j in enumerate(model.joints):
        if i > 0:
            q[j.idx_q : j.idx_q + j.nq] = named[model.names[i]]
    return q


def _pinocchio(path: Path, configs: list[dict[str, np.ndarray]]) -> tuple[list[dict[str, np.ndarray]], dict]:
    import pinocchio as pin

    model = pin.buildModelFromUrdf(str(path))
    data = model.createData()
    poses = []
    for named in configs:
        pin.framesForwardKinematics(model, data, _q_of(model, named))
        poses.append({f"{f.name}/{f.type}": data.oMf[i].homogeneous.copy() for i, f in enumerate(model.frames)})
    bodies = {
        model.names[i]: np.concatenate(([y.mass], y.lever, y.inertia.ravel())) for i, y in enumerate(model.inertias)
    }
    return poses, bodies


def _one_dof(named: dict[str, np.ndarray]) -> dict[str, float]:
    """yourdfpy's configuration: revolute/prismatic value; a continuous joint from (cos, sin)."""
    return {n: float(v[0]) if len(v) == 1 else math.atan2(v[1], v[0]) for n, v in named.items() if len(v) in (1, 2)}


def _yourdfpy(path: Path, configs: list[dict[str, np.ndarray]]) -> tuple[list[dict[str, np.ndarray]], dict]:
    import yourdfpy

    u = yourdfpy.URDF.load(str(path), build_scene_graph=True, load_meshes=False, build_collision_scene_graph=False)
    poses = []
    for named in configs:
        cfg = {n: v for n, v in _one_dof(named).items() if n in u.actuated_joint_names}
        u.update_cfg(cfg)
        poses.append({lk.name: np.array(u.get_transform(lk.name)) for lk in u.robot.links})
    inertials = {}
    for lk in u.robot.links:
        i = lk.inertial
        if i is not None:
            origin = np.eye(4) if i.origin is None else np.array(i.origin)
            inertia = np.zeros((3, 3)) if i.inertia is None else np.array(i.inertia)
            inertials[lk.name] = np.concatenate(([i.mass or 0.0], origin.ravel(), inertia.ravel()))
    return poses, inertials


def _same(a: dict[str, np.ndarray], b: dict[str, np.ndarray], what: str) -> None:
    assert sorted(a) == sorted(b), what
    for k in a:
        assert np.allclose(a[k], b[k], rtol=0, atol=TOL), f"{what}: {k}"


def _compare(tmp_path: Path, ident: str, urdf: Path, srdf: Path | None) -> None:
    import pinocchio as pin

    written = _generated_urdf(tmp_path, urdf, srdf)
    configs = _random_configs(pin.buildModelFromUrdf(str(urdf)), ident)
    for reader in (_pinocchio, _yourdfpy):
        poses_a, bodies_a = reader(urdf, configs)
        poses_b, bodies_b = reader(written, configs)
        _same(bodies_a, bodies_b, f"{reader.__name__} inertials")
        for k, (pa, pb) in enumerate(zip(poses_a, poses_b, strict=True)):
            _same(pa, pb, f"{reader.__name__} poses at configuration {k}")


@pytest.mark.parametrize(("ident", "urdf", "srdf"), [d for d in PROVEN if d[0] in FAST], ids=lambda v: str(v))
def test_renamed_robots_generate_the_same_robot(tmp_path: Path, ident: str, urdf: Path, srdf: Path | None) -> None:
    _compare(tmp_path, ident, urdf, srdf)


@pytest.mark.slow
@pytest.mark.parametrize(("ident", "urdf", "srdf"), [d for d in PROVEN if d[0] not in FAST], ids=lambda v: str(v))
def test_every_proven_robot_generates_the_same_robot(tmp_path: Path, ident: str, urdf: Path, srdf: Path | None) -> None:
    _compare(tmp_path, ident, urdf, srdf)


def test_the_oracle_sees_a_moved_joint(tmp_path: Path) -> None:
    """The comparison can fail: one joint origin moved by 1e-6 m in the generated URDF."""
    ident, urdf, srdf = next(d for d in PROVEN if d[0] == "panda_description/urdf/panda.urdf")
    written = _generated_urdf(tmp_path, urdf, srdf)
    text = written.read_text()
    moved = re.sub(r'(<joint name="panda_joint4".*?<origin xyz=")([-\d.e]+)', _nudge, text, count=1, flags=re.S)
    assert moved != text
    written.write_text(moved)
    import pinocchio as pin

    configs = _random_configs(pin.buildModelFromUrdf(str(urdf)), ident)
    for reader in (_pinocchio, _yourdfpy):
        a, _ = reader(urdf, configs)
        b, _ = reader(written, configs)
        with pytest.raises(AssertionError):
            _same(a[0], b[0], reader.__name__)


def _nudge(m: re.Match[str]) -> str:
    return m.group(1) + repr(float(m.group(2)) + 1e-6)
