"""Validated spec -> SI robot model: assembles what the modules beside it build.

Each step has its module: ``convert`` (quantities whose kind depends on context, with
findings at the YAML position), ``geometry`` and ``inertial`` (shapes, inertia from a
primitive), ``links`` and ``joints``, ``parts`` (repeated parts), ``sensors`` (sensor links
and the camera's optical frame), ``ros2_control``, ``semantic`` (known poses and SRDF
groups and states) and ``rules`` (spec-wide rules). Problems become findings at the YAML
position of the value, in :attr:`Builder.findings`.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

from descgen.codes.spec import SPEC148
from descgen.core import model as m
from descgen.core import units
from descgen.core.findings import Finding, Where
from descgen.infra.yamlsource import Document
from descgen.spec import calibration, parts, sensors
from descgen.spec import models as s
from descgen.spec.convert import Converter
from descgen.spec.joints import joint
from descgen.spec.links import link
from descgen.spec.moveit import moveit
from descgen.spec.prefix import namespaced, prefixed
from descgen.spec.ros2_control import ros2_control
from descgen.spec.rules import duplicate_materials, duplicate_semantics
from descgen.spec.semantic import complete_states, known_pose, semantic
from descgen.spec.sources import cites_sources


class Builder:
    def __init__(
        self,
        doc: Document,
        spec: s.RobotSpec,
        ranges: dict[str, units.Range],
        package_paths: tuple[Path, ...] = (),
        stand_ins: bool = False,
    ) -> None:
        """``stand_ins``: ``spec`` was validated from data holding stand-in values (spec/load.py),
        which carry a source the document does not have."""
        self.doc = doc
        self.spec = spec
        self.conv = Converter(doc, ranges, package_paths=package_paths, cited=stand_ins or cites_sources(doc))

    @property
    def findings(self) -> list[Finding]:
        return self.conv.findings

    def build(self) -> m.Robot:
        spec, conv = self.spec, self.conv
        materials = tuple(
            m.Material(mt.name, mt.rgba, mt.texture, conv.where(("materials", i)))
            for i, mt in enumerate(spec.materials)
        )
        links = [link(conv, lk.name, lk, ("links", i)) for i, lk in enumerate(spec.links)]
        joints = [joint(conv, jt.name, jt, jt.child, jt.origin, ("joints", i)) for i, jt in enumerate(spec.joints)]
        part_links, part_joints = parts.expand(conv, spec.parts)
        sensor_links, sensor_joints, sensor_list = sensors.expand(conv, spec.sensors)
        links += part_links + sensor_links
        joints += part_joints + sensor_joints
        # every joint exists now: values given per joint (poses, initial positions) take its unit
        conv.joint_types = {j.name: j.type for j in joints}
        layer = calibration.apply(conv, spec.calibration, joints, sensor_list) if spec.calibration else None
        if layer is not None:  # the robot as measured; the layer keeps the nominal origins
            moved = {j.name: j for j in layer.joints}
            joints = [moved.get(j.name, j) for j in joints]
        rc = ros2_control(conv, spec.ros2_control, {lk.name for lk in links}) if spec.ros2_control else None
        virtual = {v.name: v.type for v in spec.semantic.virtual_joints} if spec.semantic else {}
        poses = tuple(known_pose(conv, kp, ("known_poses", i), virtual) for i, kp in enumerate(spec.known_poses))
        robot = m.Robot(
            spec.name,
            tuple(links),
            tuple(joints),
            materials,
            tuple(sensor_list),
            rc,
            None,
            poses,
            description=spec.description,
            where=conv.where(()),
            package=m.PackageInfo(
                spec.package.version,
                spec.package.maintainer,
                spec.package.email,
                spec.package.license,
                spec.package.name,
            ),
            external_frames=tuple(
                m.ExternalFrame(e.parent, e.child, e.owner, e.static, conv.where(("frames", "external", i)))
                for i, e in enumerate(spec.frames.external)
            ),
            joint_state_sources=tuple(
                m.JointStateSource(js.node, js.kind, tuple(js.joints), conv.where(("frames", "joint_state_sources", i)))
                for i, js in enumerate(spec.frames.joint_state_sources)
            ),
            passthrough=tuple(p.xml for p in spec.passthrough),
            waivers=tuple(
                m.Waiver(w.code, w.subject, w.reason, conv.where(("waivers", i))) for i, w in enumerate(spec.waivers)
            ),
            calibration=layer.calibration if layer else (),
            calibration_sources=layer.calibration_sources if layer else (),
        )
        if spec.passthrough:  # a block kept verbatim is judged as Jazzy reads it (one verdict with audit)
            robot = replace(robot, control_refusals=self._refusals(spec))
        if rc is not None and spec.passthrough:
            # a Gazebo plugin kept in pass-through is the robot's, as in the description it came
            # from: the rules that judge it (CTRL047) see it in the spec too (one verdict)
            robot = replace(robot, ros2_control=replace(rc, sim_plugins=self._sim_plugins(spec)))
        conv.findings += duplicate_materials(self.doc, spec)
        if spec.semantic is not None:
            conv.findings += duplicate_semantics(self.doc, spec.semantic)
            with_semantic = replace(robot, semantic=semantic(conv, spec.semantic, poses))
            robot = complete_states(with_semantic, spec.semantic)
        if spec.moveit is not None:
            robot = replace(robot, moveit=moveit(conv, spec.moveit, robot))
        if spec.namespace:
            robot = namespaced(robot, spec.namespace)
            if spec.moveit is not None:
                conv.error(
                    SPEC148,
                    "moveit: and namespace: are both set; the MoveIt config package does not run in a namespace yet",
                    "leave namespace: out for the MoveIt package, or moveit: out for the namespaced robot",
                    "namespace",
                    conv.where(("namespace",)),
                )
        if spec.prefix:  # last: everything above names things as the spec does, unprefixed
            robot = prefixed(robot, spec.prefix, conv.where(("prefix",)))
        return robot

    def _passthrough(self, spec: Any, tag: str) -> list[tuple[Any, Where]]:
        """The pass-through elements of ``tag``, parsed, each with its place in the spec (one
        that does not parse is refused with its own finding: descgen/spec/passthrough.py)."""
        from lxml import etree

        out = []
        for i, p in enumerate(spec.passthrough):
            try:
                e = etree.fromstring(p.xml.encode("utf-8"), etree.XMLParser(resolve_entities=False, no_network=True))
            except etree.XMLSyntaxError:
                continue
            if e.tag == tag:
                out.append((e, self.conv.where(("passthrough", i))))
        return out

    def _refusals(self, spec: Any) -> tuple[tuple[str, str, Where], ...]:
        """Where Jazzy's parser would throw on a pass-through ``<ros2_control>`` (CTRL066), at
        the pass-through entry."""
        from descgen.physics.component_parser import refusals

        return tuple(
            ((e.get("name") or "").strip(), message, at)
            for e, at in self._passthrough(spec, "ros2_control")
            for message, _ in refusals(e)
        )

    def _sim_plugins(self, spec: Any) -> tuple[tuple[str, Where], ...]:
        """(filename, where) of every ``<gazebo><plugin filename>`` of the pass-through elements."""
        return tuple(
            ((pe.get("filename") or "").strip(), at)
            for e, at in self._passthrough(spec, "gazebo")
            for pe in e.findall("plugin")
        )
