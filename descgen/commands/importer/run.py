"""``descgen import``: a URDF or Xacro (+ SRDF) -> a spec, proven by a round trip before writing.

read (the audit's readers, the Xacro sandbox) -> model -> spec data (:mod:`.spec`) -> YAML;
then the spec is loaded with the spec loader, rendered with the templates and the URDF
re-read: it must be the same robot (:mod:`.roundtrip`). Nothing is written unless it is.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from lxml import etree

from descgen.codes.importer import (
    IMP002,
    IMP003,
    IMP004,
    IMP005,
    IMP011,
    IMP013,
    IMP026,
    IMP027,
    IMP029,
    IMP035,
    IMP037,
    IMP038,
    IMP039,
    IMP040,
    IMP041,
)
from descgen.commands.importer import control, variants
from descgen.commands.importer.packages import package_meshes, package_name, package_paths, symbolic, with_package_name
from descgen.commands.importer.poses import known_poses
from descgen.commands.importer.quantity import Units
from descgen.commands.importer.spec import SpecWriter, number, source_name
from descgen.commands.importer.structure import Structure, recognise
from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.core.xmlcompare import line_of
from descgen.infra.safeio import check_file, read_bounded
from descgen.meshes.paths import package_root
from descgen.read.description import Options, kind_of
from descgen.read.srdf import read_srdf_text
from descgen.read.urdf import element_sources, parse_xml, read_urdf_text
from descgen.read.xacro_file import expand_located
from descgen.spec import passthrough


@dataclass(frozen=True)
class ImportOptions:
    description: Options = field(default_factory=Options)
    units: Units = field(default_factory=Units)
    spec_name: str = "robot.yaml"  # the spec's file name, for messages about it
    variants: tuple[variants.Variant, ...] = ()  # --variant: hardware variants of a Xacro
    waive: bool = True  # write a waiver for each defect of the description (IMP038); --no-waivers: not
    fix: bool = False  # --fix: the safe fixes of descgen/commands/fix.py applied to the spec first (IMP039)
    take_prefix: bool = True  # a prefixed Xacro's prefix as the spec's prefix: (IMP041); False: name for name


@dataclass(frozen=True)
class Variants:
    """What the variants' expansions give the spec and the round trip."""

    hardware: dict[str, dict[str, Any]]  # block name -> the spec's hardware: (mock + variants)
    mock_blocks: tuple[str, ...]  # what the generated URDF (the mock variant) must give back
    others: dict[str, tuple[str, ...]]  # gazebo/real -> their original blocks
    report: Finding


@dataclass
class Imported:
    spec_text: str
    robot: m.Robot  # the description as read (inline materials included), what the spec must give back
    audit: list[Finding]  # the description's defects, as descgen audit reports them
    report: list[Finding] = field(default_factory=list)  # what went to pass-through, what was not kept
    differences: list[Finding] = field(default_factory=list)  # the round trip; empty: proven
    kept: list[passthrough.Kept] = field(default_factory=list)
    control: control.Imported = field(default_factory=lambda: control.Imported())  # ros2_control: and controllers
    structured: bool = False  # parts: or sensors: written
    spec_name: str = "robot.yaml"
    variants: Variants | None = None


def read(path: Path, options: Options) -> tuple[bytes, str, tuple[Where | None, ...] | None]:
    """The URDF document of ``path`` (a Xacro is expanded in the sandbox), its display name and,
    for a Xacro, where each element of the expanded document was written."""
    shown = str(path)
    check_file(path, "description", display=shown)
    kind = kind_of(path)
    if kind == "spec":
        raise InputError(
            [
                IMP002.finding(
                    "this is already a descgen spec",
                    "import reads a URDF or a Xacro; a spec needs no import",
                    "file",
                    Where(shown),
                )
            ]
        )
    if kind == "xacro":
        ex = expand_located(path, shown, options.xacro_args, options.package_paths, options.trust_xacro)
        return ex.xml, f"{shown} (expanded)", ex.sources
    return read_bounded(path, "URDF", display=shown), shown, None


def _inline_materials(root: etree._Element, robot: m.Robot, file: str) -> tuple[m.Material, ...]:
    """Materials defined inside a visual (``<material name><color/></material>``): the spec
    declares materials once, so they become top-level materials (URDF readers treat both alike)."""
    known = {mt.name for mt in robot.materials}
    out: list[m.Material] = []
    for me in root.iterfind("link/visual/material"):
        name = me.get("name", "")
        color = me.find("color")
        texture = me.find("texture")
        if not name or name in known or (color is None and texture is None):
            continue
        try:
            rgba = tuple(float(t) for t in (color.get("rgba", "") if color is not None else "").split())
        except ValueError:
            continue
        known.add(name)
        out.append(
            m.Material(
                name,
                (rgba[0], rgba[1], rgba[2], rgba[3]) if len(rgba) == 4 else None,
                texture.get("filename") if texture is not None else None,
                Where(file, line_of(me)),
            )
        )
    return robot.materials + tuple(out)


def _no_empty_materials(robot: m.Robot) -> tuple[m.Link, ...]:
    """``<material name=""/>`` names no material (URDF readers treat it as none)."""
    return tuple(
        dataclasses.replace(lk, visuals=tuple(dataclasses.replace(v, material=v.material or None) for v in lk.visuals))
        for lk in robot.links
    )


def _continuous_limits(robot: m.Robot) -> tuple[m.Robot, list[Finding]]:
    """A continuous joint's ``lower``/``upper`` are left out, and each is reported (IMP026).

    urdfdom reads them, but nothing acts on them: ros2_control's joint_limits marks the joint
    angle_wraparound and ignores them, MoveIt's RevoluteJointModel::setContinuous unbounds the
    variable after reading them (moveit_core revolute_joint_model.cpp, jazzy); descgen's URDF does
    not write them. Kept in the spec they would read as limits the robot does not have."""
    joints, report = [], []
    for j in robot.joints:
        lm = j.limit
        if j.type != "continuous" or lm is None or (lm.lower is None and lm.upper is None):
            joints.append(j)
            continue
        joints.append(dataclasses.replace(j, limit=dataclasses.replace(lm, lower=None, upper=None)))
        shown = ", ".join(f"{k}={v:g} rad" for k, v in (("lower", lm.lower), ("upper", lm.upper)) if v is not None)
        report.append(
            IMP026.finding(
                f"continuous joint '{j.name}' limit {shown} is left out: no consumer applies it to a continuous joint",
                "nothing to do; make the joint revolute if it really stops at these angles",
                f"joint:{j.name}",
                lm.where if lm.where.file else j.where,
            )
        )
    return dataclasses.replace(robot, joints=tuple(joints)), report


def _finite_states(robot: m.Robot, srdf: tuple[bytes, str, Any]) -> tuple[m.Robot, list[Finding]]:
    """Group-state values the spec cannot hold (several numbers for a joint that is no planar or
    floating virtual joint, or unreadable ones): each one left out is reported (IMP011), with
    the value as the SRDF writes it. A virtual joint's list is kept (``GroupState.multi``)."""
    sem = robot.semantic
    assert sem is not None
    dropped = [(s, n) for s in sem.states for n, v in s.values if not math.isfinite(v)]
    report = []
    if dropped:
        root = parse_xml(srdf[0], srdf[1])
        for s, n in dropped:
            je = root.find(f"group_state[@name={_quoted(s.name)}]/joint[@name={_quoted(n)}]")
            raw = je.get("value", "") if je is not None else ""
            where = Where(srdf[1], line_of(je)) if je is not None else s.where
            report.append(
                IMP011.finding(
                    f"group state '{s.name}' joint '{n}' value '{raw}' is not kept: the spec holds one number per "
                    "joint, or a list for a planar/floating virtual joint (this one is neither, or unreadable)"
                    + ("" if _finite(s) else "; the state has no other value, so it is left out"),
                    "the generated SRDF lacks this value; add it to the state by hand if MoveIt needs it",
                    f"group_state:{s.name}",
                    where,
                )
            )
    lost = {id(s) for s, _ in dropped}
    states = tuple(
        dataclasses.replace(s, values=tuple((n, v) for n, v in s.values if math.isfinite(v)))
        for s in sem.states
        if id(s) not in lost or _finite(s)  # a state left with no value cannot be in the spec (SPEC004)
    )
    return dataclasses.replace(robot, semantic=dataclasses.replace(sem, states=states)), report


def _finite(state: m.GroupState) -> bool:
    return bool(state.multi) or any(math.isfinite(v) for _, v in state.values)


def _quoted(text: str) -> str:
    """An XPath string literal for ``text`` (which may hold either quote)."""
    if "'" not in text:
        return f"'{text}'"
    if '"' not in text:
        return f'"{text}"'
    return "concat(" + ', "\'", '.join(f"'{p}'" for p in text.split("'")) + ")"


def _states_with_a_group(robot: m.Robot) -> tuple[m.Robot, list[Finding]]:
    """The SRDF's group states that name a group; IMP040 for each that does not (srdfdom skips
    it: MoveIt never has it)."""
    sem = robot.semantic
    if sem is None or all(s.group for s in sem.states):
        return robot, []
    found = [
        IMP040.finding(
            f"group state '{s.name}' names no group; MoveIt's SRDF parser skips it, and so does the spec",
            "add group=\"...\" to the SRDF's <group_state>, or write the state in the spec's group_states:",
            f"semantic.group_states:{s.name}",
            s.where,
        )
        for s in sem.states
        if not s.group
    ]
    kept = tuple(s for s in sem.states if s.group)
    return dataclasses.replace(robot, semantic=dataclasses.replace(sem, states=kept)), found


def _one_pair_each(robot: m.Robot) -> tuple[m.Robot, list[Finding]]:
    """The SRDF's disabled pairs, each link pair once (the first, with its reason); IMP037 for
    each repeat left out."""
    sem = robot.semantic
    if sem is None:
        return robot, []
    seen: dict[frozenset[str], m.DisabledPair] = {}
    found: list[Finding] = []
    for d in sem.disabled_collisions:
        key = frozenset((d.link1, d.link2))
        if key in seen:
            first = seen[key]
            found.append(
                IMP037.finding(
                    f"disabled pair {d.link1}/{d.link2} (reason {d.reason}) repeats the pair disabled at "
                    f"{first.where.file}:{first.where.line} (reason {first.reason}); the spec keeps the first",
                    "nothing to do: MoveIt's collision matrix holds the pair once",
                    f"semantic.disable_collisions:{d.link1}/{d.link2}",
                    d.where,
                )
            )
            continue
        seen[key] = d
    if not found:
        return robot, []
    return dataclasses.replace(
        robot, semantic=dataclasses.replace(sem, disabled_collisions=tuple(seen.values()))
    ), found


def _semantic(srdf: tuple[bytes, str, Any], robot: m.Robot) -> tuple[m.Robot, list[Finding]]:
    semantic, name, found = read_srdf_text(*srdf)
    return dataclasses.replace(robot, semantic=dataclasses.replace(semantic, robot_name=name)), found


def describe(opts: ImportOptions, path: Path, structured: bool = True, hv: Variants | None = None) -> Imported:
    """Read ``path`` and write its spec text; the round trip is :func:`prove`. With
    ``structured``, cameras and repeated parts are written as ``sensors:`` and ``parts:``."""
    from descgen.read.description import audit, srdf_bytes

    data, shown, sources = read(path, opts.description)
    root = parse_xml(data, shown)
    located = element_sources(root, sources) if sources is not None else {}
    robot, _ = read_urdf_text(data, shown, sources)
    _refuse_too_large(robot, shown)
    robot = dataclasses.replace(
        robot, materials=_inline_materials(root, robot, shown), links=_no_empty_materials(robot)
    )
    robot, report = _continuous_limits(robot)
    # the description's own package and the folders searched: what $(find) and file:// name
    search = [*opts.description.package_paths, package_root(path.resolve().parent)]
    robot, absolute = package_meshes(robot, search, shown)
    report += absolute
    if opts.description.srdf is not None:
        srdf = srdf_bytes(opts.description)  # an .srdf.xacro expanded, as the audit reads it
        robot, _ = _semantic(srdf, robot)
        robot, more_states = _finite_states(robot, srdf)
        report += more_states
        robot, repeated = _one_pair_each(robot)
        report += repeated
        robot, groupless = _states_with_a_group(robot)
        report += groupless
    kept, refused = passthrough.collect(root, located.get)
    # a $(find pkg) the expansion turned into this machine's path is written $(find pkg) again
    kept = [dataclasses.replace(k, xml=symbolic(k.xml, search)) for k in kept]
    writer = SpecWriter(opts.units, source_name)
    ctl = control.import_control(
        root,
        robot,
        writer,
        control.locate_source(located.get, shown, source_name),
        lambda e: located.get(e) or Where(shown, line_of(e)),
        opts.description.controllers,
        dict(opts.description.xacro_args),
        opts.description.launch_args,
    )
    if ctl.data is not None:  # the blocks are in ros2_control:, not in pass-through
        kept = [k for k in kept if k.tag != "ros2_control"]
    if hv is not None:
        ctl = _with_variants(ctl, hv, Where(shown))
    report += ctl.report
    robot = dataclasses.replace(robot, passthrough=tuple(k.xml for k in kept), ros2_control=None)
    report += [
        IMP003.finding(
            f"<{k.tag}> is kept verbatim in passthrough: (the spec has no field for it)",
            "review it in the spec; generate writes it back unchanged",
            f"passthrough:{k.tag}",
            k.where or Where(shown, k.line),
        )
        for k in kept
    ]
    report += [
        IMP004.finding(
            f"<{k.tag}> is not kept: {passthrough.problem(k.xml)}",
            "it is left out of the spec; add what it means by hand if the robot needs it",
            f"passthrough:{k.tag}",
            k.where or Where(shown, k.line),
        )
        for k in refused
    ]
    report += _not_imported(root, opts.description, shown, located, ctl.data is not None)
    structure = recognise(robot, writer) if structured else Structure()
    data_ = spec_data(robot, writer, kept, shown, structure, ctl.data)
    if opts.take_prefix:
        data_, more = _prefixed(data_, path, opts.description, robot, root)
        report += more
    folders, more = package_paths(robot, path, Path(opts.spec_name), opts.description.package_paths)
    report += more
    if folders:
        data_ = _with_package_paths(data_, folders)
    named, why = package_name(robot, Where(opts.spec_name))
    report += why
    if named is not None:
        data_ = with_package_name(data_, named)
    text = dump(data_, shown, opts.units)
    _refuse_too_large(robot, shown, text)
    structured = bool(structure.parts or structure.sensors)
    return Imported(
        text,
        robot,
        audit(path, opts.description),
        report,
        kept=kept,
        control=ctl,
        structured=structured,
        spec_name=opts.spec_name,
        variants=hv,
    )


# The largest description import takes (IMP035): what descgen answers for. Its spec must also fit
# what validate reads (yamlsource.MAX_BYTES, MAX_NODES), else every command would refuse it.
MAX_LINKS = 10_000


def _prefixed(
    data: dict[str, Any], path: Path, options: Options, robot: m.Robot, root: etree._Element
) -> tuple[dict[str, Any], list[Finding]]:
    """The spec data with the description's prefix as ``prefix:`` (commands/importer/prefix.py)."""
    if kind_of(path) != "xacro":
        return data, []
    from descgen.commands.importer import prefix
    from descgen.read.xacro_prefix import declared

    name = declared(path, str(path), options.xacro_args)
    if name is None:
        return data, []
    names = prefix.names_behind(name.value, robot, root, data)
    if names is None:
        return data, []  # some name lacks it: imported as it is (the audit's NAME014 names each)
    note = IMP041.finding(
        f"every name carries {name.declared} '{name.value}': written once as prefix:, and taken out of the names",
        "generate writes it back ($(arg prefix) in the Xacro, default this value)",
        "prefix",
        name.where,
    )
    return prefix.with_prefix(prefix.without(data, name.value, names), name.value), [note]


def _refuse_too_large(robot: m.Robot, shown: str, text: str | None = None) -> None:
    """IMP035 (exit 2, nothing written) for a description past :data:`MAX_LINKS`, or spec
    ``text`` larger than validate reads."""
    from descgen.infra import yamlsource

    why = ""
    if len(robot.links) > MAX_LINKS:
        why = f"{len(robot.links):,} links, more than the {MAX_LINKS:,} descgen imports"
    elif text is not None and len(text.encode("utf-8")) > yamlsource.MAX_BYTES:
        size = len(text.encode("utf-8"))
        why = f"its spec would be {size:,} bytes, more than the {yamlsource.MAX_BYTES:,} validate reads"
    if why:
        raise _too_large(why, Where(shown, 1, 1))


def _too_large(why: str, where: Where) -> InputError:
    return InputError(
        [
            IMP035.finding(
                f"the description is too large to import: {why}",
                "split the description into smaller robots; nothing was written",
                "import",
                where,
            )
        ]
    )


def _with_variants(ctl: control.Imported, hv: Variants, where: Where) -> control.Imported:
    """Each block's hardware as the variants give it; the mock blocks are what the generated
    URDF must give back. IMP030 says so instead of IMP020's "one variant"."""
    if ctl.data is None:
        why = next((f.message for f in ctl.report if f.code == "IMP021"), "it stays in passthrough:")
        raise InputError(
            [
                IMP029.finding(
                    f"the hardware variants cannot be imported: {why}",
                    "import one variant (--xacro-arg) and keep the block in passthrough:, or simplify the block",
                    "ros2_control",
                    where,
                )
            ]
        )
    data = dict(ctl.data)
    data["hardware"] = hv.hardware[data["name"]]
    if "blocks" in data:
        data["blocks"] = [b | {"hardware": hv.hardware[b["name"]]} for b in data["blocks"]]
    report = [f for f in ctl.report if f.code != "IMP020"] + [hv.report]
    return dataclasses.replace(ctl, data=data, blocks=hv.mock_blocks, report=report)


def expand_variants(path: Path, opts: ImportOptions) -> tuple[ImportOptions, Variants]:
    """Expand the Xacro once per variant; the same robot in each (IMP028), hardware the spec
    can hold under each name (IMP029). Returns the options of the base variant's expansion."""
    chosen = opts.variants
    variants.check_set(chosen)
    where = Where(str(path))
    if kind_of(path) != "xacro":
        raise InputError(
            [
                IMP027.finding(
                    "--variant selects Xacro arguments, but this is not a Xacro",
                    "leave --variant out for a URDF",
                    "option",
                    where,
                )
            ]
        )
    common = dict(opts.description.xacro_args)

    def options(v: variants.Variant) -> ImportOptions:
        return dataclasses.replace(
            opts, description=dataclasses.replace(opts.description, xacro_args=common | dict(v.args))
        )

    ex = tuple(variants.expanded(v, read(path, options(v).description)[0]) for v in chosen)
    first = next(e for e in ex if e.variant == variants.base(chosen))
    for e in ex:
        if e is not first:
            variants.same_robot(first, e, where)
    mock = next(e for e in ex if e.variant.name == "mock")
    return options(first.variant), Variants(
        variants.hardware(ex, where),
        variants.block_xml(mock),
        {e.variant.name: variants.block_xml(e) for e in ex if e.variant.name != "mock"},
        variants.report(ex, where),
    )


def _with_package_paths(data: dict[str, Any], folders: list[str]) -> dict[str, Any]:
    """``package_paths:`` right after the robot's name and sources flag, where a reader looks."""
    head = {k: data[k] for k in ("name", "require_sources")}
    return head | {"package_paths": folders} | {k: v for k, v in data.items() if k not in head}


def _not_imported(
    root: etree._Element,
    options: Options,
    shown: str,
    located: dict[etree._Element, Where],
    control_imported: bool = False,
) -> list[Finding]:
    """Elements inside links and joints that no reader keeps: said, never silently lost."""
    known = {
        "link": {"visual", "collision", "inertial"},
        "joint": {
            "origin",
            "parent",
            "child",
            "axis",
            "limit",
            "dynamics",
            "mimic",
            "safety_controller",
            "calibration",
        },
    }
    out = []
    for tag, allowed in known.items():
        for e in root.iterfind(tag):
            for c in e:
                if isinstance(c.tag, str) and c.tag not in allowed:
                    out.append(
                        IMP004.finding(
                            f"<{c.tag}> inside {tag} '{e.get('name', '')}' is not kept (the spec has no field for it)",
                            "add what it means by hand if the robot needs it",
                            f"{tag}:{e.get('name', '')}",
                            located.get(c) or Where(shown, line_of(c)),
                        )
                    )
    if options.controllers is not None and not control_imported:
        out.append(
            IMP005.finding(
                "the controllers YAML is not imported: <ros2_control> stays in passthrough:, so the "
                "controllers stay in their own file",
                "keep using your ros2_controllers.yaml beside the generated package",
                "controllers",
                Where(str(options.controllers)),
            )
        )
    return out


def spec_data(
    robot: m.Robot,
    w: SpecWriter,
    kept: list[passthrough.Kept],
    shown: str,
    structure: Structure | None = None,
    ros2_control: dict[str, Any] | None = None,
) -> dict[str, Any]:
    st = structure or Structure()
    materials = [w.material(mt) for mt in robot.materials]
    links = [w.link(lk) for lk in robot.links if lk.name not in st.links]
    joints = [w.joint(j) for j in robot.joints if j.name not in st.joints]
    poses = known_poses(robot, w, source_name(robot.where if robot.where.file else Where(shown)))
    out: dict[str, Any] = {"name": robot.name, "require_sources": True}
    plaus = w.plausibility()
    if plaus:
        out["plausibility"] = plaus
    if materials:
        out["materials"] = materials
    out["links"] = links
    if joints:
        out["joints"] = joints
    if st.parts:
        out["parts"] = st.parts
    if st.sensors:
        out["sensors"] = st.sensors
    if ros2_control is not None:
        out["ros2_control"] = ros2_control
    if robot.semantic is not None:
        from descgen.commands.importer.semantic import semantic_data

        out["semantic"] = semantic_data(robot, w)
    if poses:
        out["known_poses"] = poses
    if kept:
        out["passthrough"] = [{"xml": k.xml, "source": source_name(k.where or Where(shown, k.line))} for k in kept]
    return out


class _Dumper(yaml.SafeDumper):
    pass


def _str(dumper: yaml.SafeDumper, data: str) -> yaml.Node:
    style = "|" if "\n" in data else None
    return dumper.represent_scalar("tag:yaml.org,2002:str", data, style=style)


def _float(dumper: yaml.SafeDumper, data: float) -> yaml.Node:
    # repr is the shortest text that reads back as the same float (YAML 1.1 needs a dot
    # or an exponent with a sign; the spec reads 1e-05 as the number it means)
    return dumper.represent_scalar("tag:yaml.org,2002:float", repr(data))


_Dumper.add_representer(str, _str)
_Dumper.add_representer(float, _float)


def dump(data: dict[str, Any], shown: str, chosen: Units) -> str:
    head = (
        f"# Imported from {Path(shown.removesuffix(' (expanded)')).name} by descgen import.\n"
        f"# Units: lengths in {chosen.length}, angles in {chosen.angle}, masses in {chosen.mass}, the rest in SI;\n"
        "# every value is exactly the description's (model values, not measurements) and cites\n"
        "# the file:line it came from. Review, then replace sources with your measurements.\n\n"
    )
    body = yaml.dump(data, Dumper=_Dumper, sort_keys=False, default_flow_style=None, width=110, allow_unicode=True)
    return head + body


__all__ = ["ImportOptions", "Imported", "describe", "number"]


@dataclass
class Outcome:
    imported: Imported
    invalid: list[Finding]  # why the spec fails validate (the description's defects); round trip not run

    @property
    def proven(self) -> bool:
        return not self.invalid and not self.imported.differences


def import_description(path: Path, opts: ImportOptions) -> Outcome:
    """Read, write the spec text, prove it by the round trip. InputError: unusable input.

    Parts and cameras are written only in a spec that is proven: when it is not, the flat
    spec is written instead, so the round trip proves it or validate fails at the very
    elements of the description (a part would fold its instances' defects into one)."""
    hv = None
    if opts.variants:
        opts, hv = expand_variants(path, opts)
    outcome = _proved(describe(opts, path, hv=hv))
    if not outcome.proven and _prefix_taken_out(outcome):
        # the prefix pass would not give the original back (a name it treats otherwise than the
        # description does): imported name for name, as a description with a name off its prefix is
        outcome = _proved(describe(dataclasses.replace(opts, take_prefix=False), path, hv=hv))
    if outcome.proven or not outcome.imported.structured:
        return _waived(outcome, opts)
    flat = _proved(describe(opts, path, structured=False, hv=hv))
    if not outcome.invalid:
        flat.imported.report.append(_unstructured(len(outcome.imported.differences), Where(opts.spec_name)))
    return _waived(flat, opts)


def _prefix_taken_out(outcome: Outcome) -> bool:
    return any(f.code == "IMP041" for f in outcome.imported.report)


WAIVER_REASON = "imported as is"


def _fixed(outcome: Outcome) -> None:
    """``import --fix``: the safe fixes applied to the proven spec before its waivers are written."""
    from descgen.commands.fix import fix_text

    imp = outcome.imported
    try:
        fixed = fix_text(imp.spec_text, imp.spec_name)
    except InputError as exc:  # a fix that could not be proven safe: the spec stays as imported
        imp.report += [dataclasses.replace(f, severity="warning") for f in exc.findings]
        return
    if fixed.fixes:
        imp.spec_text = fixed.after
        done = "; ".join(f"{x.code} {x.subject}: {x.what}" for x in fixed.fixes)
        hint = "review the diff of descgen fix --dry-run on the unfixed import if in doubt"
        imp.report.append(
            IMP039.finding(f"{len(fixed.fixes)} fix(es) applied: {done}", hint, "import", Where(imp.spec_name))
        )


def _waived(outcome: Outcome, opts: ImportOptions) -> Outcome:
    """A proven import whose spec the rules reject at the description's own defects gets a
    waiver for each (code, subject), reason "imported as is" (IMP038): validate, generate and
    check then pass, and every defect is still reported, as waived. Input errors (the spec
    cannot be built) and descgen's proofs are never waived (descgen/audit/waivers.py)."""
    from descgen.audit.registry import RULES, run
    from descgen.audit.spec import check_stage, load_spec_text

    if outcome.proven and opts.fix:
        _fixed(outcome)
    if not outcome.proven or not opts.waive:
        return outcome
    imp = outcome.imported
    keys: dict[tuple[str, str], None] = {}
    text = imp.spec_text
    for _ in range(2):  # the input stage's errors, then (the spec now loads) the check stage's
        try:
            loaded = load_spec_text(text, imp.spec_name)
        except InputError as exc:
            new = [(f.code, f.subject) for f in exc.findings if f.blocks and f.code in RULES]
            if not new or any(f.blocks and f.code not in RULES for f in exc.findings):
                return outcome  # an input error no waiver may hide: as before (validate says why)
            keys.update(dict.fromkeys(new))
            text = _with_waivers(imp.spec_text, keys)
            continue
        later = [(f.code, f.subject) for f in run(loaded.robot, stage="check") if f.blocks and check_stage(f.code)]
        if not later or all(k in keys for k in later):
            break
        keys.update(dict.fromkeys(later))
        text = _with_waivers(imp.spec_text, keys)
    if not keys:
        return outcome
    imp.spec_text = text
    codes = sorted({code for code, _ in keys})
    imp.report.append(
        IMP038.finding(
            f"{len(keys)} waiver(s) written for the description's defects ({', '.join(codes)}); "
            "each is still reported, as waived",
            "fix a defect in the spec and remove its waiver; descgen audit of the original lists them too",
            "waivers",
            Where(imp.spec_name),
        )
    )
    return outcome


def _with_waivers(spec_text: str, keys: dict[tuple[str, str], None]) -> str:
    import yaml

    block = [{"code": code, "subject": subject, "reason": WAIVER_REASON} for code, subject in keys]
    return spec_text.rstrip("\n") + "\n\n" + yaml.safe_dump({"waivers": block}, sort_keys=False, width=1000)


def _proved(imported: Imported) -> Outcome:
    from descgen.commands.importer.roundtrip import prove

    try:
        others = imported.variants.others if imported.variants is not None else None
        imported.differences = prove(imported.spec_text, imported.robot, imported.spec_name, imported.control, others)
    except InputError as exc:
        if any(f.code == "YAML003" for f in exc.findings):  # the spec's size, not the description's defect
            bound = next(f for f in exc.findings if f.code == "YAML003")
            raise _too_large(f"its spec has {bound.message}", Where(imported.spec_name)) from None
        invalid = [
            dataclasses.replace(
                f,
                severity="warning",
                message=f"the imported spec fails validate here (a defect of the description): {f.message}",
            )
            for f in exc.findings
            if f.blocks  # the refusal carries the spec's warnings too: those are not why it fails
        ]
        return Outcome(imported, invalid)
    return Outcome(imported, [])


def _unstructured(n: int, where: Where) -> Finding:
    return IMP013.finding(
        f"repeated parts and cameras are written as plain links and joints: as parts:/sensors: the round trip "
        f"differed at {n} place(s)",
        "nothing is lost; group them by hand if you want, and let validate and check prove it",
        "import",
        where,
    )
