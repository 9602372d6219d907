"""The spec's ``prefix:`` written before every name the robot puts into a ROS graph.

ROS 2 has no tf_prefix: robots that share a graph keep apart by prefixing every frame, joint,
ros2_control joint, sensor and GPIO, and every name their controllers are given (joint lists,
wheel names, frame ids), as the ros2_control demos' ``prefix`` and the UR description's
``tf_prefix`` do. A spec names things once, unprefixed; this is the one place the prefix is
applied, to the whole model, after everything else is built, so every file generate writes
(URDF, Xacro, SRDF, controllers YAML, MoveIt config) and every check sees the same names. The
Xacro writes the prefix as its ``prefix`` argument (descgen/render/views.py), and NAME014 checks
names written by hand in pass-through and controller parameters.

Left as written: the robot's name, ``<ros2_control>`` block names, planning group and state
names, controller names (one controller manager per robot, or a namespace, keeps those apart;
compose, which puts robots in one manager, prefixes blocks and controllers itself), waivers
(their subjects are what findings print: prefixed), and the global frames ``map``, ``earth``
and ``world``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from descgen.core import model as m
from descgen.core.findings import Where
from descgen.core.naming import GLOBAL_FRAMES
from descgen.physics.control_claims import FRAME_LEAVES, FRAME_PARAMS, default_frames, prefixes_tf_frames, split

# controller parameters that hold the prefix itself (the UR controllers' tf_prefix): the spec
# writes them empty, and they take the robot's prefix
PREFIX_PARAMS = ("tf_prefix", "prefix")


def prefixed(robot: m.Robot, prefix: str, where: Where) -> m.Robot:
    """``robot`` with ``prefix`` before each of its names (module docstring), declared at ``where``."""
    if not prefix:
        return robot

    def p(name: str) -> str:
        return name if name in GLOBAL_FRAMES else prefix + name

    def po(name: str | None) -> str | None:
        return None if name is None else p(name)

    def names(values: tuple[str, ...]) -> tuple[str, ...]:
        return tuple(p(v) for v in values)

    # a repeated part's name is its Xacro macro's: robots composed into one need one macro each
    links = tuple(replace(lk, name=p(lk.name), part=prefix + lk.part if lk.part else None) for lk in robot.links)
    joints = tuple(
        replace(
            j,
            name=p(j.name),
            parent=po(j.parent),
            child=po(j.child),
            mimic=replace(j.mimic, joint=p(j.mimic.joint)) if j.mimic is not None else None,
            part=prefix + j.part if j.part else None,
        )
        for j in robot.joints
    )
    sensors = tuple(
        replace(
            s,
            name=p(s.name),
            link=p(s.link),
            joint=p(s.joint),
            optical_frame=po(s.optical_frame),
            optical_joint=po(s.optical_joint),
        )
        for s in robot.sensors
    )
    poses = tuple(
        replace(
            kp,
            joints=tuple((p(n), v) for n, v in kp.joints),
            frames=tuple(replace(f, frame=p(f.frame), relative_to=po(f.relative_to)) for f in kp.frames),
        )
        for kp in robot.known_poses
    )
    return replace(
        robot,
        links=links,
        joints=joints,
        sensors=sensors,
        ros2_control=_control(robot.ros2_control, p, _own(robot)) if robot.ros2_control is not None else None,
        semantic=_semantic(robot.semantic, p) if robot.semantic is not None else None,
        known_poses=poses,
        external_frames=tuple(replace(e, parent=p(e.parent), child=p(e.child)) for e in robot.external_frames),
        joint_state_sources=tuple(replace(js, joints=names(js.joints)) for js in robot.joint_state_sources),
        calibration=tuple(replace(c, joint=p(c.joint), sensor=po(c.sensor)) for c in robot.calibration),
        drift_check=replace(robot.drift_check, frame=p(robot.drift_check.frame), base=po(robot.drift_check.base))
        if robot.drift_check is not None
        else None,
        prefix=m.NamePrefix(prefix, "the spec's prefix", where),
    )


def _own(robot: m.Robot) -> frozenset[str]:
    """The names the prefix goes before, as the spec writes them (links, joints, ros2_control
    joints, sensors and GPIOs): a controller parameter that is one of them names it."""
    rc = robot.ros2_control
    control: list[str] = []
    if rc is not None:
        control = [*(e.name for e in rc.joints), *(e.name for e in rc.sensors), *(e.name for e in rc.gpios)]
    return frozenset([*(lk.name for lk in robot.links), *(j.name for j in robot.joints), *control]) - GLOBAL_FRAMES


def _control(rc: m.Ros2Control, p: Callable[[str], str], own: frozenset[str]) -> m.Ros2Control:
    def params(items: tuple[tuple[str, str], ...], keys: tuple[str, ...]) -> tuple[tuple[str, str], ...]:
        return tuple((k, p(v) if k in keys and v else v) for k, v in items)

    def hardware(items: tuple[tuple[str, str], ...]) -> tuple[tuple[str, str], ...]:
        # a hardware param holding the prefix itself (the UR driver's tf_prefix): written empty
        return tuple((k, p("") if k in PREFIX_PARAMS and v == "" else v) for k, v in items)

    def variants(vs: tuple[m.HardwareVariant, ...]) -> tuple[m.HardwareVariant, ...]:
        return tuple(replace(v, params=hardware(v.params)) for v in vs)

    # block names are hardware component names, one controller manager's own (the UR description
    # does not prefix its block): left as written; compose, which puts blocks in one manager, does
    return replace(
        rc,
        params=hardware(rc.params),
        variants=variants(rc.variants),
        blocks=tuple(replace(b, params=hardware(b.params), variants=variants(b.variants)) for b in rc.blocks),
        joints=tuple(replace(cj, name=p(cj.name)) for cj in rc.joints),
        sensors=tuple(
            replace(s, name=p(s.name), frame=p(s.frame) if s.frame else s.frame, params=params(s.params, ("frame_id",)))
            for s in rc.sensors
        ),
        gpios=tuple(replace(g, name=p(g.name)) for g in rc.gpios),
        controllers=tuple(_controller(c, p, own) for c in rc.controllers),
    )


def _controller(c: m.Controller, p: Callable[[str], str], own: frozenset[str]) -> m.Controller:
    """A controller's parameters with the robot's names prefixed wherever they stand: a value or
    a list item that is one of ``own`` (a joint, a link, a ros2_control sensor), the component of
    a full interface name (``joint/position``), a key segment (JTC's ``constraints.<joint>.goal``,
    ``gains.<joint>.p``); and the frame ids (FRAME_PARAMS), which may name frames the robot
    does not have (``odom``)."""

    def name(v: object) -> object:
        if not isinstance(v, str) or not v:
            return v
        if v in own:
            return p(v)
        component, iface = split(v)
        return f"{p(component)}/{iface}" if component in own else v

    def value(v: object, leaf: str = "") -> object:
        if isinstance(v, tuple) and v and all(isinstance(x, tuple) and len(x) == 2 for x in v):
            # a parameter namespace (tf: {child_frame_id: ...}, constraints: {<joint>: ...})
            return tuple((p(k) if k in own else k, frames(x) if k in FRAME_LEAVES else value(x, k)) for k, x in v)
        if "interface" in leaf:  # interface names (a GPIO's may be spelled like a link): only full names
            return type(v)(_full(x) for x in v) if isinstance(v, list | tuple) else _full(v)
        if isinstance(v, list | tuple):
            return type(v)(name(x) for x in v)
        return name(v)

    def _full(v: object) -> object:
        return name(v) if isinstance(v, str) and "/" in v else v

    def key(k: str) -> str:
        return ".".join(p(seg) if seg in own else seg for seg in k.split("."))

    def frames(v: object) -> object:
        if isinstance(v, list | tuple):
            return type(v)(p(x) if isinstance(x, str) and x else x for x in v)
        return p(v) if isinstance(v, str) and v else v

    def prefixed_value(k: str, v: object) -> object:
        if k in PREFIX_PARAMS and v == "":  # the robot's prefix, written empty in the spec
            return p("")
        leaf = k.rsplit(".", 1)[-1]
        return frames(v) if k in FRAME_PARAMS or leaf in FRAME_LEAVES else value(v, leaf)

    params = tuple((key(k), prefixed_value(k, v)) for k, v in c.params)
    given = {k for k, _ in params}
    # unset, the controller would publish its default frames, the same for every robot: set, prefixed
    added = tuple((k, p(default)) for k, default in default_frames(c.type) if k not in given)
    return replace(c, params=params + added)


def _semantic(sem: m.Semantic, p: Callable[[str], str]) -> m.Semantic:
    def names(values: tuple[str, ...]) -> tuple[str, ...]:
        return tuple(p(v) for v in values)

    return replace(
        sem,
        groups=tuple(
            replace(
                g,
                links=names(g.links),
                joints=names(g.joints),
                chains=tuple((p(a), p(b)) for a, b in g.chains),
            )
            for g in sem.groups
        ),
        states=tuple(
            replace(
                st,
                values=tuple((p(n), v) for n, v in st.values),
                multi=tuple((p(n), v) for n, v in st.multi),
            )
            for st in sem.states
        ),
        end_effectors=tuple(replace(e, parent_link=p(e.parent_link)) for e in sem.end_effectors),
        # the frame it hangs from is the robot's own odometry frame (left_odom), or a global one
        virtual_joints=tuple(
            replace(v, name=p(v.name), child_link=p(v.child_link), parent_frame=p(v.parent_frame))
            for v in sem.virtual_joints
        ),
        passive_joints=names(sem.passive_joints),
        disabled_collisions=tuple(replace(d, link1=p(d.link1), link2=p(d.link2)) for d in sem.disabled_collisions),
    )


def namespaced(robot: m.Robot, namespace: str) -> m.Robot:
    """``robot`` to run in ``namespace``: a controller that would write the namespace before its
    tf frame ids (``tf_frame_prefix_enable``, default true in Jazzy: ``left/odom``) is told not to,
    since the frames it publishes are the robot's own names (prefixed by ``prefix:``), which the
    URDF's frames must meet."""
    rc = robot.ros2_control
    if rc is None:
        return replace(robot, namespace=namespace)
    controllers = tuple(
        replace(c, params=(*c.params, ("tf_frame_prefix_enable", False)))
        if prefixes_tf_frames(c.type) and c.param("tf_frame_prefix_enable") is None
        else c
        for c in rc.controllers
    )
    return replace(robot, namespace=namespace, ros2_control=replace(rc, controllers=controllers))
