"""Written quantities whose kind depends on context -> SI, at their YAML position.

A joint limit is an angle or a length depending on the joint type, a pose value depends on
the joint it moves. They are converted here with the same ``units.to_si`` as the schema;
a value that cannot be converted becomes a finding at its YAML node and a stand-in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from descgen.codes import Code, raisable
from descgen.core import units
from descgen.core.findings import Finding, Where
from descgen.infra.yamlsource import Document, Path_
from descgen.spec.quantity import Written, convert
from descgen.spec.sources import sources

# What a joint's limit, value and gains are, by joint type: (value kind, plausibility role).
POSITION = {
    "revolute": ("angle", "joint_angle"),
    "continuous": ("angle", "joint_angle"),
    "prismatic": ("length", "joint_travel"),
}
EFFORT = {"prismatic": ("force", "force")}
VELOCITY = {"prismatic": ("linear_velocity", "linear_velocity")}
ACCELERATION = {"prismatic": ("linear_acceleration", "linear_acceleration")}
DAMPING = {"prismatic": "linear_damping"}
FRICTION = {"prismatic": "force"}


_PLAIN = (str, int, float)  # written values that are their own memo key (a list is not hashable)


@dataclass
class Converter:
    """One build's conversions and the findings they (and the other build steps) make."""

    doc: Document
    ranges: dict[str, units.Range]
    findings: list[Finding] = field(default_factory=list)
    joint_types: dict[str, str] = field(default_factory=dict)  # set once every joint is built
    # --package-path: searched for package:// meshes after the spec's package_paths: (inertia from a mesh)
    package_paths: tuple[Path, ...] = ()
    # whether a source can be cited anywhere in this build (spec/sources.py cites_sources): when
    # not, every element's source is None without walking its values (~20 % of a build)
    cited: bool = True
    # (type, text, kind, role) -> SI of the values converted so far: a spec repeats its limits
    # and offsets ("-90 deg", "100 mm") on every joint; a value that fails is not kept
    _done: dict[tuple[type, object, str, str | None], float] = field(default_factory=dict, init=False, repr=False)

    def where(self, path: Path_) -> Where:
        return self.doc.where(path)

    def sources(self, *objs: object) -> str | None:
        """:func:`sources.sources` of spec elements; None when nothing in the build cites one."""
        return sources(*objs) if self.cited else None

    def error(self, code: Code, message: str, hint: str, subject: str, where: Where) -> None:
        self.findings.append(code.finding(message, hint, subject, where))

    def si(
        self, w: Written | None, kind: str, role: str | None, path: Path_, default: float | None = None
    ) -> float | None:
        if w is None:
            return default
        key = (type(w.value), w.value, kind, role) if type(w.value) in _PLAIN else None
        if key is not None and key in self._done:
            return self._done[key]
        try:
            si = convert(w, kind, role, self.ranges).si
            if key is not None:
                self._done[key] = si
            return si
        except Exception as exc:  # PydanticCustomError from convert/check_range
            ctx: dict[str, Any] = getattr(exc, "context", None) or {}
            code = raisable(getattr(exc, "type", "UNIT002"))  # the error type is the finding code
            self.error(
                code, str(ctx.get("message", exc)), str(ctx.get("hint", "")), ".".join(map(str, path)), self.where(path)
            )
            return default

    def joint_value(self, joint: str, w: Written, path: Path_) -> float:
        """A value of ``joint`` (a pose, an initial position) in the joint's own unit."""
        jt = self.joint_types.get(joint)
        if jt in POSITION:
            kind, role = POSITION[jt]
            return self.si(w, kind, role, path, math.nan) or 0.0
        # unknown or non-1-DOF joint: a rule reports it; keep the value if it reads as anything
        for kind in ("angle", "length"):
            try:
                return units.to_si(w.value, kind)
            except units.QuantityError:
                continue
        return math.nan
