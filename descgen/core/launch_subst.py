"""Launch substitutions (``$(var NAME)``) in a controllers YAML, as launch would read it.

A Jazzy launch file may load a controller_manager YAML with ``ParameterFile(path,
allow_substs=True)`` (ros2_control_demos example_1: ``$(var joint_prefix)1``). launch_ros then
parses the whole file text, comments and keys included, with launch's frontend substitution
grammar (``launch/share/launch/frontend/grammar.lark``, jazzy), joins the evaluated pieces into
one text and only then reads that text as YAML. So we substitute on the text too, and keep a
map from the new text back to the file so that findings still point at the file's line:col.

Only ``$(var NAME)`` (and ``$(var NAME DEFAULT)``) is evaluated, from ``--launch-arg`` values:
an audited file is data. ``$(env)``, ``$(eval)``, ``$(command)``, ``$(find-pkg-share)`` and
every other substitution are left as written and reported (CTRL053): nothing runs and no
environment variable or file is read. Text between substitutions loses its backslash escapes
(``\\X`` -> ``X``), as launch's ``replace_escaped_characters`` does, and a ``$(`` right after a
backslash is text. Files without a substitution are not touched.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Mapping
from dataclasses import dataclass

from descgen.core.findings import Finding, InputError, Where
from descgen.core.record import record

MAX_SITES = 1000  # a real file has a handful; more is a bomb, not a parameter file
MAX_DEPTH = 8  # nesting of substitutions inside substitution arguments
MAX_RESULT = 5 * 1024 * 1024  # the substituted text obeys the YAML reader's own size limit
MAX_VALUE = 4096  # one --launch-arg value

_IDENT = re.compile(r"[A-Za-z][A-Za-z0-9_-]*")  # the grammar's IDENTIFIER
_ESCAPE = re.compile(r"\\(.)")  # launch's replace_escaped_characters ('.' is not a newline)
_WHY = {
    "env": "descgen never reads the environment (it holds secrets); write the value, or a $(var) "
    "given with --launch-arg",
    "optenv": "descgen never reads the environment (it holds secrets); write the value, or a $(var) "
    "given with --launch-arg",
    "eval": "descgen never evaluates Python from an audited file; write the value",
    "command": "descgen never runs a command from an audited file; write the value",
}


@record
class Site:
    """One substitution in the file: its text, its name (``var``, ``env``, ...), the variable it
    names (``var`` only), where it starts, and what it became (None: left as written)."""

    text: str
    kind: str
    name: str
    where: Where
    value: str | None


@record
class Substituted:
    text: str  # what launch would hand to the YAML parser (the file's text if it has no site)
    sites: tuple[Site, ...]
    findings: tuple[Finding, ...]
    _segments: tuple[tuple[int, int, bool], ...]  # (start in text, start in the file, copied 1:1?)
    _new_lines: tuple[int, ...]  # offsets where the lines of ``text`` start
    _old_lines: tuple[int, ...]  # and those of the file

    def position(self, line: int, col: int) -> tuple[int, int]:
        """The file's (line, col), 1-based, of a (line, col) in ``text``; inside a substituted
        value, the position of its ``$(``."""
        if not self._segments or line < 1 or line > len(self._new_lines):
            return line, col
        offset = self._new_lines[line - 1] + col - 1
        i = bisect.bisect_right(self._segments, (offset, 1 << 62, True)) - 1
        start, old, exact = self._segments[max(i, 0)]
        old += offset - start if exact else 0
        row = bisect.bisect_right(self._old_lines, old) - 1
        return row + 1, old - self._old_lines[row] + 1


def _lines(text: str) -> tuple[int, ...]:
    return (0, *(m.end() for m in re.finditer("\n", text)))


class _MalformedError(Exception):
    """A ``$(`` that launch's grammar cannot parse (launch would refuse the whole file)."""


@dataclass
class _Parsed:
    end: int
    kind: str
    args: list[str]  # the raw text of each argument
    plain: bool  # no quotes and no nested substitution in the arguments


def _limit(file: str, where: Where, message: str, hint: str) -> InputError:
    return InputError([Finding("CTRL054", "error", message, hint, "file", where)])


class _Scanner:
    def __init__(self, text: str, file: str) -> None:
        self.text, self.file = text, file
        self.old_lines = _lines(text)

    def where(self, offset: int) -> Where:
        row = bisect.bisect_right(self.old_lines, offset) - 1
        return Where(self.file, row + 1, offset - self.old_lines[row] + 1)

    def site(self, i: int, depth: int) -> _Parsed:
        """The substitution that starts at ``text[i:i+2] == '$('``, per the grammar's
        ``substitution`` rule: ``$(`` IDENTIFIER (" " value)* ``)``."""
        if depth > MAX_DEPTH:
            raise _limit(
                self.file,
                self.where(i),
                f"launch substitutions nested more than {MAX_DEPTH} deep",
                "a controllers file needs at most $(var NAME); remove the nesting",
            )
        text = self.text
        m = _IDENT.match(text, i + 2)
        if m is None:
            raise _MalformedError("'$(' is not followed by a substitution name")
        j, args, plain = m.end(), [], True
        while j < len(text) and text[j] == " ":
            j += 1
            start = j
            if j < len(text) and text[j] in "'\"":
                j, plain = self.quoted(j, depth), False
            else:
                while j < len(text) and text[j] not in " )":
                    c = text[j]
                    if c == "\\":
                        j += 2
                    elif text.startswith("$(", j):
                        j, plain = self.site(j, depth + 1).end, False
                    elif c in "('\"":
                        raise _MalformedError(f"unescaped {c!r} inside a substitution argument")
                    else:
                        j += 1
                if j == start:
                    raise _MalformedError("an empty argument (two spaces, or a space before ')')")
            args.append(text[start:j])
        if j >= len(text) or text[j] != ")":
            raise _MalformedError("the substitution is not closed with ')'")
        return _Parsed(j + 1, m.group(), args, plain)

    def quoted(self, j: int, depth: int) -> int:
        quote, j = self.text[j], j + 1
        while j < len(self.text) and self.text[j] != quote:
            if self.text[j] == "\\":
                j += 2
            elif self.text.startswith("$(", j):
                j = self.site(j, depth + 1).end
            else:
                j += 1
        if j >= len(self.text):
            raise _MalformedError(f"a {quote} argument is not closed")
        return j + 1


def _starts(text: str) -> list[int]:
    """Offsets of every ``$(`` that starts a substitution (not right after a backslash)."""
    return [m.start() for m in re.finditer(r"\$\(", text) if m.start() == 0 or text[m.start() - 1] != "\\"]


def substitute(text: str, file: str, values: Mapping[str, str]) -> Substituted:
    """``text`` as launch would evaluate it with ``values`` as its launch configurations,
    evaluating only ``$(var)``; with findings for what stays as written. InputError (CTRL054)
    for a substitution bomb."""
    starts = _starts(text)
    if not starts:
        return Substituted(text, (), (), (), (), ())
    scan = _Scanner(text, file)
    pieces: list[str] = []
    segments: list[tuple[int, int, bool]] = []
    sites: list[Site] = []
    found: list[Finding] = []
    size = 0

    def emit(piece: str, old: int, exact: bool) -> None:
        nonlocal size
        if piece:
            segments.append((size, old, exact))
            pieces.append(piece)
            size += len(piece)

    def plain_text(a: int, b: int) -> None:
        # launch drops the backslash of every escape in the text between substitutions
        for m in _ESCAPE.finditer(text, a, b):
            emit(text[a : m.start()], a, True)
            emit(m.group(1), m.start(1), True)
            a = m.end()
        emit(text[a:b], a, True)

    pos = 0
    for i in starts:
        if i < pos:
            continue  # inside the previous substitution
        if len(sites) >= MAX_SITES:
            raise _limit(
                file,
                scan.where(i),
                f"more than {MAX_SITES} launch substitutions in one controllers file",
                "a controllers file names a few $(var NAME); this one is built to exhaust the reader",
            )
        plain_text(pos, i)
        where = scan.where(i)
        try:
            parsed = scan.site(i, 0)
        except _MalformedError as exc:
            end = text.find("\n", i)
            end = len(text) if end < 0 else end
            shown = text[i:end][:60]
            found.append(
                Finding(
                    "CTRL053",
                    "warning",
                    f"'{shown}' is not a launch substitution launch can parse ({exc}); left as written",
                    "fix the substitution (see launch's frontend grammar), or escape the $ as \\$ if it is text",
                    "file",
                    where,
                )
            )
            emit(text[i : i + 2], i, True)
            pos = i + 2
            continue
        raw = text[i : parsed.end]
        value = _value(parsed, values)
        name = _ESCAPE.sub(r"\1", parsed.args[0]) if parsed.kind == "var" and parsed.args else ""
        sites.append(Site(raw, parsed.kind, name, where, value))
        if value is not None:
            emit(value, i, False)
        else:
            emit(raw, i, True)
            found.append(_unevaluated(parsed, raw, name, where))
        if size > MAX_RESULT:
            raise _limit(
                file,
                where,
                f"the controllers file grows past {MAX_RESULT // (1024 * 1024)} MB with its launch substitutions",
                "give shorter --launch-arg values",
            )
        pos = parsed.end
    plain_text(pos, len(text))
    out = "".join(pieces)
    return Substituted(out, tuple(sites), tuple(found), tuple(segments), _lines(out), scan.old_lines)


def _value(parsed: _Parsed, values: Mapping[str, str]) -> str | None:
    """A ``$(var NAME [DEFAULT])`` with plain arguments: the given value, else the default."""
    if parsed.kind != "var" or not parsed.plain or len(parsed.args) not in (1, 2):
        return None
    name = _ESCAPE.sub(r"\1", parsed.args[0])
    if name in values:
        return values[name]
    return _ESCAPE.sub(r"\1", parsed.args[1]) if len(parsed.args) == 2 else None


def _unevaluated(parsed: _Parsed, raw: str, name: str, where: Where) -> Finding:
    if parsed.kind == "var" and parsed.plain and len(parsed.args) == 1:
        return Finding(
            "CTRL052",
            "warning",
            f"'{raw}' has no value: the file is meant to be loaded by a launch file with "
            "ParameterFile(..., allow_substs=True); names that hold it are not checked",
            f"give the launch argument's value with --launch-arg {name}:=VALUE (see the launch file's "
            "DeclareLaunchArgument default)",
            "file",
            where,
        )
    shown = raw if len(raw) <= 60 else raw[:57] + "..."
    why = _WHY.get(
        parsed.kind,
        "descgen evaluates only $(var NAME) (from --launch-arg); write the value, or a $(var) given with --launch-arg",
    )
    return Finding(
        "CTRL053",
        "warning",
        f"launch substitution '{shown}' is not evaluated; it is left as written and names that hold it are not checked",
        why,
        "file",
        where,
    )


def unresolved(text: object) -> bool:
    """Whether a value still holds a launch substitution (CTRL052/CTRL053 stand for it: rules
    that compare names with the URDF skip it)."""
    return isinstance(text, str) and "$(" in text


def check_value(name: str, value: str) -> str | None:
    """Why a ``--launch-arg`` name or value is refused (None: fine). A newline would let a value
    add YAML keys and break the map to the file's lines."""
    if not _IDENT.fullmatch(name) and not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]*", name):
        return f"{name[:40]!a} is not a launch argument name (letters, digits, _ . -)"
    if len(value) > MAX_VALUE:
        return f"the value of {name!a} is longer than {MAX_VALUE} characters"
    if any(ord(c) < 32 or ord(c) == 127 for c in value):
        return f"the value of {name!a} holds a control character (a newline would add YAML lines)"
    return None
