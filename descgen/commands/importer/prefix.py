"""A prefixed description imported as a spec with ``prefix:`` (descgen/spec/prefix.py applies it
back): the Xacro's ``prefix`` or ``tf_prefix`` argument (descgen/read/xacro_prefix.py), when every
name the prefix pass would prefix carries it, is taken out of every name in the spec data.

A description where some name lacks the prefix is imported as it is (no ``prefix:``): taking the
prefix out of some names only would give a spec whose generated robot differs from the original;
the audit's NAME014 names the ones without it, and import waives them as defects of the original.
"""

from __future__ import annotations

from typing import Any

from lxml import etree

from descgen.core import model as m
from descgen.core.naming import GLOBAL_FRAMES
from descgen.physics.control_claims import FRAME_LEAVES, FRAME_PARAMS, default_frames
from descgen.spec.prefix import PREFIX_PARAMS


def names_behind(
    prefix: str, robot: m.Robot, root: etree._Element, data: dict[str, Any] | None = None
) -> set[str] | None:
    """Every name the prefix pass prefixes (links, joints, every ``<ros2_control>`` joint, sensor
    and gpio), when each carries ``prefix``; None when one does not, or when a controller's frame
    id does not, or an odometry controller leaves its frames to their unprefixed defaults (the
    prefix pass would write them prefixed: the robot would not be the original)."""
    names: list[str] = [lk.name for lk in robot.links] + [j.name for j in robot.joints]
    for block in root.iter("ros2_control"):
        names += [(e.get("name") or "").strip() for tag in ("joint", "sensor", "gpio") for e in block.iter(tag)]
    kept = {n for n in names if n not in GLOBAL_FRAMES}
    if not kept or not all(n.startswith(prefix) and len(n) > len(prefix) for n in kept):
        return None
    controllers = ((data or {}).get("ros2_control") or {}).get("controllers") or []
    for c in controllers:
        params = c.get("params") or {}
        frames = [params.get(k) for k in FRAME_PARAMS]
        if any(isinstance(f, str) and f and f not in GLOBAL_FRAMES and not f.startswith(prefix) for f in frames):
            return None
        if any(k not in params for k, _ in default_frames(str(c.get("type", "")))):
            return None
    return kept


def without(data: Any, prefix: str, names: set[str], path: tuple[str, ...] = ()) -> Any:
    """``data`` (the spec as import writes it) with ``prefix`` taken out of each of ``names``
    wherever the prefix pass puts it back (descgen/spec/prefix.py): a value, a list item, a
    mapping key, the component of a full interface name, a controller's frame ids, a param that
    holds the prefix itself. Import's round trip proves the two agree; where they do not, the
    description is imported name for name (run.py)."""
    key = path[-1] if path else ""
    if isinstance(data, dict):
        return {_bare(k, prefix, names): without(v, prefix, names, (*path, str(k))) for k, v in data.items()}
    if isinstance(data, list):
        return [without(v, prefix, names, path) for v in data]
    if key in PREFIX_PARAMS and data == prefix and "params" in path:
        return ""
    controller = "controllers" in path and (key in FRAME_PARAMS or key in FRAME_LEAVES)
    sensor = "sensors" in path and key == "frame_id"
    if (controller or sensor) and isinstance(data, str) and data.startswith(prefix) and data not in GLOBAL_FRAMES:
        return data[len(prefix) :]
    if "interface" in key and isinstance(data, str) and "/" not in data:
        return data  # an interface name is never prefixed
    return _bare(data, prefix, names)


def _bare(value: Any, prefix: str, names: set[str]) -> Any:
    if not isinstance(value, str):
        return value
    if value in names:
        return value[len(prefix) :]
    component, _, iface = value.rpartition("/")
    return f"{component[len(prefix) :]}/{iface}" if component in names else value


def with_prefix(data: dict[str, Any], prefix: str) -> dict[str, Any]:
    """The spec data with ``prefix:`` right after ``name:``."""
    out: dict[str, Any] = {}
    for k, v in data.items():
        out[k] = v
        if k == "name":
            out["prefix"] = prefix
    return out
