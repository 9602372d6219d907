"""Compare two XML documents as data: elements, attributes and text in order, numbers as
numbers, comments and layout ignored. Reports the path of the first difference."""

from __future__ import annotations

import math

from lxml import etree


def _numbers(text: str) -> list[float] | None:
    try:
        return [float(t) for t in text.split()]
    except ValueError:
        return None


def same_value(a: str, b: str, rel: float = 1e-12, abs_: float = 1e-12) -> bool:
    if a == b:
        return True
    na, nb = _numbers(a), _numbers(b)
    if na is None or nb is None or len(na) != len(nb) or not na:
        return False
    return all(math.isclose(x, y, rel_tol=rel, abs_tol=abs_) for x, y in zip(na, nb, strict=True))


def _elements(e: etree._Element) -> list[etree._Element]:
    return list(e.iterchildren(etree.Element))  # elements only: no comments, PIs or entities


def _label(e: etree._Element) -> str:
    name = e.get("name")
    return f"{e.tag!s}[@name='{name!s}']" if name is not None else str(e.tag)


def first_difference(a: etree._Element, b: etree._Element, path: str = "") -> str | None:
    """None when equal, else ``path: what differs``."""
    if _same_tree(a, b):
        return None
    found = _difference(a, b)
    if found is None:
        return None
    trail, what = found
    return path + "".join(f"/{_label(e)}" for e in reversed(trail)) + what


def _same_tree(a: etree._Element, b: etree._Element) -> bool:
    """True when the two trees are node for node the same in document order: tags, attributes
    in any order (xacro writes them sorted, the URDF in template order; _difference compares
    them by name), texts (up to surrounding whitespace, as _difference compares them: xacro
    drops the indentation the URDF has) and child counts (which with the order fix the tree's
    shape). Then nothing differs; otherwise _difference walks the trees to say what (a
    generated URDF and its Xacro's expansion are usually equal, and this pass costs half of
    that walk)."""
    try:
        for x, y in zip(a.iter(), b.iter(), strict=True):
            if x.tag != y.tag or len(x) != len(y):
                return False
            items = x.items()
            if items != y.items() and sorted(items) != sorted(y.items()):
                return False
            if x.text != y.text and (x.text or "").strip() != (y.text or "").strip():
                return False
    except ValueError:  # one tree has more nodes
        return False
    return True


def _difference(a: etree._Element, b: etree._Element) -> tuple[list[etree._Element], str] | None:
    """None when equal, else the elements from the difference up to ``a`` (innermost
    first) and what differs there. The path is built only for a difference: the check
    compares every element of a 1000-link URDF, where labels cost more than comparing."""
    if a.tag != b.tag:
        return [a], f": element <{a.tag}> vs <{b.tag}>"
    if a.items() != b.items():  # the same attributes written the same way are equal values
        for k in sorted(set(a.attrib) | set(b.attrib)):
            va, vb = a.get(k), b.get(k)
            if va is None or vb is None:
                return [a], f"/@{k!s}: present only in {'first' if vb is None else 'second'}"
            if not same_value(str(va), str(vb)):
                return [a], f"/@{k!s}: {va!r} vs {vb!r}"
    if a.text != b.text:
        ta, tb = (a.text or "").strip(), (b.text or "").strip()
        if not same_value(ta, tb):
            return [a], f"/text(): {ta!r} vs {tb!r}"
    ca, cb = _elements(a), _elements(b)
    for x, y in zip(ca, cb, strict=False):
        found = _difference(x, y)
        if found is not None:
            found[0].append(a)
            return found
    if len(ca) != len(cb):
        extra = (ca if len(ca) > len(cb) else cb)[min(len(ca), len(cb))]
        return [a], f": {_label(extra)} present only in {'first' if len(ca) > len(cb) else 'second'}"
    return None


def parse(text: str | bytes) -> etree._Element:
    """Parse XML safely: no network, no external entities, no entity expansion."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True, huge_tree=False)
    data = text.encode("utf-8") if isinstance(text, str) else text
    return etree.fromstring(data, parser)


def line_of(e: etree._Element) -> int:
    """The source line of an element (0 when unknown)."""
    v = e.sourceline
    return v if isinstance(v, int) else 0
