"""Structure the import recognises in a flat description: REP 103 cameras (``sensors:``) and
exactly repeated parts (``parts:``).

Only what is exact: a camera is ``<n>_link`` on a fixed ``<n>_joint`` with an empty
``<n>_optical_frame`` on a fixed ``<n>_optical_joint`` at zero offset and exactly the REP 103
rotation (what ``sensors:`` generates); a part is two or more links with the same body,
hung by joints that differ only in name, child and origin. The spec data of each candidate
is compared as written (sources aside), so a part generates exactly the links and joints it
replaces; the round trip then proves the whole robot, and the import falls back to plain
links and joints if it did not (run.py).
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

from descgen.commands.importer.spec import Data, SpecWriter
from descgen.core import model as m
from descgen.render.views import identifier
from descgen.spec.models import NAME_PATTERN, XACRO_TAGS, is_element_name
from descgen.spec.sensors import OPTICAL_RPY


@dataclass
class Structure:
    parts: list[Data] = field(default_factory=list)
    sensors: list[Data] = field(default_factory=list)
    links: set[str] = field(default_factory=set)  # written by parts or sensors, not under links:
    joints: set[str] = field(default_factory=set)


def _plain(joint: m.Joint | None, kind: str = "fixed") -> bool:
    return (
        joint is not None
        and joint.type == kind
        and joint.limit is None
        and joint.dynamics is None
        and joint.mimic is None
        and joint.safety is None
    )


def _empty(link: m.Link | None) -> bool:
    return link is not None and not link.visuals and not link.collisions and link.inertial is None


def _unsourced(data: Any) -> Any:
    """Spec data without its sources: what two instances must share exactly."""
    if isinstance(data, dict):
        return {k: _unsourced(v) for k, v in data.items() if k != "source"}
    if isinstance(data, list):
        return [_unsourced(v) for v in data]
    return data


def _body(data: Data, *drop: str) -> Data:
    return {k: v for k, v in data.items() if k not in drop}


def _cameras(robot: m.Robot, w: SpecWriter, out: Structure) -> None:
    by_child = {j.child: j for j in robot.joints}
    links = {lk.name: lk for lk in robot.links}
    for lk in robot.links:
        name = lk.name.removesuffix("_link")
        if name == lk.name or not is_element_name(name):
            continue
        body = by_child.get(lk.name)
        optical = by_child.get(f"{name}_optical_frame")
        if (
            body is None
            or body.name != f"{name}_joint"
            or not _plain(body)
            or optical is None
            or optical.name != f"{name}_optical_joint"
            or optical.parent != lk.name
            or not _plain(optical)
            or any(optical.origin.xyz)
            or optical.origin.rpy != OPTICAL_RPY
            or not _empty(links.get(f"{name}_optical_frame"))
        ):
            continue
        sensor: Data = {"name": name, "type": "camera", "parent": body.parent}
        if (o := w.origin(body.origin)) is not None:
            sensor["origin"] = o
        link_body = _body(w.link(lk), "name", "source")
        if link_body:
            sensor["link"] = link_body
        sensor["source"] = w.source_of(body.where)
        out.sensors.append(sensor)
        out.links |= {lk.name, f"{name}_optical_frame"}
        out.joints |= {body.name, optical.name}


def _common_ending(names: list[str]) -> str:
    """The ``_``-separated words all names end with (``left_wheel``, ``right_wheel`` -> ``wheel``)."""
    words = [n.split("_") for n in names]
    k = 0
    while all(len(w) > k for w in words) and len({w[-1 - k] for w in words}) == 1:
        k += 1
    return "_".join(words[0][len(words[0]) - k :]) if k else ""


def _part_name(links: list[str], taken: set[str]) -> str:
    """The link names' common ending (``left_wheel``, ``right_wheel`` -> ``wheel``), else the
    first name; made unique and never a xacro tag."""
    ending = _common_ending(links).strip("_")
    # a part becomes a xacro macro: its name is an identifier even when the link names are not
    base = ending if re.fullmatch(NAME_PATTERN, ending) else identifier(links[0])
    name, k = base, 2
    while name in taken or name in XACRO_TAGS:
        name, k = f"{base}_{k}", k + 1
    return name


def _parts(robot: m.Robot, w: SpecWriter, out: Structure) -> None:
    groups: dict[str, list[tuple[m.Link, m.Joint, Data, Data]]] = {}
    by_child = {j.child: j for j in robot.joints}
    for lk in robot.links:
        j = by_child.get(lk.name)
        if j is None or lk.name in out.links or (not lk.visuals and not lk.collisions and lk.inertial is None):
            continue  # a root, a sensor's, or an empty frame (a repeated frame is no part)
        link_body = _body(w.link(lk), "name")
        joint_body = _body(w.joint(j), "name", "child", "origin")
        key = repr((_unsourced(link_body), _unsourced(joint_body)))
        groups.setdefault(key, []).append((lk, j, link_body, joint_body))
    taken: set[str] = {lk.name for lk in robot.links} | {j.name for j in robot.joints}
    for members in groups.values():
        if len(members) < 2:
            continue
        _, _, link_body, joint_body = members[0]
        name = _part_name([lk.name for lk, *_ in members], taken)
        taken.add(name)
        instances = []
        for lk, j, _, _ in members:
            inst: Data = {"link": lk.name, "joint": j.name}
            if (o := w.origin(j.origin)) is not None:
                inst["origin"] = o
            inst["source"] = w.source_of(j.where)
            instances.append(inst)
            out.links.add(lk.name)
            out.joints.add(j.name)
        out.parts.append({"name": name, "link": link_body, "joint": joint_body, "instances": instances})


def recognise(robot: m.Robot, w: SpecWriter) -> Structure:
    """Cameras and parts of ``robot`` (nothing when its names are not unique: a defect the
    spec must show where it is, not folded into a part)."""
    out = Structure()
    counts = (
        Counter(lk.name for lk in robot.links),
        Counter(j.name for j in robot.joints),
        Counter(j.child or "" for j in robot.joints),
    )
    if any(n > 1 for c in counts for n in c.values()):
        return out
    _cameras(robot, w, out)
    _parts(robot, w, out)
    return out
