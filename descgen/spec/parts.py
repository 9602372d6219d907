"""Repeated parts (``parts:``): one link and joint body, one link and joint per instance,
each placed at the instance's origin and located at the instance for messages."""

from __future__ import annotations

from dataclasses import replace

from descgen.core import model as m
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.joints import joint
from descgen.spec.links import link


def expand(conv: Converter, parts: list[s.PartSpec]) -> tuple[list[m.Link], list[m.Joint]]:
    links: list[m.Link] = []
    joints: list[m.Joint] = []
    for i, part in enumerate(parts):
        pp = ("parts", i)
        for k, inst in enumerate(part.instances):
            ip = (*pp, "instances", k)
            source = conv.sources(part, inst.source)
            links.append(link(conv, inst.link, part.link, (*pp, "link"), part.name, source, conv.where(ip)))
            j = joint(conv, inst.joint, part.joint, inst.link, inst.origin, (*pp, "joint"), part.name, source)
            joints.append(replace(j, where=conv.where(ip)))
    return links, joints
