"""Our self-collision matrix against published SRDFs (example-robot-data's UR5 and Panda, with
meshes): the counts in docs/collision_matrix.md stay true. The published SRDF is the oracle for
agreement; the URDF read with lxml is the oracle for Adjacent; pinocchio/coal, driven directly
here with its own random configurations, is the oracle for "that pair really collides"."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from lxml import etree

from tests.helpers import ROOT

pin = pytest.importorskip("pinocchio")
sys.path.insert(0, str(ROOT / "benchmarks"))
import corpus_matrix as cm  # noqa: E402

pytestmark = pytest.mark.slow
if cm.share() is None:
    pytest.skip("example-robot-data is not installed", allow_module_level=True)

# docs/collision_matrix.md: (our pairs, also disabled by the published SRDF) per reason
AGREEMENT = {
    "ur5": {"Adjacent": (7, 6), "Default": (0, 0), "Always": (0, 0), "Never": (3, 1)},
    "panda": {"Adjacent": (10, 10), "Default": (3, 3), "Always": (0, 0), "Never": (22, 22)},
}


def _adjacent_by_lxml(urdf: Path) -> set[frozenset[str]]:
    """Links with collision geometry joined directly or only through links without any."""
    root = etree.parse(str(urdf)).getroot()
    geometry = {lk.get("name") for lk in root.findall("link") if lk.find("collision") is not None}
    edges: dict[str, set[str]] = {}
    for j in root.findall("joint"):  # direct children: <transmission> has <joint> too
        a, b = j.find("parent").get("link"), j.find("child").get("link")
        edges.setdefault(a, set()).add(b)
        edges.setdefault(b, set()).add(a)
    pairs = set()
    for start in geometry:
        seen, todo = {start}, [start]
        while todo:
            for n in edges.get(todo.pop(), ()):
                if n not in seen:
                    seen.add(n)
                    (pairs.add(frozenset((start, n))) if n in geometry else todo.append(n))
    return pairs


def _direct_hits(urdf: Path, pairs: list[frozenset[str]], samples: int = 10_000) -> dict[frozenset[str], int]:
    """pinocchio alone: its URDF loader, its random configurations (seed 3), every geometry pair
    of ``pairs`` active, no padding."""
    share = cm.share()
    model, geom, _ = pin.buildModelsFromUrdf(str(urdf), package_dirs=[str(share)])  # (model, collision, visual)
    link = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    owner = {}
    for a in range(len(link)):
        for b in range(a + 1, len(link)):
            p = frozenset((link[a], link[b]))
            if p in pairs:
                geom.addCollisionPair(pin.CollisionPair(a, b))
                owner[len(geom.collisionPairs) - 1] = p
    data, gdata = model.createData(), pin.GeometryData(geom)
    pin.seed(3)
    hits = dict.fromkeys(pairs, 0)
    for _ in range(samples):
        q = pin.randomConfiguration(model)
        pin.computeCollisions(model, data, geom, gdata, q, False)
        for p in {owner[k] for k, r in enumerate(gdata.collisionResults) if r.isCollision()}:
            hits[p] += 1
    return hits


@pytest.mark.parametrize("name", ["ur5", "panda"])
def test_agreement_with_the_published_srdf(name: str) -> None:
    c = cm.load(name)
    m = cm.matrix(c)
    ours = {frozenset((d.link1, d.link2)): d.reason for d in m.pairs}
    counts = {
        r: (sum(1 for x in ours.values() if x == r), sum(1 for p, x in ours.items() if x == r and p in c.published))
        for r in AGREEMENT[name]
    }
    assert counts == AGREEMENT[name]
    urdf = cm.share() / "example-robot-data" / "robots" / cm.ROBOTS[name][0]  # type: ignore[operator]
    assert {p for p, r in ours.items() if r == "Adjacent"} == _adjacent_by_lxml(urdf)
    # every pair the published SRDF disables and we keep checking does collide somewhere
    kept = [p for p in c.published if p not in ours]
    hits = _direct_hits(urdf, kept)
    assert all(hits[p] > 0 for p in kept), hits
    # and every pair we call Never is free in pinocchio's own 10,000 samples
    never = [p for p, r in ours.items() if r == "Never"]
    assert not any(_direct_hits(urdf, never).values())
