"""URDF elements written from the model with lxml, for the consumers descgen hands a URDF of its
own to (pinocchio for contacts, MuJoCo for simulation). Not the package's URDF: that is rendered
from templates (descgen/render/) and proven; these are in-memory inputs to other libraries, with
every float written by ``repr`` so it reads back as the same double."""

from __future__ import annotations

from collections.abc import Sequence

from lxml import etree

from descgen.core.model import Box, Cylinder, Geometry, Pose, Sphere


def xyz(v: Sequence[float]) -> str:
    return " ".join(repr(float(x)) for x in v)


def origin(parent: etree._Element, pose: Pose) -> None:
    etree.SubElement(parent, "origin", xyz=xyz(pose.xyz), rpy=xyz(pose.rpy))


def geometry(parent: etree._Element, g: Geometry, filename: str | None = None) -> None:
    """``<geometry>`` with its shape; a mesh names ``filename`` (a resolved path) if given."""
    geo = etree.SubElement(parent, "geometry")
    if isinstance(g, Box):
        etree.SubElement(geo, "box", size=xyz(g.size))
    elif isinstance(g, Cylinder):
        etree.SubElement(geo, "cylinder", radius=repr(g.radius), length=repr(g.length))
    elif isinstance(g, Sphere):
        etree.SubElement(geo, "sphere", radius=repr(g.radius))
    else:
        etree.SubElement(geo, "mesh", filename=filename or g.filename, scale=xyz(g.scale))
