"""Planted faults: copy a robot, plant one known mistake, audit the copy, and report
whether a finding of the fault's expected code, on the element the fault was planted in,
caught it (a new finding of another code or about another element does not count: it
would hide a rule that stopped working behind a side effect).

Faults are planted in the model, so the same catalogue works for specs, URDFs and Xacros.
A description that lacks what a fault needs (no ros2_control block, no optical frame)
gets the minimum added, and the report says so.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

from descgen.audit import run
from descgen.core.findings import Finding
from descgen.core.model import (
    ONE_DOF,
    WITH_LIMITS,
    Box,
    ControlJoint,
    Controller,
    Cylinder,
    ExternalFrame,
    Geometry,
    Inertia,
    Interface,
    Joint,
    JointStateSource,
    Link,
    Mesh,
    Pose,
    Robot,
    Ros2Control,
    Sphere,
)
from descgen.core.naming import mirror_name
from descgen.physics import calibration
from descgen.physics.bodies import dims, moving_links


@dataclass(frozen=True)
class Planting:
    robot: Robot  # the copy with the fault
    what: str  # what was changed, for people
    subjects: tuple[str, ...]  # the elements a catching finding must name (joint:x, link:y, ...)


Planted = Planting | None


@dataclass(frozen=True)
class Fault:
    name: str
    description: str
    expects: tuple[str, ...]
    plant: Callable[[Robot], Planted]

    def catches(self, f: Finding, planting: Planting) -> bool:
        return f.code in self.expects and f.subject in planting.subjects


@dataclass(frozen=True)
class Result:
    fault: Fault
    planted: str  # what was changed, or why nothing could be
    caught: bool
    by: Finding | None = None
    applicable: bool = True


def _key(f: Finding) -> tuple[str, str, str]:
    return (f.code, f.subject, f.message)


def _swap_joint(robot: Robot, old: Joint, new: Joint) -> Robot:
    return calibration.with_joint(robot, old, new)


def _swap_link(robot: Robot, old: Link, new: Link) -> Robot:
    return replace(robot, links=tuple(new if lk is old else lk for lk in robot.links))


def _one_dof(robot: Robot, types: tuple[str, ...] = WITH_LIMITS) -> list[Joint]:
    return [j for j in robot.joints if j.type in types]


def _moving_links(robot: Robot) -> list[Link]:
    names = moving_links(robot)
    return [lk for lk in robot.links if lk.name in names]


def _poses_below(robot: Robot, j: Joint) -> tuple[str, ...]:
    """Known poses that measure a frame the joint moves: a wrong origin shows there (POSE010)."""
    below = {j.child, *robot.descendants(j.child)} if j.child else set()
    return tuple(f"pose:{kp.name}" for kp in robot.known_poses if any(fm.frame in below for fm in kp.frames))


def _tree_ends(robot: Robot, j: Joint) -> tuple[str, ...]:
    """The links a removed joint leaves as roots or orphans: its two ends and the old root."""
    root = robot.root()
    return tuple(f"link:{name}" for name in (j.child, j.parent, root) if name)


def origin_x1000(robot: Robot) -> Planted:
    joints = [j for j in robot.joints if any(j.origin.xyz)]
    if not joints:
        return None
    j = max(joints, key=lambda x: math.hypot(*x.origin.xyz))
    x, y, z = j.origin.xyz
    xyz = (x * 1000, y * 1000, z * 1000)
    return Planting(
        _swap_joint(robot, j, replace(j, origin=replace(j.origin, xyz=xyz))),
        f"joint {j.name} origin ×1000",
        (j.subject, *_poses_below(robot, j)),
    )


def _scaled(g: Geometry | None, k: float) -> Geometry | None:
    if isinstance(g, Box):
        return Box((g.size[0] * k, g.size[1] * k, g.size[2] * k))
    if isinstance(g, Cylinder):
        return Cylinder(g.radius * k, g.length * k)
    if isinstance(g, Sphere):
        return Sphere(g.radius * k)
    if isinstance(g, Mesh):
        return Mesh(g.filename, (g.scale[0] * k, g.scale[1] * k, g.scale[2] * k))
    return g


def geometry_x1000(robot: Robot) -> Planted:
    candidates = [lk for lk in robot.links if lk.shapes()]
    if not candidates:
        return None
    link = max(candidates, key=lambda lk: max((d for s in lk.shapes() for d in dims(s.geometry)), default=0.0))
    new = replace(
        link,
        visuals=tuple(replace(v, geometry=_scaled(v.geometry, 1000)) for v in link.visuals),
        collisions=tuple(replace(c, geometry=_scaled(c.geometry, 1000)) for c in link.collisions),
    )
    return Planting(_swap_link(robot, link, new), f"link {link.name} geometry ×1000", (link.subject,))


def _heaviest(robot: Robot, moving_only: bool = True) -> Link | None:
    pool = _moving_links(robot) if moving_only else list(robot.links)
    weighed = [lk for lk in pool if lk.inertial and lk.inertial.mass and lk.inertial.mass > 0]
    return max(weighed, key=lambda lk: lk.inertial.mass or 0.0) if weighed else None  # type: ignore[union-attr]


def mass_x1000(robot: Robot) -> Planted:
    link = _heaviest(robot) or _heaviest(robot, moving_only=False)
    if link is None or link.inertial is None or link.inertial.mass is None:
        return None
    new = replace(link, inertial=replace(link.inertial, mass=link.inertial.mass * 1000))
    # the joints that carry the link must hold it (JOINT008)
    carriers = tuple(j.subject for j in robot.path_to_root(link.name))
    return Planting(_swap_link(robot, link, new), f"link {link.name} mass ×1000", (link.subject, *carriers))


def _perpendicular(axis: tuple[float, float, float]) -> tuple[float, float, float]:
    basis = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    return min(basis, key=lambda b: abs(sum(x * y for x, y in zip(axis, b, strict=True))))


def wrong_axis(robot: Robot) -> Planted:
    moving = [j for j in robot.joints if j.type in ONE_DOF and j.axis]
    posed = {name for kp in robot.known_poses for name, v in kp.joints if v != 0}
    mirrored = [j for j in moving if (m := mirror_name(j.name)) and robot.joint(m) is not None]
    candidates = [j for j in moving if j.name in posed] + mirrored + moving
    if not candidates:
        return None
    j = candidates[0]
    assert j.axis is not None
    axis = _perpendicular(j.axis)
    mirror = mirror_name(j.name)
    posed_in = tuple(f"pose:{kp.name}" for kp in robot.known_poses if any(n == j.name and v for n, v in kp.joints))
    drives = tuple(
        f"controller:{c.name}"
        for c in (robot.ros2_control.controllers if robot.ros2_control else ())
        if j.name in repr(c.params)
    )
    return Planting(
        _swap_joint(robot, j, replace(j, axis=axis)),
        f"joint {j.name} axis {list(j.axis)} -> {list(axis)}",
        (j.subject, *((f"joint:{mirror}",) if mirror else ()), *posed_in, *drives),
    )


def zero_axis(robot: Robot) -> Planted:
    joints = _one_dof(robot, ONE_DOF)
    if not joints:
        return None
    j = joints[0]
    return Planting(
        _swap_joint(robot, j, replace(j, axis=(0.0, 0.0, 0.0))), f"joint {j.name} axis (0, 0, 0)", (j.subject,)
    )


def limits_swapped(robot: Robot) -> Planted:
    for j in _one_dof(robot):
        lm = j.limit
        if lm and lm.lower is not None and lm.upper is not None and lm.lower < lm.upper:
            new = replace(j, limit=replace(lm, lower=lm.upper, upper=lm.lower))
            return Planting(_swap_joint(robot, j, new), f"joint {j.name} lower and upper swapped", (j.subject,))
    return None


def missing_limits(robot: Robot) -> Planted:
    joints = [j for j in _one_dof(robot) if j.limit is not None]
    if not joints:
        return None
    j = joints[0]
    return Planting(_swap_joint(robot, j, replace(j, limit=None)), f"joint {j.name} <limit> removed", (j.subject,))


def negative_mass(robot: Robot) -> Planted:
    link = _heaviest(robot) or _heaviest(robot, moving_only=False)
    if link is None or link.inertial is None or link.inertial.mass is None:
        return None
    new = replace(link, inertial=replace(link.inertial, mass=-link.inertial.mass))
    return Planting(_swap_link(robot, link, new), f"link {link.name} mass negated", (link.subject,))


def non_physical_inertia(robot: Robot) -> Planted:
    for link in _moving_links(robot) + list(robot.links):
        i = link.inertial
        if i is None or i.inertia is None or not i.mass or i.mass <= 0:
            continue
        t = i.inertia
        if t.ixx <= 0 or t.iyy <= 0:
            continue
        bad = Inertia(t.ixx, 0.0, 0.0, t.iyy, 0.0, 3 * (t.ixx + t.iyy))
        return Planting(
            _swap_link(robot, link, replace(link, inertial=replace(i, inertia=bad))),
            f"link {link.name} izz = 3 (ixx + iyy): breaks the triangle inequality",
            (link.subject,),
        )
    return None


def duplicate_name(robot: Robot) -> Planted:
    if len(robot.links) < 2:
        return None
    first, last = robot.links[0], robot.links[-1]
    return Planting(
        _swap_link(robot, last, replace(last, name=first.name)),
        f"link {last.name} renamed to {first.name}",
        (first.subject,),
    )


def second_parent(robot: Robot) -> Planted:
    root = robot.root()
    targets = [j.child for j in robot.joints if j.child and j.parent != root]
    if root is None or not targets:
        return None
    extra = Joint("planted_second_parent_joint", "fixed", root, targets[-1], axis=None)
    return Planting(
        replace(robot, joints=(*robot.joints, extra)),
        f"added a second parent joint to {targets[-1]}",
        (extra.subject, f"link:{targets[-1]}"),
    )


def cycle(robot: Robot) -> Planted:
    for j in robot.joints:
        below = robot.descendants(j.child) if j.child else []
        if below:
            loop = [j, *robot.chain_joints(j.child, below[-1])] if j.child else [j]
            links = {name for x in loop for name in (x.parent, x.child) if name}
            return Planting(
                _swap_joint(robot, j, replace(j, parent=below[-1])),
                f"joint {j.name} parent -> its descendant {below[-1]}",
                ("robot", *(x.subject for x in loop), *(f"link:{name}" for name in sorted(links))),
            )
    return None


def dangling_joint(robot: Robot) -> Planted:
    if not robot.joints:
        return None
    j = robot.joints[-1]
    return Planting(
        _swap_joint(robot, j, replace(j, child="planted_missing_link")),
        f"joint {j.name} child -> a missing link",
        (j.subject,),
    )


def second_root(robot: Robot) -> Planted:
    for j in robot.joints:
        if j.child and robot.descendants(j.child):
            return Planting(
                replace(robot, joints=tuple(x for x in robot.joints if x is not j)),
                f"joint {j.name} removed: {j.child} starts a second tree",
                _tree_ends(robot, j),
            )
    if robot.joints:
        j = robot.joints[-1]
        return Planting(
            replace(robot, joints=robot.joints[:-1]),
            f"joint {j.name} removed: {j.child} becomes a root",
            _tree_ends(robot, j),
        )
    return None


def missing_optical_rotation(robot: Robot) -> Planted:
    for j in robot.joints:
        if j.child and "optical" in j.child.lower() and j.type == "fixed" and any(j.origin.rpy):
            return Planting(
                _swap_joint(robot, j, replace(j, origin=replace(j.origin, rpy=(0.0, 0.0, 0.0)))),
                f"joint {j.name} rotation removed",
                (j.subject, f"link:{j.child}"),
            )
    root = robot.root()
    if root is None:
        return None
    links = (Link("planted_camera_link"), Link("planted_camera_optical_frame"))
    joints = (
        Joint("planted_camera_joint", "fixed", root, "planted_camera_link", Pose((0.1, 0.0, 0.1)), None),
        Joint(
            "planted_camera_optical_joint", "fixed", "planted_camera_link", "planted_camera_optical_frame", Pose(), None
        ),
    )
    return Planting(
        replace(robot, links=robot.links + links, joints=robot.joints + joints),
        "added a camera whose optical frame lacks the REP 103 rotation (the description had none)",
        (joints[1].subject, links[1].subject),
    )


def missing_collision(robot: Robot) -> Planted:
    for link in _moving_links(robot):
        if link.visuals and link.collisions:
            return Planting(
                _swap_link(robot, link, replace(link, collisions=())),
                f"link {link.name} collision removed",
                (link.subject,),
            )
    return None


def _with_control(robot: Robot) -> Ros2Control:
    if robot.ros2_control is not None:
        return robot.ros2_control
    return Ros2Control("planted_system", update_rate=100.0)


def controller_on_missing_joint(robot: Robot) -> Planted:
    rc = _with_control(robot)
    joints = [j.name for j in _one_dof(robot, ONE_DOF)][:2]
    ctrl = Controller(
        "planted_controller",
        "forward_command_controller/ForwardCommandController",
        (("joints", (*joints, "planted_missing_joint")), ("interface_name", "position")),
    )
    added = "" if robot.ros2_control else " (added a ros2_control block)"
    return Planting(
        replace(robot, ros2_control=replace(rc, controllers=(*rc.controllers, ctrl))),
        f"controller commanding missing joint planted_missing_joint{added}",
        (f"controller:{ctrl.name}", "joint:planted_missing_joint"),
    )


def command_beyond_limit(robot: Robot) -> Planted:
    rc = _with_control(robot)
    for j in _one_dof(robot):
        lm = j.limit
        if lm is None or lm.lower is None or lm.upper is None:
            continue
        iface = Interface("position", lm.lower, lm.upper + max(0.1, abs(lm.upper) * 0.1))
        existing = next((cj for cj in rc.joints if cj.name == j.name), None)
        if existing is not None:
            others = tuple(i for i in existing.command if i.name != "position")
            new_joint = replace(existing, command=(iface, *others))
            joints = tuple(new_joint if cj is existing else cj for cj in rc.joints)
        else:
            joints = (*rc.joints, ControlJoint(j.name, (iface,), (Interface("position"),)))
        added = "" if robot.ros2_control else " (added a ros2_control block)"
        return Planting(
            replace(robot, ros2_control=replace(rc, joints=joints)),
            f"'{j.name}/position' command max {iface.max:.6g} beyond upper limit {lm.upper:.6g}{added}",
            (f"ros2_control:{j.name}", j.subject),
        )
    return None


def second_frame_owner(robot: Robot) -> Planted:
    movable = [j for j in robot.joints if j.type != "fixed"]
    for j in movable or list(robot.joints):
        if j.parent is not None and j.child is not None:
            extra = ExternalFrame(j.parent, j.child, "planted_odometry_node")
            return Planting(
                replace(robot, external_frames=(*robot.external_frames, extra)),
                f"a second publisher (planted_odometry_node) for {j.parent} -> {j.child}",
                (extra.subject,),
            )
    return None


def joint_without_state(robot: Robot) -> Planted:
    movable = [j.name for j in robot.joints if j.type in ONE_DOF]
    driven = [j.name for j in robot.joints if j.name in movable and j.mimic is None]  # a mimic follows its leader
    if not driven:
        return None
    victim = driven[-1]
    movable.remove(victim)
    rc = robot.ros2_control
    if rc is None:
        joints = tuple(ControlJoint(n, (Interface("position"),), (Interface("position"),)) for n in movable)
        jsb = Controller("joint_state_broadcaster", "joint_state_broadcaster/JointStateBroadcaster")
        planted = Ros2Control("planted_system", joints=joints, controllers=(jsb,), update_rate=100.0)
        return Planting(
            replace(robot, ros2_control=planted),
            f"ros2_control block without joint {victim} (added; the description had none)",
            (f"joint:{victim}",),
        )
    # a joint whose only feed is its position state interface: removing it leaves the joint
    # unpublished (a joint already unpublished, a FRAME002 of the description, catches nothing new)
    declared = {n for src in robot.joint_state_sources for n in (src.joints or [*movable, victim])}
    fed = [
        cj.name
        for cj in rc.joints
        if cj.name in driven and cj.name not in declared and any(i.name == "position" for i in cj.state)
    ]
    if not fed:
        return None
    victim = fed[-1]
    joints = tuple(
        replace(cj, state=tuple(i for i in cj.state if i.name != "position")) if cj.name == victim else cj
        for cj in rc.joints
    )
    return Planting(
        replace(robot, ros2_control=replace(rc, joints=joints)),
        f"position state interface of {victim} removed",
        (f"joint:{victim}",),
    )


def desired_on_joint_states(robot: Robot) -> Planted:
    source = JointStateSource("trajectory_preview", "desired")
    # the node covers every joint, so the finding may name the node or each joint it publishes
    every = tuple(j.subject for j in robot.joints if j.movable)
    return Planting(
        replace(robot, joint_state_sources=(*robot.joint_state_sources, source)),
        "a node publishing desired (commanded) positions on /joint_states",
        (f"node:{source.node}", *every),
    )


def broadcaster_on_commands(robot: Robot) -> Planted:
    rc = _with_control(robot)
    movable = [j.name for j in robot.joints if j.type in ONE_DOF]
    if not movable:
        return None
    joints = rc.joints or (ControlJoint(movable[0], (Interface("position"),), (Interface("position"),)),)
    first = joints[0]
    wired = replace(first, command=(*first.command, Interface("desired_position")))
    jsb = next((c for c in rc.controllers if c.type.startswith("joint_state_broadcaster/")), None)
    mapping = (("map_interface_to_joint_state", (("position", "desired_position"),)),)
    if jsb is None:
        jsb = Controller("joint_state_broadcaster", "joint_state_broadcaster/JointStateBroadcaster", mapping)
        controllers = (*rc.controllers, jsb)
    else:
        controllers = tuple(replace(c, params=(*c.params, *mapping)) if c is jsb else c for c in rc.controllers)
    return Planting(
        replace(robot, ros2_control=replace(rc, joints=(wired, *joints[1:]), controllers=controllers)),
        f"joint_state_broadcaster mapped to the command interface '{first.name}/desired_position'",
        (f"controller:{jsb.name}",),
    )


def prismatic_travel_mm(robot: Robot) -> Planted:
    """A prismatic limit in millimetres typed as metres (a finger's upper="40" for 40 mm)."""
    for j in _one_dof(robot, ("prismatic",)):
        lm = j.limit
        if lm is None or lm.lower is None or lm.upper is None or max(abs(lm.lower), abs(lm.upper)) == 0:
            continue
        new = replace(j, limit=replace(lm, lower=lm.lower * 1000, upper=lm.upper * 1000))
        return Planting(
            _swap_joint(robot, j, new),
            f"joint {j.name} limits [{lm.lower:.6g}, {lm.upper:.6g}] m written as [{lm.lower * 1000:.6g}, "
            f"{lm.upper * 1000:.6g}] (millimetres typed as metres)",
            (j.subject,),
        )
    return None


def inertia_x10000(robot: Robot) -> Planted:
    """A tensor in kg*cm^2 written as kg*m^2 (10,000 times too large; no common unit slip
    is smaller). Planted in the heaviest moving link whose tensor is plausible now: one
    whose primitive shapes bound it is preferred (the tightest check), then one checked
    against the whole robot's span, then any link."""
    from descgen.physics.extent import half_trace_by_span, moment_by_shapes, robot_span

    span = robot_span(robot)

    def plausible(links: list[Link], by_shapes: bool) -> list[Link]:
        out = []
        for lk in links:
            if lk.inertial is None or lk.inertial.inertia is None or (lk.inertial.mass or 0.0) <= 1e-3:
                continue
            found = moment_by_shapes(lk) if by_shapes else half_trace_by_span(lk, span)
            if found is not None and 0 < found.ratio <= 1:  # a defect already there is no place to plant one
                out.append(lk)
        return out

    moving, every = _moving_links(robot), list(robot.links)
    pools = (plausible(moving, True), plausible(moving, False), plausible(every, True), plausible(every, False))
    pool = next((p for p in pools if p), None)
    if pool is None:
        return None
    link = max(pool, key=lambda lk: (lk.inertial.mass or 0.0) if lk.inertial else 0.0)
    i = link.inertial
    assert i is not None and i.inertia is not None
    t = i.inertia
    big = Inertia(*(10_000 * v for v in (t.ixx, t.ixy, t.ixz, t.iyy, t.iyz, t.izz)))
    return Planting(
        _swap_link(robot, link, replace(link, inertial=replace(i, inertia=big))),
        f"link {link.name} inertia tensor ×10,000 (kg*cm^2 written as kg*m^2)",
        (link.subject,),
    )


CATALOGUE: tuple[Fault, ...] = (
    Fault("origin-x1000", "a joint origin written in millimetres as metres", ("UNIT011", "POSE010"), origin_x1000),
    Fault(
        "geometry-x1000",
        "a geometry written in millimetres as metres",
        ("UNIT012", "UNIT010", "UNIT013"),
        geometry_x1000,
    ),
    Fault("mass-x1000", "a mass written in grams as kilograms", ("UNIT010", "INER006", "JOINT008"), mass_x1000),
    Fault("wrong-axis", "a joint turning about the wrong axis", ("POSE010", "JOINT009", "CTRL006"), wrong_axis),
    Fault("zero-axis", "an <axis/> without xyz (0 0 0)", ("JOINT001",), zero_axis),
    Fault("limits-swapped", "lower and upper limits swapped", ("JOINT004",), limits_swapped),
    Fault("missing-limits", "a revolute/prismatic joint without <limit>", ("JOINT003",), missing_limits),
    Fault("negative-mass", "a negative mass", ("INER001",), negative_mass),
    Fault("non-physical-inertia", "an inertia tensor no body can have", ("INER004", "INER003"), non_physical_inertia),
    Fault("duplicate-name", "two links with one name", ("NAME001",), duplicate_name),
    Fault("second-parent", "a link with two parent joints", ("TOPO002",), second_parent),
    Fault("cycle", "joints forming a loop", ("TOPO003", "TOPO001"), cycle),
    Fault("dangling-joint", "a joint naming a missing link", ("TOPO004",), dangling_joint),
    Fault("second-root", "a second tree", ("TOPO001", "TOPO005"), second_root),
    Fault(
        "missing-optical-rotation",
        "an optical frame without the REP 103 rotation",
        ("NAME013",),
        missing_optical_rotation,
    ),
    Fault("missing-collision", "a moving link with visual but no collision", ("GEOM001",), missing_collision),
    Fault(
        "controller-on-missing-joint",
        "a controller commanding a joint that does not exist",
        ("CTRL009", "CTRL002"),
        controller_on_missing_joint,
    ),
    Fault("command-beyond-limit", "a command limit beyond the URDF limit", ("CTRL008",), command_beyond_limit),
    Fault(
        "two-frame-owners",
        "a second node publishing a transform the robot already publishes",
        ("FRAME001",),
        second_frame_owner,
    ),
    Fault(
        "joint-without-state", "a movable joint with no position state interface", ("FRAME002",), joint_without_state
    ),
    Fault(
        "desired-on-joint-states", "desired commands published on /joint_states", ("FRAME005",), desired_on_joint_states
    ),
    Fault(
        "broadcaster-on-commands",
        "joint_state_broadcaster fed from a command interface",
        ("CTRL010",),
        broadcaster_on_commands,
    ),
    Fault("prismatic-travel-mm", "prismatic travel in mm typed as m", ("JOINT020",), prismatic_travel_mm),
    Fault("inertia-x10000", "an inertia tensor in kg*cm^2 written as kg*m^2", ("INER011",), inertia_x10000),
)


def plant_all(robot: Robot, catalogue: tuple[Fault, ...] = CATALOGUE) -> list[Result]:
    """Plant each fault in a copy, audit it, and report the new finding of an expected code
    about the planted element that caught it (None: missed)."""
    baseline = {_key(f) for f in run(robot)}
    results = []
    for fault in catalogue:
        planting = fault.plant(robot)
        if planting is None:
            results.append(
                Result(fault, "not applicable: the description has nothing to plant it in", False, applicable=False)
            )
            continue
        new = [f for f in run(planting.robot) if _key(f) not in baseline]
        by = next((f for f in new if fault.catches(f, planting)), None)
        results.append(Result(fault, planting.what, by is not None, by))
    return results
