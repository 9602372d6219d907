"""controller_manager YAML -> the model's controllers and update rate (pyyaml, with lines)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from typing import Any

from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.core.launch_subst import Site, substitute
from descgen.core.record import record
from descgen.infra.yamlsource import Document, loads


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


def load_substituted(
    text: str, file: str, launch_args: Mapping[str, str] | None = None
) -> tuple[Document, tuple[Site, ...], list[Finding]]:
    """The controllers file as launch's ``ParameterFile(allow_substs=True)`` would hand it to the
    YAML parser (``$(var NAME)`` from ``launch_args`` only; readers/launch_subst.py), with every
    mark pointing at the file as written, its substitution sites, and findings for those left
    as written (CTRL052/CTRL053)."""
    subst = substitute(text, file, launch_args or {})
    if not subst.sites and not subst.findings:
        return loads(text, file), (), []
    try:
        doc = loads(subst.text, file)
    except InputError as exc:  # a YAML error in the substituted text: say where in the file
        raise InputError([_moved(f, subst.position) for f in exc.findings]) from None

    def back(marks: dict[tuple[str | int, ...], tuple[int, int]]) -> dict[tuple[str | int, ...], tuple[int, int]]:
        return {k: subst.position(*v) for k, v in marks.items()}

    moved = Document(file, doc.data, back(doc.key_marks), back(doc.value_marks), subst.text)
    return moved, subst.sites, list(subst.findings)


def _moved(f: Finding, position: Callable[[int, int], tuple[int, int]]) -> Finding:
    if not f.where.line:
        return f
    line, col = position(f.where.line, f.where.col or 1)
    return dataclasses.replace(f, where=dataclasses.replace(f.where, line=line, col=col))


@record
class ControllersFile:
    controllers: tuple[m.Controller, ...]
    update_rate: float | None
    update_rate_where: Where  # the value as written (or the file, when not given)
    found: tuple[Finding, ...]


def _marks(doc: Document, params: Mapping[str, Any], base: tuple[str, ...]) -> tuple[tuple[str, Where], ...]:
    """Where each parameter's value (and each item of a list value) is written, so a finding
    about one joint name points at that name, not at the controller."""
    out: list[tuple[str, Where]] = []
    for k, v in params.items():
        paths: list[tuple[str, tuple[str | int, ...]]] = [(str(k), (*base, str(k)))]
        paths += [(f"{k}[{i}]", (*base, str(k), i)) for i in range(len(v) if isinstance(v, list) else 0)]
        for label, path in paths:
            if path in doc.value_marks:
                out.append((label, Where(doc.file, *doc.value_marks[path])))
    return tuple(out)


def read_controllers_text(
    text: str, file: str, launch_args: Mapping[str, str] | None = None
) -> tuple[tuple[m.Controller, ...], float | None, list[Finding]]:
    """Controllers (type from the classic ``controller_manager.ros__parameters.<name>.type``
    or from ``<name>.ros__parameters.type``), their parameters, and the update rate.
    ``launch_args``: the values of the file's ``$(var NAME)`` launch substitutions."""
    f = read_controllers_file(text, file, launch_args)
    return f.controllers, f.update_rate, list(f.found)


def read_controllers_file(text: str, file: str, launch_args: Mapping[str, str] | None = None) -> ControllersFile:
    """As read_controllers_text, with where the update rate is written. Each controller is
    located at its own mapping key (its top-level entry, else its entry under
    controller_manager) and carries the places of its parameters (Controller.marks)."""
    doc, _, early = load_substituted(text, file, launch_args)
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
    shape.found += early
    cm_path = ("controller_manager", "ros__parameters")
    cm = shape.mapping(shape.mapping(data.get("controller_manager"), cm_path[:1]).get("ros__parameters"), cm_path)
    types: dict[str, str] = {}
    type_marks: dict[str, tuple[tuple[str, Where], ...]] = {}
    for name, entry in cm.items():
        if isinstance(entry, dict) and "type" in entry:
            types[str(name)] = str(entry["type"])
            type_marks[str(name)] = _marks(doc, {"type": entry["type"]}, (*cm_path, str(name)))
    own: dict[str, dict[str, Any]] = {}
    for name, entry in data.items():
        if name == "controller_manager" or not isinstance(entry, dict) or "ros__parameters" not in entry:
            continue
        own[name] = shape.mapping(entry["ros__parameters"], (name, "ros__parameters"))
        if "type" in own[name] and str(name) not in types:
            types[str(name)] = str(own[name]["type"])
            type_marks[str(name)] = _marks(doc, {"type": own[name]["type"]}, (name, "ros__parameters"))
    for name in own:
        if str(name) not in types:
            # a spawner may give the type (--controller-type), or the file may also hold another
            # node's parameters: not an error, but nothing below checks this entry, so say so
            shape.found.append(
                Finding(
                    "CTRL056",
                    "info",
                    f"'{name}' has ros__parameters but no type (neither its own 'type' nor "
                    f"controller_manager.ros__parameters.{name}.type): it is not read as a controller and "
                    "nothing in it is checked",
                    f"give its type ({name}.ros__parameters.type), or ignore this for another node's "
                    "parameters or a spawner that passes --controller-type",
                    f"controller:{name}",
                    doc.where((name,), key=True),
                )
            )
    controllers = []
    for name, type_ in types.items():
        params = own.get(name, {})
        controllers.append(
            m.Controller(
                name,
                type_,
                shape.params(params, (name, "ros__parameters")),
                # the key that names the controller, not its value (the ros__parameters: line)
                doc.where((name,), key=True) if name in data else doc.where((*cm_path, name), key=True),
                marks=type_marks.get(name, ())
                + _marks(doc, {k: v for k, v in params.items() if k != "type"}, (name, "ros__parameters")),
            )
        )
    rate = cm.get("update_rate")
    rate_where = doc.where((*cm_path, "update_rate"))
    if not isinstance(rate, int | float) or isinstance(rate, bool) or not shape.finite(rate, (*cm_path, "update_rate")):
        return ControllersFile(tuple(controllers), None, rate_where, tuple(shape.found))
    return ControllersFile(tuple(controllers), float(rate), rate_where, tuple(shape.found))
