"""The self-collision matrix: which link pairs the SRDF disables, and why.

MoveIt's Setup Assistant reasons, computed with pinocchio's collision API (coal) on the
collision geometry of the expanded URDF:

- ``Adjacent``: two links with collision geometry one joint apart, or apart only through
  links without collision geometry (their shapes meet at the joint by design);
- ``Default``: in collision at the named default state (``collision_matrix.default_state``);
- ``Always``: in collision in more than ``fraction`` of the samples;
- ``Never``: in collision in none of ``samples`` random configurations.

The samples come from numpy's PCG64 seeded with ``seed``, uniform within each joint's
limits, so the same spec gives the same pairs on any machine. A URDF ``<mimic>`` follower is
not a free variable: pinocchio loads it as an independent joint, so every sample and the
default state overwrite it with ``multiplier * leader + offset`` (chains resolved to the
driving joint, the follower not clamped to its own limits), as MoveIt's
``RobotModel::getVariableRandomPositions`` / ``getVariableDefaultPositions`` do through
``updateMimicJoints`` (moveit2 jazzy, robot_model.cpp). Pairs the user disabled in the
spec keep their own reason (the SRDF template lists them after these). pinocchio is an
optional extra (``descgen[collision]``); without it a spec that asks for a matrix is refused
with GEN070 rather than silently getting none.

Cost: a pair seen both in and out of collision can be neither Always nor Never, so it is
switched off as soon as that is certain; after a few hundred samples only the Never and
Always candidates are still checked.

The matrix is keyed (:func:`input_hash`, descgen/infra/keys.py) by the URDF, the meshes, the
settings, :data:`ALGORITHM`, descgen's release and the versions of pinocchio, coal and numpy
(the samples are numpy's), and the SRDF records the key with those versions. A committed
matrix whose key matches is reused without sampling; on a machine without pinocchio or coal,
where nothing could sample, the key is taken with the versions the SRDF records; on one with
other versions the matrix is sampled again (once: the pairs are kept in the local result cache)
and the committed record stands when the pairs are the same (:func:`compute`).
"""

from __future__ import annotations

import math
import re
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from descgen.core.findings import Finding, InputError, Where
from descgen.core.model import CollisionMatrix, DisabledPair, MatrixSettings, Robot
from descgen.infra import keys
from descgen.infra.evidence_hash import recompute, sha256
from descgen.infra.progress import Step, counting
from descgen.physics import mimic

if TYPE_CHECKING:  # numpy is imported where the sampling needs it: check reuses the committed
    import numpy as np  # matrix and must not pay numpy's import (~60 ms) for it

# bump when the way pairs are computed changes: a cached matrix is then recomputed
# (tests/test_evidence_recompute.py samples the committed example again and fails on a change)
ALGORITHM = "descgen-collision-3"  # 2: mimic followers follow their leaders; 3: unnamed joints at MoveIt's default
# what computes the pairs: pinocchio (its distribution is "pin") with coal, and numpy's PCG64 samples
LIBRARIES = ("pin", "coal", "numpy")
_SAMPLERS = ("pin", "coal")  # without either, nothing here can sample
# What pinocchio is given (load_scene refuses more, GEN070; the sweep says SWEEP008): it keeps
# ~40 KB per pair of collision shapes (requests, results), 1.25 GB for 250 one-shape links, and
# its URDF parser recurses down the tree, a stack overflow (exit 139, no message) past ~3,500
# joints deep with an 8 MB stack.
MAX_SHAPE_PAIRS = 20_000  # ~0.8 GB: 200 collision shapes
MAX_DEPTH = 1_000  # joints from the root to the deepest link
COMPUTED_REASONS = ("Adjacent", "Default", "Always", "Never")
_CACHE_LINE = re.compile(r"collision matrix input-sha256=([0-9a-f]{64})(?: computed with ([^>\n]*?))? -->")
_LIBRARY = re.compile(r"([A-Za-z0-9][A-Za-z0-9._-]*) ([A-Za-z0-9][A-Za-z0-9.+!_-]*)")


def geometry_links(robot: Robot) -> tuple[list[str], list[str]]:
    """(links with collision geometry, links without), each in model order."""
    with_geometry = [lk.name for lk in robot.links if lk.collisions]
    without = [lk.name for lk in robot.links if not lk.collisions]
    return with_geometry, without


def adjacent_pairs(robot: Robot) -> set[frozenset[str]]:
    """Pairs of links with geometry whose tree path passes only through links without any:
    parent and child, and also siblings or grandparents joined through an empty link."""
    with_geometry = set(geometry_links(robot)[0])
    neighbours: dict[str, set[str]] = {lk.name: set() for lk in robot.links}
    for j in robot.joints:
        if j.parent is None or j.child is None:
            continue
        neighbours.setdefault(j.parent, set()).add(j.child)
        neighbours.setdefault(j.child, set()).add(j.parent)
    pairs: set[frozenset[str]] = set()
    for start in sorted(with_geometry):
        seen, todo = {start}, [start]
        while todo:  # walk outwards, stopping at the first link with geometry on each branch
            for nxt in sorted(neighbours[todo.pop()]):
                if nxt in seen:
                    continue
                seen.add(nxt)
                if nxt in with_geometry:
                    pairs.add(frozenset((start, nxt)))
                else:
                    todo.append(nxt)
    return pairs


def input_hash(
    robot: Robot,
    urdf: str,
    mesh_hashes: Mapping[str, str],
    settings: MatrixSettings,
    libraries: Mapping[str, str] | None = None,
) -> str:
    """The cache key (descgen/infra/keys.py): the URDF (geometry and joints), the meshes' bytes,
    the settings and the default state's values, with :data:`ALGORITHM`, descgen's release and
    ``libraries`` (name -> version; the installed :data:`LIBRARIES` when None). The spec's
    other content (sources, descriptions) does not count."""
    state = _state_values(robot, settings)[1]
    inputs = {
        "urdf": sha256(urdf),
        "meshes": dict(sorted(mesh_hashes.items())),
        "settings": [settings.default_state, settings.seed, settings.samples, settings.fraction, settings.padding],
        "state": sorted(state.items()),
    }
    used = keys.libraries(LIBRARIES) if libraries is None else libraries
    return keys.key("collision matrix", ALGORITHM, inputs, used, keys.RELEASE)


def libraries_text(libraries: Mapping[str, str] | tuple[tuple[str, str], ...]) -> str:
    """``pin 3.4.0, coal 3.0.1, numpy 2.1.0``: how the SRDF and the evidence name them."""
    pairs = libraries.items() if isinstance(libraries, Mapping) else libraries
    return ", ".join(f"{name} {version}" for name, version in pairs)


def recorded(committed_srdf: str | None) -> tuple[str, dict[str, str] | None] | None:
    """(key, libraries it was computed with) of the SRDF's record line; the libraries are None
    when the line names none (an SRDF written before they were recorded) or not all of
    :data:`LIBRARIES` as descgen writes them."""
    found = _CACHE_LINE.search(committed_srdf) if committed_srdf is not None else None
    if found is None:
        return None
    named = [_LIBRARY.fullmatch(part) for part in (found.group(2) or "").split(", ")]
    libraries = {m.group(1): m.group(2) for m in named if m is not None}
    whole = all(named) and list(libraries) == list(LIBRARIES)
    return found.group(1), libraries if whole else None


def _state_values(robot: Robot, settings: MatrixSettings) -> tuple[str, dict[str, float]]:
    """The default state's name and joint values: the named one, else the first group state;
    every joint it does not name at MoveIt's default position (zero, or the middle of limits that
    exclude it), as the sweep starts (descgen/physics/start_state.py): "Default" pairs describe the
    state the sweep starts in, and the Setup Assistant's default state."""
    from descgen.physics.start_state import inside_limits

    states = robot.semantic.states if robot.semantic else ()
    chosen = next((s for s in states if s.name == settings.default_state), None) if settings.default_state else None
    if chosen is None and settings.default_state is None and states:
        chosen = states[0]
    base = inside_limits(robot)
    return (chosen.name, {**base, **dict(chosen.values)}) if chosen else ("", base)


def cached(robot: Robot, committed_srdf: str | None, key: str) -> tuple[DisabledPair, ...] | None:
    """The computed pairs of the committed SRDF when it records the same input hash (never
    with ``DESCGEN_RECOMPUTE=1``: descgen/infra/evidence_hash.py)."""
    found = recorded(committed_srdf)
    if committed_srdf is None or found is None or found[0] != key or recompute():
        return None
    return _committed_pairs(committed_srdf)


def _committed_pairs(committed_srdf: str) -> tuple[DisabledPair, ...]:
    pairs = re.findall(r'<disable_collisions link1="([^"]*)" link2="([^"]*)" reason="([^"]*)"/>', committed_srdf)
    return tuple(DisabledPair(a, b, r) for a, b, r in pairs if r in COMPUTED_REASONS)


def installed() -> dict[str, str]:
    """The installed versions of :data:`LIBRARIES` ("absent" for one not installed)."""
    return keys.libraries(LIBRARIES)


def reusable_here(libraries: Mapping[str, str]) -> bool:
    """Whether a result computed with ``libraries`` may be taken without computing it here:
    they are the installed ones, or pinocchio or coal is missing (nothing here could compute)."""
    local = installed()
    return dict(libraries) == local or any(local[n] == "absent" for n in _SAMPLERS)


def _same(a: tuple[DisabledPair, ...], b: tuple[DisabledPair, ...]) -> bool:
    """The same pairs with the same reasons, in whatever order."""

    def pairs(ds: tuple[DisabledPair, ...]) -> set[tuple[frozenset[str], str]]:
        return {(frozenset((d.link1, d.link2)), d.reason) for d in ds}

    return pairs(a) == pairs(b)


def compute(
    robot: Robot,
    urdf: str,
    meshes: Mapping[str, bytes],
    package: str,
    settings: MatrixSettings,
    committed_srdf: str | None = None,
    show_progress: bool = False,
) -> CollisionMatrix:
    """The matrix for ``robot`` (its expanded ``urdf``; ``meshes``: package path -> bytes of
    the package's own meshes), or the committed one when nothing it depends on changed.
    ``show_progress``: the samples drawn on a terminal (descgen/infra/progress.py).

    The committed record stands when its key is the key of these inputs with the versions it
    records, and either those are the installed versions (or nothing here can sample: it is
    taken as it is) or sampling here with the installed ones gives the same pairs (it is
    reproduced, and stays as committed: a machine with another numpy does not rewrite the
    SRDF). Else the matrix is the one sampled here, keyed with the installed versions."""
    mesh_hashes = {k: sha256(v) for k, v in meshes.items()}
    local = installed()
    key = input_hash(robot, urdf, mesh_hashes, settings, local)
    with_geometry, without = geometry_links(robot)
    checked = len(with_geometry) * (len(with_geometry) - 1) // 2
    state_name = _state_values(robot, settings)[0]

    def matrix(k: str, pairs: tuple[DisabledPair, ...], libraries: Mapping[str, str]) -> CollisionMatrix:
        return CollisionMatrix(settings, k, pairs, tuple(without), checked, state_name, tuple(libraries.items()))

    record = recorded(committed_srdf)
    # the committed pairs, with the record's key and versions, when the record is of these inputs
    committed: tuple[str, tuple[DisabledPair, ...], dict[str, str]] | None = None
    versions = record[1] if record is not None else None
    if committed_srdf is not None and record is not None and versions is not None:
        same_inputs = input_hash(robot, urdf, mesh_hashes, settings, versions) == record[0]
        committed = (record[0], _committed_pairs(committed_srdf), versions) if same_inputs else None
    if committed is not None and not recompute() and reusable_here(committed[2]):
        return matrix(*committed)
    pairs = None if recompute() else _SAMPLED.get(key)
    if pairs is None and not recompute():
        pairs = _stored(key)
    if pairs is None:
        pairs = _SAMPLED[key] = _sample(robot, urdf, meshes, package, settings, show_progress)
        if not recompute():
            _store(key, pairs)
    if committed is not None and _same(pairs, committed[1]):
        return matrix(committed[0], pairs, committed[2])  # reproduced with the installed versions
    return matrix(key, pairs, local)


_STORED = "collision-matrix"  # sampled pairs in the local result cache, by the key with the installed versions


def _stored(key: str) -> tuple[DisabledPair, ...] | None:
    """Pairs sampled here before (descgen/infra/result_cache.py; a machine whose versions differ
    from the committed record's reproduces it once, not on every check)."""
    from descgen.infra import result_cache

    value = result_cache.get(_STORED, result_cache.key(_STORED, key, LIBRARIES))
    if not isinstance(value, list) or not all(
        isinstance(v, list) and len(v) == 3 and all(isinstance(x, str) for x in v) and v[2] in COMPUTED_REASONS
        for v in value
    ):
        return None
    return tuple(DisabledPair(a, b, r) for a, b, r in value)


def _store(key: str, pairs: tuple[DisabledPair, ...]) -> None:
    from descgen.infra import result_cache

    result_cache.put(_STORED, result_cache.key(_STORED, key, LIBRARIES), [[d.link1, d.link2, d.reason] for d in pairs])


# matrices sampled in this process, by input hash: generate followed by check (or a test that
# plans the same robot twice) samples once; a few entries of pair names, so no bound is needed
_SAMPLED: dict[str, tuple[DisabledPair, ...]] = {}


# --- sampling with pinocchio ---------------------------------------------------------------------


@dataclass
class _Scene:
    pin: Any
    model: Any
    data: Any
    geom: Any
    gdata: Any
    link_pairs: dict[frozenset[str], list[int]]  # link pair -> its geometry pair indices
    mimics: tuple[mimic.Relation, ...] = ()  # followers pinocchio would move on their own


def _refuse(message: str, hint: str, robot: Robot) -> InputError:
    where = robot.semantic.collision_matrix.where if robot.semantic and robot.semantic.collision_matrix else Where("")
    return InputError([Finding("GEN070", "error", message, hint, "semantic:collision_matrix", where)])


def too_large(robot: Robot) -> str:
    """Why pinocchio may not be given ``robot`` (beyond :data:`MAX_SHAPE_PAIRS` or
    :data:`MAX_DEPTH`), or "". Linear in the model."""
    shapes = sum(len(lk.collisions) for lk in robot.links)
    if shapes * (shapes - 1) // 2 > MAX_SHAPE_PAIRS:
        return (
            f"{shapes:,} collision shapes make {shapes * (shapes - 1) // 2:,} pairs, more than the "
            f"{MAX_SHAPE_PAIRS:,} pinocchio is given (~40 KB of memory each)"
        )
    parent = {j.child: j.parent for j in robot.joints if j.child is not None and j.parent is not None}
    depth: dict[str, int] = {}
    for link in parent:
        path: list[str] = []
        n = link
        while n in parent and n not in depth and len(path) <= len(parent):  # a cycle ends the walk
            path.append(n)
            n = parent[n]
        d = depth.get(n, 0)
        for m in reversed(path):
            d += 1
            depth[m] = d
    deepest = max(depth.values(), default=0)
    if deepest > MAX_DEPTH:
        return (
            f"the tree is {deepest:,} joints deep, more than the {MAX_DEPTH:,} pinocchio is given "
            "(its URDF parser recurses down the tree and overflows the stack)"
        )
    return ""


def load_scene(robot: Robot, urdf: str, meshes: Mapping[str, bytes], package: str, padding: float) -> _Scene:
    """pinocchio's model and every geometry pair between two different links. GEN070 for a
    robot past pinocchio's bounds (:func:`too_large`)."""
    why = too_large(robot)
    if why:
        raise _refuse(
            f"the collision check is not run: {why}",
            "give fewer collision shapes (simpler collision geometry), or leave semantic.collision_matrix out "
            "and list the disabled pairs yourself",
            robot,
        )
    try:
        import pinocchio as pin
    except ImportError:
        raise _refuse(
            "the collision matrix needs pinocchio, which is not installed",
            "pip install 'descgen[collision]', or remove semantic.collision_matrix from the spec",
            robot,
        ) from None
    with tempfile.TemporaryDirectory(prefix="descgen-collision-") as tmp:
        # package://<package>/meshes/... resolves under package_dirs: lay the meshes out there
        for rel, data in meshes.items():
            target = Path(tmp) / package / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        try:
            model = pin.buildModelFromXML(urdf)
            geom = pin.buildGeomFromUrdfString(model, urdf, pin.GeometryType.COLLISION, package_dirs=[tmp])
        except (RuntimeError, ValueError) as exc:
            raise _refuse(
                f"pinocchio could not load the collision geometry: {str(exc).splitlines()[0][:200]}",
                "check the collision meshes exist and are readable (descgen validate lists them)",
                robot,
            ) from None
    link_of = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    link_pairs: dict[frozenset[str], list[int]] = {}
    for a in range(len(link_of)):
        for b in range(a + 1, len(link_of)):
            if link_of[a] == link_of[b]:
                continue
            geom.addCollisionPair(pin.CollisionPair(a, b))
            link_pairs.setdefault(frozenset((link_of[a], link_of[b])), []).append(len(geom.collisionPairs) - 1)
    gdata = pin.GeometryData(geom)
    for req in gdata.collisionRequests:
        req.security_margin = padding
    # only followers pinocchio knows as one-variable joints, driven by one: a follower with no
    # driver (a cycle, a missing leader) stays a free joint, as in MoveIt (which drops the mimic)
    known = {model.names[j] for j in range(1, model.njoints) if model.joints[j].nv == 1}
    mimics = tuple(r for r in mimic.analyse(robot).relations.values() if r.follower in known and r.leader in known)
    return _Scene(pin, model, model.createData(), geom, gdata, link_pairs, mimics)


def configuration(scene: _Scene, values: Mapping[str, float]) -> np.ndarray:
    """pinocchio's q for joint values by name (others at zero; continuous joints as cos, sin;
    a mimic follower from its leader's value, whatever ``values`` gives it)."""
    import numpy as np

    values = {**values, **{r.follower: r.value(values.get(r.leader, 0.0)) for r in scene.mimics}}
    q = np.array(scene.pin.neutral(scene.model))
    for jid in range(1, scene.model.njoints):
        name = scene.model.names[jid]
        if name not in values:
            continue
        jm = scene.model.joints[jid]
        if jm.nq == 2:
            q[jm.idx_q : jm.idx_q + 2] = (math.cos(values[name]), math.sin(values[name]))
        elif jm.nq == 1:
            q[jm.idx_q] = values[name]
    return q


def random_configurations(scene: _Scene, samples: int, seed: int) -> np.ndarray:
    """``samples`` rows of q, each driving joint uniform within its limits (continuous: full
    turn), each mimic follower ``multiplier * leader + offset``."""
    import numpy as np

    rng = np.random.default_rng(seed)
    model = scene.model
    qs = np.tile(np.array(scene.pin.neutral(model)), (samples, 1))
    drawn: dict[str, np.ndarray] = {}  # joint name -> its values (continuous: the angle)
    for jid in range(1, model.njoints):
        jm = model.joints[jid]
        # a follower draws too, then is overwritten: the stream of every other joint, and so a
        # robot without mimic joints, gets the same numbers as before followers were handled
        u = rng.random(samples)
        if jm.nq == 2:
            drawn[model.names[jid]] = angle = -math.pi + 2 * math.pi * u
            _put(qs, jm, angle)
        elif jm.nq == 1:
            lo, hi = float(model.lowerPositionLimit[jm.idx_q]), float(model.upperPositionLimit[jm.idx_q])
            drawn[model.names[jid]] = qs[:, jm.idx_q] = lo + (hi - lo) * u
    for r in scene.mimics:  # leaders are driving joints (chains resolved), so order is free
        _put(qs, model.joints[model.getJointId(r.follower)], r.multiplier * drawn[r.leader] + r.offset)
    return qs


def _put(qs: np.ndarray, jm: Any, values: np.ndarray) -> None:
    """One joint's column(s) of ``qs``: the value, or cos and sin for a continuous joint."""
    import numpy as np

    if jm.nq == 2:
        qs[:, jm.idx_q] = np.cos(values)
        qs[:, jm.idx_q + 1] = np.sin(values)
    else:
        qs[:, jm.idx_q] = values


def activate(scene: _Scene, pairs: list[frozenset[str]]) -> None:
    """Only the geometry pairs of ``pairs`` are checked from now on."""
    active = {k for p in pairs for k in scene.link_pairs.get(p, [])}
    for k in range(len(scene.geom.collisionPairs)):
        if k in active:
            scene.gdata.activateCollisionPair(k)
        else:
            scene.gdata.deactivateCollisionPair(k)


def colliding(scene: _Scene, q: np.ndarray, pairs: list[frozenset[str]], switch: bool = True) -> set[frozenset[str]]:
    """Which of ``pairs`` are in collision at ``q``; ``switch=False`` when :func:`activate`
    already made exactly those pairs active (the sampling loop)."""
    if switch:
        activate(scene, pairs)
    scene.pin.computeCollisions(scene.model, scene.data, scene.geom, scene.gdata, q, False)
    results = scene.gdata.collisionResults
    return {p for p in pairs if any(results[k].isCollision() for k in scene.link_pairs.get(p, []))}


def _sample(
    robot: Robot,
    urdf: str,
    meshes: Mapping[str, bytes],
    package: str,
    settings: MatrixSettings,
    show_progress: bool = False,
) -> tuple[DisabledPair, ...]:
    scene = load_scene(robot, urdf, meshes, package, settings.padding)
    with_geometry = geometry_links(robot)[0]
    adjacent = adjacent_pairs(robot)
    every = [frozenset((a, b)) for i, a in enumerate(with_geometry) for b in with_geometry[i + 1 :]]
    reasons: dict[frozenset[str], str] = {p: "Adjacent" for p in every if p in adjacent}
    rest = [p for p in every if p not in reasons]
    default = colliding(scene, configuration(scene, _state_values(robot, settings)[1]), rest)
    reasons.update({p: "Default" for p in default})
    with counting(settings.samples, "collision matrix", "sample", show_progress) as step:
        counts = _counts(scene, [p for p in rest if p not in default], settings, step)
    for p, hits in counts.items():
        if hits == 0:
            reasons[p] = "Never"
        elif hits > settings.fraction * settings.samples:
            reasons[p] = "Always"
    order = {n: i for i, n in enumerate(with_geometry)}
    out = []
    for p, reason in reasons.items():
        a, b = sorted(p, key=order.__getitem__)
        out.append(DisabledPair(a, b, reason))
    return tuple(sorted(out, key=lambda d: (COMPUTED_REASONS.index(d.reason), order[d.link1], order[d.link2])))


def _counts(
    scene: _Scene, pairs: list[frozenset[str]], settings: MatrixSettings, step: Step | None = None
) -> dict[frozenset[str], int]:
    """Samples in collision per pair; -1 for a pair dropped once it can be neither Never nor
    Always (seen in collision, and free in more than 1 - fraction of all samples). ``step``
    is told the samples drawn, every 100."""
    hits = dict.fromkeys(pairs, 0)
    free_budget = (1.0 - settings.fraction) * settings.samples
    live = list(pairs)
    activate(scene, live)
    for i, q in enumerate(random_configurations(scene, settings.samples, settings.seed)):
        if not live:
            break
        for p in colliding(scene, q, live, switch=False):
            hits[p] += 1
        seen = i + 1
        dropped = [p for p in live if hits[p] > 0 and seen - hits[p] >= free_budget]
        for p in dropped:
            hits[p] = -1
        if dropped:
            live = [p for p in live if hits[p] >= 0]
            activate(scene, live)
        if step is not None and seen % 100 == 0:
            step(100)
    return hits
