"""controller_manager YAML -> the model's controllers and update rate (pyyaml, with lines)."""

from __future__ import annotations

import math
from typing import Any

from .. import model as m
from ..findings import Finding, InputError, Where
from ..yamlsource import Document, loads


def _freeze(v: Any) -> object:
    if isinstance(v, dict):
        return tuple((str(k), _freeze(x)) for k, x in v.items())
    if isinstance(v, list):
        return tuple(_freeze(x) for x in v)
    return v


def _kind(value: object) -> str:
    if isinstance(value, list):
        return "a list"
    if isinstance(value, bool):
        return "a boolean"
    return "a number" if isinstance(value, int | float) else "a string" if isinstance(value, str) else "a scalar"


def _dotted(path: tuple[str | int, ...]) -> str:
    return ".".join(map(str, path))


class _Shape:
    """Reads the nested mappings of a controllers file; a list or scalar where a mapping
    belongs becomes a finding (READ043) and reads as empty, never an AttributeError."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.found: list[Finding] = []

    def mapping(self, value: object, path: tuple[str | int, ...]) -> dict[str, Any]:
        if isinstance(value, dict):
            return value
        if value is not None:
            self.found.append(
                Finding(
                    "READ043",
                    "error",
                    f"'{_dotted(path)}' is {_kind(value)}, not a mapping",
                    "write it as 'key: value' lines indented below it (see the ros2_control docs)",
                    "file",
                    self.doc.where(path),
                )
            )
        return {}

    def finite(self, value: object, path: tuple[str | int, ...]) -> bool:
        """False (and a READ042 finding) for a float that is nan or infinite."""
        if isinstance(value, float) and not math.isfinite(value):
            self.found.append(
                Finding(
                    "READ042",
                    "error",
                    f"'{_dotted(path)}' is {value}, not a finite number",
                    "write a plain decimal number",
                    "file",
                    self.doc.where(path),
                )
            )
            return False
        return True

    def params(self, params: dict[str, Any], path: tuple[str, ...]) -> tuple[tuple[str, object], ...]:
        out = []
        for k, v in params.items():
            if k == "type":
                continue
            if isinstance(v, list):
                v = [x for i, x in enumerate(v) if self.finite(x, (*path, str(k), i))]
            elif not self.finite(v, (*path, str(k))):
                continue  # a non-finite value reads as missing
            out.append((str(k), _freeze(v)))
        return tuple(out)


def read_controllers_text(text: str, file: str) -> tuple[tuple[m.Controller, ...], float | None, list[Finding]]:
    """Controllers (type from the classic ``controller_manager.ros__parameters.<name>.type``
    or from ``<name>.ros__parameters.type``), their parameters, and the update rate."""
    doc = loads(text, file)
    data = doc.data
    if not isinstance(data, dict):
        raise InputError(
            [
                Finding(
                    "READ020", "error", "a controllers file is a YAML mapping", "check the file", "file", Where(file, 1)
                )
            ]
        )
    shape = _Shape(doc)
    cm_path = ("controller_manager", "ros__parameters")
    cm = shape.mapping(shape.mapping(data.get("controller_manager"), cm_path[:1]).get("ros__parameters"), cm_path)
    types: dict[str, str] = {}
    for name, entry in cm.items():
        if isinstance(entry, dict) and "type" in entry:
            types[str(name)] = str(entry["type"])
    own: dict[str, dict[str, Any]] = {}
    for name, entry in data.items():
        if name == "controller_manager" or not isinstance(entry, dict) or "ros__parameters" not in entry:
            continue
        own[name] = shape.mapping(entry["ros__parameters"], (name, "ros__parameters"))
        if "type" in own[name]:
            types.setdefault(str(name), str(own[name]["type"]))
    controllers = []
    for name, type_ in types.items():
        controllers.append(
            m.Controller(
                name,
                type_,
                shape.params(own.get(name, {}), (name, "ros__parameters")),
                doc.where((name,)) if name in data else doc.where((*cm_path, name)),
            )
        )
    rate = cm.get("update_rate")
    if not isinstance(rate, int | float) or isinstance(rate, bool) or not shape.finite(rate, (*cm_path, "update_rate")):
        return tuple(controllers), None, shape.found
    return tuple(controllers), float(rate), shape.found
