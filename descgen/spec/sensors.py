"""Sensors (``sensors:``) -> ``<name>_link`` on a fixed ``<name>_joint``; a camera also gets
``<name>_optical_frame`` with the REP 103 rotation."""

from __future__ import annotations

import math

from descgen.core import model as m
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.geometry import pose
from descgen.spec.links import link

# REP 103: the optical frame is z forward, x right, y down relative to the body frame
# (x forward, y left, z up); as fixed-axis rpy this is (-pi/2, 0, -pi/2). See
# docs/reference/conventions.md.
OPTICAL_RPY = (-math.pi / 2, 0.0, -math.pi / 2)


def expand(conv: Converter, specs: list[s.SensorSpec]) -> tuple[list[m.Link], list[m.Joint], list[m.Sensor]]:
    links: list[m.Link] = []
    joints: list[m.Joint] = []
    sensors: list[m.Sensor] = []
    for i, sn in enumerate(specs):
        sp = ("sensors", i)
        where = conv.where(sp)
        link_name, joint_name = f"{sn.name}_link", f"{sn.name}_joint"
        links.append(link(conv, link_name, sn.link, (*sp, "link"), None, conv.sources(sn), where))
        joints.append(
            m.Joint(
                joint_name,
                "fixed",
                sn.parent,
                link_name,
                pose(sn.origin),
                None,
                where=where,
                source=conv.sources(sn, sn.origin.source),
                description=sn.description,
            )
        )
        optical = optical_joint = None
        if sn.type == "camera":
            optical, optical_joint = f"{sn.name}_optical_frame", f"{sn.name}_optical_joint"
            links.append(
                m.Link(optical, where=where, source="REP 103", description="optical frame: z forward, x right, y down")
            )
            joints.append(
                m.Joint(
                    optical_joint,
                    "fixed",
                    link_name,
                    optical,
                    m.Pose((0.0, 0.0, 0.0), OPTICAL_RPY),
                    None,
                    where=where,
                    source="REP 103",
                )
            )
        sensors.append(m.Sensor(sn.name, sn.type, link_name, joint_name, optical, optical_joint, where))
    return links, joints, sensors
