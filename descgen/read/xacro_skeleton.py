"""A Xacro's static parts set aside while xacro expands the rest.

xacro's walk leaves an element and everything below it exactly as they are when nothing in
them is for xacro: no ``xacro:*`` element or attribute, no namespace declaration, no ``$`` in a
value or text, no ``xacro:eval-comments`` comment (readers/xacro_file._static_size, whose walk
the sandbox already skips). In descgen's own Xacro of a 1000-link robot nearly every element
is static, and parsing them into minidom nodes, writing them back as text and parsing that
text again was most of check 1 (~0.2 s of a 1000-link ``generate``).

:func:`split` parses the top file once with lxml and replaces each run of outermost static
sibling elements (with the comments and plain text between them) by one placeholder element;
xacro expands what is left (the skeleton) in the same sandbox; :func:`join` replaces each
placeholder of the expansion by the nodes it stood for (copies for each further use: a
placeholder in a macro body is cloned with it). The result is the tree xacro gives for the
whole file (tests/test_xacro_skeleton.py compares them with ``xacro.process_file``), not the
same text: every reader of an expansion reads it as data.

What this cannot mirror exactly, it leaves to the whole-file expansion (:func:`split`
returns None): a DOCTYPE, CDATA (minidom keeps a CDATA section out of xacro's reach, lxml
reads it as text), a namespace declared below the root, an encoding other than UTF-8, XML
that lxml or expat (xacro's parser) refuses. Values and texts minidom would write differently
(a character reference to a tab, newline or carriage return) stay in the skeleton. Children
of a ``xacro:*`` element (or any namespaced one) stay in the skeleton: a macro call takes its
blocks by position and a ``**`` block inserts the children of its element. The sandbox's
bounds still hold: :func:`join` counts the elements and text the parts add (a macro may clone
one thousands of times) before copying any, and refuses what the sandbox would refuse.
"""

from __future__ import annotations

import collections
import copy
import functools
import re
import secrets
from collections.abc import Sequence
from dataclasses import dataclass
from xml.parsers import expat

from lxml import etree

from descgen.read.xacro_eval import MAX_SIZE

PLACEHOLDER = "descgen-static-part-"
"""The placeholders' tag, followed by a random token of each split: a file cannot write one (in
a macro, an included file, ``xacro:element``) that :func:`join` would take for its own."""
_DECLARED_ENCODING = re.compile(r"""^\s*<\?xml[^>]*\bencoding\s*=\s*["']([^"']*)["']""")


@dataclass(frozen=True)
class Skeleton:
    """The text xacro expands instead of the file, and the nodes its placeholders stand for
    (placeholder ``n`` is ``parts[n]``: a run of static sibling elements with the comments and
    text between them)."""

    text: str
    parts: Sequence[tuple[etree._Element, ...]]
    tag: str  # the placeholders' tag (PLACEHOLDER and this split's token)
    elements: int  # of the whole file: what the parts hold at most, each put back once
    chars: int


def _parser() -> etree.XMLParser:
    # no entity expansion, no network, no recovery: what lxml cannot read as it is goes whole
    return etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)


def split(text: str) -> Skeleton | None:
    """The skeleton of a Xacro file's text, or None when it must be expanded whole (see the
    module docstring) or holds nothing static to set aside."""
    if "<!DOCTYPE" in text or "<![CDATA[" in text:
        return None
    declared = _DECLARED_ENCODING.match(text)
    if declared and declared.group(1).lower().replace("_", "-") not in ("utf-8", "utf8"):
        return None
    data = text.encode("utf-8")
    try:
        root = etree.fromstring(data, _parser())
        # xacro parses with expat, which refuses some names libxml2 takes (XML 1.0's fifth
        # edition name characters): a part only lxml read would pass where xacro fails
        expat.ParserCreate(namespace_separator=" ").Parse(data, True)
    except (etree.XMLSyntaxError, ValueError, expat.ExpatError):
        return None
    # every "xmlns" of the text is one of the root's declarations: none below it, where xacro
    # would remove an xmlns:xacro attribute (a comment or text naming xmlns sends it whole too)
    if text.count("xmlns") != len(root.nsmap):
        return None
    walked = set(_dynamic(text, root))  # holding the proxies keeps each node's one identity for `in`
    # comments may join a run of static siblings unless one switches xacro:eval-comments on
    # (then a later comment may be evaluated: each stays in the skeleton)
    comments_join = "xacro:eval-comments" not in text
    tag = PLACEHOLDER + secrets.token_hex(8)
    elements = int(_xpath("count(//*)")(root))  # type: ignore[arg-type]
    parts: list[tuple[etree._Element, ...]] = []
    stack = [root]
    while stack:
        e = stack.pop()
        if str(e.tag).startswith("{"):  # a xacro:* element: its children are its arguments
            stack.extend(c for c in e if isinstance(c.tag, str))
            continue
        run: list[etree._Element] = []
        for c in list(e):  # replaced while walked
            static = isinstance(c.tag, str) and c not in walked
            if static or (c.tag is etree.Comment and run and comments_join):
                run.append(c)
                if _plain(c.tail):
                    continue  # text xacro leaves as it is: the run goes on
            _set_aside(e, run, parts, tag)  # the run ends before c, or with c (its tail is evaluated)
            run = []
            if isinstance(c.tag, str) and c in walked:
                stack.append(c)
        _set_aside(e, run, parts, tag)
    if not parts:
        return None
    return Skeleton(etree.tostring(root.getroottree(), encoding="unicode"), tuple(parts), tag, elements, len(text))


def _plain(text: str | None) -> bool:
    """Text xacro's walk and writer leave as they are: no "$", not longer than one evaluation
    takes, no carriage return (only a character reference makes one, which minidom writes raw
    and the next parser reads as a newline)."""
    return text is None or ("$" not in text and "\r" not in text and len(text) <= MAX_SIZE)


def _set_aside(
    parent: etree._Element, run: list[etree._Element], parts: list[tuple[etree._Element, ...]], tag: str
) -> None:
    """Replace ``run`` (siblings: static elements, the comments between them, the text between
    them) up to its last element by one placeholder; its last element's tail stays, after it."""
    while run and not isinstance(run[-1].tag, str):
        run.pop()  # comments after the last element stay in the skeleton
    if not run:
        return
    stand_in = etree.Element(tag, n=str(len(parts)))
    stand_in.tail, run[-1].tail = run[-1].tail, None
    parent.replace(run[0], stand_in)  # each node leaves with its own tail (lxml keeps them together)
    for node in run[1:]:
        parent.remove(node)
    parts.append(tuple(run))


def _dynamic(text: str, root: etree._Element) -> list[etree._Element]:
    """The elements xacro's walk does something in or below: each holder of an attribute or
    text with "$" (or longer than one eval_text takes), of a namespaced (xacro:*) attribute, of
    a comment that switches xacro:eval-comments, of a processing instruction, each namespaced
    (xacro:*) element, and all their ancestors. Every other element is left as it is (see
    readers/xacro_file._static_size, the same rules for minidom nodes). One XPath pass in C,
    asking only what the text can hold: no "$" and no character reference, no value with a "$";
    no prefix of the root's followed by ":" (and no default namespace), nothing namespaced; a
    text shorter than the limit, no value longer."""
    texts, values, tests = [], [], ["//processing-instruction()"]
    if "$" in text or "&#" in text:
        texts.append("contains(., '$')")
        values.append("contains(., '$')")
    if "&#" in text:
        # minidom (Python 3.11) writes a tab, newline or carriage return of an attribute value,
        # and a carriage return of a text, as the character: read again, they are a space and
        # a newline. Only a character reference puts one there (parsers normalise the rest)
        texts.append("contains(., '\r')")
        values.append("contains(., '\t') or contains(., '\n') or contains(., '\r')")
    if len(text) > MAX_SIZE:
        texts.append(f"string-length(.) > {MAX_SIZE}")
        values.append(f"string-length(.) > {MAX_SIZE}")
    if texts:
        tests.append(f"//text()[{' or '.join(texts)}]")
    nsmap = root.nsmap
    if None in nsmap or any(f"{prefix}:" in text.replace(f"xmlns:{prefix}", "") for prefix in nsmap):
        values.append("namespace-uri() != ''")
        tests.append("//*[namespace-uri() != '']")
    if values:
        tests.append(f"//@*[{' or '.join(values)}]")
    if "xacro:eval-comments" in text:
        tests.append("//comment()[contains(., 'xacro:eval-comments')]")
    found = _xpath(f"({' | '.join(tests)})/ancestor-or-self::*")(root)
    assert isinstance(found, list)
    return [e for e in found if isinstance(e, etree._Element)]  # elements only (the path's last step)


@functools.cache
def _xpath(path: str) -> etree.XPath:
    return etree.XPath(path)


def join(expanded: str, skeleton: Skeleton, most_elements: int, most_text: int) -> str | None:
    """The expansion of the skeleton with each placeholder replaced by the nodes it stands for
    (moved there, so a skeleton is joined once; copies where xacro cloned the placeholder), as
    XML text. None when a placeholder came back changed or in a namespace (a default one
    declared around it), or the result would hold more than ``most_elements`` elements or
    ``most_text`` characters of values and text (the sandbox's bounds, which never saw the
    parts): the caller then expands the whole file, and the sandbox refuses it as before."""
    try:
        root = etree.fromstring(expanded.encode("utf-8"), _parser())
    except (etree.XMLSyntaxError, ValueError):
        return None
    stand_ins = list(root.iter("{*}" + skeleton.tag))  # the tag in any namespace, or none
    uses: collections.Counter[int] = collections.Counter()
    for stand_in in stand_ins:
        n = stand_in.get("n", "")
        if stand_in.tag != skeleton.tag or not n.isdigit() or int(n) >= len(skeleton.parts):
            return None
        if len(stand_in) or stand_in.text or stand_in.getparent() is None:
            return None
        uses[int(n)] += 1
    # counted before any copy: a macro that clones a large part thousands of times is refused
    # at its size, not after building it. Parts put back once hold at most the whole file;
    # only a part put back more than once is measured (a macro body's: small, as a rule)
    elements = sum(1 for _ in root.iter()) + skeleton.elements
    chars = len(expanded) + skeleton.chars
    for n, count in uses.items():
        if count > 1:
            size = _size(skeleton.parts[n])
            elements += count * size[0]
            chars += count * size[1]
    if elements > most_elements or chars > most_text:
        return None
    used: set[int] = set()
    for stand_in in stand_ins:
        n = int(stand_in.get("n", ""))
        nodes = list(skeleton.parts[n])
        if n in used:  # a placeholder xacro cloned (a macro body, a block inserted twice)
            nodes = [copy.deepcopy(node) for node in nodes]
        used.add(n)
        nodes[-1].tail = stand_in.tail
        parent = stand_in.getparent()
        assert parent is not None  # checked above
        at = parent.index(stand_in)
        parent[at : at + 1] = nodes  # the placeholder (and its tail, now the last node's) replaced
    return etree.tostring(root.getroottree(), encoding="unicode")


def _size(run: tuple[etree._Element, ...]) -> tuple[int, int]:
    """The elements of a run (and below them) and the characters of their values and texts."""
    elements = chars = 0
    for top in run:
        for node in top.iter():
            chars += len(node.text or "") + len(node.tail or "")
            if isinstance(node.tag, str):  # an element (a comment has text, no attributes)
                elements += 1
                chars += sum(len(v) for v in node.values())
    return elements, chars
