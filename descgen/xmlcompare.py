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
    return [c for c in e if isinstance(c.tag, str)]


def _label(e: etree._Element) -> str:
    name = e.get("name")
    return f"{e.tag!s}[@name='{name!s}']" if name is not None else str(e.tag)


def first_difference(a: etree._Element, b: etree._Element, path: str = "") -> str | None:
    """None when equal, else ``path: what differs``."""
    here = f"{path}/{_label(a)}"
    if a.tag != b.tag:
        return f"{here}: element <{a.tag}> vs <{b.tag}>"
    keys = sorted(set(a.attrib) | set(b.attrib))
    for k in keys:
        va, vb = a.get(k), b.get(k)
        if va is None or vb is None:
            return f"{here}/@{k!s}: present only in {'first' if vb is None else 'second'}"
        if not same_value(str(va), str(vb)):
            return f"{here}/@{k!s}: {va!r} vs {vb!r}"
    ta, tb = (a.text or "").strip(), (b.text or "").strip()
    if not same_value(ta, tb):
        return f"{here}/text(): {ta!r} vs {tb!r}"
    ca, cb = _elements(a), _elements(b)
    for x, y in zip(ca, cb, strict=False):
        diff = first_difference(x, y, here)
        if diff:
            return diff
    if len(ca) != len(cb):
        extra = (ca if len(ca) > len(cb) else cb)[min(len(ca), len(cb))]
        return f"{here}: {_label(extra)} present only in {'first' if len(ca) > len(cb) else 'second'}"
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
