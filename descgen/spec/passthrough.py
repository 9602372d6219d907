"""What the spec cannot express (Gazebo tags, transmissions, ``<ros2_control>``, unknown
tags), kept as XML text and re-emitted verbatim by generate.

Pass-through text is data from someone else, and the generated Xacro is expanded by xacro
(display.launch.py, MoveItConfigsBuilder). In the Xacro output every ``$`` of a text or an
attribute becomes ``${'$'}`` (xacro evaluates that to a literal dollar), so no
``${...}``/``$(...)`` in it is ever evaluated, except ``$(find pkg)`` with a package name
(:func:`for_xacro`), which xacro evaluates to that package's folder on the machine that
launches the robot; the plain URDF keeps it as written. xacro 2.x evaluates nothing else of plain XML:
it walks elements, attributes and texts, and leaves processing instructions and CDATA alone
(pinocchio's urdfdom refuses the former, the spec the latter). The exceptions are comments
after a ``<!-- xacro:eval-comments -->`` comment, and every ``xacro:``-prefixed element and
attribute, which xacro acts on by its prefix alone (minidom, not namespaces). So a
pass-through element is refused when it holds such a comment, an element or attribute in
xacro's namespace (under any prefix, or as the default namespace), or one with the prefix
``xacro`` (bound to any namespace); the rest of a comment is left alone (xacro keeps it
verbatim).
"""

from __future__ import annotations

import re
from collections.abc import Callable

from lxml import etree

from descgen.core.findings import Where
from descgen.core.record import record
from descgen.core.xmlcompare import line_of

XACRO_NS = "http://www.ros.org/wiki/xacro"
# what the spec itself expresses: a pass-through of these would duplicate the robot's elements
OWN_TAGS = frozenset(("robot", "link", "joint", "material"))
EVAL_COMMENTS = "xacro:eval-comments"  # xacro evaluates the comments after one that holds this
MAX_CHARS = 1_000_000  # one pass-through element; a description is bounded too (safeio)


@record
class Kept:
    tag: str
    xml: str
    line: int
    where: Where | None = None  # where it was written (an expanded Xacro's source line), if known


def _parser() -> etree.XMLParser:
    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False)


def problem(xml: str) -> str | None:
    """Why ``xml`` cannot be a pass-through element (None if it can)."""
    if len(xml) > MAX_CHARS:
        return f"is {len(xml)} characters long; a pass-through element is at most {MAX_CHARS}"
    if "<!" in xml.replace("<!--", ""):
        return "holds a DOCTYPE, entity or CDATA declaration"
    try:
        e = etree.fromstring(xml.encode("utf-8"), _parser())
    except etree.XMLSyntaxError as exc:
        return f"is not one well-formed XML element ({exc.msg})"
    if not isinstance(e.tag, str) or (etree.QName(e).localname in OWN_TAGS and etree.QName(e).namespace is None):
        return f"is a <{e.tag}>, which the spec writes itself"
    # what stands before or after the element is copied too: an XML declaration or a processing
    # instruction there makes the URDF one that pinocchio's parser refuses (GEN070 at generate)
    if xml.lstrip().startswith("<?") or any(
        isinstance(x, etree._ProcessingInstruction) for x in (*e.itersiblings(preceding=True), *e.itersiblings())
    ):
        return "holds an XML declaration or processing instruction outside its element"
    if any(EVAL_COMMENTS in (x.text or "") for x in (*e.itersiblings(preceding=True), *e.itersiblings())):
        return f"holds a comment with '{EVAL_COMMENTS}', which makes xacro evaluate the comments after it"
    for x in e.iter():
        if isinstance(x, etree._Comment):
            if EVAL_COMMENTS in (x.text or ""):
                return f"holds a comment with '{EVAL_COMMENTS}', which makes xacro evaluate the comments after it"
            continue
        if isinstance(x, etree._ProcessingInstruction):
            # xacro leaves it alone, but the urdfdom pinocchio bundles (its tinyxml2) takes it for
            # a misplaced XML declaration and refuses the whole URDF (the collision matrix's GEN070)
            return f"holds the processing instruction <?{x.target!s} ...?>, which pinocchio's URDF parser refuses"
        if not isinstance(x.tag, str):
            continue
        if etree.QName(x).namespace == XACRO_NS or (x.prefix or "") == "xacro" or str(x.tag).startswith("xacro:"):
            return f"holds <{x.tag}>, a xacro instruction (xacro would run it)"
        # xacro acts on a 'xacro:' attribute whatever the prefix is bound to (a declaration alone
        # is harmless: xacro drops xmlns:xacro, and an expanded Xacro's elements often carry one)
        own = {XACRO_NS, x.nsmap.get("xacro")}
        for k in x.attrib:
            if str(k).startswith("{") and str(k)[1:].split("}")[0] in own:
                return f"holds the attribute xacro:{etree.QName(k).localname} (xacro acts on it)"
    return None


def collect(
    root: etree._Element, locate: Callable[[etree._Element], Where | None] = lambda e: None
) -> tuple[list[Kept], list[Kept]]:
    """(kept, refused): every element below ``<robot>`` the spec does not write itself;
    ``locate`` says where an element was written (the Xacro source), when it knows."""
    kept: list[Kept] = []
    refused: list[Kept] = []
    for e in root:
        if not isinstance(e.tag, str) or e.tag in OWN_TAGS:
            continue  # comments and processing instructions are not robot data
        xml = etree.tostring(e, encoding="unicode", with_tail=False)
        item = Kept(str(e.tag), xml, line_of(e), locate(e))
        (refused if problem(xml) else kept).append(item)
    return kept, refused


def for_xacro(xml: str) -> str:
    """``xml`` with every ``$`` of its texts and attributes written ``${'$'}``; a comment
    stays as written unless it would switch xacro's comment evaluation on (:func:`problem`
    refuses that; a model built by other means gets it broken up, as render's comment filter
    does)."""
    e = etree.fromstring(xml.encode("utf-8"), _parser())
    for x in e.iter():
        if x is not e and x.tail:
            x.tail = _escaped(x.tail)
        if isinstance(x, etree._Comment):
            if x.text and EVAL_COMMENTS in x.text:
                x.text = x.text.replace(EVAL_COMMENTS, "xacro: eval-comments")
            continue
        if not isinstance(x.tag, str):
            continue  # a processing instruction: xacro leaves it alone
        if x.text:
            x.text = _escaped(x.text)
        for k, v in x.attrib.items():
            x.set(k, _escaped(str(v)))
    return etree.tostring(e, encoding="unicode", with_tail=False)


# ``$(find pkg)`` with a package name and nothing else: the one substitution left live, so a
# Gazebo plugin's parameters file is this package's on the machine that launches it (xacro
# evaluates it there), never the absolute path of the machine that imported it. It reads the
# package index, nothing more: no code, no file, no environment variable of the input's choice.
_LIVE = re.compile(r"\$\(find [A-Za-z0-9][A-Za-z0-9_-]*\)|\$")


def _escaped(text: str) -> str:
    return _LIVE.sub(lambda m: m.group() if len(m.group()) > 1 else "${'$'}", text)


Canon = tuple[object, ...]


def canonical(e: etree._Element) -> Canon:
    """The XML data of an element: tag, attributes, non-blank text, children, comments; what
    pretty-printing (xacro re-indents) cannot change."""

    def text(t: str | None) -> str:
        return "" if t is None or not t.strip() else t

    children = tuple((canonical(c), text(c.tail)) for c in e)
    if not isinstance(e.tag, str):
        return ("#comment", e.text or "")
    return (e.tag, tuple(sorted(e.attrib.items())), text(e.text), children)


def canonical_text(xml: str) -> Canon:
    return canonical(etree.fromstring(xml.encode("utf-8"), _parser()))
