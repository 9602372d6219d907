"""Hardware variants of one Xacro (``descgen import --variant mock:use_mock_hardware:=true ...``).

The Xacro is expanded once per variant. The variants must be the same robot apart from each
``<ros2_control>`` block's ``<hardware>`` (IMP028 names the first difference): that is all the
spec's ``hardware.variants`` can say. The spec's own hardware is the mock variant (SPEC080), its
``variants`` are gazebo and real; a variant whose plugin the spec would refuse under its name
is refused here, before anything is written (IMP029).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from lxml import etree

from descgen.codes import Code
from descgen.codes.importer import IMP027, IMP028, IMP029, IMP030
from descgen.core.findings import Finding, InputError, Where
from descgen.core.xmlcompare import first_difference, parse
from descgen.spec.models import GZ_PLUGIN, MOCK_PLUGIN

NAMES = ("mock", "gazebo", "real")
_STAND_INS = ("mock_components", "gz_ros2_control")  # what a real variant must not name (SPEC082)


@dataclass(frozen=True)
class Variant:
    name: str  # mock, gazebo or real: the spec's hardware:= values
    args: tuple[tuple[str, str], ...]  # the Xacro arguments that select it


@dataclass(frozen=True)
class Expanded:
    variant: Variant
    root: etree._Element  # the expanded document, comments removed
    blocks: tuple[etree._Element, ...]  # its <ros2_control> blocks


def _error(code: Code, message: str, hint: str, subject: str, where: Where) -> InputError:
    return InputError([code.finding(message, hint, subject, where)])


def shown(v: Variant) -> str:
    return f"{v.name} ({', '.join(f'{k}:={x}' for k, x in v.args) or 'no arguments'})"


def check_set(variants: tuple[Variant, ...]) -> None:
    """Names known and unique, a mock variant (the spec's own hardware), at least two."""
    names = [v.name for v in variants]
    hint = "e.g. --variant mock:use_mock_hardware:=true --variant real:use_mock_hardware:=false"
    if len(set(names)) != len(names):
        twice = next(n for n in names if names.count(n) > 1)
        raise _error(IMP027, f"--variant {twice} is given twice", "give each variant once; " + hint, "option", _CL)
    if len(variants) < 2 or "mock" not in names:
        raise _error(
            IMP027,
            f"--variant gives {', '.join(names)}: the spec's hardware variants need a mock variant and at least one "
            "other (gazebo or real)",
            "add --variant mock:<the args that select mock_components/GenericSystem>; " + hint,
            "option",
            _CL,
        )


_CL = Where("<command line>")


def base(variants: tuple[Variant, ...]) -> Variant:
    """The variant whose expansion gives the robot and its pass-through: real, else the first."""
    return next((v for v in variants if v.name == "real"), variants[0])


def _without_hardware(root: etree._Element) -> etree._Element:
    out = copy.deepcopy(root)
    for hw in out.findall("ros2_control/hardware"):
        hw.getparent().remove(hw)  # type: ignore[union-attr]
    return out


def expanded(variant: Variant, xml: bytes) -> Expanded:
    root = parse(xml)
    return Expanded(variant, root, tuple(root.findall("ros2_control")))


def same_robot(first: Expanded, other: Expanded, where: Where) -> None:
    """IMP028 unless ``other`` equals ``first`` apart from the blocks' ``<hardware>``."""
    diff = first_difference(_without_hardware(first.root), _without_hardware(other.root))
    if diff is None and not first.blocks:
        diff = "no <ros2_control> block: there is no hardware to vary"
    if diff is not None:
        raise _error(
            IMP028,
            f"variants {shown(first.variant)} and {shown(other.variant)} are not the same robot apart from the "
            f"<ros2_control> hardware: {diff}",
            "the spec's hardware variants change only the hardware plugin and its params; import each "
            "robot on its own (--xacro-arg), or choose arguments that change only the hardware",
            "import",
            where,
        )


def _params(hw: etree._Element) -> dict[str, str]:
    return {p.get("name", ""): (p.text or "").strip() for p in hw.findall("param")}


def hardware(ex: tuple[Expanded, ...], where: Where) -> dict[str, dict[str, Any]]:
    """Each block's spec ``hardware:``: the mock variant's plugin and params, the others under
    ``variants``. IMP029 when a variant's plugin is not what the spec allows under its name."""
    allowed: dict[str, tuple[Callable[[str], bool], str]] = {
        "mock": (lambda p: p == MOCK_PLUGIN, f"the mock variant must be {MOCK_PLUGIN}"),
        "gazebo": (lambda p: p == GZ_PLUGIN, f"the gazebo variant must be {GZ_PLUGIN} (Jazzy's gz_ros2_control)"),
        "real": (lambda p: p.split("/")[0] not in _STAND_INS, "the real variant must name the vendor's plugin"),
    }
    out: dict[str, dict[str, Any]] = {}
    mock = next(e for e in ex if e.variant.name == "mock")
    for i, block in enumerate(mock.blocks):
        name = block.get("name", "")
        hw: dict[str, Any] = {}
        variants: dict[str, Any] = {}
        for e in sorted(ex, key=lambda e: NAMES.index(e.variant.name)):
            h = e.blocks[i].find("hardware")
            plugin = (h.findtext("plugin") or "").strip() if h is not None else ""
            ok, why = allowed[e.variant.name]
            if not ok(plugin):
                raise _error(
                    IMP029,
                    f"variant {shown(e.variant)} gives ros2_control block '{name}' the hardware '{plugin}': {why}",
                    "pass the arguments that select that hardware, or name the variant after the hardware it selects",
                    f"ros2_control:{name}",
                    where,
                )
            entry: dict[str, Any] = {"plugin": plugin}
            if params := _params(h) if h is not None else {}:
                entry["params"] = params
            if e.variant.name == "mock":
                hw = entry
            else:
                variants[e.variant.name] = entry
        out[name] = hw | {"variants": variants}
    return out


def block_xml(ex: Expanded) -> tuple[str, ...]:
    return tuple(etree.tostring(b, encoding="unicode", with_tail=False) for b in ex.blocks)


def report(ex: tuple[Expanded, ...], where: Where) -> Finding:
    return IMP030.finding(
        "ros2_control hardware imported for the variants " + ", ".join(shown(e.variant) for e in ex) + "; the "
        "generated Xacro selects them with hardware:=" + "|".join(e.variant.name for e in ex),
        "the robot is the same in every variant (checked); launch with hardware:=<variant> instead of these arguments",
        "ros2_control",
        where,
    )
