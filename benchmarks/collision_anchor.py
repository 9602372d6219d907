"""The anchor of bench_collision.py: the self-collision matrix's sampling written with plain
pinocchio/coal and numpy, no descgen import: what a pinocchio user writes to do the same work.

Given a URDF (pinocchio's input, as descgen builds it), the link pairs to check (every pair of
links with collision geometry but the Adjacent ones, as descgen's matrix checks), the default
state's joint values, the mimic relations, and the sampling settings (samples, seed,
fraction), it

1. builds pinocchio's model and collision geometry from the URDF, with a collision pair for
   every geometry pair of the link pairs to check;
2. checks them all at the default state (those in collision are ``Default``);
3. draws the same configurations as descgen (numpy PCG64 seeded with ``seed``, one uniform
   draw per joint in model order, continuous joints as cos/sin of a full turn, mimic followers
   overwritten from their leaders), and checks the remaining pairs at each, with the same early
   stop per pair: a pair seen in collision and free in at least (1 - fraction) of the samples
   is switched off (it can be neither Never nor Always);
4. returns the Default pairs, the hits per pair (-1: switched off) and the geometry-pair checks
   made (the number of active geometry pairs summed over every computeCollisions call).

Run: python benchmarks/collision_anchor.py INPUT.json   (what bench_collision.py's cold row runs)
"""

from __future__ import annotations

import json
import math
import sys
from typing import Any

import numpy as np
import pinocchio as pin

LinkPair = frozenset[str]


def _put(qs: np.ndarray, jm: Any, values: np.ndarray) -> None:
    if jm.nq == 2:
        qs[:, jm.idx_q] = np.cos(values)
        qs[:, jm.idx_q + 1] = np.sin(values)
    else:
        qs[:, jm.idx_q] = values


def run(work: dict[str, Any]) -> tuple[set[LinkPair], dict[LinkPair, int], int]:
    urdf: str = work["urdf"]
    pairs = [frozenset(p) for p in work["pairs"]]
    mimics = [(f, lead, m, o) for f, lead, m, o in work["mimics"]]
    samples, seed, fraction = int(work["samples"]), int(work["seed"]), float(work["fraction"])

    # 1. the model, and a collision pair per geometry pair of the link pairs to check
    model = pin.buildModelFromXML(urdf)
    geom = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.COLLISION)
    link_of = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    index: dict[LinkPair, list[int]] = {p: [] for p in pairs}
    for a in range(len(link_of)):
        for b in range(a + 1, len(link_of)):
            p = frozenset((link_of[a], link_of[b]))
            if p in index and link_of[a] != link_of[b]:
                geom.addCollisionPair(pin.CollisionPair(a, b))
                index[p].append(len(geom.collisionPairs) - 1)
    data, gdata = model.createData(), pin.GeometryData(geom)

    def activate(live: list[LinkPair]) -> int:
        on = {k for p in live for k in index[p]}
        for k in range(len(geom.collisionPairs)):
            if k in on:
                gdata.activateCollisionPair(k)
            else:
                gdata.deactivateCollisionPair(k)
        return len(on)

    def hit(p: LinkPair) -> bool:
        results = gdata.collisionResults
        return any(results[k].isCollision() for k in index[p])

    # 2. the default state
    values = dict(work["default"])
    values |= {f: m * values.get(lead, 0.0) + o for f, lead, m, o in mimics}
    q0 = np.array(pin.neutral(model))
    for jid in range(1, model.njoints):
        name, jm = model.names[jid], model.joints[jid]
        if name in values and jm.nq == 2:
            q0[jm.idx_q : jm.idx_q + 2] = (math.cos(values[name]), math.sin(values[name]))
        elif name in values and jm.nq == 1:
            q0[jm.idx_q] = values[name]
    checks = activate(pairs)
    pin.computeCollisions(model, data, geom, gdata, q0, False)
    default = {p for p in pairs if hit(p)}

    # 3. the samples, drawn as descgen draws them
    rng = np.random.default_rng(seed)
    qs = np.tile(np.array(pin.neutral(model)), (samples, 1))
    drawn: dict[str, np.ndarray] = {}
    for jid in range(1, model.njoints):
        jm = model.joints[jid]
        u = rng.random(samples)
        if jm.nq == 2:
            drawn[model.names[jid]] = angle = -math.pi + 2 * math.pi * u
            _put(qs, jm, angle)
        elif jm.nq == 1:
            lo, hi = float(model.lowerPositionLimit[jm.idx_q]), float(model.upperPositionLimit[jm.idx_q])
            drawn[model.names[jid]] = qs[:, jm.idx_q] = lo + (hi - lo) * u
    for f, lead, m, o in mimics:
        _put(qs, model.joints[model.getJointId(f)], m * drawn[lead] + o)

    live = [p for p in pairs if p not in default]
    hits = dict.fromkeys(live, 0)
    budget = (1.0 - fraction) * samples
    active = activate(live)
    for i, q in enumerate(qs):
        if not live:
            break
        pin.computeCollisions(model, data, geom, gdata, q, False)
        checks += active
        for p in live:
            if hit(p):
                hits[p] += 1
        seen = i + 1
        dropped = [p for p in live if hits[p] > 0 and seen - hits[p] >= budget]
        if dropped:
            for p in dropped:
                hits[p] = -1
            live = [p for p in live if hits[p] >= 0]
            active = activate(live)
    return default, hits, checks


if __name__ == "__main__":
    with open(sys.argv[1], encoding="utf-8") as f:
        default, hits, checks = run(json.load(f))
    print(json.dumps({"default": len(default), "checks": checks}))
