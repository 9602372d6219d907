"""``evidence/sweep.md``: the sweep of a generated package, at the matrix's state.

Rendered by generate when the spec has a sampled collision matrix (the same condition as
``evidence/collision_matrix.md``), with fixed settings (:data:`~descgen.physics.sweep.DEFAULT_STEPS`
steps) and values rounded for display, so the same spec gives the same bytes.

``check`` must stay fast: the directions are plain forward kinematics, and the collision runs
(the only part that needs pinocchio) are memoised per process and written into the file on a
comment line with their input hash; ``check`` reads them back from the committed file when
the hash matches (:func:`reuse`), as the matrix reuses the committed SRDF. A file edited by
hand still shows: its content no longer matches its header, and anything rendered from the
runs is compared with a fresh render.

The table itself (:func:`context`, forward kinematics at every grid step, most of a warm
``check``'s sweep) is kept in the result cache (descgen/infra/result_cache.py) under the hash of the
model's values (every field but where it was written), the collision runs, the steps and
descgen's own source (a local cache's key, descgen/infra/keys.py): an unchanged robot is shown
from the cache, and the file is still rendered and compared with the committed one every time.
The runs' key in the file is the sweep's memo key (``physics.sweep.memo_key``: the matrix's key,
the state, the steps, the disabled pairs, the sweep's ALGORITHM and pinocchio's and coal's
versions), the same on every machine with those libraries.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

from descgen.core.findings import InputError
from descgen.core.model import Robot
from descgen.infra import evidence_hash, result_cache
from descgen.infra.safeio import read_bounded
from descgen.physics import collision
from descgen.physics.sweep import (
    DEFAULT_STEPS,
    Settings,
    compute,
    disabled_pairs,
    limit_of,
    memo_key,
    remember,
    remembered,
    span_text,
    state_values,
)
from descgen.physics.sweep.contacts import Run
from descgen.physics.sweep.motion import axis_text, direction, sentence, value_text
from descgen.render.formatting import num

PATH = "evidence/sweep.md"
_DATA = re.compile(r"<!-- sweep input-sha256=([0-9a-f]{64}) runs=(.*) -->")


_KIND = "sweep-evidence"


def context(robot: Robot) -> dict[str, Any]:
    """What the template shows (strings already rounded; names escaped by the template): from
    the result cache when the robot and its collision runs are as when it was stored (module
    doc), else computed. Only a sweep whose runs are known is kept: without them the table
    says why (pinocchio missing, a mesh refused), which depends on more than the model."""
    key = _cache_key(robot)
    if key is not None:
        hit = result_cache.get(_KIND, key)
        if _is_context(hit):
            return hit  # type: ignore[no-any-return]
    found = computed(robot)
    key = key or _cache_key(robot)  # the runs are known now when the sweep computed them
    if key is not None:
        result_cache.put(_KIND, key, found)
    return found


def _cache_key(robot: Robot) -> str | None:
    """The hash of everything :func:`computed` reads, or None when the runs are not memoised
    yet (or the model holds a value :func:`evidence_hash.model_values` cannot see whole)."""
    state, values = state_values(robot, None)
    runs = remembered(memo_key(robot, state, values, DEFAULT_STEPS, disabled_pairs(robot)[0]))
    if runs is None:
        return None
    try:
        model = evidence_hash.model_values(robot)
    except TypeError:
        return None
    inputs = {
        "robot": model,
        "steps": DEFAULT_STEPS,
        "runs": [[r.joint, r.link1, r.link2, r.first, r.last] for r in runs],
    }
    return result_cache.key(_KIND, inputs)  # plain-float kinematics: no library computes it


# the context's shape, checked on what the cache gives back (an entry is data, never trusted)
_TOP = {
    "state": str,
    "steps": int,
    "padding": str,
    "disabled": int,
    "disabled_by": str,
    "checked": bool,
    "note": str,
    "collisions": int,
    "joints": list,
    "no_range": list,
    "skipped": list,
    "unresolved": list,
    "data": str,
}
_JOINT = {
    "name": str,
    "type": str,
    "range": str,
    "axis": str,
    "sentence": str,
    "followers": list,
    "between": str,
    "moved": list,
    "pairs": int,
    "collisions": list,
}


def _typed(doc: object, shape: dict[str, type]) -> bool:
    return isinstance(doc, dict) and set(doc) == set(shape) and all(type(doc[k]) is t for k, t in shape.items())


def _strings(items: object, keys: tuple[str, ...]) -> bool:
    """A list of dicts holding exactly ``keys``, each a string."""
    return isinstance(items, list) and all(
        isinstance(x, dict) and set(x) == set(keys) and all(isinstance(x[k], str) for k in keys) for x in items
    )


def _is_context(doc: object) -> bool:
    if not _typed(doc, _TOP):
        return False
    assert isinstance(doc, dict)
    if not all(isinstance(x, str) for key in ("skipped", "unresolved") for x in doc[key]):
        return False
    if not _strings(doc["no_range"], ("name", "why")):
        return False
    for j in doc["joints"]:
        if not _typed(j, _JOINT) or not all(isinstance(x, str) for x in j["followers"]):
            return False
        if not _strings(j["moved"], ("link", "direction", "tip")):
            return False
        if not _strings(j["collisions"], ("link1", "link2", "span", "limit")):
            return False
    return True


def computed(robot: Robot) -> dict[str, Any]:
    """:func:`context` computed: the sweep at :data:`DEFAULT_STEPS` steps, rounded for display."""
    sw = compute(robot, Settings(steps=DEFAULT_STEPS))
    joints: list[dict[str, Any]] = []
    for m in sw.motions:
        j = m.joint
        mine = [r for r in sw.runs or () if r.joint == j.name]
        joints.append(
            {
                "name": j.name,
                "type": j.type,
                "range": f"{value_text(j, m.values[0])} to {value_text(j, m.values[-1])}",
                "axis": axis_text(m.axis),
                "sentence": sentence(m),
                "followers": list(m.followers),
                "between": "a quarter turn from the state" if m.quarter_turn else "lower to upper limit",
                "moved": [
                    {"link": x.link, "direction": direction(x.displacement) or "origin stays", "tip": x.tip}
                    for x in m.moved
                ],
                "pairs": len(m.pairs),
                "collisions": [
                    {
                        "link1": r.link1,
                        "link2": r.link2,
                        "span": span_text(m, r),
                        "limit": " and ".join(limit_of(m, r)) or "no",
                    }
                    for r in mine
                ],
            }
        )
    runs = None if sw.runs is None else [[r.joint, r.link1, r.link2, r.first, r.last] for r in sw.runs]
    # an HTML comment ends at "--": link names may hold "-", so JSON escapes every one
    data = json.dumps(runs, separators=(",", ":")).replace("-", "\\u002d")
    return {
        "state": sw.state or "all joints at MoveIt's default (zero, or the middle of limits that exclude it)",
        "steps": sw.steps,
        "padding": num(sw.padding),
        "disabled": sw.disabled,
        "disabled_by": sw.disabled_by,
        "checked": sw.runs is not None,
        "note": sw.note,
        "collisions": sum(len(j["collisions"]) for j in joints),
        "joints": joints,
        "no_range": [{"name": nr.joint.name, "why": nr.why} for nr in sw.no_range],
        "skipped": list(sw.skipped),
        "unresolved": list(sw.unresolved),
        "data": f"<!-- sweep input-sha256={sw.key} runs={data} -->" if sw.key else "",
    }


def reuse_committed(robot: Robot, package_dir: Path) -> bool:
    """:func:`reuse` with the package's committed file (a link or an unreadable file is not read:
    the sweep runs again and check reports the file)."""
    target = package_dir / PATH
    if not target.is_file() or target.is_symlink():
        return False
    try:
        text = read_bounded(target, "sweep evidence").decode("utf-8", errors="replace")
    except InputError:
        return False
    return reuse(robot, text)


def reuse(robot: Robot, committed: str | None) -> bool:
    """Take the collision runs from the committed ``evidence/sweep.md`` when it records the
    same input hash as ``robot`` (with its matrix) has now. True when they were taken; never
    with ``DESCGEN_RECOMPUTE=1`` (descgen/infra/evidence_hash.py), nor when pinocchio and coal
    are installed in other versions than those that computed the matrix (the runs are then
    computed here, and the file reads the same when they are the same)."""
    if committed is None or evidence_hash.recompute():
        return False
    sem = robot.semantic
    if sem is not None and sem.matrix is not None and not collision.reusable_here(dict(sem.matrix.libraries)):
        return False
    found = _DATA.search(committed)
    state, values = state_values(robot, None)
    key = memo_key(robot, state, values, DEFAULT_STEPS, disabled_pairs(robot)[0])
    if found is None or not key or found.group(1) != key:
        return False
    try:
        rows = json.loads(found.group(2))
        runs = [Run(str(a), str(b), str(c), int(d), int(e)) for a, b, c, d, e in rows]
    except (ValueError, TypeError):
        return False  # not as we wrote it: sweep again, and check reports the file
    joints = {j.name for j in robot.joints}
    if any(r.joint not in joints or not 0 <= r.first <= r.last <= DEFAULT_STEPS for r in runs):
        return False
    remember(key, runs)
    return True
