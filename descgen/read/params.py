"""A ROS 2 parameter file read as ROS reads it: rcl_yaml_param_parser's rules, then rclcpp's
node matching (docs/ros2_parameters.md has the facts with their sources).

- Keys above ``ros__parameters`` name a node: nested keys join with ``/`` (``/**:`` then
  ``controller_manager:`` is the node ``/**/controller_manager``), a leading ``/`` is added.
- A node named twice (two ``/**:`` blocks, common in Jazzy packages) is one node: rcl finds
  it again and adds to it. A parameter given twice keeps its first place and the later value
  (rcl overwrites); descgen reports that as a warning, since one of the two is dead text.
- Nested mappings under ``ros__parameters`` are parameter namespaces: ``gains: {j1: {p: 1}}``
  is the parameter ``gains.j1.p``.
- Values are typed as rcl types them, not as PyYAML does: unquoted ``y``/``n``/``on``/``off``
  are booleans, ``010`` is octal 8, ``0x1F`` is 31, a quoted or ``!!str`` scalar is a string;
  a list holds scalars of one type.
- What rcl refuses (an alias, a value above ``ros__parameters``, an empty value, a list of
  mixed types or of mappings, an invalid node name) makes the whole file unloadable: reported
  as errors, and the file reads as nothing.
- A node's parameters, as rclcpp gives them to the node ``fqn``: every entry whose name
  matches (``/*`` one token, ``/**`` any number), in the order the entries first appear,
  a later entry's value winning (:func:`resolve`)."""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Collection, Iterator
from typing import Any

import yaml

from descgen.core.findings import Where
from descgen.core.record import record

PARAMS_KEY = "ros__parameters"
MAX_DEPTH = 64  # nested mappings: no real file comes near; the reader recurses once per level
Scalar = bool | int | float | str
Value = Scalar | tuple[Scalar, ...]


@record
class Param:
    name: str  # dotted, as rcl names it
    value: Value
    where: Where  # the value as written (a list: its first item)
    key_where: Where
    items: tuple[Where, ...] = ()  # each list item as written


@record
class Node:
    name: str  # as rclcpp sees it: leading '/', wildcards kept
    where: Where  # the key that first named it (the last one above ros__parameters)
    params: tuple[Param, ...]  # first-appearance order; a repeated parameter has the later value
    # each parameter namespace ("gains", "gains.j1"): where its key and its value are first written
    spaces: tuple[tuple[str, Where, Where], ...] = ()

    @property
    def wildcard(self) -> bool:
        return "*" in self.name

    def get(self, name: str) -> Param | None:
        return next((p for p in self.params if p.name == name), None)


@record
class Problem:
    """What rcl refuses (``error``: the file does not load), what rclcpp refuses for the nodes it
    reaches (``empty``: a parameter without a value), or what is dead text (``twice``)."""

    kind: str  # "error" | "empty" | "twice"
    message: str
    where: Where


@record
class ParamFile:
    file: str
    nodes: tuple[Node, ...]
    problems: tuple[Problem, ...]

    @property
    def loads(self) -> bool:
        return not any(p.kind == "error" for p in self.problems)


# -- values, typed as rcl_yaml_param_parser's get_value types them -------------------------------

_TRUE = {"Y", "y", "yes", "Yes", "YES", "true", "True", "TRUE", "on", "On", "ON"}
_FALSE = {"N", "n", "no", "No", "NO", "false", "False", "FALSE", "off", "Off", "OFF"}
_SPECIAL = {".nan", ".NaN", ".NAN", ".inf", ".Inf", ".INF", "+.inf", "+.Inf", "+.INF", "-.inf", "-.Inf", "-.INF"}
# strtoll(value, &end, 0) consuming the whole text: optional sign, then hex, octal or decimal
_INT = re.compile(r"[ \t\n\v\f\r]*([+-]?)(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)")
# strtod consuming the whole text: decimal with optional exponent, hex float, inf/infinity, nan(...)
_FLOAT = re.compile(
    r"[ \t\n\v\f\r]*[+-]?(?:"
    r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
    r"|0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?[0-9]+)?"
    r"|[iI][nN][fF](?:[iI][nN][iI][tT][yY])?"
    r"|[nN][aA][nN](?:\([0-9A-Za-z_]*\))?)"
)
_INT64 = (-(2**63), 2**63 - 1)


def typed(value: str, quoted: bool, str_tag: bool) -> Scalar:
    """A scalar as rcl types it (parse.c, get_value)."""
    if str_tag or quoted:
        return value
    if value in _TRUE:
        return True
    if value in _FALSE:
        return False
    m = _INT.fullmatch(value)
    if m:
        digits = m.group(2)
        base = 16 if digits[:2].lower() == "0x" else 8 if digits.startswith("0") and len(digits) > 1 else 10
        n = int(digits, base) * (-1 if m.group(1) == "-" else 1)
        if _INT64[0] <= n <= _INT64[1]:  # else strtoll sets ERANGE: not an integer
            return n
    if value in _SPECIAL:
        body = value.lstrip("+-.").lower()
        return math.nan if body == "nan" else (-math.inf if value.startswith("-") else math.inf)
    if _FLOAT.fullmatch(value):
        text = value.strip(" \t\n\v\f\r")
        try:
            f = float.fromhex(text) if "x" in text.lower() else float(re.sub(r"\(.*\)", "", text))
        except ValueError:
            return value
        if not math.isinf(f) or "inf" in text.lower():  # strtod overflow sets ERANGE: a string
            return f
    return value


# -- the event tree (PyYAML's parser: the same events libyaml gives rcl) -------------------------


def _events(text: str) -> Iterator[yaml.Event]:
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    return iter(yaml.parse(text, Loader=loader))


def parse(text: str, file: str, position: Callable[[int, int], tuple[int, int]] | None = None) -> ParamFile:
    """The file's nodes and parameters as rcl reads them. ``position`` maps a (line, column) of
    ``text`` back to the file as written (after launch substitutions). A file PyYAML cannot
    parse raises yaml.YAMLError (the caller reports it as it reports any YAML error)."""
    state = _State(file, position or (lambda line, col: (line, col)))
    events = _events(text)
    for event in events:
        if isinstance(event, yaml.MappingStartEvent):
            state.node_level(events, (), None)
        elif isinstance(event, yaml.SequenceStartEvent | yaml.ScalarEvent | yaml.AliasEvent):
            state.error(event, "a parameter file is a mapping of node names")
            _skip(events, event)
    nodes = tuple(
        Node(
            name,
            state.node_where[name],
            tuple(state.params[name].values()),
            tuple((space, k, v) for space, (k, v) in state.spaces[name].items()),
        )
        for name in state.order
        if not state.refused
    )
    return ParamFile(file, nodes if not state.refused else (), tuple(state.problems))


def _skip(events: Iterator[yaml.Event], start: yaml.Event) -> None:
    if isinstance(start, yaml.MappingStartEvent | yaml.SequenceStartEvent):
        depth = 1
        for e in events:
            if isinstance(e, yaml.MappingStartEvent | yaml.SequenceStartEvent):
                depth += 1
            elif isinstance(e, yaml.MappingEndEvent | yaml.SequenceEndEvent):
                depth -= 1
                if depth == 0:
                    return


_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*|\*\*?")


def _valid_name(name: str) -> bool:
    """rcl's _validate_name: '/**' and '/*' as they are, else every namespace token and the
    node name a ROS name (letters, digits, underscores, not starting with a digit) or a wildcard."""
    if name in ("/**", "/*"):
        return True
    tokens = name.lstrip("/").split("/")
    return all(_TOKEN.fullmatch(t) for t in tokens)


class _State:
    def __init__(self, file: str, position: Callable[[int, int], tuple[int, int]]) -> None:
        self.file = file
        self.position = position
        self.order: list[str] = []
        self.node_where: dict[str, Where] = {}
        self.params: dict[str, dict[str, Param]] = {}
        self.spaces: dict[str, dict[str, tuple[Where, Where]]] = {}
        self.problems: list[Problem] = []
        self.refused = False

    def where(self, event: yaml.Event) -> Where:
        mark = event.start_mark
        if mark is None:  # PyYAML's parser marks every event; a stand-in keeps the finding
            return Where(self.file, 1, 1)
        line, col = self.position(mark.line + 1, mark.column + 1)
        return Where(self.file, line, col)

    def error(self, event: yaml.Event, message: str) -> None:
        self.refused = True
        self.problems.append(Problem("error", message, self.where(event)))

    def node_level(self, events: Iterator[yaml.Event], path: tuple[str, ...], named: Where | None) -> None:
        """Inside a mapping above ros__parameters: keys extend the node name."""
        for key in events:
            if isinstance(key, yaml.MappingEndEvent):
                return
            if not isinstance(key, yaml.ScalarEvent):
                self.error(key, "a node name must be a plain key")
                _skip(events, key)
                _skip(events, next(events))
                continue
            value = next(events)
            if key.value.startswith(PARAMS_KEY):  # rcl compares the prefix (strncmp)
                self.params_key(events, key, value, path, named)
            elif isinstance(value, yaml.MappingStartEvent) and len(path) >= MAX_DEPTH:
                self.error(value, f"mappings nested more than {MAX_DEPTH} deep")
                _skip(events, value)
            elif isinstance(value, yaml.MappingStartEvent):
                self.node_level(events, (*path, key.value), self.where(key))
            else:
                self.error(value, f"'{key.value}' holds a value, but no {PARAMS_KEY} key above it names its node")
                _skip(events, value)

    def params_key(
        self,
        events: Iterator[yaml.Event],
        key: yaml.ScalarEvent,
        value: yaml.Event,
        path: tuple[str, ...],
        named: Where | None,
    ) -> None:
        if not path:
            self.error(key, f"{PARAMS_KEY} with no node name above it")
            _skip(events, value)
            return
        name = "/".join(path)
        name = name if name.startswith("/") else "/" + name
        if not _valid_name(name):
            self.error(key, f"'{name}' is not a valid node name (letters, digits, _, and the wildcards * and **)")
            _skip(events, value)
            return
        if name not in self.params:
            self.order.append(name)
            self.params[name] = {}
            self.spaces[name] = {}
            self.node_where[name] = named or self.where(key)  # the key that names the node
        if isinstance(value, yaml.MappingStartEvent):
            self.param_level(events, name, ())
        elif not (isinstance(value, yaml.ScalarEvent) and value.value == ""):
            self.error(value, f"{PARAMS_KEY} of '{name}' must be a mapping of parameters")
            _skip(events, value)

    def param_level(self, events: Iterator[yaml.Event], node: str, prefix: tuple[str, ...]) -> None:
        for key in events:
            if isinstance(key, yaml.MappingEndEvent):
                return
            value = next(events)
            if not isinstance(key, yaml.ScalarEvent):
                self.error(key, "a parameter name must be a plain key")
                _skip(events, key)
                _skip(events, value)
                continue
            if key.value == "":
                self.error(key, "an empty parameter name: ROS loads no file with one")
                _skip(events, value)
                continue
            if isinstance(value, yaml.MappingStartEvent) and len(prefix) >= MAX_DEPTH:
                self.error(value, f"mappings nested more than {MAX_DEPTH} deep")
                _skip(events, value)
                continue
            if isinstance(value, yaml.MappingStartEvent):  # its value starts at the first inner key
                self.spaces[node].setdefault(".".join((*prefix, key.value)), (self.where(key), self.where(value)))
                self.param_level(events, node, (*prefix, key.value))
                continue
            name = ".".join((*prefix, key.value))
            param = self.param_value(events, name, key, value)
            if param is None:
                continue
            before = self.params[node].get(name)
            if before is not None:
                self.problems.append(
                    Problem(
                        "twice",
                        f"parameter '{name}' of node '{node}' is given twice (also at line {before.key_where.line}):"
                        " ROS keeps the later value",
                        param.key_where,
                    )
                )
            self.params[node][name] = param

    def param_value(
        self, events: Iterator[yaml.Event], name: str, key: yaml.ScalarEvent, value: yaml.Event
    ) -> Param | None:
        if isinstance(value, yaml.AliasEvent):
            self.error(value, f"'{name}' is a YAML alias: ROS does not load aliases")
            return None
        if isinstance(value, yaml.ScalarEvent):
            quoted = value.style in ("'", '"')
            if value.value == "" and not quoted:
                self.error(value, f"'{name}' has no value")
                return None
            v = typed(value.value, quoted, value.tag == "tag:yaml.org,2002:str")
            return Param(name, v, self.where(value), self.where(key))
        if isinstance(value, yaml.SequenceStartEvent):
            items: list[Scalar] = []
            wheres: list[Where] = []
            refused = False
            for item in events:
                if isinstance(item, yaml.SequenceEndEvent):
                    break
                if not isinstance(item, yaml.ScalarEvent):
                    what = "aliases" if isinstance(item, yaml.AliasEvent) else "lists or mappings"
                    self.error(item, f"'{name}' is a list of {what}: ROS loads lists of plain values only")
                    _skip(events, item)
                    refused = True
                    continue
                quoted = item.style in ("'", '"')
                items.append(typed(item.value, quoted, item.tag == "tag:yaml.org,2002:str"))
                wheres.append(self.where(item))
            if refused:
                return None
            if not items:  # rcl keeps it without a value; rclcpp refuses it for each node it reaches
                self.problems.append(
                    Problem(
                        "empty",
                        f"'{name}' is an empty list: rclcpp refuses a parameter without a value "
                        '("No parameter value set"), so no node it reaches starts',
                        self.where(value),
                    )
                )
            kinds = {type(x) for x in items}
            if len(kinds) > 1:
                mixed = ", ".join(sorted(k.__name__ for k in kinds))
                self.error(value, f"'{name}' mixes {mixed} in one list: ROS loads a list of one type")
                return None
            return Param(name, tuple(items), wheres[0] if wheres else self.where(value), self.where(key), tuple(wheres))
        self.error(value, f"'{name}' has a value ROS cannot load")
        _skip(events, value)
        return None


# -- which entries reach a node, as rclcpp gives them ---------------------------------------------


def matches(entry: str, fqn: str) -> bool:
    """rclcpp's is_node_name_matched: '/*' becomes one '/token', '/**' any number of them."""
    # the entry is a valid name (letters, digits, _, /, *), so nothing else in it is a regex
    return re.fullmatch(entry.replace("/*", r"(/\w+)"), fqn, re.ASCII) is not None


def resolve(pf: ParamFile, fqn: str) -> dict[str, Param]:
    """The parameters node ``fqn`` is given: every matching entry in first-appearance order, a
    later entry's value replacing an earlier one's (rclcpp resolve_parameter_overrides)."""
    out: dict[str, Param] = {}
    for node in pf.nodes:
        if matches(node.name, fqn):
            for p in node.params:
                out[p.name] = p
    return out


def nested(params: dict[str, Param], spaces: Collection[str] = ()) -> dict[str, Any]:
    """Parameters in the shape the file wrote them: a dotted name becomes nested mappings where
    the file opened a mapping (``spaces``: ``gains: {p: 1}`` -> {gains: {p: 1}}), and stays one
    key where the file wrote the dots (``linear.x.max_velocity: 1.0``); both are the same
    parameter to ROS. Values as plain Python (a list for a list)."""
    out: dict[str, Any] = {}
    for name, p in params.items():
        parts = name.split(".")
        at, start = out, 0
        for i in range(1, len(parts)):
            prefix = ".".join(parts[:i])
            if prefix in spaces:
                key = ".".join(parts[start:i])
                nxt = at.setdefault(key, {})
                if not isinstance(nxt, dict):  # 'a: 1' and 'a: {b: 2}' in one node: the first keeps its place
                    break
                at, start = nxt, i
        else:
            at[".".join(parts[start:])] = list(p.value) if isinstance(p.value, tuple) else p.value
    return out
