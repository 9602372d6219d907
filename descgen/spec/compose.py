"""A spec's ``compose:``: another robot mounted on a frame of this one, as one robot.

The mounted robot is built from its own spec (descgen/spec/load.py reads it), every name put
behind its prefix by the one prefix pass (descgen/spec/prefix.py), its root hung from the
parent frame on a fixed joint, and its parts merged into this robot: links and joints, sensors,
its ``<ros2_control>`` block beside this robot's (one controller manager, so its controllers'
names are prefixed too), its SRDF groups, states and end effectors (names prefixed; its
virtual joints dropped, since its root is now fixed), its known poses (names prefixed, frames
measured from its own root), calibration and waivers (subjects prefixed). Its own meshes are
copied into this robot's package, under ``meshes/<prefix>/`` (one folder per mount).

What cannot be merged is refused (SPEC144): pass-through XML (its names are text descgen does
not rewrite), hardware variants that differ (one ``hardware:=`` selects every block), and two
elements that would share a name.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from descgen.codes.spec import SPEC143, SPEC144, SPEC145
from descgen.core import model as m
from descgen.core.findings import Finding, Where
from descgen.core.naming import GLOBAL_FRAMES
from descgen.meshes.paths import package_name
from descgen.spec.prefix import prefixed


def mounted(
    host: m.Robot,
    sub: m.Robot,
    spec: str,
    prefix: str,
    parent: str,
    origin: m.Pose,
    joint: str | None,
    where: Where,
    source: str | None = None,
) -> tuple[m.Robot, list[Finding]]:
    """``host`` with ``sub`` mounted on its frame ``parent`` (module docstring), and why not."""
    problems: list[Finding] = []
    if host.link(parent) is None:
        problems.append(
            SPEC143.finding(
                f"compose: parent '{parent}' is not a frame of {host.name}",
                f"name one of {host.name}'s links (or of a robot composed before this one)",
                f"compose:{prefix}",
                where,
            )
        )
    if sub.passthrough:
        problems.append(
            SPEC144.finding(
                f"{sub.name} has {len(sub.passthrough)} pass-through element(s): their names cannot be prefixed",
                "move them to this spec's passthrough:, written with the prefixed names",
                f"compose:{prefix}",
                where,
            )
        )
    root = sub.root()
    if root in GLOBAL_FRAMES:
        problems.append(
            SPEC144.finding(
                f"{sub.name}'s root is the global frame '{root}', which every robot shares: it cannot be mounted",
                f"give {sub.name} a root of its own (e.g. base_link on a fixed joint from {root}), and mount that",
                f"compose:{prefix}",
                where,
            )
        )
    if sub.prefix is not None:
        problems.append(
            SPEC144.finding(
                f"{sub.name}'s spec has its own prefix: '{sub.prefix.value}', and compose: gives it '{prefix}'",
                "remove prefix: from the mounted spec (compose: gives each copy its own)",
                f"compose:{prefix}",
                where,
            )
        )
    if problems or root is None:
        return host, problems
    p = prefixed(sub, prefix, where)
    sub_root = prefix + root
    mount = m.Joint(
        joint or f"{sub_root}_mount_joint",
        "fixed",
        parent,
        sub_root,
        origin,
        None,
        where=where,
        source=source,
        description=f"{sub.name} mounted on {parent}",
    )
    p = _meshes_moved(p, sub, host, prefix)
    materials = {mt.name: replace(mt, name=prefix + mt.name) for mt in p.materials}
    links = tuple(
        replace(
            lk,
            visuals=tuple(
                replace(v, material=materials[v.material].name if v.material in materials else v.material)
                for v in lk.visuals
            ),
        )
        for lk in p.links
    )
    problems += _clashes(host, p, links, mount, where, prefix)
    p, notes = _odometry_off(p, sub_root, where, prefix)
    rc, more = _control(host, p, prefix, where)
    problems += more
    if problems:
        return host, problems
    poses = tuple(
        replace(
            kp,
            name=prefix + kp.name,
            frames=tuple(replace(f, relative_to=f.relative_to or sub_root) for f in kp.frames),
        )
        for kp in p.known_poses
    )
    merged = replace(
        host,
        links=host.links + links,
        joints=(*host.joints, mount, *p.joints),
        materials=host.materials + tuple(materials.values()),
        sensors=host.sensors + p.sensors,
        ros2_control=rc,
        semantic=_semantic(host.semantic, p.semantic, prefix),
        known_poses=host.known_poses + poses,
        # the mounted robot's root is now the mount joint's child: whoever published it is not
        external_frames=host.external_frames + tuple(e for e in p.external_frames if e.child != sub_root),
        joint_state_sources=host.joint_state_sources + p.joint_state_sources,
        mesh_status=host.mesh_status + p.mesh_status,
        mesh_files=host.mesh_files + p.mesh_files,
        waivers=host.waivers + tuple(replace(w, subject=_subject(w.subject, prefix, host.name)) for w in sub.waivers),
        # sources behind the prefix too: two robots' "tracker" are two measurements
        calibration=host.calibration + tuple(replace(c, source=prefix + c.source) for c in p.calibration),
        calibration_sources=host.calibration_sources
        + tuple(replace(c, name=prefix + c.name) for c in p.calibration_sources),
        control_refusals=host.control_refusals + p.control_refusals,
        mounted=(*host.mounted, m.Mounted(sub.name, spec, prefix, parent, mount.name, where)),
    )
    return merged, notes


def _odometry_off(p: m.Robot, root: str, where: Where, prefix: str) -> tuple[m.Robot, list[Finding]]:
    """The mounted robot with its diff drives' odom tf off where they published its root (SPEC145)."""
    rc = p.ros2_control
    if rc is None:
        return p, []
    notes = []
    controllers = []
    for c in rc.controllers:
        drives = c.type.startswith("diff_drive_controller/") and c.param("enable_odom_tf", True) is not False
        if drives and c.param("base_frame_id") == root:
            c = replace(c, params=(*((k, v) for k, v in c.params if k != "enable_odom_tf"), ("enable_odom_tf", False)))
            notes.append(
                SPEC145.finding(
                    f"{prefix}{c.name} published {c.param('odom_frame_id')} -> {root}; mounted on a fixed joint, its "
                    "odometry tf is off (enable_odom_tf: false)",
                    "to drive the robots, give each its own spec with prefix: and namespace:, and audit them with "
                    "--together",
                    f"controller:{prefix}{c.name}",
                    where,
                )
            )
        controllers.append(c)
    return replace(p, ros2_control=replace(rc, controllers=tuple(controllers))), notes


def _subject(subject: str, prefix: str, host: str) -> str:
    """A waiver's subject (``link:finger``, ``disable_collisions:a:b``) as the composed robot's
    finding prints it: every name behind the prefix, a ``robot:`` subject the composing robot's."""
    kind, *names = subject.split(":")
    if not names:
        return subject
    if kind == "robot":
        return f"robot:{host}"
    return ":".join([kind, *(n if not n or n in GLOBAL_FRAMES else prefix + n for n in names)])


def _meshes_moved(p: m.Robot, sub: m.Robot, host: m.Robot, prefix: str) -> m.Robot:
    """The mounted robot's own meshes (``package://<its package>/meshes/...``) renamed into the
    composing robot's package, under ``meshes/<prefix>/`` (the prefix without its last _): that package is
    the one generated, and two mounted robots of one name may have different files."""
    old = f"package://{package_name(sub)}/meshes/"
    new = f"package://{package_name(host)}/meshes/{prefix.rstrip('_') or prefix}/"  # one folder per mount

    def moved(name: str) -> str:
        return new + name[len(old) :] if name.startswith(old) else name

    def shape(g: m.Geometry | None) -> m.Geometry | None:
        return replace(g, filename=moved(g.filename)) if isinstance(g, m.Mesh) else g

    links = tuple(
        replace(
            lk,
            visuals=tuple(replace(v, geometry=shape(v.geometry)) for v in lk.visuals),
            collisions=tuple(replace(c, geometry=shape(c.geometry)) for c in lk.collisions),
        )
        for lk in p.links
    )
    return replace(
        p,
        links=links,
        mesh_files=tuple((moved(n), f) for n, f in p.mesh_files),
        mesh_status=tuple((moved(n), s) for n, s in p.mesh_status),
    )


def _clashes(
    host: m.Robot, p: m.Robot, links: tuple[m.Link, ...], mount: m.Joint, where: Where, prefix: str
) -> list[Finding]:
    out = []
    taken_links = {lk.name for lk in host.links}
    taken_joints = {j.name for j in host.joints}
    for kind, names, taken in (
        ("link", [lk.name for lk in links], taken_links),
        ("joint", [mount.name, *(j.name for j in p.joints)], taken_joints),
    ):
        for name in names:
            if name in taken:
                out.append(
                    SPEC144.finding(
                        f"{kind} '{name}' of the robot mounted with prefix '{prefix}' is already a {kind} here",
                        "give each mounted robot its own prefix, and no name here that starts with one",
                        f"compose:{prefix}",
                        where,
                    )
                )
    return out


def _control(host: m.Robot, p: m.Robot, prefix: str, where: Where) -> tuple[m.Ros2Control | None, list[Finding]]:
    """One controller manager for both: every ``<ros2_control>`` block of each, each joint,
    sensor and GPIO marked with its block, the mounted robot's controllers named behind its prefix."""
    a, b = host.ros2_control, p.ros2_control
    if b is None:
        return a, []
    # one joint_state_broadcaster without a joint list publishes every joint of the controller
    # manager: a second one (the mounted robot's) would publish them all again
    broadcasts_all = a is not None and any(_broadcasts_all(c) for c in a.controllers)
    b = replace(
        b,
        controllers=tuple(
            replace(c, name=prefix + c.name) for c in b.controllers if not (broadcasts_all and _broadcasts_all(c))
        ),
        # hardware component names: one controller manager holds both robots' blocks
        name=prefix + b.name,
        blocks=tuple(replace(hb, name=prefix + hb.name) for hb in b.blocks),
        joints=tuple(replace(j, block=prefix + j.block if j.block else "") for j in b.joints),
        sensors=tuple(replace(s, block=prefix + s.block if s.block else "") for s in b.sensors),
        gpios=tuple(replace(g, block=prefix + g.block if g.block else "") for g in b.gpios),
    )
    if a is None:
        return b, []
    problems = []
    va, vb = [v.name for v in a.variants], [v.name for v in b.variants]
    if va != vb:
        problems.append(
            SPEC144.finding(
                f"{host.name}'s hardware variants {va or 'none'} differ from the mounted robot's {vb or 'none'}",
                "give both robots the same hardware: variants (hardware:= selects one for every block)",
                f"compose:{prefix}",
                where,
            )
        )
    if "mujoco" in va:  # each block's MujocoSystemInterface would run its own simulation (SPEC149's rule)
        problems.append(
            SPEC144.finding(
                "both robots have a mujoco hardware variant: composed, their two <ros2_control> blocks would each run "
                "a simulation of the whole model",
                "compose robots without the mujoco variant, and give the composing spec none",
                f"compose:{prefix}",
                where,
            )
        )
    names = {c.name for c in a.controllers}
    for c in b.controllers:
        if c.name in names:
            problems.append(
                SPEC144.finding(
                    f"controller '{c.name}' of the robot mounted with prefix '{prefix}' is already a controller here",
                    "rename this robot's controller (the mounted robot's are named behind its prefix)",
                    f"compose:{prefix}",
                    where,
                )
            )
    blocks = (*_owned(a), *_owned(b))
    merged = replace(
        a,
        joints=tuple(j for _, js, _, _ in blocks for j in js),
        sensors=tuple(s for _, _, ss, _ in blocks for s in ss),
        gpios=tuple(g for _, _, _, gs in blocks for g in gs),
        blocks=tuple(hb for hb, _, _, _ in blocks),
        controllers=a.controllers + b.controllers,
        sim_plugins=a.sim_plugins + tuple(s for s in b.sim_plugins if s not in a.sim_plugins),
    )
    return merged, problems


def _broadcasts_all(c: m.Controller) -> bool:
    return c.type == "joint_state_broadcaster/JointStateBroadcaster" and not c.param("joints")


Owned = tuple[m.HardwareBlock, tuple[m.ControlJoint, ...], tuple[m.ControlSensor, ...], tuple[m.ControlGpio, ...]]


def _owned(rc: m.Ros2Control) -> list[Owned]:
    """Each block of ``rc`` with what it holds, each element naming its block (a spec's one
    block leaves ``block`` empty: with a second robot's blocks beside it, it must say)."""
    blocks = rc.hardware_blocks()
    one = len(blocks) == 1

    def mine(block: str, hb: m.HardwareBlock) -> bool:
        return one or block == hb.name

    return [
        (
            hb,
            tuple(replace(j, block=hb.name) for j in rc.joints if mine(j.block, hb)),
            tuple(replace(s, block=hb.name) for s in rc.sensors if mine(s.block, hb)),
            tuple(replace(g, block=hb.name) for g in rc.gpios if mine(g.block, hb)),
        )
        for hb in blocks
    ]


def _semantic(a: m.Semantic | None, b: m.Semantic | None, prefix: str) -> m.Semantic | None:
    """The SRDF of both: the mounted robot's groups, states and end effectors behind its prefix;
    its virtual joints dropped (its root hangs from a fixed joint now)."""
    if b is None:
        return a
    g: Callable[[str], str] = lambda name: prefix + name  # noqa: E731 - group names, not frames
    groups = tuple(replace(x, name=g(x.name), subgroups=tuple(g(s) for s in x.subgroups)) for x in b.groups)
    states = tuple(replace(s, name=g(s.name), group=g(s.group)) for s in b.states)
    effectors = tuple(
        replace(e, name=g(e.name), group=g(e.group), parent_group=g(e.parent_group) if e.parent_group else None)
        for e in b.end_effectors
    )
    if a is None:
        settings = b.collision_matrix
        if settings is not None and settings.default_state is not None:  # a state of b: renamed above
            settings = replace(settings, default_state=g(settings.default_state))
        return replace(
            b,
            groups=groups,
            states=states,
            end_effectors=effectors,
            virtual_joints=(),
            robot_name=None,
            collision_matrix=settings,
        )
    return replace(
        a,
        groups=a.groups + groups,
        states=a.states + states,
        end_effectors=a.end_effectors + effectors,
        passive_joints=a.passive_joints + b.passive_joints,
        disabled_collisions=a.disabled_collisions + b.disabled_collisions,
    )
