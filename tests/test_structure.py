"""The layout DESIGN.md "Where shared pieces live" promises, checked with ``ast``:

- rule modules hold rules only: nothing imports from ``descgen.audit.rules.*`` but the
  registry and the rules package's own ``__init__`` (which loads every rule module);
- the model has no untyped side channel (``Robot.extras``);
- joint-type tuples are written once, in ``descgen/core/model.py``.
"""

from __future__ import annotations

import ast
import dataclasses
import typing
from pathlib import Path

import pytest

from descgen.core import model
from descgen.spec import models as spec_models

PACKAGE = Path(__file__).resolve().parents[1] / "descgen"
RULES = PACKAGE / "audit" / "rules"
# the only modules allowed to import the rule modules: they load them to register the rules
RULE_LOADERS = {PACKAGE / "audit" / "registry.py", RULES / "__init__.py"}
JOINT_TYPES = {"fixed", "revolute", "continuous", "prismatic", "floating", "planar"}


def _modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imported(path: Path, tree: ast.Module) -> list[tuple[int, str]]:
    """(line, absolute module) for every import in ``path``, relative ones resolved.
    ``from X import a`` also yields ``X.a``: ``from descgen.audit import rules`` imports a module."""
    package = _module_name(path).split(".")
    if path.name != "__init__.py":
        package = package[:-1]
    out: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            mod = ".".join([*base, *([node.module] if node.module else [])])
            out += [(node.lineno, mod)] + [(node.lineno, f"{mod}.{a.name}") for a in node.names]
    return out


def _rule_imports(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    return [
        f"{path.relative_to(PACKAGE.parent)}:{line} imports {mod}"
        for line, mod in _imported(path, tree)
        if mod == "descgen.audit.rules" or mod.startswith("descgen.audit.rules.")
    ]


def test_resolves_relative_imports() -> None:
    """The checker itself: relative imports (one and three dots) and absolute ones all name
    the rule module they import (else the test below would see nothing)."""
    rule_module = RULES / "density.py"
    tree = ast.parse(
        "from .scale import dims\nfrom ...audit.rules.inertia import x\nimport descgen.audit.rules.joints\n"
    )
    mods = {m for _, m in _imported(rule_module, tree)}
    assert {"descgen.audit.rules.scale", "descgen.audit.rules.inertia.x", "descgen.audit.rules.joints"} <= mods
    faults = PACKAGE / "faults.py"
    tree = ast.parse("from .audit.rules.scale import dims\nfrom .audit import rules\n")
    assert {m for _, m in _imported(faults, tree)} >= {"descgen.audit.rules.scale.dims", "descgen.audit.rules"}


def test_nothing_imports_from_rule_modules() -> None:
    """Shared physics and derivations live below the rules (physics.py, naming.py,
    control/claims.py, control/hardware_info.py); a rule module imports no other one."""
    offenders = [hit for path in _modules() if path not in RULE_LOADERS for hit in _rule_imports(path)]
    assert offenders == []


def test_robot_has_no_untyped_side_channel() -> None:
    fields = {f.name: f.type for f in dataclasses.fields(model.Robot)}
    assert "extras" not in fields
    # what extras carried is typed now: the readers' mesh states, the spec's density range, the SRDF's name
    assert {"mesh_status", "density_range"} <= set(fields)
    assert "robot_name" in {f.name for f in dataclasses.fields(model.Semantic)}
    hints = typing.get_type_hints(model.Robot)
    assert all(h is not dict and typing.get_origin(h) is not dict for h in hints.values())


def _joint_type_literals(text: str, shown: str) -> list[str]:
    """Tuples, lists and sets of two or more joint-type strings, outside a ``Literal[...]``
    (a type mypy needs spelled out; tested against the model's constant below)."""
    tree = ast.parse(text, shown)
    in_literal: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Subscript) and ast.unparse(node.value).endswith("Literal"):
            in_literal |= {id(n) for n in ast.walk(node.slice)}
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Tuple | ast.List | ast.Set) and id(node) not in in_literal:
            names = [e.value for e in node.elts if isinstance(e, ast.Constant) and e.value in JOINT_TYPES]
            if len(names) >= 2:
                out.append(f"{shown}:{node.lineno} {ast.unparse(node)}")
    return out


def test_joint_type_tuples_only_in_the_model() -> None:
    """Joint-type sets use model.py's constants (MOVABLE, ONE_DOF, ROTATING, WITH_LIMITS, ...)."""
    offenders = [
        hit
        for path in _modules()
        # the read-back reader of proof 2 is independent of the model on purpose (it is the
        # parser that checks what the model wrote), so it spells urdfdom's joint types itself
        if path not in (PACKAGE / "core" / "model.py", PACKAGE / "read" / "urdf_readback.py")
        for hit in _joint_type_literals(path.read_text(encoding="utf-8"), str(path.relative_to(PACKAGE.parent)))
    ]
    assert offenders == []


@pytest.mark.parametrize(
    ("source", "found"),
    [
        ('if j.type in ("revolute", "prismatic"):\n    pass', 1),
        ('x = ["fixed", "floating"]', 1),
        ('ok = j.type not in {"planar", "continuous"}', 1),
        ('T = Literal["fixed", "planar"]', 0),  # a type: exempt, checked against the model instead
        ('x = ("revolute", "box")', 0),  # one joint type is not a joint-type tuple
    ],
)
def test_joint_type_checker_sees_literals(source: str, found: int) -> None:
    assert len(_joint_type_literals(source, "probe.py")) == found


def test_schema_joint_types_are_the_models() -> None:
    """The spec schema spells its Literals out (mypy needs them); they must be the model's."""
    assert set(typing.get_args(spec_models.JointType)) == set(model.JOINT_TYPES)
    virtual = typing.get_type_hints(spec_models.VirtualJointSpec)["type"]
    assert set(typing.get_args(virtual)) == set(model.VIRTUAL_JOINT_TYPES)
