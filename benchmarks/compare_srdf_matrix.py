"""Our self-collision matrix against the disabled pairs of published SRDFs (example-robot-data's
UR5 and Panda, meshes included): per our reason, how many of our pairs the SRDF also disables,
and every pair only one side disables, with how often it collides in an independent count.

Our matrix: descgen.physics.collision, 10,000 samples, seed 1, fraction 0.95, padding 0, default state
zero. The independent count: pinocchio/coal with only the disagreeing pairs active, 10,000
other samples (seed 2), so "collides in N samples" is not our matrix's own word.

Run: .venv/bin/python benchmarks/compare_srdf_matrix.py   (the table of docs/collision_matrix.md)
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import corpus_matrix as cm

from descgen.physics import collision

REASONS = ("Adjacent", "Default", "Always", "Never")


def hits(c: cm.Corpus, pairs: list[frozenset[str]]) -> dict[frozenset[str], int]:
    """Samples (seed 2) in which each of ``pairs`` collides: only those pairs are checked."""
    scene = collision.load_scene(c.robot, c.urdf, {}, "", 0.0)
    counts = dict.fromkeys(pairs, 0)
    known = [p for p in pairs if p in scene.link_pairs]
    if not known:
        return counts
    collision.activate(scene, known)
    for q in collision.random_configurations(scene, cm.SAMPLES, cm.CHECK_SEED):
        for p in collision.colliding(scene, q, known, switch=False):
            counts[p] += 1
    return counts


def compare(name: str) -> dict[str, object]:
    c = cm.load(name)
    m = cm.matrix(c)
    ours = {frozenset((d.link1, d.link2)): d.reason for d in m.pairs}
    only_ours = [p for p in ours if p not in c.published]
    only_theirs = [p for p in c.published if p not in ours]
    counted = hits(c, only_ours + only_theirs)
    return {
        "name": name,
        "per_reason": {
            r: (
                sum(1 for p, x in ours.items() if x == r),
                sum(1 for p, x in ours.items() if x == r and p in c.published),
            )
            for r in REASONS
        },
        "published": len(c.published),
        "checked": m.checked,
        "skipped": m.skipped,
        "only_ours": [(sorted(p), ours[p], counted[p]) for p in only_ours],
        "only_theirs": [(sorted(p), c.published[p], counted[p]) for p in only_theirs],
    }


def main() -> None:
    for name in cm.ROBOTS:
        r = compare(name)
        print(
            f"## {name}: {r['published']} pairs in the published SRDF; {r['checked']} link pairs with geometry; "
            f"links without collision geometry: {', '.join(r['skipped']) or 'none'}"
        )  # type: ignore[arg-type]
        print("| our reason | our pairs | also disabled by the published SRDF |")
        print("|---|---|---|")
        for reason, (n, agree) in r["per_reason"].items():  # type: ignore[attr-defined]
            print(f"| {reason} | {n} | {agree} |")
        for title, key in (("only we disable", "only_ours"), ("only the published SRDF disables", "only_theirs")):
            print(f"\n{title}:")
            for pair, reason, n in r[key] or [("—", "", 0)]:  # type: ignore[attr-defined]
                print(
                    f"- {' / '.join(pair) if isinstance(pair, list) else pair} ({reason}): "
                    f"collides in {n} of {cm.SAMPLES} independent samples"
                )
        print()


if __name__ == "__main__":
    main()
