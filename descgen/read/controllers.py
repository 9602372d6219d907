"""controller_manager YAML -> the model's controllers and update rate, read as ROS reads a
parameter file (descgen/read/params.py: rcl's parser, rclcpp's node matching)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from typing import Any

import yaml

from descgen.codes.read import CTRL056, READ042, READ045, READ046, READ048
from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.core.launch_subst import Site, substitute
from descgen.core.record import record
from descgen.infra.yamlsource import refusal
from descgen.read import params


def _freeze(v: Any) -> object:
    if isinstance(v, dict):
        return tuple((str(k), _freeze(x)) for k, x in v.items())
    if isinstance(v, list):
        return tuple(_freeze(x) for x in v)
    return v


@record
class ControllersFile:
    controllers: tuple[m.Controller, ...]
    update_rate: float | None
    update_rate_where: Where  # the value as written (or the file, when not given)
    found: tuple[Finding, ...]


def read_controllers_text(
    text: str, file: str, launch_args: Mapping[str, str] | None = None
) -> tuple[tuple[m.Controller, ...], float | None, list[Finding]]:
    """Controllers (type from the classic ``controller_manager.ros__parameters.<name>.type``
    or from ``<name>.ros__parameters.type``), their parameters, and the update rate.
    ``launch_args``: the values of the file's ``$(var NAME)`` launch substitutions."""
    f = read_controllers_file(text, file, launch_args)
    return f.controllers, f.update_rate, list(f.found)


@record
class Parsed:
    params: params.ParamFile
    sites: tuple[Site, ...]  # the launch substitutions evaluated
    found: tuple[Finding, ...]
    text: str  # what launch hands to the parser (the file's text when it has no substitution)


def parse_substituted(text: str, file: str, launch_args: Mapping[str, str] | None = None) -> Parsed:
    """The file as ROS loads it (docs/ros2_parameters.md): launch's ``$(var NAME)`` substitutions
    first (``launch_args`` only; core/launch_subst.py), then rcl's parameter parser, every place
    pointing at the file as written. Findings: substitutions left as written (CTRL052/CTRL053),
    what rcl refuses (READ045, the file then reads as nothing) and parameters given twice
    (READ046). A file that is not YAML at all is an InputError (YAML001)."""
    subst = substitute(text, file, launch_args or {})
    try:
        pf = params.parse(subst.text, file, subst.position if subst.sites or subst.findings else None)
    except (yaml.YAMLError, RecursionError) as exc:
        refused = refusal(exc, subst.text, file)
        if subst.sites or subst.findings:  # say where in the file, not in the substituted text
            refused = InputError([_moved(f, subst.position) for f in refused.findings])
        raise refused from None
    found = list(subst.findings)
    for problem in pf.problems:
        if problem.kind == "error":
            found.append(
                READ045.finding(
                    f"ROS does not load this file: {problem.message}",
                    "fix this place; until then the controller manager starts without any of the file",
                    "file",
                    problem.where,
                )
            )
        elif problem.kind == "empty":
            found.append(
                READ048.finding(problem.message, "give the list its values, or delete it", "file", problem.where)
            )
        else:
            found.append(READ046.finding(problem.message, "delete the line that is not meant", "file", problem.where))
    return Parsed(pf, subst.sites, tuple(found), subst.text)


def _moved(f: Finding, position: Callable[[int, int], tuple[int, int]]) -> Finding:
    if not f.where.line:
        return f
    line, col = position(f.where.line, f.where.col or 1)
    return dataclasses.replace(f, where=dataclasses.replace(f.where, line=line, col=col))


@record
class Declared:
    """A controller as the file declares it to the controller manager."""

    name: str
    type: str
    type_param: params.Param  # where its type is written
    where: Where  # its own entry's key, else its key under the controller manager's parameters
    params: dict[str, params.Param]  # its own parameters (type aside), from the entries naming it
    spaces: frozenset[str]  # the parameter namespaces those entries open as mappings (params.nested)


@record
class Manager:
    """The controller manager's view of a parameter file."""

    fqn: str  # /controller_manager, or /<ns>/controller_manager when the file names one namespace
    params: dict[str, params.Param]  # what reaches the controller manager
    controllers: tuple[Declared, ...]
    untyped: tuple[tuple[str, Where], ...]  # entries naming a node that no type makes a controller


def _last(name: str) -> str:
    return name.rsplit("/", 1)[-1]


def manager_view(pf: params.ParamFile) -> Manager:
    """Which controllers the file declares, with their types and own parameters, as the
    controller manager and each controller node receive them (docs/ros2_parameters.md)."""
    named = [n for n in pf.nodes if _last(n.name) == "controller_manager" and "*" not in n.name]
    fqn = named[0].name if named else "/controller_manager"
    ns = fqn.rsplit("/", 1)[0]
    cm = params.resolve(pf, fqn)
    cm_space = {space: key for n in pf.nodes if params.matches(n.name, fqn) for space, key, _ in n.spaces}
    types: dict[str, tuple[str, params.Param, Where]] = {}
    for key, p in cm.items():
        head, dot, tail = key.partition(".")
        if dot and tail == "type":
            types[head] = (str(p.value), p, cm_space.get(head, p.key_where))
    own: dict[str, dict[str, params.Param]] = {}
    own_where: dict[str, Where] = {}
    own_spaces: dict[str, set[str]] = {}
    for node in pf.nodes:
        name = _last(node.name)
        if "*" in name or name == "controller_manager" or not params.matches(node.name, f"{ns}/{name}"):
            continue
        own.setdefault(name, {}).update({p.name: p for p in node.params})
        own_where.setdefault(name, node.where)
        own_spaces.setdefault(name, set()).update(space for space, _, _ in node.spaces)
    for name, ps in own.items():
        if name not in types and "type" in ps:
            types[name] = (str(ps["type"].value), ps["type"], own_where[name])
    controllers = tuple(
        Declared(
            name,
            type_,
            type_param,
            own_where.get(name, where),
            {k: v for k, v in own.get(name, {}).items() if k != "type"},
            frozenset(own_spaces.get(name, ())),
        )
        for name, (type_, type_param, where) in types.items()
    )
    untyped = tuple((name, own_where[name]) for name in own if name not in types)
    return Manager(fqn, cm, controllers, untyped)


def _marks(declared: Declared, spaces: Mapping[str, Where]) -> tuple[tuple[str, Where], ...]:
    """Where each parameter's value (each item of a list value, each parameter namespace) is
    written, so a finding about one joint name points at that name, not at the controller."""
    out: list[tuple[str, Where]] = [("type", declared.type_param.where)]
    for name, p in declared.params.items():
        out.append((name, p.where))
        out += [(f"{name}[{i}]", w) for i, w in enumerate(p.items)]
    out += [(space, w) for space, w in spaces.items() if space not in declared.params]
    return tuple(out)


def _finite(p: params.Param, found: list[Finding]) -> bool:
    """False (and a READ042 finding) for a value, or list item, that is nan or infinite."""
    values = p.value if isinstance(p.value, tuple) else (p.value,)
    places = p.items or (p.where,)
    bad = [w for v, w in zip(values, places, strict=False) if isinstance(v, float) and not math.isfinite(v)]
    for w in bad:
        found.append(
            READ042.finding(
                f"'{p.name}' holds {p.value}, not a finite number", "write a plain decimal number", "file", w
            )
        )
    return not bad


def read_controllers_file(text: str, file: str, launch_args: Mapping[str, str] | None = None) -> ControllersFile:
    """As read_controllers_text, with where the update rate is written. Each controller is
    located at its own entry's key (else its key under the controller manager's parameters)
    and carries the places of its parameters (Controller.marks)."""
    parsed = parse_substituted(text, file, launch_args)
    pf, found = parsed.params, list(parsed.found)
    view = manager_view(pf)
    for name, where in view.untyped:
        # a spawner may give the type (--controller-type), or the file may also hold another
        # node's parameters: not an error, but nothing below checks this entry, so say so
        found.append(
            CTRL056.finding(
                f"'{name}' has ros__parameters but no type (neither its own 'type' nor "
                f"controller_manager.ros__parameters.{name}.type): it is not read as a controller and "
                "nothing in it is checked",
                f"give its type ({name}.ros__parameters.type), or ignore this for another node's "
                "parameters or a spawner that passes --controller-type",
                f"controller:{name}",
                where,
            )
        )
    controllers = []
    for d in view.controllers:
        kept = {k: p for k, p in d.params.items() if _finite(p, found)}  # a non-finite value reads as missing
        spaces = {space: value for n in pf.nodes if _last(n.name) == d.name for space, _, value in n.spaces}
        values = params.nested(kept, d.spaces)
        controllers.append(
            m.Controller(
                d.name,
                d.type,
                tuple((str(k), _freeze(v)) for k, v in values.items()),
                d.where,
                marks=_marks(dataclasses.replace(d, params=kept), spaces),
            )
        )
    rate = view.params.get("update_rate")
    rate_where = rate.where if rate is not None else Where(file, 1, 1)
    value = rate.value if rate is not None else None
    if not isinstance(value, int | float) or isinstance(value, bool) or rate is None or not _finite(rate, found):
        return ControllersFile(tuple(controllers), None, rate_where, tuple(found))
    return ControllersFile(tuple(controllers), float(value), rate_where, tuple(found))
