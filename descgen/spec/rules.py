"""Spec rules that need the whole validated spec and no model: every measured value cites a
source (SPEC010, with ``require_sources: true``), MoveIt's keys are unique (SPEC024), and so are
the materials' names (SPEC026).
The model's own rules run later, in ``descgen.audit``."""

from __future__ import annotations

from pydantic import BaseModel

from descgen.codes.spec import SPEC010, SPEC024, SPEC026, SPEC120, SPEC121
from descgen.core.findings import Finding
from descgen.infra.yamlsource import Document, Path_
from descgen.spec import models as s
from descgen.spec.quantity import Measured, Written


def duplicate_semantics(doc: Document, sem: s.SemanticSpec) -> list[Finding]:
    """SPEC024: MoveIt keys SRDF elements by name (a group state by name and group, a
    disabled pair by its links), so a second one with the same key would silently
    replace the first; refuse it at the second."""
    keyed: list[tuple[str, list[tuple[object, str]]]] = [
        ("groups", [(g.name, f"group '{g.name}'") for g in sem.groups]),
        ("group_states", [((g.name, g.group), f"group state '{g.name}' of '{g.group}'") for g in sem.group_states]),
        ("end_effectors", [(e.name, f"end effector '{e.name}'") for e in sem.end_effectors]),
        ("virtual_joints", [(v.name, f"virtual joint '{v.name}'") for v in sem.virtual_joints]),
        ("passive_joints", [(n, f"passive joint '{n}'") for n in sem.passive_joints]),
        (
            "disable_collisions",
            [(frozenset((d.link1, d.link2)), f"disabled pair {d.link1}/{d.link2}") for d in sem.disable_collisions],
        ),
    ]
    out: list[Finding] = []
    for section, entries in keyed:
        seen: set[object] = set()
        for i, (key, what) in enumerate(entries):
            if key in seen:
                out.append(
                    SPEC024.finding(
                        f"{what} is declared twice in semantic.{section}",
                        "remove or rename the second one (the SRDF keeps one per name)",
                        f"semantic.{section}.{i}",
                        doc.where(("semantic", section, i)),
                    )
                )
            seen.add(key)
    return out


def duplicate_materials(doc: Document, spec: s.RobotSpec) -> list[Finding]:
    """SPEC026: urdfdom refuses a URDF whose robot-level materials share a name, so the
    generated URDF would fail every reader (GEN070 at generate, before this rule); refuse the
    second at validate."""
    out: list[Finding] = []
    first: dict[str, int] = {}
    for i, mt in enumerate(spec.materials):
        if mt.name in first:
            out.append(
                SPEC026.finding(
                    f"material '{mt.name}' is listed twice in materials (first as entry {first[mt.name] + 1})",
                    "remove the second entry or give it another name (urdfdom refuses a repeated material)",
                    f"materials.{i}",
                    doc.where(("materials", i)),
                )
            )
        else:
            first[mt.name] = i
    return out


def missing_sources(doc: Document, spec: s.RobotSpec) -> list[Finding]:
    """``require_sources: true``: every written quantity needs a source, on itself or on
    an element that contains it."""
    out: list[Finding] = []

    def walk(obj: object, path: Path_, covered: bool) -> None:
        if isinstance(obj, Measured | Written):
            if not covered and not obj.source and path in doc.value_marks:
                out.append(
                    SPEC010.finding(
                        f'measured value "{getattr(obj, "text", obj)}" has no source',
                        "add source: <row ID> to the value or to its element, or set require_sources: false",
                        ".".join(map(str, path)),
                        doc.where(path),
                    )
                )
        elif isinstance(obj, BaseModel):
            fields = type(obj).__pydantic_fields__
            # not getattr(obj, "source", None): on a model without the field that goes through
            # pydantic's __getattr__ and an exception (~50 us, thousands of times in a large spec)
            here = covered or ("source" in fields and bool(obj.source))  # type: ignore[attr-defined]
            for name, info in fields.items():
                walk(getattr(obj, name), (*path, info.alias or name), here)
        elif isinstance(obj, list | tuple):
            for i, item in enumerate(obj):
                walk(item, (*path, i), covered)
        elif isinstance(obj, dict):
            for k, item in obj.items():
                walk(item, (*path, k), covered)

    for name, info in type(spec).model_fields.items():
        if name != "plausibility":  # bounds chosen for checking, not measurements
            walk(getattr(spec, name), (info.alias or name,), False)
    return out


def derived_package_name(doc: Document, spec: s.RobotSpec) -> list[Finding]:
    """SPEC120/SPEC121: without ``package.name`` the package is ``<robot>_description``
    (mesh_paths.package_name), which must be a REP 144 name. A name that does not start with
    a lowercase letter breaks colcon and the ament index (SPEC120, the robot names that used to
    be refused: ``2dof_planar``); uppercase or ``__`` only break REP 144's advice (SPEC121,
    a warning, so specs that validated before still do). The hint is the exact fix."""
    if spec.package.name is not None:
        return []  # checked by the schema (models._package_name)
    derived = f"{spec.name}_description"
    why = s.rep144_problem(derived)
    if why is None:
        return []
    suggested = s.suggest_package_name(derived)
    has_package = isinstance(doc.data, dict) and isinstance(doc.data.get("package"), dict)
    fix = f"add name: {suggested} under package:" if has_package else f"add package: {{name: {suggested}}} to the spec"
    digit = not derived[:1].isalpha()
    return [
        (SPEC120 if digit else SPEC121).finding(
            f"the package name '{derived}' (<robot>_description, from the robot's name) is not a ROS package "
            f"name: {why} (REP 144)",
            fix,
            "package",
            doc.where(("name",)),
        )
    ]
