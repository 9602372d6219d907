"""Names that mean something by convention: the left/right twin of a joint or link name.

The mirror-axes rule (JOINT009) and the wrong-axis fault both pair ``l_elbow`` with
``r_elbow`` this way, so the pairing lives here once.
"""

from __future__ import annotations

_SIDES = {"left": "right", "l": "r", "lf": "rf", "lh": "rh", "fl": "fr", "rl": "rr", "hl": "hr", "lb": "rb", "bl": "br"}
_SIDES.update({v: k for k, v in list(_SIDES.items())})


def mirror_name(name: str) -> str | None:
    """The name with its left/right token swapped (``l_elbow`` -> ``r_elbow``, ``FL_hip`` -> ``FR_hip``)."""
    parts = name.split("_")
    for i, p in enumerate(parts):
        swap = _SIDES.get(p.lower())
        if swap is not None:
            swap = swap.upper() if p.isupper() else swap.capitalize() if p[:1].isupper() else swap
            return "_".join([*parts[:i], swap, *parts[i + 1 :]])
    return None


# frames of the world, not of one robot (REP 105): shared by every robot of a graph, so never
# prefixed (descgen/spec/prefix.py) and never asked to carry a prefix (NAME014)
GLOBAL_FRAMES = frozenset({"map", "earth", "world"})
