"""The self-collision matrix (descgen/physics/collision.py), checked against pinocchio used directly,
the URDF's own tree (lxml) and the committed SRDF."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from lxml import etree

from descgen.audit.spec import load_spec
from descgen.core.findings import InputError
from descgen.core.model import MatrixSettings
from descgen.physics import collision
from descgen.render import header
from tests.helpers import EXAMPLE_TEXT, ROOT, errors_of, line_of, plant

pin = pytest.importorskip("pinocchio")

PKG = ROOT / "generated" / "warehouse_arm_description"
URDF = PKG / "urdf" / "warehouse_arm.urdf"
SRDF = PKG / "srdf" / "warehouse_arm.srdf"


def _committed_pairs() -> dict[frozenset[str], str]:
    root = etree.parse(str(SRDF)).getroot()
    return {frozenset((d.get("link1"), d.get("link2"))): d.get("reason") for d in root.iter("disable_collisions")}


def _tree_adjacent(urdf: Path) -> set[frozenset[str]]:
    """Oracle from the URDF XML: geometry links joined by a path whose inner links have no
    <collision> (an independent walk over parent/child elements, not descgen's model)."""
    root = etree.parse(str(urdf)).getroot()
    has_geom = {lk.get("name") for lk in root.findall("link") if lk.find("collision") is not None}
    edges: dict[str, set[str]] = {}
    for j in root.findall("joint"):
        a, b = j.find("parent").get("link"), j.find("child").get("link")
        edges.setdefault(a, set()).add(b)
        edges.setdefault(b, set()).add(a)
    out: set[frozenset[str]] = set()
    for start in has_geom:
        stack, seen = [start], {start}
        while stack:
            for n in edges.get(stack.pop(), ()):
                if n not in seen:
                    seen.add(n)
                    (out.add(frozenset((start, n))) if n in has_geom else stack.append(n))
    return out


def test_never_pairs_never_collide_in_10000_other_samples() -> None:
    """10,000 configurations from pinocchio's own generator with another seed: no pair the
    committed SRDF marks Never is in collision (a wrongly sampled or mislabelled pair is)."""
    model = pin.buildModelFromUrdf(str(URDF))
    geom = pin.buildGeomFromUrdf(model, str(URDF), pin.GeometryType.COLLISION)
    link_of = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    never = {p for p, r in _committed_pairs().items() if r == "Never"}
    assert len(never) > 10
    index = []
    for a in range(len(link_of)):
        for b in range(a + 1, len(link_of)):
            if frozenset((link_of[a], link_of[b])) in never:
                geom.addCollisionPair(pin.CollisionPair(a, b))
                index.append(frozenset((link_of[a], link_of[b])))
    assert set(index) == never  # every Never pair has geometry on both sides
    data, gdata = model.createData(), pin.GeometryData(geom)
    pin.seed(987654)
    hits: set[frozenset[str]] = set()
    for _ in range(10_000):
        if pin.computeCollisions(model, data, geom, gdata, pin.randomConfiguration(model), False):
            hits |= {index[k] for k, r in enumerate(gdata.collisionResults) if r.isCollision()}
    assert hits == set()


def test_adjacent_pairs_are_exactly_the_trees() -> None:
    committed = {p for p, r in _committed_pairs().items() if r == "Adjacent"}
    oracle = _tree_adjacent(URDF)
    assert committed == oracle
    # by hand: forearm and camera meet through tool_link, which has no geometry
    assert frozenset(("forearm_link", "camera_link")) in oracle


def test_a_pair_that_collides_somewhere_is_not_disabled() -> None:
    """shoulder/upper are Adjacent; upper/lidar can meet when the arm reaches down: a sampler
    that marked every non-adjacent pair Never would disable it."""
    pairs = _committed_pairs()
    model = pin.buildModelFromUrdf(str(URDF))
    geom = pin.buildGeomFromUrdf(model, str(URDF), pin.GeometryType.COLLISION)
    geom.addAllCollisionPairs()
    data, gdata = model.createData(), pin.GeometryData(geom)
    pin.seed(5)
    seen: set[frozenset[str]] = set()
    names = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    for _ in range(3000):
        pin.computeCollisions(model, data, geom, gdata, pin.randomConfiguration(model), False)
        for k, r in enumerate(gdata.collisionResults):
            if r.isCollision():
                cp = geom.collisionPairs[k]
                seen.add(frozenset((names[cp.first], names[cp.second])))
    colliding_non_adjacent = {p for p in seen if pairs.get(p) != "Adjacent"}
    assert colliding_non_adjacent, "the example should have pairs MoveIt must keep checking"
    assert all(pairs.get(p) not in ("Never",) for p in colliding_non_adjacent)


def _example() -> tuple[object, str]:
    robot = load_spec(ROOT / "specs" / "warehouse_arm.yaml").robot
    stamp = header.read(URDF.read_text())  # generate keys the matrix by the URDF without its header
    assert stamp is not None
    return robot, stamp.body


def test_same_input_same_pairs_and_cache_hit(monkeypatch: pytest.MonkeyPatch) -> None:
    robot, urdf = _example()
    settings = robot.semantic.collision_matrix  # type: ignore[attr-defined]
    fresh = collision.compute(robot, urdf, {}, PKG.name, settings)  # type: ignore[arg-type]
    committed = {frozenset((d.link1, d.link2)): d.reason for d in fresh.pairs}
    assert committed == _committed_pairs()  # the committed SRDF is what a fresh sample gives

    def boom(*_: object) -> None:
        raise AssertionError("sampled although the input hash matched")

    monkeypatch.setattr(collision, "_sample", boom)
    again = collision.compute(robot, urdf, {}, PKG.name, settings, SRDF.read_text())  # type: ignore[arg-type]
    assert again.pairs == fresh.pairs and again.input_hash == fresh.input_hash
    # another seed is another input: the cache must not answer
    with pytest.raises(AssertionError, match="sampled although"):
        collision.compute(robot, urdf, {}, PKG.name, replace(settings, seed=2), SRDF.read_text())  # type: ignore[arg-type]


def test_default_state_collision_is_reason_default() -> None:
    """A state that drives the lift far down puts the shoulder into the arm base? Instead of
    guessing, take a pair pinocchio finds colliding at a hand-made state and make it the default."""
    robot, urdf = _example()
    scene = collision.load_scene(robot, urdf, {}, PKG.name, 0.0)  # type: ignore[arg-type]
    every = list(scene.link_pairs)
    adjacent = collision.adjacent_pairs(robot)  # type: ignore[arg-type]
    qs = collision.random_configurations(scene, 400, 3)
    names = [scene.model.names[j] for j in range(1, scene.model.njoints)]
    for q in qs:
        hit = collision.colliding(scene, q, [p for p in every if p not in adjacent])
        if hit:
            break
    else:
        pytest.skip("no colliding configuration among 400")
    values = _values_of(scene, q, names)
    state = robot.semantic.states[0]  # type: ignore[attr-defined]
    robot2 = replace(
        robot,
        semantic=replace(robot.semantic, states=(replace(state, values=tuple(values.items())),)),  # type: ignore[arg-type]
    )
    m = collision.compute(robot2, urdf, {}, PKG.name, MatrixSettings(state.name, samples=200))  # type: ignore[arg-type]
    defaults = {frozenset((d.link1, d.link2)) for d in m.pairs if d.reason == "Default"}
    assert defaults == hit


def _values_of(scene: collision._Scene, q: np.ndarray, names: list[str]) -> dict[str, float]:
    out = {}
    for jid, name in enumerate(names, start=1):
        jm = scene.model.joints[jid]
        if jm.nq == 2:
            out[name] = float(np.arctan2(q[jm.idx_q + 1], q[jm.idx_q]))
        elif jm.nq == 1:
            out[name] = float(q[jm.idx_q])
    return out


def test_unknown_default_state_is_spec100(tmp_path: Path) -> None:
    text = plant("default_state: ready", "default_state: raedy")
    found = errors_of(text, tmp_path)
    hit = [f for f in found if f.code == "SPEC100"]
    assert hit and hit[0].where.line == line_of(text, "collision_matrix:")
    assert "raedy" in hit[0].message and "ready" in hit[0].hint


def test_padding_out_of_range_is_spec101(tmp_path: Path) -> None:
    text = plant("fraction: 0.95}", "fraction: 0.95, padding: {value: 0.5 m, source: K1}}")
    text = plant("require_sources: true", "require_sources: false", text) if "require_sources: true" in text else text
    found = errors_of(text, tmp_path)
    assert [f.code for f in found if f.code == "SPEC101"] == ["SPEC101"]


def test_without_pinocchio_the_matrix_is_refused_gen070(monkeypatch: pytest.MonkeyPatch) -> None:
    robot, urdf = _example()
    monkeypatch.setitem(sys.modules, "pinocchio", None)  # import pinocchio raises ImportError
    with pytest.raises(InputError) as exc:
        collision.compute(robot, urdf, {}, PKG.name, MatrixSettings(seed=9))  # type: ignore[arg-type]
    (f,) = exc.value.findings
    assert f.code == "GEN070" and "descgen[collision]" in f.hint


def test_example_text_asks_for_the_matrix() -> None:
    assert "collision_matrix:" in EXAMPLE_TEXT


def test_the_samples_drawn_are_told_to_the_progress_bar() -> None:
    # every 100 samples drawn, until the pairs left can be neither Never nor Always (then the
    # loop stops early); the example's settings draw its samples to the end or stop early, and
    # either way the steps add up to the samples drawn, in hundreds
    robot, urdf = _example()
    settings = replace(robot.semantic.collision_matrix, samples=1000)  # type: ignore[attr-defined]
    scene = collision.load_scene(robot, urdf, {}, PKG.name, settings.padding)  # type: ignore[arg-type]
    names = collision.geometry_links(robot)[0]  # type: ignore[arg-type]
    pairs = [frozenset((a, b)) for i, a in enumerate(names) for b in names[i + 1 :]]
    told: list[int] = []
    counts = collision._counts(scene, pairs, settings, told.append)
    assert told and set(told) == {100} and sum(told) <= 1000
    # a pair still live at the end was looked at in every sample, so the loop ran to the end
    if any(n >= 0 for n in counts.values()):
        assert sum(told) == 1000


def test_generate_draws_the_sampling_on_a_terminal(tmp_path: Path) -> None:
    import os
    import shutil

    from tests.helpers import on_a_terminal

    project = tmp_path / "project"
    for rel in ("specs/warehouse_arm.yaml", "specs/trajectories/ready.yaml"):
        (project / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / rel, project / rel)
    spec = project / "specs" / "warehouse_arm.yaml"
    text = spec.read_text()
    assert "seed: 1, samples: 10000" in text
    spec.write_text(text.replace("seed: 1, samples: 10000", "seed: 7, samples: 2000"))  # sampled anew
    env = {k: v for k, v in os.environ.items() if k != "CI"} | {"DESCGEN_CACHE_DIR": ""}
    shown = on_a_terminal(["generate", str(spec), "--out", str(project / "generated")], env, cwd=project)
    assert "collision matrix" in shown and "sample/s" in shown, shown[:400]
