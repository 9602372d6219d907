"""Expand a Xacro in process with the PyPI ``xacro`` package, as data.

xacro runs ``${...}`` and ``$(eval ...)`` through Python's ``eval`` and lets a file read any
file and environment variable (docs/reference/xacro.md, "Security"). An audited Xacro is someone
else's file, so by default it is expanded in a sandbox: xacro still does the XML work
(properties, macros, includes, conditionals), but

- expressions go through :mod:`descgen.read.xacro_eval` (no code, bounded numbers);
- includes, ``xacro.load_yaml`` and ``$(find)`` reach only the file's own package (the
  nearest folder holding a package.xml, else the file's folder) and ``--package-path``
  folders, and only regular files of bounded size;
- ``$(env)``/``$(optenv)`` see only :data:`ENV_ALLOWED`, and ``$(cwd)`` is refused;
- macro calls, produced text and time are bounded.

``trusted=True`` (``--trust-xacro``) uses xacro's own evaluator for files the user trusts;
only ``$(find)`` is still answered from ``--package-path``, since there is no ament index.
xacro keeps its state in module globals, so one expansion runs at a time.

In both modes every element of the expanded document also gets the place it was written
(:func:`expand_located`): xacro's minidom keeps no line numbers, so its files are parsed by
an expat builder that records file, line and column as DOM user data (which minidom copies
onto clones of macro bodies and blocks, and never serialises), and each macro call adds
its call site to the elements its body produced.
"""

from __future__ import annotations

import contextlib
import os
import re
import threading
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any
from xml.dom import Node, expatbuilder

from descgen.codes.read import READ004, READ030, READ031, READ032, READ033
from descgen.core.findings import Finding, InputError, Where
from descgen.infra import collector
from descgen.meshes.packages import find_package as find_package  # re-exported: importer, simulate
from descgen.meshes.packages import manifest_name
from descgen.read import xacro_eval as xe

_LOCK = threading.RLock()
_PACKAGE_NAME = re.compile(r"[a-zA-Z0-9][a-zA-Z0-9_-]+")

ENV_ALLOWED = frozenset({"ROS_DISTRO", "ROS_VERSION", "ROS_PYTHON_VERSION"})
"""Environment variables an audited Xacro may read: they say which ROS it is for, nothing
about the machine or the user."""

MAX_FILE_BYTES = 16 * 1024 * 1024  # one Xacro, include or YAML file
MAX_MACRO_CALLS = 20_000
# elements walked or skipped: a 1000-link robot has ~20,000. Without a bound, macros of empty
# elements grow the document until the clock runs out (500,000 took ~20 s and ~470 MB)
MAX_ELEMENTS = 200_000
MAX_TEXT = 50 * 1024 * 1024  # characters of all evaluated text together
MAX_SECONDS = 30.0

_CODES = {"expression": READ030, "file": READ031, "environment": READ032, "limit": READ033}
_HINTS = {
    "expression": "audited Xacro is expanded with a restricted evaluator (docs/security.md); "
    "if you trust this file, pass --trust-xacro",
    "file": "an audited Xacro may read files only in its own package and the --package-path folders; "
    "add the package's folder with --package-path",
    "environment": "pass the value with --xacro-arg if the file takes it as an argument, or --trust-xacro "
    "if you trust the file",
    "limit": "real descriptions stay far below these limits; if you trust this file, pass --trust-xacro",
}


def package_root(start: Path) -> Path:
    """The nearest folder at or above ``start`` holding a package.xml, else ``start``."""
    for folder in (start, *start.parents):
        if (folder / "package.xml").is_file():
            return folder
    return start


@dataclass
class _Sandbox:
    roots: tuple[Path, ...]
    deadline: float
    budget: xe.Budget = field(default_factory=xe.Budget)
    macro_calls: int = 0
    elements: int = 0
    text: int = 0
    refusal: _Refusal | None = None


@dataclass
class _Refusal:
    error: xe.RefusedError
    file: str | None
    needle: str


def _confine(box: _Sandbox, filename: str, what: str) -> str:
    """``filename`` if it is a regular, bounded file inside the sandbox's folders."""
    real = Path(os.path.realpath(filename))
    if not any(real.is_relative_to(root) for root in box.roots):
        raise xe.RefusedError(f"{what} '{filename}' is outside the folders this Xacro may read", "file")
    try:
        st = real.stat()
    except OSError as exc:
        raise xe.RefusedError(f"{what} '{filename}' cannot be read: {exc.strerror}", "file") from None
    import stat

    if not stat.S_ISREG(st.st_mode):
        raise xe.RefusedError(f"{what} '{filename}' is not a regular file", "file")
    if st.st_size > MAX_FILE_BYTES:
        raise xe.RefusedError(f"{what} '{filename}' is larger than {MAX_FILE_BYTES // 2**20} MiB", "limit")
    with open(real, "rb") as fh:
        if b"<!DOCTYPE" in fh.read(MAX_FILE_BYTES) and what == "include":
            raise xe.RefusedError(f"{what} '{filename}' has a DOCTYPE (entities are not allowed in an audited Xacro)")
    return str(real)


def _globals(box: _Sandbox) -> tuple[dict[str, Any], frozenset[int]]:
    """The symbol table an expression starts from, and the ids of every callable in it."""
    import xacro

    def load_yaml(filename: str) -> Any:
        return xacro.load_yaml(_confine(box, xacro.abs_filename_spec(filename), "YAML file"))

    def namespace(items: Mapping[str, Any]) -> Any:
        ns = xacro.NameSpace()
        ns.update(items)
        return ns

    original = xacro._global_symbols["xacro"]
    original_python = dict(xacro._global_symbols["python"])
    helpers = {
        "load_yaml": load_yaml,
        "dotify": xacro.YamlDictWrapper,
        "abs_filename": xacro.abs_filename_spec,
        "arg": original["arg"],
        "tokenize": xacro.tokenize,
        **{k: original[k] for k in ("message", "warning", "error", "fatal", "print_location") if k in original},
    }
    maths = xe.math_names()
    top: dict[str, Any] = {k: v for k, v in xacro._global_symbols.items() if k not in ("python", "math", "xacro")}
    top.update({k: xe.BUILTINS[k] for k in ("list", "dict", "map", "len", "str", "float", "int")})
    top.update({k: xe.BUILTINS[k] for k in ("bool", "min", "max", "round", "sorted", "range")})
    top.update(dotify=xacro.YamlDictWrapper, abs_filename=xacro.abs_filename_spec)
    top.update(maths)
    top.update(
        {
            "True": True,
            "False": False,
            "load_yaml": load_yaml,
            # xacro's other builtins stay visible so that using one is refused by name (not "undefined")
            "python": namespace({**original_python, **xe.BUILTINS}),
            "math": namespace(maths),
            "xacro": namespace(helpers),
        }
    )
    allowed = frozenset(
        id(v) for table in (top, xe.BUILTINS, maths, helpers) for v in table.values() if callable(v)
    ) | frozenset({id(xacro.YamlDictWrapper), id(xacro.YamlListWrapper)})
    return top, allowed


def _eval_names(box: _Sandbox, context: dict[str, Any]) -> tuple[Mapping[str, Any], frozenset[int]]:
    """The names ``$(eval ...)`` sees in xacro: arg(), find(), env(), optenv(), dirname(),
    math, and the substitution args themselves."""
    import xacro.substitution_args as sa

    args = context.setdefault("arg", {})

    def arg(name: str) -> Any:
        return sa.convert_value(sa._eval_arg(name, args=args), "auto")

    def dirname() -> str:
        return sa._eval_dirname(context.get("filename"))  # type: ignore[no-any-return]

    functions: dict[str, Any] = {
        "true": True,
        "false": False,
        "True": True,
        "False": False,
        "arg": arg,
        "dirname": dirname,
        "env": sa._eval_env,
        "optenv": sa._eval_optenv,
        "find": sa._eval_find,
        **xe.math_names(),
        **{k: xe.BUILTINS[k] for k in ("list", "dict", "map", "str", "float", "int")},
    }

    class Names(Mapping[str, Any]):
        def __getitem__(self, key: str) -> Any:
            if key in functions:
                return functions[key]
            return sa.convert_value(args[key], "auto")

        def __iter__(self) -> Iterator[str]:
            return iter({**args, **functions})

        def __len__(self) -> int:
            return len({**args, **functions})

    return Names(), frozenset(id(v) for v in functions.values() if callable(v))


def _refuse(box: _Sandbox, error: xe.RefusedError, needle: str) -> xe.RefusedError:
    import xacro

    if box.refusal is None:
        box.refusal = _Refusal(error, xacro.filestack[-1] if xacro.filestack else None, needle)
    return error


def _count_elements(box: _Sandbox, n: int, needle: str) -> None:
    box.elements += n
    if box.elements > MAX_ELEMENTS:
        raise _refuse(box, xe.RefusedError(f"more than {MAX_ELEMENTS} elements", "limit"), needle)


def _tick(box: _Sandbox) -> None:
    if time.monotonic() > box.deadline:
        raise xe.RefusedError(f"expanding this Xacro took longer than {MAX_SECONDS:g} s", "limit")


@contextlib.contextmanager
def _patched(obj: Any, **attrs: Any) -> Iterator[None]:
    saved = {k: getattr(obj, k) for k in attrs}
    for k, v in attrs.items():
        setattr(obj, k, v)
    try:
        yield
    finally:
        for k, v in saved.items():
            setattr(obj, k, v)


@contextlib.contextmanager
def _find_from(package_paths: Sequence[Path], symbolic: bool = False, own: Path | None = None) -> Iterator[None]:
    """``$(find pkg)`` answered by the one package order (descgen/meshes/packages.py): the
    folders given (--package-path, then the sourced environment's), then ``own``, the file's
    own package (the nearest folder above it holding a package.xml), by the name it gives."""
    import xacro.substitution_args as sa

    def eval_find(pkg: str) -> str:
        # ament_index_python refuses other names too; "..", "/" must not walk out of the folders
        if not _PACKAGE_NAME.fullmatch(pkg):
            raise LookupError(f"'{pkg}' is not a package name")
        found = find_package(pkg, package_paths)
        if found is None and own is not None and manifest_name(own / "package.xml") == pkg:
            found = own
        if found is None and symbolic:
            return f"$(find {pkg})"  # as the plain URDF writes it (descgen/spec/passthrough.py)
        if found is None:
            raise LookupError(
                f"package '{pkg}' is in no --package-path folder ({', '.join(map(str, package_paths)) or 'none'}), "
                "no sourced workspace (AMENT_PREFIX_PATH, ROS_PACKAGE_PATH) and is not the file's own package"
            )
        return str(found.resolve())

    with _patched(sa, _eval_find=eval_find), _patched_item(sa._eval_dict, "find", eval_find):
        yield


@contextlib.contextmanager
def _patched_item(table: dict[str, Any], key: str, value: Any) -> Iterator[None]:
    saved = table.get(key)
    table[key] = value
    try:
        yield
    finally:
        table[key] = saved


@contextlib.contextmanager
def _sandboxed(box: _Sandbox) -> Iterator[None]:
    """xacro with every door to code, files and the environment replaced (see module doc)."""
    import xacro
    import xacro.substitution_args as sa

    symbols, allowed = _globals(box)
    original_eval_text = xacro.eval_text
    original_extension = xacro.eval_extension
    original_macro_call = xacro.handle_macro_call

    def safe_eval(expr: str, names: Any, locals_: Any = None) -> Any:
        _tick(box)
        try:
            return xe.Evaluator(names, allowed, box.budget).run(expr)
        except xe.RefusedError as exc:
            raise _refuse(box, exc, expr) from None

    def eval_dollar(s: str, context: dict[str, Any]) -> str:
        names, fns = _eval_names(box, context)
        try:
            return str(xe.Evaluator(names, fns, box.budget).run(s))
        except xe.RefusedError as exc:
            raise _refuse(box, exc, s) from None

    def env(name: str) -> str:
        if name not in ENV_ALLOWED:
            raise _refuse(
                box,
                xe.RefusedError(
                    f"$(env {name}): an audited Xacro may read only {', '.join(sorted(ENV_ALLOWED))}", "environment"
                ),
                f"env {name}",
            )
        return sa.os.environ[name]  # type: ignore[no-any-return]  # KeyError: unset, as in xacro

    def optenv(name: str, default: str = "") -> str:
        # not on the allow-list: read as unset, so the file's own default applies
        return os.environ.get(name, default) if name in ENV_ALLOWED else default

    def eval_extension(s: str) -> Any:
        _tick(box)
        if s.strip() == "$(cwd)":
            raise _refuse(box, xe.RefusedError("$(cwd) is not available to an audited Xacro", "environment"), "$(cwd)")
        return original_extension(s)

    def eval_text(text: Any, symbols: Any) -> Any:  # xacro passes symbols= by name (xacro:element)
        _tick(box)
        # xacro's lexer reads a str without '$' as one TEXT token and returns it unchanged
        # (the empty str too): the same value, without a lexer per attribute and text node
        out = text if type(text) is str and "$" not in text else original_eval_text(text, symbols)
        if isinstance(out, str):
            box.text += len(out)
            if len(out) > xe.MAX_SIZE or box.text > MAX_TEXT:
                raise _refuse(box, xe.RefusedError("this Xacro produces more text than an audit reads", "limit"), "")
        return out

    def handle_macro_call(node: Any, macros: Any, names: Any) -> Any:
        # xacro asks this of every element it walks; only a xacro:* tag is a call (xacro returns
        # False for the rest), so only those count: a plain 20,000-element URDF is no bomb
        if not node.tagName.startswith("xacro:"):
            _count_elements(box, 1, node.tagName)
            return original_macro_call(node, macros, names)
        box.macro_calls += 1
        _tick(box)
        if box.macro_calls > MAX_MACRO_CALLS:
            raise _refuse(
                box, xe.RefusedError(f"more than {MAX_MACRO_CALLS} macro calls", "limit"), node.tagName if node else ""
            )
        return original_macro_call(node, macros, names)

    def get_include_files(filename_spec: str, names: Any) -> Iterator[str]:
        spec = xacro.abs_filename_spec(str(original_eval_text(filename_spec, names)))
        if re.search("[*[?]+", spec):
            head = Path(re.split("[*[?]", spec, maxsplit=1)[0]).parent
            if not any(Path(os.path.realpath(head)).is_relative_to(r) for r in box.roots):
                raise _refuse(
                    box,
                    xe.RefusedError(f"include '{spec}' is outside the folders this Xacro may read", "file"),
                    filename_spec,
                )
        for filename in xacro.__dict__["_original_get_include_files"](filename_spec, names):
            try:
                yield _confine(box, filename, "include")
            except xe.RefusedError as exc:
                raise _refuse(box, exc, filename_spec) from None

    xacro.__dict__.setdefault("_original_get_include_files", xacro.get_include_files)
    with contextlib.ExitStack() as stack:
        stack.enter_context(
            _patched(
                xacro,
                _global_symbols=symbols,
                safe_eval=safe_eval,
                eval_text=eval_text,
                eval_extension=eval_extension,
                handle_macro_call=handle_macro_call,
                get_include_files=get_include_files,
            )
        )
        stack.enter_context(_patched(sa, _eval=eval_dollar, _eval_env=env, _eval_optenv=optenv))
        yield


def _line_of(file: str | None, needle: str) -> tuple[int, int]:
    if not file or not needle:
        return 0, 0
    try:
        text = Path(file).read_text(encoding="utf-8", errors="replace")
    except OSError:
        return 0, 0
    from xml.sax.saxutils import escape

    # the expression was read from XML: look for it as written there too
    plain = needle.strip()
    forms = (plain, escape(plain), escape(plain, {'"': "&quot;"}), escape(plain, {"'": "&apos;"}))
    idx = next((i for i in (text.find(f) for f in forms) if i >= 0), -1)
    if idx < 0:
        return 0, 0
    line = text.count("\n", 0, idx) + 1
    return line, idx - (text.rfind("\n", 0, idx) + 1) + 1


@dataclass(frozen=True)
class Expansion:
    """An expanded Xacro and where each of its elements was written.

    ``sources[i]`` is the i-th element of ``xml`` in document order (the root first, as
    lxml's ``root.iter()`` yields elements): the file, line and column of its start tag,
    with ``via`` the macro calls that produced it, innermost first. None where unknown."""

    xml: bytes
    sources: tuple[Where | None, ...]


def expand(
    path: Path,
    display: str,
    mappings: Mapping[str, str] | None = None,
    package_paths: Sequence[Path] = (),
    trusted: bool = False,
    symbolic_find: bool = False,
) -> bytes:
    """The expanded XML of a Xacro file, or an InputError saying why it was refused.

    Same sandbox, without recording where each element was written (nobody asks here; on a
    1000-link Xacro the bookkeeping is ~15 % of the expansion). ``symbolic_find``: a
    ``$(find pkg)`` of a package not in ``package_paths`` expands to itself (the proof of a
    generated package, whose plain URDF keeps it so)."""
    return expand_located(
        path, display, mappings, package_paths, trusted, locate=False, symbolic_find=symbolic_find
    ).xml


def expand_located(
    path: Path,
    display: str,
    mappings: Mapping[str, str] | None = None,
    package_paths: Sequence[Path] = (),
    trusted: bool = False,
    locate: bool = True,
    symbolic_find: bool = False,
) -> Expansion:
    """:func:`expand`, and where each element of the result was written. ``display`` names
    the top file; an included file is named relative to it when it lies beside or below it.
    With ``locate=False`` the sources are empty (and xacro parses with its own parser)."""
    import xacro

    top = Path(os.path.realpath(path))
    roots = tuple(dict.fromkeys([package_root(top.parent), *(Path(os.path.realpath(p)) for p in package_paths)]))
    box = _Sandbox(roots, time.monotonic() + MAX_SECONDS)
    with _LOCK:
        try:
            if not trusted:
                _confine(box, str(top), "include")
            with contextlib.ExitStack() as stack:
                stack.enter_context(_find_from(package_paths, symbolic_find, None if symbolic_find else roots[0]))
                if not trusted:
                    stack.enter_context(_sandboxed(box))
                if locate:
                    stack.enter_context(_locating(_namer(top, display)))
                stack.enter_context(_skipping_static(None if trusted else box))
                doc = xacro.process_file(str(path), mappings=dict(mappings or {}))
                text = to_xml(doc)
                sources = _sources(doc.documentElement) if locate else ()
                # minidom's nodes point at each other: freed now, not by a later collection. Leaving
                # them to the collector while it is paused (the CLI) was slower, not faster: the
                # collection at interpreter exit traverses them (+0.08 s, +14 MB at 1000 links)
                release(doc)
        except xe.RefusedError as exc:
            box.refusal = box.refusal or _Refusal(exc, str(top), "")
            raise InputError([_refusal_finding(box.refusal, top, display)]) from None
        except Exception as exc:  # xacro raises XacroException, XML errors, lookup errors, ...
            if box.refusal is not None:
                raise InputError([_refusal_finding(box.refusal, top, display)]) from None
            message = " ".join(str(exc).split()) or type(exc).__name__
            raise InputError(
                [
                    READ004.finding(
                        f"xacro could not expand the file: {message}",
                        "pass --xacro-arg name:=value for its arguments and --package-path for $(find)",
                        "file",
                        Where(display),
                    )
                ]
            ) from None
    return Expansion(text.encode("utf-8"), sources)


def release(doc: Any) -> None:
    """What ``doc.unlink()`` does for memory, in a third of its time: cut every reference
    that makes a cycle (a parent's child list, which its children point back from; a node's
    siblings, which point back at it; an element's attributes, which name their element), so
    that reference counting frees the whole tree when the document goes; and, as unlink
    does, its parent, so that a node xacro detached (and left in a cycle of its own, pointing
    at a sibling) keeps no more of the tree alive than after unlink. minidom's unlink also
    empties each attribute and clears what no cycle needs, one method call per node
    (~100,000 on a 1000-link Xacro). tests/test_xacro_release.py compares the two."""
    from xml.dom.minicompat import NodeList

    stack = [doc]
    while stack:
        node = stack.pop()
        children = node.childNodes
        if children:
            stack.extend(children)
            node.childNodes = NodeList()
        node.parentNode = node.previousSibling = node.nextSibling = None
        if node.nodeType == _ELEMENT:
            node._attrs = node._attrsNS = None
    doc._id_cache, doc._id_search_stack = {}, None  # getElementById's memo and the walk it paused


# --- the expanded document as text ----------------------------------------------------------


class _Appender:
    """A writer (what minidom's ``writexml`` methods write to) that collects the pieces."""

    __slots__ = ("write",)

    def __init__(self, out: list[str]) -> None:
        self.write = out.append


def to_xml(doc: Any) -> str:
    """``doc.toxml()``, the text xacro's own output is (xacro.process_file + toprettyxml), in
    half its time: the same walk as xacro's ``fixed_writexml`` (which xacro installs as
    minidom's ``Element.writexml``) with ``indent``, ``addindent`` and ``newl`` empty, written
    into one list. Attribute values are escaped by minidom's own ``_write_data`` with xacro's
    arguments (each distinct value once); every node that is not an element or a text goes
    to its own ``writexml``. When minidom or xacro is not the one this mirrors (another
    writer installed, a helper gone), ``toxml()`` itself. tests/test_xacro_serialize.py
    compares the two, so a xacro that changes fixed_writexml's layout fails there."""
    import xml.dom.minidom as md

    from xacro import xmlutils

    extra = getattr(xmlutils, "_WRITE_DATA_EXTRA_KWARGS", None)  # what xacro passes to _write_data
    write_data = getattr(md, "_write_data", None)
    if (
        extra is None
        or write_data is None
        or md.Element.writexml is not getattr(xmlutils, "fixed_writexml", None)
        or type(doc).writexml is not md.Document.writexml
    ):
        return str(doc.toxml())
    out: list[str] = ['<?xml version="1.0" ?>']
    writer = _Appender(out)
    escaped: dict[str, str] = {}

    def attribute(value: str) -> str:
        text = escaped.get(value)
        if text is None:
            pieces: list[str] = []
            write_data(_Appender(pieces), value, **extra)
            text = escaped[value] = "".join(pieces)
        return text

    element, text_node = md.Node.ELEMENT_NODE, md.Node.TEXT_NODE

    def write(e: Any) -> None:  # fixed_writexml, one call per element as there (the same depth)
        tag = e.tagName
        out.append("<" + tag)
        attrs = e._attrs
        if attrs:
            for name in sorted(attrs):
                out.append(f' {name}="{attribute(attrs[name]._value)}"')
        children = e.childNodes
        if not children:
            out.append("/>")
            return
        if len(children) == 1 and children[0].nodeType == text_node:
            out.append(">")
            children[0].writexml(writer, "", "", "")
            out.append(f"</{tag}>")
            return
        out.append(">")
        for c in children:
            kind = c.nodeType
            if kind == element:
                write(c)
            elif kind == text_node:
                data = c._data
                if data and not data.isspace():
                    c.writexml(writer, "", "", "")
            else:
                c.writexml(writer, "", "", "")
        out.append(f"</{tag}>")

    for node in doc.childNodes:
        if node.nodeType == element:
            write(node)
        else:
            node.writexml(writer, "", "", "")
    return "".join(out)


# --- content xacro would leave as it is -----------------------------------------------------

_STATIC = "_descgen_static_text"  # on a parsed element whose content xacro's walk leaves as it is
_ELEMENT, _TEXT, _COMMENT = Node.ELEMENT_NODE, Node.TEXT_NODE, Node.COMMENT_NODE


def _static_size(e: Any) -> tuple[int, int] | None:
    """The characters of ``e``'s attribute values and text, and the elements below it, when
    ``xacro.eval_all(e)`` would leave ``e`` and everything below it exactly as they are, else
    None.

    That is so when xacro's walk finds nothing to do: no attribute named ``xacro:*`` or
    ``xmlns:xacro`` (it removes those), no ``$`` in a value or text (without one,
    ``eval_text`` returns its input: xacro's lexer reads it as a single TEXT token), no child
    element ``xacro:*`` (every directive and every macro call is one; xacro returns False from
    ``handle_macro_call`` for any other tag and walks into it), no comment that switches
    ``xacro:eval-comments`` on, and the same for every child element. Nothing depends on the
    symbols, so the answer holds wherever the element is walked. A value too long for one
    ``eval_text`` is not static: the walk refuses it there, as before."""
    total = below = 0
    # minidom's own fields, read directly: e.attributes builds a map per call, and an Attr's
    # value and a text's data are properties whose getters return _value and _data (~80,000
    # Python calls on a 1000-link Xacro); tests/test_xacro_static_skip.py compares the walk
    attrs = e._attrs  # name -> Attr (None before any)
    if attrs:
        for name, attr in attrs.items():
            value = attr._value
            if name.startswith("xacro:") or name == "xmlns:xacro" or "$" in value or len(value) > xe.MAX_SIZE:
                return None
            total += len(value)
    for c in e.childNodes:
        kind = c.nodeType
        if kind == _ELEMENT:
            size = None if c.tagName.startswith("xacro:") else c.__dict__.get(_STATIC)
            if size is None:
                return None
            total += size[0]
            below += 1 + size[1]
        elif kind == _TEXT:
            data = c._data
            if "$" in data or len(data) > xe.MAX_SIZE:
                return None
            total += len(data)
        elif kind == _COMMENT and "xacro:eval-comments" in c._data:
            return None
    return total, below


def _mark_static(doc: Any) -> None:
    """Flag each element of a freshly parsed document that :func:`_static_size` finds static
    (children first, iteratively: a deep document cannot exhaust the stack here). The flag is
    a plain attribute of the node, so a clone (a macro body, an inserted block) has none and
    is walked in full; xacro changes a flagged element only to empty a macro call's
    arguments, which keeps it static."""
    order: list[Any] = []
    stack = [doc.documentElement]
    while stack:
        e = stack.pop()
        order.append(e)
        for c in e.childNodes:
            if c.nodeType == _ELEMENT:
                stack.append(c)
    for e in reversed(order):
        size = _static_size(e)
        if size is not None:
            e.__dict__[_STATIC] = size


@contextlib.contextmanager
def _skipping_static(box: _Sandbox | None) -> Iterator[None]:
    """xacro's walk without the elements it would leave unchanged: most of a plain URDF and
    of descgen's own Xacro (on 1000 links ~90 % of the expansion). The sandbox's accounts see
    the same text and the same clock as when the walk visited them."""
    import xacro

    original_parse = xacro.parse
    original_eval_all = xacro.eval_all

    def parse(inp: Any, filename: str | None = None) -> Any:
        with collector.paused():
            doc = original_parse(inp, filename)
            _mark_static(doc)
        return doc

    def eval_all(node: Any, macros: Any, symbols: Any) -> Any:
        size = node.__dict__.get(_STATIC)
        if size is None:
            return original_eval_all(node, macros, symbols)
        if box is not None:
            _tick(box)
            _count_elements(box, size[1], node.tagName)  # the element itself was counted by its parent's walk
            box.text += size[0]
            if box.text > MAX_TEXT:
                raise _refuse(box, xe.RefusedError("this Xacro produces more text than an audit reads", "limit"), "")
        return None

    with _patched(xacro, parse=parse, eval_all=eval_all):
        yield


# --- where each element was written ---------------------------------------------------------

_WHERE = "descgen.where"  # the DOM user-data key


class _KeepWhere:
    """minidom calls this when it clones a node (a macro body, an inserted block): the copy
    was written where the original was."""

    def handle(self, operation: int, key: str, data: Any, src: Any, dst: Any) -> None:
        if dst is not None:
            dst.setUserData(key, data, self)


_KEEP = _KeepWhere()


class _LocatingBuilder(expatbuilder.ExpatBuilderNS):
    """minidom's own builder (what ``xml.dom.minidom.parse`` uses, so the document is the
    same) that also records each element's start tag position."""

    def __init__(self, file: str) -> None:
        super().__init__()
        self._file = file

    def start_element_handler(self, name: str, attributes: list[str]) -> None:
        super().start_element_handler(name, attributes)
        parser = self.getParser()  # the one parsing now
        where = Where(self._file, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
        self.curNode.setUserData(_WHERE, where, _KEEP)


def _namer(top: Path, display: str) -> Callable[[str], str]:
    """How a file xacro opens is named in findings: the top file as the user gave it, a file
    beside or below it relative to that, any other by its real path."""
    import xacro

    def name(filename: str) -> str:
        real = Path(os.path.realpath(os.path.join(xacro.root_dir, filename)))
        if real == top:
            return display
        if real.is_relative_to(top.parent):
            return str(Path(display).parent / real.relative_to(top.parent))
        return str(real)

    return name


def _elements(node: Any) -> Iterator[Any]:
    """The element descendants of a DOM node in document order (not the node itself);
    iterative, so a deep document cannot exhaust the stack here."""
    stack = list(reversed(node.childNodes))
    while stack:
        n = stack.pop()
        if n.nodeType == n.ELEMENT_NODE:
            yield n
            stack.extend(reversed(n.childNodes))


def _sources(root: Any) -> tuple[Where | None, ...]:
    return tuple(e.getUserData(_WHERE) for e in (root, *_elements(root)))


def _stamp(call: Any, body: Any) -> None:
    """The elements a macro call's body produced were also made by this call: add its site
    to their chain. Blocks handed to the call are the caller's elements: they keep theirs."""
    here: Where | None = call.getUserData(_WHERE)
    if here is None:
        return
    link = (here.bare(), *here.via)
    passed = {id(e.getUserData(_WHERE)) for e in _elements(call)}  # alive under `call`: ids stay unique
    for e in _elements(body):
        where: Where | None = e.getUserData(_WHERE)
        if where is not None and id(where) not in passed:
            e.setUserData(_WHERE, replace(where, via=(*where.via, *link)), _KEEP)


@contextlib.contextmanager
def _locating(name: Callable[[str], str]) -> Iterator[None]:
    """xacro parsing with positions, and macro calls that extend the call chain."""
    import xacro

    original_parse = xacro.parse
    original_call = xacro.handle_macro_call
    original_replace = xacro.replace_node
    calls: dict[int, Any] = {}  # macro call nodes being expanded, by id (the node keeps its id alive)

    def parse(inp: Any, filename: str | None = None) -> Any:
        if inp is not None or filename is None:
            return original_parse(inp, filename)
        # as xacro.parse opens a file, error included
        try:
            f = open(os.path.join(xacro.root_dir, filename))  # noqa: SIM115 (closed below)
        except OSError as e:
            xacro.filestack.pop()
            raise xacro.XacroException(f"{e.strerror}: {e.filename}", exc=e) from None
        with f:
            return _LocatingBuilder(name(filename)).parseFile(f)

    def handle_macro_call(node: Any, macros: Any, symbols: Any) -> Any:
        if node.tagName.startswith("xacro:"):  # every other element is not a call: xacro returns False
            calls[id(node)] = node
        return original_call(node, macros, symbols)

    def replace_node(node: Any, by: Any, content_only: bool = False) -> Any:
        # a macro call ends by replacing its node with the expanded body
        if calls.pop(id(node), None) is node and by is not None and by is not node:
            _stamp(node, by)
        return original_replace(node, by, content_only)

    with _patched(xacro, parse=parse, handle_macro_call=handle_macro_call, replace_node=replace_node):
        yield


def _refusal_finding(refusal: _Refusal, top: Path, display: str) -> Finding:
    file = refusal.file
    shown = display if file is None or Path(os.path.realpath(file)) == top else file
    line, col = _line_of(file or str(top), refusal.needle)
    kind = refusal.error.kind
    return _CODES[kind].finding(refusal.error.message, _HINTS[kind], "file", Where(shown, line, col))
