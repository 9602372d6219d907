"""Shared by compare_srdf_matrix.py, bench_collision.py and tests/test_collision_published.py:
example-robot-data's UR5 and Panda (URDF with meshes, published SRDF), our matrix for them,
and a raw pinocchio/coal count of collisions per link pair over the same kind of samples."""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from descgen.core.model import CollisionMatrix, MatrixSettings, Robot  # noqa: E402
from descgen.physics import collision  # noqa: E402
from descgen.physics.sweep.contacts import pinocchio_urdf  # noqa: E402

SEED = 1  # our matrix (the example's seed)
CHECK_SEED = 2  # the independent count of collisions per pair
SAMPLES = 10_000
ROBOTS = {
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "ur_description/srdf/ur5.srdf"),
    "panda": ("panda_description/urdf/panda.urdf", "panda_description/srdf/panda.srdf"),
}


def share() -> Path | None:
    sys.path.insert(0, str(ROOT / "tests"))
    from corpus import share as found

    return found()


@dataclass(frozen=True)
class Corpus:
    name: str
    robot: Robot
    urdf: str  # for pinocchio: collision shapes, meshes by absolute path
    published: dict[frozenset[str], str]  # the SRDF's disabled pairs -> reason


def load(name: str) -> Corpus:
    from descgen.read.description import Options, load_description
    from descgen.read.srdf import read_srdf_text

    root = share()
    assert root is not None, "example-robot-data is not installed"
    robots = root / "example-robot-data" / "robots"
    urdf_rel, srdf_rel = ROBOTS[name]
    robot, _ = load_description(robots / urdf_rel, Options(package_paths=(root,)))
    semantic, _, _ = read_srdf_text((robots / srdf_rel).read_bytes(), str(robots / srdf_rel))
    published = {frozenset((d.link1, d.link2)): d.reason for d in semantic.disabled_collisions}
    return Corpus(name, robot, pinocchio_urdf(robot), published)


def settings(seed: int = SEED, samples: int = SAMPLES) -> MatrixSettings:
    return MatrixSettings(default_state=None, seed=seed, samples=samples, fraction=0.95, padding=0.0)


def matrix(c: Corpus, seed: int = SEED, samples: int = SAMPLES) -> CollisionMatrix:
    """Our matrix (descgen.physics.collision), at zero as the default state; never memoised here."""
    collision._SAMPLED.clear()
    return collision.compute(c.robot, c.urdf, {}, "", settings(seed, samples))


def raw_counts(c: Corpus, seed: int = CHECK_SEED, samples: int = SAMPLES) -> dict[frozenset[str], int]:
    """Samples in collision per link pair: pinocchio's computeCollisions with every pair
    active over ``samples`` random configurations (the anchor any implementation pays)."""
    scene = collision.load_scene(c.robot, c.urdf, {}, "", 0.0)
    pin = scene.pin
    qs = collision.random_configurations(scene, samples, seed)
    owner = {k: p for p, ks in scene.link_pairs.items() for k in ks}
    counts = dict.fromkeys(scene.link_pairs, 0)
    for q in qs:
        pin.computeCollisions(scene.model, scene.data, scene.geom, scene.gdata, q, False)
        hit = {owner[k] for k, r in enumerate(scene.gdata.collisionResults) if r.isCollision()}
        for p in hit:
            counts[p] += 1
    return counts


def adjacent_in_tree(robot: Robot) -> set[frozenset[str]]:
    """Parent and child links joined by a joint, both with collision geometry (the oracle)."""
    geometry = {lk.name for lk in robot.links if lk.collisions}
    return {frozenset((j.parent, j.child)) for j in robot.joints if j.parent in geometry and j.child in geometry}
