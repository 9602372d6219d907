"""The proof of a rendered MoveIt config package: every file parsed back by an independent
parser (yaml.safe_load, ast.parse, catkin_pkg) and compared with the model.

A YAML value MoveIt declares as a double must read back as a float (GEN091); every other
difference is GEN090; a file that does not parse is GEN092. config/<robot>.urdf.xacro is
expanded with xacro and its mock hardware's initial values compared with the initial state (GEN093).
"""

from __future__ import annotations

import ast
import dataclasses
import math
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml
from lxml import etree

from descgen.codes import Code
from descgen.codes.generate import GEN090, GEN091, GEN092, GEN093
from descgen.core import model as m
from descgen.core.findings import Finding, InputError, Where
from descgen.physics import moveit_groups as derive
from descgen.prove.controllers import safe_load
from descgen.render.moveit import moveit_package_name


class _Proof:
    def __init__(self, files: dict[str, str], package_dir: Path) -> None:
        self.files = files
        self.dir = package_dir
        self.findings: list[Finding] = []

    def fail(self, code: Code, rel: str, message: str) -> None:
        hint = (
            "a descgen or template bug: report it (with the spec); a template override must keep the values"
            if code != GEN092
            else "fix the template that wrote it (or report a descgen bug)"
        )
        self.findings.append(code.finding(f"{rel}: {message}", hint, f"file:{rel}", Where(str(self.dir / rel))))

    def yaml(self, rel: str) -> Any:
        try:
            return safe_load(self.files[rel])  # yaml.safe_load, through libyaml when there
        except yaml.YAMLError as exc:
            self.fail(GEN092, rel, f"does not parse as YAML: {str(exc).splitlines()[0]}")
            return None

    def number(self, rel: str, key: str, got: object, want: float) -> None:
        """``got`` must be a float (not an int, not a bool) equal to ``want``."""
        if not isinstance(got, float):
            self.fail(GEN091, rel, f"{key} reads back as {type(got).__name__} {got!r}, not a float")
        elif got != want:
            self.fail(GEN090, rel, f"{key} is {got!r}, the model says {want!r}")

    def equal(self, rel: str, key: str, got: object, want: object) -> None:
        if got != want:
            self.fail(GEN090, rel, f"{key} is {got!r}, the model says {want!r}")


def check(
    files: dict[str, str], robot: m.Robot, package_dir: Path, description: Mapping[str, str] | None = None
) -> list[Finding]:
    """``description``: the description package's files, for expanding the MoveIt package's
    Xacro (which includes the description's); without them that proof is skipped."""
    p = _Proof(files, package_dir)
    settings = robot.moveit
    if settings is None:
        return []
    _joint_limits(p, robot, settings)
    _kinematics(p, settings)
    _pilz(p, settings)
    _controllers(p, robot)
    _initial_positions(p, robot)
    if description is not None:
        _mock_start(p, robot, description)
        _srdf(p, robot, description)
    for rel in (".setup_assistant", "config/moveit.rviz"):
        p.yaml(rel)
    for rel, text in files.items():
        if rel.endswith(".py"):
            try:
                ast.parse(text, filename=rel)
            except SyntaxError as exc:
                p.fail(GEN092, rel, f"is not valid Python: {exc.msg} (line {exc.lineno})")
    _package_xml(p, robot)
    return p.findings + _audit(files, robot, package_dir)


def _audit(files: dict[str, str], robot: m.Robot, package_dir: Path) -> list[Finding]:
    """The MOVEIT audit rules (the ones any MoveIt config gets) on the rendered package, before
    it is written: the files go to a scratch folder because the audit reads a folder, and the
    findings are pointed back at the package's own paths."""
    from descgen.read.moveit_package import audit_moveit_config

    with tempfile.TemporaryDirectory(prefix="descgen-moveit-") as scratch:
        root = Path(scratch)
        for rel, text in files.items():
            if rel.startswith("config/"):
                (root / rel).parent.mkdir(parents=True, exist_ok=True)
                (root / rel).write_text(text, encoding="utf-8")
        found = audit_moveit_config(robot, root)
        return [_moved(f, scratch, str(package_dir)) for f in found]


def _moved(f: Finding, scratch: str, package_dir: str) -> Finding:
    if not f.where.file.startswith(scratch):
        return f
    where = dataclasses.replace(f.where, file=package_dir + f.where.file[len(scratch) :])
    return dataclasses.replace(f, where=where)


def _mapping(p: _Proof, rel: str, doc: object, key: str) -> dict[str, Any]:
    value = doc.get(key) if isinstance(doc, dict) else None
    if not isinstance(value, dict):
        p.fail(GEN090, rel, f"has no mapping '{key}'")
        return {}
    return value


def _joint_limits(p: _Proof, robot: m.Robot, settings: m.MoveItSettings) -> None:
    rel = "config/joint_limits.yaml"
    doc = p.yaml(rel)
    if doc is None:
        return
    p.number(
        rel, "default_velocity_scaling_factor", doc.get("default_velocity_scaling_factor"), settings.velocity_scaling
    )
    p.number(
        rel,
        "default_acceleration_scaling_factor",
        doc.get("default_acceleration_scaling_factor"),
        settings.acceleration_scaling,
    )
    limits = _mapping(p, rel, doc, "joint_limits")
    joints = derive.planning_joints(robot)
    p.equal(rel, "the joints", sorted(limits), sorted(j.name for j in joints))
    for j in joints:
        got = limits.get(j.name)
        if not isinstance(got, dict):
            continue
        lm = j.limit or m.Limit()
        for key, want in (("velocity", lm.velocity), ("acceleration", lm.acceleration)):
            value = want or 0.0
            p.equal(rel, f"{j.name}.has_{key}_limits", got.get(f"has_{key}_limits"), value > 0.0)
            p.number(rel, f"{j.name}.max_{key}", got.get(f"max_{key}"), value)


def _kinematics(p: _Proof, settings: m.MoveItSettings) -> None:
    rel = "config/kinematics.yaml"
    doc = p.yaml(rel)
    if not isinstance(doc, dict):
        p.fail(GEN090, rel, "is not a mapping of groups")
        return
    p.equal(rel, "the groups", sorted(doc), sorted(k.group for k in settings.kinematics))
    for k in settings.kinematics:
        got = doc.get(k.group)
        if not isinstance(got, dict):
            continue
        p.equal(rel, f"{k.group}.kinematics_solver", got.get("kinematics_solver"), k.solver)
        p.number(
            rel,
            f"{k.group}.kinematics_solver_search_resolution",
            got.get("kinematics_solver_search_resolution"),
            k.search_resolution,
        )
        p.number(rel, f"{k.group}.kinematics_solver_timeout", got.get("kinematics_solver_timeout"), k.timeout)


def _pilz(p: _Proof, settings: m.MoveItSettings) -> None:
    rel = "config/pilz_cartesian_limits.yaml"
    limits = _mapping(p, rel, p.yaml(rel), "cartesian_limits")
    for key in ("max_trans_vel", "max_trans_acc", "max_trans_dec", "max_rot_vel"):
        p.number(rel, f"cartesian_limits.{key}", limits.get(key), getattr(settings, key))


def _controllers(p: _Proof, robot: m.Robot) -> None:
    rel = "config/moveit_controllers.yaml"
    doc = p.yaml(rel)
    if not isinstance(doc, dict):
        p.fail(GEN090, rel, "is not a mapping")
        return
    p.equal(
        rel,
        "moveit_controller_manager",
        doc.get("moveit_controller_manager"),
        "moveit_simple_controller_manager/MoveItSimpleControllerManager",
    )
    want = derive.controllers(robot)
    if not want:
        # an empty controller_names list would stop the launch (moveit/moveit2#3165): no section at all
        p.equal(rel, "moveit_simple_controller_manager", doc.get("moveit_simple_controller_manager"), None)
        return
    smcm = _mapping(p, rel, doc, "moveit_simple_controller_manager")
    p.equal(rel, "controller_names", smcm.get("controller_names"), [c.name for c in want])
    groups = (
        [{j.name for j in derive.group_joints(robot, g.name)} for g in robot.semantic.groups] if robot.semantic else []
    )
    for c in want:
        got = smcm.get(c.name)
        if not isinstance(got, dict):
            p.fail(GEN090, rel, f"has no entry for controller '{c.name}'")
            continue
        p.equal(rel, f"{c.name}.type", got.get("type"), c.type)
        p.equal(rel, f"{c.name}.action_ns", got.get("action_ns"), c.action_ns)
        p.equal(rel, f"{c.name}.default", got.get("default"), True)
        p.equal(rel, f"{c.name}.joints", got.get("joints"), list(c.joints))
        if not any(set(got.get("joints") or ()) <= g for g in groups):
            p.fail(GEN090, rel, f"{c.name}.joints are not the joints of one planning group")


def _initial_positions(p: _Proof, robot: m.Robot) -> None:
    rel = "config/initial_positions.yaml"
    got = _mapping(p, rel, p.yaml(rel), "initial_positions")
    want = derive.initial_positions(robot)
    p.equal(rel, "the joints", sorted(got), sorted(n for n, _ in want))
    for name, value in want:
        if name in got:
            p.number(rel, f"initial_positions.{name}", got[name], value)


def _mock_start(p: _Proof, robot: m.Robot, description: Mapping[str, str]) -> None:
    """GEN093: config/<robot>.urdf.xacro expanded as the builder expands it (default arguments;
    both packages found by ``$(find)``) gives every planning joint's position state the initial
    state's value. Sandboxed like every Xacro made from a spec (checks/xacro_expand.py)."""
    from descgen.prove.xacro_expand import expand_packages  # the expansion cached like check 1's
    from descgen.render.context import package_name

    rel = f"config/{robot.name}.urdf.xacro"
    if rel not in p.files:
        return
    moveit = moveit_package_name(robot)
    try:
        xml, _ = expand_packages({package_name(robot): description, moveit: p.files}, moveit, rel, {})
    except InputError as exc:
        p.fail(GEN093, rel, f"xacro failed: {'; '.join(f.message for f in exc.findings)}")
        return
    doc = etree.fromstring(xml.encode("utf-8"), etree.XMLParser(resolve_entities=False, no_network=True))
    for name, value in derive.initial_positions(robot):
        params = [
            e
            for j in doc.iterfind("ros2_control/joint")
            if j.get("name") == name
            for e in j.iterfind("state_interface[@name='position']/param[@name='initial_value']")
        ]
        if not params:
            continue  # a planning joint no ros2_control block drives: no hardware to start
        for e in params:
            try:
                got = float(e.text or "")
            except ValueError:
                got = math.nan
            if got != value:
                p.fail(GEN093, rel, f"the mock hardware starts {name} at {e.text!r}, the initial state says {value!r}")


def _srdf(p: _Proof, robot: m.Robot, description: Mapping[str, str]) -> None:
    """GEN090: config/<robot>.srdf as the builder loads it (expanded by xacro) is the
    description's SRDF: the same body when it holds nothing xacro acts on, else its sandboxed
    expansion compared as data (a ``$`` is written escaped for xacro: moveit/render.py)."""
    from descgen.core.xmlcompare import first_difference, parse
    from descgen.prove.xacro_expand import expand_packages
    from descgen.render import header

    rel, source = f"config/{robot.name}.srdf", f"srdf/{robot.name}.srdf"
    if rel not in p.files or source not in description:
        return
    ours, theirs = header.read(p.files[rel]), header.read(description[source])
    if ours is None or theirs is None:
        return  # a file without its header is the package check's finding
    if ours.body == theirs.body and "$" not in ours.body and "xacro" not in ours.body:
        return  # nothing for xacro to evaluate: the builder gets these very bytes
    moveit = moveit_package_name(robot)
    try:
        xml, _ = expand_packages({moveit: p.files}, moveit, rel, {})
        diff = first_difference(parse(xml), parse(description[source]))
    except InputError as exc:
        p.fail(GEN090, rel, f"xacro failed: {'; '.join(f.message for f in exc.findings)}")
        return
    except etree.XMLSyntaxError as exc:
        p.fail(GEN092, rel, f"does not parse: {exc}")
        return
    if diff:
        p.fail(GEN090, rel, f"expanded by xacro (as MoveItConfigsBuilder loads it) differs from {source} at {diff}")


def _package_xml(p: _Proof, robot: m.Robot) -> None:
    from descgen.prove.package import invalid_package, read_manifest  # catkin_pkg's verdict, cached

    rel = "package.xml"
    try:
        pkg = read_manifest(p.files[rel])
    except (invalid_package(), ValueError) as exc:
        p.fail(GEN092, rel, f"is invalid: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}")
        return
    p.equal(rel, "the package name", pkg.name, moveit_package_name(robot))
    from descgen.render.context import package_name

    if package_name(robot) not in set(pkg.exec_depends):
        p.fail(GEN090, rel, f"does not exec_depend on {package_name(robot)}")
