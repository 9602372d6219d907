"""A Xacro's static parts set aside while xacro expands the rest.

xacro's walk leaves an element and everything below it exactly as they are when nothing in
them is for xacro: no ``xacro:*`` element or attribute, no namespace declaration, no ``$`` in a
value or text, no ``xacro:eval-comments`` comment (readers/xacro_file._static_size, whose walk
the sandbox already skips). In descgen's own Xacro of a 1000-link robot nearly every element
is static, and parsing them into minidom nodes, writing them back as text and parsing that
text again was most of check 1 (~0.2 s of a 1000-link ``generate``).

:func:`split` parses the top file once with lxml and replaces each outermost static element
by a placeholder element; xacro expands what is left (the skeleton) in the same sandbox;
:func:`join` replaces each placeholder of the expansion by the element it stood for (a copy
for each further use: a placeholder in a macro body is cloned with it). The result is the
tree xacro gives for the whole file (tests/test_xacro_skeleton.py compares them with
``xacro.process_file``), not the same text: every reader of an expansion reads it as data.

What this cannot mirror exactly, it leaves to the whole-file expansion (:func:`split`
returns None): a DOCTYPE, CDATA (minidom keeps a CDATA section out of xacro's reach, lxml
reads it as text), a namespace declared below the root, an encoding other than UTF-8, a
placeholder name the file already uses, XML lxml refuses. Children of a ``xacro:*`` element
(or any namespaced one) stay in the skeleton: a macro call takes its blocks by position and a
``**`` block inserts the children of its element.
"""

from __future__ import annotations

import copy
import functools
import re
from collections.abc import Sequence
from dataclasses import dataclass

from lxml import etree

from .xacro_eval import MAX_SIZE

PLACEHOLDER = "descgen-static-part"
_DECLARED_ENCODING = re.compile(r"""^\s*<\?xml[^>]*\bencoding\s*=\s*["']([^"']*)["']""")


@dataclass(frozen=True)
class Skeleton:
    """The text xacro expands instead of the file, and the elements its placeholders stand for
    (placeholder ``n`` is ``parts[n]``)."""

    text: str
    parts: Sequence[etree._Element]


def _parser() -> etree.XMLParser:
    # no entity expansion, no network, no recovery: what lxml cannot read as it is goes whole
    return etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)


def split(text: str) -> Skeleton | None:
    """The skeleton of a Xacro file's text, or None when it must be expanded whole (see the
    module docstring) or holds nothing static to set aside."""
    if "<!DOCTYPE" in text or "<![CDATA[" in text or PLACEHOLDER in text:
        return None
    declared = _DECLARED_ENCODING.match(text)
    if declared and declared.group(1).lower().replace("_", "-") not in ("utf-8", "utf8"):
        return None
    try:
        root = etree.fromstring(text.encode("utf-8"), _parser())
    except (etree.XMLSyntaxError, ValueError):
        return None
    # every "xmlns" of the text is one of the root's declarations: none below it, where xacro
    # would remove an xmlns:xacro attribute (a comment or text naming xmlns sends it whole too)
    if text.count("xmlns") != len(root.nsmap):
        return None
    dynamic = _dynamic(text, root)  # kept alive: each element keeps one proxy, so `in` is identity
    walked = set(dynamic)
    parts: list[etree._Element] = []
    stack = [root]
    while stack:
        e = stack.pop()
        keep_children = str(e.tag).startswith("{")  # a xacro:* element's children are its arguments
        for c in list(e):  # replaced while walked
            if not isinstance(c.tag, str):
                continue  # a comment or processing instruction stays where it is
            if c in walked or keep_children:
                stack.append(c)
            else:
                stand_in = etree.Element(PLACEHOLDER, n=str(len(parts)))
                stand_in.tail = c.tail
                e.replace(c, stand_in)
                c.tail = None
                parts.append(c)
    if not parts:
        return None
    return Skeleton(etree.tostring(root.getroottree(), encoding="unicode"), tuple(parts))


def _dynamic(text: str, root: etree._Element) -> list[etree._Element]:
    """The elements xacro's walk does something in or below: each holder of an attribute or
    text with "$" (or longer than one eval_text takes), of a namespaced (xacro:*) attribute, of
    a comment that switches xacro:eval-comments, of a processing instruction, each namespaced
    (xacro:*) element, and all their ancestors. Every other element is left as it is (see
    readers/xacro_file._static_size, the same rules for minidom nodes). One XPath pass in C,
    asking only what the text can hold: no "$" and no character reference, no value with a "$";
    no prefix of the root's followed by ":" (and no default namespace), nothing namespaced; a
    text shorter than the limit, no value longer."""
    values, tests = [], ["//processing-instruction()"]
    if "$" in text or "&#" in text:
        values.append("contains(., '$')")
    if len(text) > MAX_SIZE:
        values.append(f"string-length(.) > {MAX_SIZE}")
    if values:
        tests.append(f"//text()[{' or '.join(values)}]")
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


def join(expanded: str, skeleton: Skeleton, most_elements: int) -> str | None:
    """The expansion of the skeleton with each placeholder replaced by the element it stands
    for (moved there, so a skeleton is joined once; a copy where xacro cloned the placeholder),
    as XML text. None when a placeholder came back changed (xacro never changes
    one) or the result has more than ``most_elements`` elements (the sandbox's bound, which it
    did not see the parts under): the caller then expands the whole file."""
    try:
        root = etree.fromstring(expanded.encode("utf-8"), _parser())
    except (etree.XMLSyntaxError, ValueError):
        return None
    used: set[int] = set()
    for stand_in in list(root.iter(PLACEHOLDER)):
        n = stand_in.get("n", "")
        parent = stand_in.getparent()
        if not n.isdigit() or int(n) >= len(skeleton.parts) or len(stand_in) or stand_in.text or parent is None:
            return None
        part = skeleton.parts[int(n)]
        if int(n) in used:  # a placeholder xacro cloned (a macro body, a block inserted twice)
            part = copy.deepcopy(part)
        used.add(int(n))
        part.tail = stand_in.tail
        parent.replace(stand_in, part)
    if sum(1 for _ in root.iter()) > most_elements:
        return None
    return etree.tostring(root.getroottree(), encoding="unicode")
