"""Where Jazzy's ros2_control component parser throws on a ``<ros2_control>`` block, in its own
words (hardware_interface/src/component_parser.cpp on the jazzy branch, 9ffbf97;
docs/ros2_control_parser_jazzy.md, section 3: the row numbers below are that table's).

The parser stops at the first throw and the controller manager does not start; descgen lists
every one, each at its element (CTRL066). Checked here: a required attribute missing (row 5),
a ``<param>`` without a name (row 6), a transmission or hardware without ``<plugin>`` (rows 12,
15), a child of ``<ros2_control>`` the parser does not know (row 17), and a boolean attribute
parse_bool refuses (E1; ``mimic`` is CTRL043's). Attribute values are stripped first, as the
parser does (hardware_interface 4.43.0).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator

from lxml import etree

# P:789-793: the only children <ros2_control> may have
CHILDREN = ("hardware", "properties", "joint", "sensor", "gpio", "transmission")
_BLANKS = " \t\n\r\f\v"

Refusal = tuple[str, etree._Element]  # the parser's message, the element it is about


def stripped(value: str) -> str:
    """An attribute value as the parser uses it: stripped of " \\t\\n\\r\\f\\v" (hardware_interface
    4.43.0; helpers.hpp strip), not of every Unicode space Python's str.strip() knows."""
    return value.strip(_BLANKS)


def _attr(e: etree._Element, name: str) -> str | None:
    value = e.get(name)
    return None if value is None else value.strip(_BLANKS)


def _missing(e: etree._Element, attr: str) -> Refusal | None:
    """Row 5: ``no attribute '{attr}' in '{tag}' tag`` plus `` with name '{name}'`` when the
    element has a non-empty name (P:125-131)."""
    if e.get(attr) is not None:
        return None
    name = _attr(e, "name")
    said = f" with name '{name}'" if name else ""
    return f"no attribute '{attr}' in '{e.tag}' tag{said}", e


def _bool(e: etree._Element, attr: str) -> Refusal | None:
    """E1: parse_bool's std::invalid_argument (L:148-150), on the stripped value."""
    value = _attr(e, attr)
    if value is None or value.lower() in ("true", "false"):
        return None
    return f"Input string : '{value}' is not a valid boolean value. Expected 'true' or 'false'.", e


INT_MAX = 2**31 - 1
_STOI = re.compile(r"[ \t\n\r\f\v]*([+-]?[0-9]+)")
_POSITIVE = re.compile(r"[1-9][0-9]*")


def _stoi(text: str) -> int | str:
    """std::stoi: the leading integer (blanks skipped, the rest ignored); "invalid" when there
    is none, "range" when it does not fit an int."""
    m = _STOI.match(text)
    if m is None:
        return "invalid"
    value = int(m.group(1))
    return value if -INT_MAX - 1 <= value <= INT_MAX else "range"


def _positive(e: etree._Element, attr: str, what: str) -> Refusal | None:
    """Rows 7 and 11 (size, thread_priority: ``[1-9][0-9]*`` after stripping, P:199-227,
    319-341), and E2 when it matches but std::stoi overflows."""
    value = _attr(e, attr)
    if value is None:
        return None
    if not _POSITIVE.fullmatch(value):
        return (
            f'Could not parse {what} tag in "{e.tag}". Got "{value}", but expected a non-zero positive integer.',
            e,
        )
    if int(value) > INT_MAX:
        return f"std::out_of_range from std::stoi: {what} '{value}' does not fit an int", e
    return None


def _rw_rate(e: etree._Element) -> Refusal | None:
    """Rows 8-10 (P:261-295)."""
    value = _attr(e, "rw_rate")
    if value is None:
        return None
    n = _stoi(value)
    if n == "invalid":
        return f'Could not parse rw_rate tag in "{e.tag}". Invalid value: "{value}", expected a positive integer.', e
    if n == "range":
        return (
            f'Could not parse rw_rate tag in "{e.tag}". Out of range value: "{value}", expected a positive valid '
            "integer.",
            e,
        )
    if isinstance(n, int) and n < 0:
        return f'Could not parse rw_rate tag in "{e.tag}". Got "{n}", but expected a positive integer.', e
    return None


def rw_rate(text: str | None) -> int | None:
    """The rw_rate the parser reads from ``text`` (std::stoi: the leading integer), or None
    when there is none or the parser throws on it (rows 8-10)."""
    n = _stoi(text) if text is not None else "invalid"
    return n if isinstance(n, int) and n >= 0 else None


def thread_priority(text: str | None) -> int | None:
    """The thread_priority the parser reads from ``text`` (``[1-9][0-9]*`` after stripping,
    within an int), or None when absent or refused (row 11, E2)."""
    value = None if text is None else text.strip(_BLANKS)
    if value is None or not _POSITIVE.fullmatch(value) or int(value) > INT_MAX:
        return None
    return int(value)


def _async(e: etree._Element) -> Refusal | None:
    """The first throw among ``<async>``'s attributes, in the order the parser reads them
    (affinity, thread_priority, print_warnings; P:742-764): one try block, one message."""
    affinity = _attr(e, "affinity")
    if affinity is not None and (why := _array_problem(affinity)):
        return why, e
    return _positive(e, "thread_priority", "thread_priority") or _bool(e, "print_warnings")


# parse_array<int> (lexical_casts.hpp, LH:116-180), its three checks in order, then each item as
# hardware_interface::stod reads it: a plain decimal (optional sign, fraction, exponent), finite
_FLAT = re.compile(r"\[\s*([^\[\]]*\s*(,\s*[^\[\]]+\s*)*)?\]")
_EMPTY = re.compile(r"\[\s*\]")
_COMMAS = re.compile(r"\[\s*([^,\s]+(\s*,\s*[^,\s]+)*)?\s*\]")
_ITEM = re.compile(r"[^\s,\[\]]+")
_DECIMAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def _array_problem(text: str) -> str | None:
    """parse_array<int>'s message for ``text``, or None when it parses."""
    if not _FLAT.fullmatch(text):  # std::regex_match: the whole string
        return "String must be a flat array: starts with '[' and ends with ']', no nested arrays"
    if _EMPTY.fullmatch(text):
        return None
    if not _COMMAS.fullmatch(text):
        return "String must be a flat array with comma-separated values and no spaces between them"
    for item in _ITEM.findall(text):
        if not _DECIMAL.fullmatch(item) or not math.isfinite(float(item)):
            return f"Failed converting string to floating point or integer: {item}"
    return None


def _params(e: etree._Element, context: str) -> Iterator[Refusal]:
    """Row 6: a ``<param>`` without a name (P:361-364)."""
    for p in e.findall("param"):
        if p.get("name") is None:
            yield f"no parameter name attribute set in param tag for '{context}'", p


def _elements(e: etree._Element) -> list[etree._Element]:
    return [c for c in e if isinstance(c.tag, str)]


def _component(c: etree._Element) -> Iterator[Refusal]:
    """A joint, sensor or gpio (P:446-551): its name, its <limits enable>, its interfaces'
    names and <limits enable>, its params and its interfaces' params."""
    for found in (_missing(c, "name"),):
        if found:
            yield found
    name = _attr(c, "name") or ""
    if c.tag != "gpio":
        limits = c.find("limits")
        if limits is not None:
            for found in (_missing(limits, "enable"), _bool(limits, "enable")):
                if found:
                    yield found
    for iface in (*c.findall("command_interface"), *c.findall("state_interface")):
        if found := _missing(iface, "name"):
            yield found
        if found := _positive(iface, "size", "size"):
            yield found
        limits = iface.find("limits")
        if limits is not None:
            for found in (_missing(limits, "enable"), _bool(limits, "enable")):
                if found:
                    yield found
        yield from _params(iface, name)
    yield from _params(c, name)


def _transmission(t: etree._Element) -> Iterator[Refusal]:
    """A transmission (P:589-629): its name and plugin, its joints' and actuators' name, role
    and read_only, its params."""
    if found := _missing(t, "name"):
        yield found
    name = _attr(t, "name") or ""
    if t.find("plugin") is None:
        yield f"Missing <plugin> tag of <transmission> element for '{name}' in your URDF.", t
    for part in (*t.findall("joint"), *t.findall("actuator")):
        for found in (_missing(part, "name"), _missing(part, "role"), _bool(part, "read_only")):
            if found:
                yield found
    yield from _params(t, name)


def refusals(block: etree._Element) -> list[Refusal]:
    """Every throw of the parser on ``block``, in document order."""
    out: list[Refusal] = []
    for found in (_missing(block, "name"), _missing(block, "type"), _rw_rate(block), _bool(block, "is_async")):
        if found:
            out.append(found)
    if (_attr(block, "is_async") or "").lower() == "true" and (
        found := _positive(block, "thread_priority", "thread_priority")
    ):
        out.append(found)  # read only for an async block (P:705-707)
    name = _attr(block, "name") or ""
    for c in _elements(block):
        if c.tag == "hardware":
            if c.find("plugin") is None:
                out.append((f"Missing <plugin> tag of <hardware> element for '{name}' in your URDF.", c))
            out += _params(c, name)
        elif c.tag == "properties":
            async_ = c.find("async")
            if async_ is not None and (found := _async(async_)):
                out.append((f"Error parsing async tag: {found[0]}", async_))
        elif c.tag in ("joint", "sensor", "gpio"):
            out += _component(c)
        elif c.tag == "transmission":
            out += _transmission(c)
        else:
            out.append((f"invalid tag name '{c.tag}'", c))
    out += _transmission_joints(block, name)
    return out


def _transmission_joints(block: etree._Element, hw: str) -> Iterator[Refusal]:
    """Rows 13 and 14 (auto_fill_transmission_interfaces, P:636-686): a transmission's joint
    that is not a <joint> of the block; in an actuator block, a transmission without exactly
    one joint (checked after row 13, per transmission)."""
    joints = {_attr(j, "name") for j in block.findall("joint")}
    kind = _attr(block, "type") or ""
    for t in block.findall("transmission"):
        tr = _attr(t, "name") or ""
        named = [_attr(j, "name") or "" for j in t.findall("joint")]
        missing = next((n for n in named if n not in joints), None)
        if missing is not None:
            yield (
                f"Error while parsing '{hw}'. Transmission '{tr}' declared joint '{missing}' is not available in "
                f"component '{hw}'.",
                t,
            )
        elif kind == "actuator" and len(named) != 1:
            yield (
                f"Error while parsing '{hw}'. There should be exactly one joint defined in this component but found "
                f"{len(named)}.",
                t,
            )


__all__ = ["CHILDREN", "Refusal", "refusals"]
