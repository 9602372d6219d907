"""The self-collision matrix (10,000 samples; 1,000 with ``--quick``) of the example and of a
7-axis arm with meshes (example-robot-data's Panda) beside an anchor doing the same work,
interleaved (benchmarks/harness.py: A B A B …, median and min of CPU time).

descgen: ``descgen.physics.collision.compute`` (through benchmarks/corpus_matrix.py's
``matrix``; result cache off, the process's memo of sampled matrices cleared before each run):
it loads pinocchio's model and collision geometry from the URDF descgen builds for pinocchio,
sets Adjacent aside (pairs one joint apart, never checked), checks every other pair of links
with geometry at the default state (Default), samples the configurations (numpy PCG64, seed 1)
and checks the remaining pairs at each, switching a pair off as soon as it can be neither
Never nor Always (seen in collision and free in at least 5% of the samples), then classifies.

Anchor: benchmarks/collision_anchor.py, plain pinocchio/coal and numpy (no descgen): the same
URDF, the same pairs to check (descgen's non-Adjacent pairs, given to it), the same default
state, the same samples drawn the same way, and the same early stop per pair, so it checks
exactly the geometry pairs descgen checks at exactly the same samples. Before timing, one run of
each verifies that: descgen's pinocchio calls are counted (``collision.colliding`` wrapped in
that run only) and must equal the anchor's count of geometry-pair checks, and the Default,
Never and Always pairs must be the same.

Rows: warm, both in this process after imports (each run loads the model and meshes again);
and cold, a fresh process per run (descgen's caches warm but for the matrix, which is never
read from its result cache: DESCGEN_RECOMPUTE=1): descgen reads the robot (the example's spec, Panda's URDF),
builds pinocchio's URDF and computes the matrix; the anchor process (collision_anchor.py) reads
a JSON file with the URDF string and the pairs, written before timing, and does the work above.

Run: .venv/bin/python benchmarks/bench_collision.py [--quick] [--pairs N]
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

os.environ["DESCGEN_CACHE_DIR"] = ""  # descgen's result cache off: every matrix is sampled
sys.path.insert(0, str(Path(__file__).resolve().parent))

import collision_anchor
import corpus_matrix as cm
import harness
from harness import in_process, python, run

from descgen.audit.spec import load_spec
from descgen.physics import collision
from descgen.physics.sweep.contacts import pinocchio_urdf

SPEC = cm.ROOT / "specs" / "warehouse_arm.yaml"
BENCH = str(Path(__file__).resolve().parent)

COLD = """
import sys
sys.path.insert(0, {bench!r})
import corpus_matrix as cm
{load}
cm.matrix(c, samples={samples})
"""


EXAMPLE = f"""from descgen.audit.spec import load_spec
from descgen.physics.sweep.contacts import pinocchio_urdf
robot = load_spec({str(SPEC)!r}).robot
c = cm.Corpus("warehouse_arm", robot, pinocchio_urdf(robot), {{}})"""


def example() -> cm.Corpus:
    robot = load_spec(SPEC).robot
    return cm.Corpus("warehouse_arm", robot, pinocchio_urdf(robot), {})


def work(c: cm.Corpus, samples: int) -> dict[str, Any]:
    """The anchor's input: what descgen's matrix is given and decides before sampling."""
    settings = cm.settings(cm.SEED, samples)
    with_geometry = collision.geometry_links(c.robot)[0]
    adjacent = collision.adjacent_pairs(c.robot)
    every = [(a, b) for i, a in enumerate(with_geometry) for b in with_geometry[i + 1 :]]
    scene = collision.load_scene(c.robot, c.urdf, {}, "", 0.0)  # the followers pinocchio would move alone
    return {
        "urdf": c.urdf,
        "pairs": [p for p in every if frozenset(p) not in adjacent],
        "default": collision._state_values(c.robot, settings)[1],
        "mimics": [[r.follower, r.leader, r.multiplier, r.offset] for r in scene.mimics],
        "samples": samples,
        "seed": settings.seed,
        "fraction": settings.fraction,
    }


def verify(c: cm.Corpus, job: dict[str, Any], samples: int) -> int:
    """One run of each side: the same geometry-pair checks and the same pairs decided."""
    checked = [0]
    original = collision.colliding

    def counting(scene: Any, q: Any, pairs: list[frozenset[str]], switch: bool = True) -> set[frozenset[str]]:
        checked[0] += len({k for p in pairs for k in scene.link_pairs.get(p, [])})
        return original(scene, q, pairs, switch)

    collision.colliding = counting  # type: ignore[assignment]
    try:
        matrix = cm.matrix(c, seed=cm.SEED, samples=samples)
    finally:
        collision.colliding = original  # type: ignore[assignment]
    default, hits, checks = collision_anchor.run(job)
    ours = {
        r: {frozenset((d.link1, d.link2)) for d in matrix.pairs if d.reason == r}
        for r in ("Default", "Never", "Always")
    }
    theirs = {
        "Default": default,
        "Never": {p for p, h in hits.items() if h == 0},
        "Always": {p for p, h in hits.items() if h > job["fraction"] * samples},
    }
    assert checked[0] == checks, f"{c.name}: descgen checked {checked[0]} geometry pairs, the anchor {checks}"
    assert ours == theirs, f"{c.name}: the anchor decided other pairs than descgen"
    decided = ", ".join(f"{len(v)} {k}" for k, v in ours.items())
    print(f"{c.name}: both sides check {checks:,} geometry pairs over {samples:,} samples; {decided} on both")
    return checks


def main() -> None:
    harness.parse(__doc__)
    samples = 1_000 if harness.QUICK else cm.SAMPLES
    loads: dict[str, tuple[Callable[[], cm.Corpus], str]] = {
        "warehouse_arm (primitives)": (example, EXAMPLE),
        "panda (7 axes + hand, STL meshes)": (lambda: cm.load("panda"), "c = cm.load('panda')"),
    }
    # cold processes: descgen's caches in a folder of this run (pint's definitions warm after the
    # uncounted pair), with DESCGEN_RECOMPUTE=1 so the matrix is never read from its result cache
    cache = harness.FreshCache()
    env = harness.env(cache.path, OPENBLAS_NUM_THREADS="1", DESCGEN_RECOMPUTE="1")
    with tempfile.TemporaryDirectory() as tmp:
        for title, (make, code) in loads.items():
            c = make()
            job = work(c, samples)
            verify(c, job, samples)
            measure = f"collision matrix, {samples:,} samples, {title}"
            harness.compare(
                measure,
                lambda c=c: in_process(lambda: cm.matrix(c, seed=cm.SEED, samples=samples)),  # type: ignore[misc]
                lambda j=job: in_process(lambda: collision_anchor.run(j)),  # type: ignore[misc]
                kind="warm",
                anchor_name="pinocchio, same pairs",
            )
            path = Path(tmp) / f"{c.name}.json"
            path.write_text(json.dumps(job))
            cold = COLD.format(bench=BENCH, load=code, samples=samples)
            harness.compare(
                f"{measure}, fresh process",
                lambda cold=cold: python(cold, env=env, cwd=cm.ROOT)[0],  # type: ignore[misc]
                lambda p=path: run([sys.executable, str(Path(BENCH) / "collision_anchor.py"), str(p)], env=env)[0],  # type: ignore[misc]
                kind="cold",
                anchor_name="pinocchio, same pairs",
            )
    cache.close()
    harness.done()


if __name__ == "__main__":
    main()
