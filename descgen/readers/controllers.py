"""controller_manager YAML -> the model's controllers and update rate (pyyaml, with lines)."""

from __future__ import annotations

from typing import Any

from .. import model as m
from ..findings import Finding, InputError, Where
from ..yamlsource import loads


def _freeze(v: Any) -> object:
    if isinstance(v, dict):
        return tuple((str(k), _freeze(x)) for k, x in v.items())
    if isinstance(v, list):
        return tuple(_freeze(x) for x in v)
    return v


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
    found: list[Finding] = []
    cm = (data.get("controller_manager") or {}).get("ros__parameters") or {}
    rate = cm.get("update_rate")
    types: dict[str, str] = {}
    for name, entry in cm.items():
        if isinstance(entry, dict) and "type" in entry:
            types[str(name)] = str(entry["type"])
    for name, entry in data.items():
        params = (entry or {}).get("ros__parameters") if isinstance(entry, dict) else None
        if isinstance(params, dict) and "type" in params and name != "controller_manager":
            types.setdefault(str(name), str(params["type"]))
    controllers = []
    for name, type_ in types.items():
        params = ((data.get(name) or {}).get("ros__parameters") or {}) if isinstance(data.get(name), dict) else {}
        frozen = tuple((str(k), _freeze(v)) for k, v in params.items() if k != "type")
        controllers.append(
            m.Controller(
                name,
                type_,
                frozen,
                doc.where((name,)) if name in data else doc.where(("controller_manager", "ros__parameters", name)),
            )
        )
    return tuple(controllers), float(rate) if isinstance(rate, int | float) else None, found
