"""A spec link body -> a model link: visuals, collisions and its inertial."""

from __future__ import annotations

from descgen.core import model as m
from descgen.core.findings import Where
from descgen.infra.yamlsource import Path_
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.geometry import geometry, pose
from descgen.spec.inertial import inertial


def link(
    conv: Converter,
    name: str,
    body: s.LinkBody,
    path: Path_,
    part: str | None = None,
    source: str | None = None,
    where: Where | None = None,
) -> m.Link:
    """``path`` is the YAML body (shared by a part's instances); ``where`` the element's own
    position when it differs (a part instance, a sensor)."""
    visuals = tuple(
        m.Visual(geometry(v.geometry), pose(v.origin), v.name, v.material, conv.where((*path, "visual", i)))
        for i, v in enumerate(body.visual)
    )
    collisions = tuple(
        m.Collision(geometry(c.geometry), pose(c.origin), c.name, conv.where((*path, "collision", i)))
        for i, c in enumerate(body.collision)
    )
    inert = None
    if body.inertial is not None:
        inert = inertial(conv, body.inertial, visuals, collisions, (*path, "inertial"))
    return m.Link(
        name,
        visuals,
        collisions,
        inert,
        where or conv.where(path),
        conv.sources(body, source),
        part,
        body.description,
    )
