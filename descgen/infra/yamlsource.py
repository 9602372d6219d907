"""Reading YAML safely while remembering where every key and value stood.

PyYAML's composer gives nodes with marks; we build plain Python data from them and a
table from each path (``("links", 3, "inertial", "mass")``) to its line and column, so
that any later error can point at the YAML node that holds the bad value.

Limits make hostile input fail fast instead of hanging: file size, alias expansion
(a "billion laughs" document references one node exponentially often) and nesting depth.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml

from descgen.codes import Code
from descgen.codes.spec import SPEC005, YAML001, YAML002, YAML003, YAML004, YAML010
from descgen.core.findings import InputError, Where
from descgen.core.record import record
from descgen.infra.safeio import Codes, read_bounded

# Sized for the largest robots descgen answers for: 10,000 links (and their joints). A link
# and its joint written out in full (visual, collision, inertial, sources, limits) are ~1 KB
# and ~100 YAML nodes, so such a spec is ~10 MB and ~1 M nodes (benchmarks/synthetic.py's
# plainer chain: 5 MB, 560,000 nodes).
MAX_BYTES = 16 * 1024 * 1024
# Nodes after alias expansion: the memory of a document (~250 bytes a node, built; ~0.5 GB).
MAX_NODES = 2_000_000
# Nodes that aliases repeat (an alias counts the whole collection it names, before it is built).
# This bound stops a document whose aliases repeat a node exponentially often (a "billion
# laughs": 30 lines that expand to 10^9 nodes) at its first large alias, in milliseconds; 10,000
# aliases of a 10-node geometry are 100,000.
MAX_REPEATED = 500_000


def nodes_hint() -> str:
    return (
        f"descgen reads at most {MAX_NODES:,} YAML nodes, aliases expanded (a 10,000-link spec has about "
        "1,000,000), so that a document cannot exhaust memory; split the file"
    )


def repeated_hint() -> str:
    return (
        f"aliases may repeat at most {MAX_REPEATED:,} YAML nodes: the bound stops aliases that repeat a node "
        "exponentially often (a 'billion laughs') from exhausting memory and time; write out what the aliases repeat"
    )


MAX_DEPTH = 64
DEPTH_HINT = (
    f"descgen reads YAML nested at most {MAX_DEPTH} levels deep; no spec, controllers or MoveIt file needs more"
)

Path_ = tuple[str | int, ...]

# YAML002 cannot read, YAML010 not a regular file (FIFO, device, folder), YAML003 too large
SPEC_CODES = Codes(unreadable=YAML002, not_regular=YAML010, too_large=YAML003)

# libyaml's composer when PyYAML was built with it (marks are the same), else pure Python
_BASE: type[yaml.SafeLoader] = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_STR = "tag:yaml.org,2002:str"
_SEQ = "tag:yaml.org,2002:seq"
_MAP = "tag:yaml.org,2002:map"
_SCALAR = yaml.ScalarNode
_SEQUENCE = yaml.SequenceNode
_IMMUTABLE = frozenset(f"tag:yaml.org,2002:{t}" for t in ("int", "float", "bool", "null"))


class _Loader(_BASE):  # type: ignore[valid-type,misc]
    """The safe loader, remembering each scalar's resolved tag within one document.

    Even libyaml's composer asks PyYAML's Python resolver for the tag of every scalar (regular
    expressions per value, ~40 % of composing a 1000-link spec); a spec repeats its texts ("0",
    "40 mm", "revolute") thousands of times. The tag of a scalar depends only on its text and
    how it was quoted, as long as no path resolver is registered (SafeLoader has none)."""

    def __init__(self, stream: str) -> None:
        super().__init__(stream)
        self._tags: dict[tuple[str, tuple[bool, bool]], str] = {}
        if not self.yaml_path_resolvers:
            # The composer calls these three for every node (~90,000 times on a 1000-link spec).
            # Without path resolvers descend_resolver and ascend_resolver return at once, so
            # builtins that take their arguments and do nothing stand in (an instance
            # attribute is found before the class's method, and is not bound to self), and
            # resolve is a closure over the table, without attribute lookups. With a path
            # resolver registered, PyYAML's own three methods run unchanged.
            self.__dict__.update(
                descend_resolver=slice,  # slice(node, index): a throwaway object, nothing else
                ascend_resolver=tuple,  # tuple(): the empty tuple
                resolve=_remembering(self._tags, super().resolve),
            )


_LOADER: type[yaml.SafeLoader] = _Loader


def _remembering(
    tags: dict[tuple[str, tuple[bool, bool]], str], resolve: Callable[[type[yaml.Node], Any, Any], Any]
) -> Callable[[type[yaml.Node], Any, Any], str]:
    """PyYAML's ``resolve`` without path resolvers, remembering each scalar's tag by its text
    and quoting (a collection's tag is its kind's: BaseResolver's answer with no path resolver)."""

    def remembered(kind: type[yaml.Node], value: Any, implicit: Any) -> str:
        if kind is _SCALAR:
            key = (value, implicit)
            tag = tags.get(key)
            if tag is None:
                tag = tags[key] = str(resolve(kind, value, implicit))
            return tag
        return _SEQ if kind is _SEQUENCE else _MAP

    return remembered


@record
class Document:
    """Parsed YAML data plus the position of every node in it."""

    file: str
    data: Any
    key_marks: dict[Path_, tuple[int, int]]
    value_marks: dict[Path_, tuple[int, int]]
    text: str

    def where(self, path: Path_, key: bool = False) -> Where:
        """The closest known position for ``path`` (walking up to its parents)."""
        p = tuple(path)
        while True:
            table = self.key_marks if key else self.value_marks
            if p in table:
                line, col = table[p]
                return Where(self.file, line, col)
            if key and p in self.value_marks:
                line, col = self.value_marks[p]
                return Where(self.file, line, col)
            if not p:
                return Where(self.file, 1, 1)
            p = p[:-1]
            key = False


def _fail(file: str, message: str, hint: str, line: int = 0, col: int = 0, code: Code = YAML001) -> InputError:
    return InputError([code.finding(message, hint, "file", Where(file, line, col))])


def read_text(path: Path, display: str, what: str = "spec") -> str:
    """The text of a YAML file (``what`` names it in messages: "spec", "trajectory"), refusing
    what cannot be one (type and size are checked before anything is read: a FIFO or
    /dev/zero must not hang the loader)."""
    raw = read_bounded(path, what, MAX_BYTES, display=display, codes=SPEC_CODES)
    if b"\0" in raw:
        raise _fail(display, "binary file (contains NUL bytes), not YAML", f"name a .yaml {what}", code=YAML003)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise _fail(display, f"not UTF-8 text (byte {exc.start})", f"save the {what} as UTF-8", code=YAML003) from None


def load(path: Path, display: str | None = None, what: str = "spec") -> Document:
    display = display or str(path)
    text = read_text(path, display, what)
    return loads(text, display)


def refusal(exc: yaml.YAMLError | RecursionError, text: str, file: str) -> InputError:
    """The error PyYAML raised for ``text`` as descgen reports it: where, and what to do (YAML001);
    every YAML reader of descgen (specs, parameter files) says it the same way."""
    if isinstance(exc, RecursionError):
        return _fail(file, "YAML nested too deeply", DEPTH_HINT)
    if isinstance(exc, yaml.MarkedYAMLError):
        mark = exc.problem_mark or exc.context_mark
        line, col = (mark.line + 1, mark.column + 1) if mark else (0, 0)
        what = " ".join((exc.problem or "malformed YAML").split())  # one line per finding
        if "nesting depth" in what:  # libyaml's own bound (PyYAML 6.0.4 on): the same refusal as ours
            return _fail(file, "YAML nested too deeply", DEPTH_HINT, line, col)
        return _fail(file, f"malformed YAML: {what}", "fix the YAML syntax at this position", line, col)
    if isinstance(exc, yaml.reader.ReaderError):
        line, col = _line_col(text, exc.position)
        char = exc.character if isinstance(exc.character, int) else ord(exc.character or "\0")
        return _fail(
            file,
            f"malformed YAML: unacceptable character #x{char:04x}: {exc.reason}",
            "remove the character, or write it as an escape (\\x1b) inside a double-quoted string",
            line,
            col,
        )
    return _fail(file, f"malformed YAML: {' '.join(str(exc).split())}", "fix the YAML syntax")


def loads(text: str, file: str = "<string>") -> Document:
    try:
        node = yaml.compose(text, Loader=_LOADER)
    except (yaml.YAMLError, RecursionError) as exc:
        raise refusal(exc, text, file) from None
    if node is None:
        raise _fail(file, "the file is empty", "write a robot spec (see specs/warehouse_arm.yaml)", 1, 1, code=YAML004)
    builder = _Builder(file)
    data = builder.build(node, (), 0)
    return Document(file, data, builder.key_marks, builder.value_marks, text)


def _line_col(text: str, position: int) -> tuple[int, int]:
    """1-based line and column of a ReaderError's position: libyaml counts UTF-8 bytes,
    the pure-Python reader counts characters."""
    if _BASE is not yaml.SafeLoader and issubclass(_LOADER, _BASE):
        prefix = text.encode("utf-8")[:position].decode("utf-8", "replace")
    else:
        prefix = text[:position]
    start = prefix.rfind("\n") + 1
    return prefix.count("\n") + 1, len(prefix) - start + 1


class _Builder:
    def __init__(self, file: str) -> None:
        self.file = file
        # a constructor per document: its cache would otherwise keep every node alive
        self.constructor = yaml.SafeLoader("")
        self.key_marks: dict[Path_, tuple[int, int]] = {}
        self.value_marks: dict[Path_, tuple[int, int]] = {}
        self.count = 0
        self.repeated = 0  # nodes that aliases repeat (MAX_REPEATED)
        self.built: set[int] = set()  # collections built once (by id: the composed tree keeps them alive)
        self.sizes: dict[int, int] = {}
        self.aliasing = False  # building a repeated collection
        # (tag, text) -> value of the scalars whose value is immutable and depends only on
        # them: a spec writes "0" thousands of times, and the constructor's path is long
        self.scalars: dict[tuple[str, str], Any] = {}

    def build(self, node: yaml.Node, path: Path_, depth: int) -> Any:
        self.count += 1
        if self.count > MAX_NODES:
            raise _fail(
                self.file,
                f"more than {MAX_NODES:,} YAML nodes after expanding aliases",
                nodes_hint(),
                node.start_mark.line + 1,
                node.start_mark.column + 1,
                code=YAML003,
            )
        if depth > MAX_DEPTH:
            raise _fail(
                self.file,
                "YAML nested too deeply",
                DEPTH_HINT,
                node.start_mark.line + 1,
                node.start_mark.column + 1,
            )
        self.value_marks.setdefault(path, (node.start_mark.line + 1, node.start_mark.column + 1))
        if type(node) is _SCALAR:
            return self.construct(node)
        alias = False
        if id(node) not in self.built:
            self.built.add(id(node))
        elif not self.aliasing:  # an alias of a collection: counted whole before it is built
            self.repeated += self._size(node)
            if self.repeated > MAX_REPEATED:
                raise _fail(
                    self.file,
                    f"more than {MAX_REPEATED:,} YAML nodes repeated through aliases (this collection is one "
                    "they repeat)",
                    repeated_hint(),
                    node.start_mark.line + 1,
                    node.start_mark.column + 1,
                    code=YAML003,
                )
            alias = self.aliasing = True  # the aliases inside it are counted in its size
        if isinstance(node, yaml.MappingNode):
            out: Any = self._mapping(node, path, depth)
        elif isinstance(node, yaml.SequenceNode):
            out = self._sequence(node, path, depth)
        else:
            out = self.construct(node)
        if alias:
            self.aliasing = False
        return out

    # A plain text scalar (most of a spec) is taken by its parent without calling build: what
    # build does with it (count it, record its mark, return its text) while no limit is near
    # (at the limits build raises). ~30 % of building a 1000-link spec is calls and lookups.

    def _sequence(self, node: yaml.SequenceNode, path: Path_, depth: int) -> list[Any]:
        out: list[Any] = []
        marks = self.value_marks
        inline = depth < MAX_DEPTH
        for i, item in enumerate(node.value):
            ipath = (*path, i)
            if inline and type(item) is _SCALAR and item.tag == _STR and self.count < MAX_NODES:
                self.count += 1
                mark = item.start_mark
                marks.setdefault(ipath, (mark.line + 1, mark.column + 1))
                out.append(item.value)
            else:
                out.append(self.build(item, ipath, depth + 1))
        return out

    def _mapping(self, node: yaml.MappingNode, path: Path_, depth: int) -> dict[Any, Any]:
        out: dict[Any, Any] = {}
        key_marks, marks = self.key_marks, self.value_marks
        inline = depth < MAX_DEPTH
        for key_node, value_node in node.value:
            # a plain name (every key of a spec) needs none of _key's checks
            key = key_node.value if type(key_node) is _SCALAR and key_node.tag == _STR else self._key(key_node)
            kpath = (*path, key)
            start = key_node.start_mark
            mark = (start.line + 1, start.column + 1)
            if key in out:
                first = key_marks.get(kpath, (0, 0))
                raise _fail(
                    self.file,
                    f"duplicate key '{key}' (first at line {first[0]})",
                    "remove one of them; YAML would silently keep the last",
                    *mark,
                    code=SPEC005,
                )
            key_marks[kpath] = mark
            if inline and type(value_node) is _SCALAR and value_node.tag == _STR and self.count < MAX_NODES:
                self.count += 1
                vmark = value_node.start_mark
                marks.setdefault(kpath, (vmark.line + 1, vmark.column + 1))
                out[key] = value_node.value
            else:
                out[key] = self.build(value_node, kpath, depth + 1)
        return out

    def _size(self, node: yaml.Node) -> int:
        """The nodes that building ``node`` counts (a mapping's keys are not), each distinct
        collection sized once: linear in the composed document however often aliases repeat.
        Only called for a collection built once already, so its height is within MAX_DEPTH."""
        if type(node) is _SCALAR:
            return 1
        known = self.sizes.get(id(node))
        if known is None:
            items = [v for _, v in node.value] if isinstance(node, yaml.MappingNode) else node.value
            known = self.sizes[id(node)] = 1 + sum(self._size(v) for v in items)
        return known

    def _key(self, key_node: yaml.Node) -> str:
        """A mapping key other than plain text: a merge key and a collection are refused, a
        scalar of another type (``1:``, ``true:``) is named by its text."""
        refused = None
        if key_node.tag == "tag:yaml.org,2002:merge":
            refused = ("YAML merge keys (<<) are not supported", "write the keys out")
        elif not isinstance(key_node, yaml.ScalarNode):
            refused = ("a mapping key must be a plain name", "use a plain name as key")
        if refused is not None:
            raise _fail(self.file, *refused, key_node.start_mark.line + 1, key_node.start_mark.column + 1)
        key = key_node.value if key_node.tag == _STR else self.construct(key_node)
        return key if isinstance(key, str) else str(key_node.value)

    def construct(self, node: yaml.Node) -> Any:
        """A scalar's Python value; explicit tags that cannot be built are errors, not crashes."""
        if node.tag == _STR and isinstance(node, yaml.ScalarNode):
            return node.value  # what SafeConstructor.construct_yaml_str returns, without its bookkeeping
        key = (node.tag, node.value) if node.tag in _IMMUTABLE and isinstance(node, yaml.ScalarNode) else None
        if key is not None and key in self.scalars:
            return self.scalars[key]
        try:
            value = self.constructor.construct_object(node)
            if key is not None:
                self.scalars[key] = value
            return value
        except (yaml.YAMLError, ValueError, TypeError, OverflowError, IndexError, KeyError, AttributeError) as exc:
            what = getattr(exc, "problem", None) or str(exc) or type(exc).__name__
            raise _fail(
                self.file,
                f"cannot read value {node.value!r}: {what}",
                "quote the value or remove its !tag",
                node.start_mark.line + 1,
                node.start_mark.column + 1,
            ) from None
