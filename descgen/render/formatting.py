"""How values are written into output files (shortest round-trip floats, escaping)."""

from __future__ import annotations

import json
import math
import re
import unicodedata
from collections.abc import Iterable

import yaml
from markupsafe import Markup

from descgen.read.params import typed


def num(x: float | int) -> str:
    """Shortest text that reads back as the same float; ``-0.0`` prints as ``0``;
    whole numbers print without a fraction."""
    try:
        text = _NUM.get(x)
    except TypeError:  # not hashable (a 0-d array): not kept
        return _num(x)
    if text is None:
        text = _num(x)
        if len(_NUM) >= _NUM_MAX:  # a bound for a long-lived process; a robot repeats far fewer
            _NUM.clear()
        _NUM[x] = text
    return text


# num's answers by value: a 1000-link robot writes ~40,000 numbers of a few dozen values.
# Keys that compare equal (1 and 1.0, 0.0 and -0.0) have the same text; NaN and infinities
# are refused before they are stored.
_NUM: dict[float | int, str] = {}
_NUM_MAX = 65536


def _num(x: float | int) -> str:
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"cannot write non-finite value {v!r}")
    if v == 0:
        return "0"
    if v.is_integer() and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def vec(values: Iterable[float]) -> str:
    if type(values) is not tuple:  # a list or an array: not a key
        return " ".join(map(num, values))
    text = _VEC.get(values)
    if text is None:
        text = " ".join(map(num, values))
        if len(_VEC) >= _NUM_MAX:
            _VEC.clear()
        _VEC[values] = text
    return text


# vec's answers for the model's tuples (origins, sizes, axes repeat from link to link); equal
# tuples are equal element by element, so num gives each the same text
_VEC: dict[tuple[float, ...], str] = {}


_DASHES = re.compile(r"-{2,}")
# Characters that end a line somewhere (Python, YAML and Markdown treat \r, \x0b, \x0c,
# \x1c-\x1e, \x85, U+2028 and U+2029 as line ends), are illegal in XML, or are invisible
# and reorder what a reviewer sees (bidi overrides): written as escapes, never raw.
_INVISIBLE = frozenset(("Cc", "Cf", "Cs", "Zl", "Zp"))


def _hidden(ch: str) -> bool:
    return unicodedata.category(ch) in _INVISIBLE or ch in "\ufffe\uffff"


def visible(text: object) -> str:
    """One line with every control, line-separator or format character as a ``\\n``,
    ``\\xNN`` or ``\\uXXXX`` escape; other text is unchanged."""
    s = str(text)
    if s.isascii() and s.isprintable():  # no ASCII control character: nothing to escape
        return s
    if not any(_hidden(ch) for ch in s):
        return s
    return "".join(json.dumps(ch)[1:-1] if ch in "\n\t\r" else _escape(ch) if _hidden(ch) else ch for ch in s)


def _escape(ch: str) -> str:
    code = ord(ch)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def comment(text: object) -> Markup:
    """Text safe inside an XML comment (no ``--``, no trailing ``-``) or after ``#``/``//``:
    one line, so that nothing can end the comment early; whitespace runs become one space.
    ``xacro:eval-comments`` would make xacro evaluate the comments after it, so it is broken up.
    Marked safe: a comment shows ``<``, ``&`` and quotes as they are (no entity escaping)."""
    s = visible(" ".join(str(text).split()))
    s = _DASHES.sub(lambda m: "- " * (len(m.group()) - 1) + "-", s)
    s = s.replace("xacro:eval-comments", "xacro: eval-comments")
    return Markup(s + " " if s.endswith("-") else s)


def pystr(text: object) -> str:
    """A Python string literal (double-quoted) whose value is ``text``: a JSON string is one."""
    return json.dumps(str(text))


def pyinner(text: object) -> str:
    """``text`` inside a double- or triple-double-quoted Python string (a docstring)."""
    return pystr(text)[1:-1]


def yamlstr(text: object) -> str:
    """A YAML scalar that reads back as the string ``text`` (quoted only when it must be:
    ``null``, ``yes``, ``1e3``, a colon...), on one line. Most YAML descgen writes is a ROS
    parameter file, which rcl types by its own rules (``y``, ``010``, ``1e3`` and ``inf`` are
    no strings there, though PyYAML leaves them plain): those are quoted too."""
    plain = yaml.safe_dump(str(text), width=2**31).removesuffix("\n").removesuffix("\n...")
    if "\n" not in plain and plain[:1] not in ("'", '"') and not isinstance(typed(plain, False, False), str):
        return yaml.safe_dump(str(text), width=2**31, default_style="'").removesuffix("\n")
    if "\n" not in plain:
        return plain
    # a line break in the text: a double-quoted scalar writes it (and every other control) as an escape
    return yaml.safe_dump(str(text), width=2**31, default_style='"').removesuffix("\n")


def dot(text: object) -> str:
    """Text inside a double-quoted Graphviz string: ``\\`` and ``"`` escaped, one line."""
    return visible(text).replace("\\", "\\\\").replace('"', '\\"')


def mermaid(text: object) -> str:
    """Text inside a quoted Mermaid label, one line: ``#`` (which starts an entity code),
    ``"``, ``|`` (ends an edge label), a backtick (a Markdown label) and ``<``/``>`` (HTML) as Mermaid entity codes."""
    s = visible(text).replace("#", "#35;")
    for ch, code in (('"', "#quot;"), ("|", "#124;"), ("`", "#96;"), ("<", "#lt;"), (">", "#gt;")):
        s = s.replace(ch, code)
    return s


def xacro_text(text: object) -> str:
    """Spec text placed where xacro evaluates ``${}``/``$()``: every ``$`` becomes the
    expression ``${'$'}``, which evaluates to a literal dollar, so no spec text can become
    a xacro expression or substitution (xacro 2.x lexer: docs/reference/xacro.md)."""
    return str(text).replace("$", "${'$'}")


# what xacro leaves alone in a document: comments (unless switched on, see xacro_document),
# processing instructions and CDATA sections (minidom keeps them out of xacro's text walk)
_XACRO_INERT = re.compile(r"<!--.*?-->|<\?.*?\?>|<!\[CDATA\[.*?\]\]>", re.DOTALL)
EVAL_COMMENTS = "xacro:eval-comments"


def xacro_document(xml: str) -> str:
    """A whole XML document (the SRDF MoveItConfigsBuilder expands with xacro) that xacro
    expands to ``xml``: every ``$`` of an attribute value or text written ``${'$'}``, and a
    comment that would switch comment evaluation on broken up (xacro drops such a comment;
    a descgen document has none). Comments, processing instructions and CDATA keep their
    ``$`` (xacro does not evaluate them). Unchanged when there is nothing to escape. The
    document must hold no ``xacro:`` element or attribute (descgen's SRDF has none). The
    quotes are character references, so the escape fits either attribute quoting."""
    if "$" not in xml and EVAL_COMMENTS not in xml:
        return xml
    dollar = "${&#39;$&#39;}"
    out: list[str] = []
    last = 0
    for m in _XACRO_INERT.finditer(xml):
        out.append(xml[last : m.start()].replace("$", dollar))
        out.append(m.group().replace(EVAL_COMMENTS, "xacro: eval-comments"))
        last = m.end()
    out.append(xml[last:].replace("$", dollar))
    return "".join(out)


# Markdown (CommonMark, and GFM's tables and strikethrough, as GitHub renders it). A value from the
# input is text or code, never markup: no raw HTML, no link or image, no emphasis, no block of its
# own, and it cannot leave the code span, fence or table cell it is written into. Plain names
# (nearly every one) print as they always did.
# inline markup anywhere in a line: escaped with a backslash ($: GitHub renders $...$ as math)
_MD_ALWAYS = frozenset("\\`*[]<>&|~$")
# what makes a line a heading, list item, thematic break or setext underline (a quote, ``>``, and
# fences, ``` and ~~~, are escaped anywhere): group 1 ends at the character to escape
_MD_BLOCK_START = re.compile(r"(#|[-+]|\d{1,9}[.)])(?=[ \t]|$)|(=)+[ \t]*$|(-)[ \t]*(?:-[ \t]*){2,}$")
_MD_DEST_SAFE = "/._-~"  # besides letters and digits: what a link destination keeps as written


def mdtext(text: object) -> str:
    """Text as Markdown text, on one line (whitespace runs become one space): every character
    that could start markup escaped (``\\ ` * [ ] < > & | ~ $``, and ``_`` unless inside a word,
    where CommonMark gives it no meaning), and a leading ``#``, ``>``, ``+``, ``-``, ``=`` or
    ``1.`` escaped, so the text starts no block even at the start of a line."""
    s = visible(" ".join(str(text).split()))
    out = []
    last = len(s) - 1
    for i, ch in enumerate(s):
        if ch in _MD_ALWAYS or (ch == "_" and not (0 < i < last and s[i - 1].isalnum() and s[i + 1].isalnum())):
            out.append("\\" + ch)
        else:
            out.append(ch)
    return _no_block("".join(out))


def _no_block(s: str) -> str:
    """``s`` with a backslash before the character that would make its line a block."""
    m = _MD_BLOCK_START.match(s)
    if m is None:
        return s
    at = m.end(1) - 1 if m.group(1) is not None else 0  # #, -, + or the . of "1."; a line of = or -
    return s[:at] + "\\" + s[at:]


def _code_fence(s: str) -> str:
    """``s`` as a CommonMark code span: fenced by more backticks than its longest run, padded
    with a space where CommonMark strips one (or a backtick would touch the fence)."""
    run = max((len(m) for m in re.findall(r"`+", s)), default=0)
    fence = "`" * (run + 1)
    strips = s.startswith(" ") and s.endswith(" ") and s.strip(" ") != ""
    pad = " " if s.startswith("`") or s.endswith("`") or strips else ""
    return fence + pad + s + pad + fence


def mdspan(text: object) -> str:
    """A value as one code span in running text (a paragraph, a heading; not a table cell, see
    :func:`mdcode`): one line, fenced so that nothing in it closes the span."""
    return _code_fence(visible(text))


def mdfence(text: str, lang: str = "") -> list[str]:
    """Lines of a fenced code block holding ``text`` as it is: the fence is longer than any
    backtick run in it (at least three), so no line of it closes the block."""
    lines = re.split(r"\r\n|\r|\n", text.rstrip("\r\n")) if text.rstrip("\r\n") else []
    run = max((len(m) for m in re.findall(r"`+", text)), default=0)
    fence = "`" * max(3, run + 1)
    return [f"{fence}{lang}", *lines, fence, ""]


def mddest(target: str) -> str:
    """A link destination (a relative path) percent-encoded: nothing in it can end the link,
    start another or name a scheme. A plain path prints as it is."""
    from urllib.parse import quote

    return quote(target, safe=_MD_DEST_SAFE)


def mdcell(text: object) -> str:
    """Text safe in a Markdown table cell: one line, pipes and markup escaped."""
    s = visible(" ".join(str(text).split()))
    for ch in "\\|`*_[]<>&~$":
        s = s.replace(ch, "\\" + ch)
    return _no_block(s)  # a cell is inline, but templates write the same text after "- " too


def mdcode(text: object) -> str:
    """A name as a code span in a Markdown table cell: fenced by more backticks than the
    longest run in it (CommonMark), with ``|`` escaped (GFM splits cells before code spans);
    a plain name prints as it always did, in single backticks."""
    s = visible(text)
    if "`" not in s and "|" not in s and not (s.startswith(" ") and s.endswith(" ")):
        return f"`{s}`"  # a plain name (nearly every one): single backticks
    fenced = _code_fence(s)
    fence = len(fenced) - len(fenced.rstrip("`"))
    return fenced[:fence] + fenced[fence:-fence].replace("|", "\\|") + fenced[-fence:]
