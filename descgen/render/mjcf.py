"""The MJCF model ``hardware:=mujoco`` loads: mujoco_ros2_control's ``mujoco_model``
(docs/mujoco_ros2_control.md: facts from the jazzy release 0.1.0, with their sources).

MuJoCo compiles the robot from the same URDF ``simulate`` gives it (descgen/render/mujoco_urdf.py),
and the compiled spec is written as MJCF, with what mujoco_ros2_control needs and the URDF cannot
say: angles in radians; one actuator per ros2_control joint, named as the joint (the plugin finds a
joint's actuator by that name), of the kind its first command interface needs (position ->
``position``, velocity -> ``velocity``, effort -> ``motor``; the plugin refuses other pairs
without PID gains), its force limited to the URDF's effort; a mimic joint as a joint equality
with the URDF's multiplier and offset, and no actuator of its own; a mobile base (the simulate
command's test) on a floor with a free joint named ``floating_base_joint``, whose odometry the
plugin publishes; a time step no longer than the controller manager's period.

Position and velocity gains are not in any description: ``kp`` gives the joint's full effort at a
0.1 rad (or 1 cm) error, ``kv`` at a 1 rad/s (or 0.1 m/s) error. They are a starting point,
written in the file's header with everything else the conversion changes (fixed links fused,
visuals dropped), for a reviewer to tune.

Meshes: a collision mesh must be an STL or OBJ file of the robot's own package; the MJCF names
it relative to itself (``../meshes/...``). Another package's mesh, or a COLLADA file, is refused
(GEN096): the plugin reads a plain path and nothing converts the file at launch.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Any

from lxml import etree

from descgen.codes.generate import GEN096
from descgen.core.findings import Finding, InputError
from descgen.core.model import ControlJoint, Mesh, Robot
from descgen.meshes.paths import own_meshes, package_name
from descgen.physics.start_state import default_base
from descgen.render.mujoco_urdf import emit

FOLDER = "mujoco"
FREE_JOINT = "floating_base_joint"  # mujoco_ros2_control's odom_free_joint_name default
FULL_EFFORT_AT = {"hinge": (0.1, 1.0), "slide": (0.01, 0.1)}  # (position error, velocity error)
MAX_TIMESTEP = 0.002  # s, MuJoCo's default


def path(robot: Robot) -> str:
    """Where the model lies in the package."""
    return f"{FOLDER}/{robot.name}.xml"


def wanted(robot: Robot) -> bool:
    """Whether the robot has a ``mujoco`` hardware variant."""
    rc = robot.ros2_control
    return rc is not None and any(v.name == "mujoco" for b in rc.hardware_blocks() for v in b.variants)


@dataclass
class Model:
    text: str  # the MJCF, its header comment saying what the conversion changed
    changes: list[str] = field(default_factory=list)


MIN_MUJOCO = (4, 0)  # 3.x's URDF import loses <frame> offsets of fused links (checked against 3.4.0)
CLEARANCE = 0.001  # m between a mobile base's lowest shape and the floor at the start


def model(robot: Robot) -> Model:
    """The MJCF of ``robot`` (module docstring); InputError (GEN096) when it cannot be made."""
    try:
        import mujoco
    except ImportError:
        raise InputError(
            [_refused(robot, "the mujoco package is not installed (pip install 'descgen[sim]')")]
        ) from None
    version = tuple(int(x) for x in mujoco.__version__.split(".")[:2])
    if version < MIN_MUJOCO:
        need = ".".join(map(str, MIN_MUJOCO))
        why = f"MuJoCo {mujoco.__version__} is installed; writing the model needs {need} or newer"
        raise InputError([_refused(robot, why)])
    emitted = emit(robot)
    if emitted.findings:
        raise InputError([_refused(robot, f.message) for f in emitted.findings])
    spec = mujoco.MjSpec.from_string(emitted.text, assets=emitted.assets)
    spec.compiler.degree = False
    # a link with no <inertial> adds no mass, as in the URDF (MuJoCo's default would give it the
    # mass of its shapes at 1000 kg/m^3)
    spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    rc = robot.ros2_control
    rate = rc.update_rate if rc is not None and rc.update_rate else None
    spec.option.timestep = min(MAX_TIMESTEP, 1.0 / rate) if rate else MAX_TIMESTEP
    changes: list[str] = []
    root = robot.root()
    if default_base(robot) == "floor" and root is not None:
        spec.worldbody.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05])
        spec.body(root).add_freejoint(name=FREE_JOINT)
        changes.append(f"a floor, and a free joint '{FREE_JOINT}' on the mobile base's root '{root}'")
    elif root is not None:
        welded = sorted(robot.body_of(root))
        changes.append(
            f"the fixed base {', '.join(welded)} welded to the world: its mass is the world's, not simulated"
        )
    changes += _actuators(robot, spec)
    changes += _mimics(robot, spec)
    try:
        compiled = spec.compile()
        if default_base(robot) == "floor" and root is not None:
            lift = _on_the_floor(compiled)
            spec.body(root).pos[2] += lift
            compiled = spec.compile()
            changes.append(f"the mobile base starts {lift:.4g} m up, its lowest shape {CLEARANCE} m above the floor")
    except ValueError as exc:
        raise InputError([_refused(robot, f"MuJoCo refuses the model: {' '.join(str(exc).split())}")]) from None
    fused = _fused(robot, compiled)
    if fused:
        changes.append(f"{len(fused)} link(s) on fixed joints fused into their parent body: {', '.join(fused)}")
    if any(lk.visuals for lk in robot.links):
        changes.append("visuals dropped: MuJoCo's URDF import keeps the collision shapes only")
    text = _with_mesh_paths(_plain(spec.to_xml()), robot, emitted.assets)
    return Model(_with_header(text, changes), changes)


def _plain(text: str) -> str:
    """MJCF that Jazzy's MuJoCo (mujoco_vendor 3.4.0) also reads: MuJoCo 4 writes ``input`` on a
    general actuator, which 3.4 refuses ("unrecognized attribute") and which gainprm and biasprm
    already say."""
    root = etree.fromstring(text.encode("utf-8"))
    for general in root.iter("general"):
        if "input" in general.attrib:
            del general.attrib["input"]
    return etree.tostring(root, encoding="unicode") + "\n"


def _on_the_floor(compiled: Any) -> float:
    """How far up the free base must start for its lowest shape to clear the floor."""
    import mujoco

    data = mujoco.MjData(compiled)
    mujoco.mj_forward(compiled, data)
    lowest = 0.0
    first = True
    for g in range(compiled.ngeom):
        if compiled.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        centre, half = compiled.geom_aabb[g][:3], compiled.geom_aabb[g][3:]
        corners = [
            data.geom_xpos[g] + data.geom_xmat[g].reshape(3, 3) @ (centre + half * [sx, sy, sz])
            for sx in (-1, 1)
            for sy in (-1, 1)
            for sz in (-1, 1)
        ]
        low = min(float(c[2]) for c in corners)
        lowest = low if first else min(lowest, low)
        first = False
    return CLEARANCE - lowest


def _actuators(robot: Robot, spec: Any) -> list[str]:
    import mujoco

    rc = robot.ros2_control
    out: list[str] = []
    if rc is None:
        return out
    gains: list[str] = []
    unlimited: list[str] = []
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is None or j.mimic is not None or not cj.command:
            continue  # a mimic joint follows its equality; a joint without commands is state only
        kind = "slide" if j.type == "prismatic" else "hinge"
        effort = j.limit.effort if j.limit is not None and j.limit.effort else None
        a = spec.add_actuator()
        a.name, a.target, a.trntype = cj.name, cj.name, mujoco.mjtTrn.mjTRN_JOINT
        command = actuator_kind(cj)
        position_error, velocity_error = FULL_EFFORT_AT[kind]
        if command == "position":
            kp = (effort or 1.0) / position_error
            a.set_to_position(kp=kp, dampratio=1.0)  # critically damped: the joint settles at its target
            gains.append(f"{cj.name} kp={kp:g}")
        elif command == "velocity":
            kv = (effort or 1.0) / velocity_error
            a.set_to_velocity(kv=kv)
            gains.append(f"{cj.name} kv={kv:g}")
        else:
            a.set_to_motor()
        if effort:
            a.forcelimited = True
            a.forcerange = [-effort, effort]
        else:
            unlimited.append(cj.name)
    if unlimited:
        out.append(
            f"no effort limit in the URDF for {', '.join(unlimited)}: gains from 1 N*m (or N), no force limit; "
            "too weak to hold against gravity, most likely"
        )
    if gains:
        out.append(f"actuator gains, full effort at a 0.1 rad (1 cm) error or 1 rad/s (0.1 m/s): {', '.join(gains)}")
    return out


def actuator_kind(cj: ControlJoint) -> str:
    """The actuator a commanded joint gets. The plugin sets up every command interface of a joint
    and refuses position on a velocity or effort actuator, and velocity on an effort one, without
    PID gains: the actuator is the most demanding kind the joint is commanded in."""
    commands = {i.name for i in cj.command}
    return "position" if "position" in commands else "velocity" if "velocity" in commands else "effort"


def _mimics(robot: Robot, spec: Any) -> list[str]:
    import mujoco

    out = []
    # MuJoCo 4's URDF import already makes a joint equality of a <mimic>; an older one (Jazzy's
    # mujoco_vendor is 3.4.0) may not: the file written holds one either way
    made = {(e.name1, e.name2) for e in spec.equalities if e.type == mujoco.mjtEq.mjEQ_JOINT}
    for j in robot.joints:
        if j.mimic is None or robot.joint(j.mimic.joint) is None:
            continue
        out.append(f"{j.name} follows {j.mimic.joint} by a joint equality (the URDF's mimic)")
        if (j.name, j.mimic.joint) in made:
            continue
        eq = spec.add_equality()
        eq.type = mujoco.mjtEq.mjEQ_JOINT
        eq.name1, eq.name2 = j.name, j.mimic.joint
        # joint1 = polycoef(joint2): offset + multiplier * q2
        eq.data[:5] = [j.mimic.offset, j.mimic.multiplier, 0.0, 0.0, 0.0]
    return out


def _fused(robot: Robot, compiled: Any) -> list[str]:
    import mujoco

    bodies = {mujoco.mj_id2name(compiled, mujoco.mjtObj.mjOBJ_BODY, b) for b in range(compiled.nbody)}
    return [lk.name for lk in robot.links if lk.name not in bodies]


def _with_mesh_paths(text: str, robot: Robot, assets: dict[str, bytes]) -> str:
    """The MJCF with each mesh named by its file in the package, relative to the MJCF."""
    if not assets:
        return text
    root = etree.fromstring(text.encode("utf-8"))
    by_source = {str(source): rel for rel, source in own_meshes(robot).items()}
    contents = _by_content(by_source)
    own = f"package://{package_name(robot)}/"
    for mesh in root.iter("mesh"):
        file = mesh.get("file", "")
        data = assets.get(file)  # render/mujoco_urdf.py hands each file over once, by its bytes
        rel = contents.get(hashlib.sha256(data).hexdigest()) if data is not None else None
        if rel is None:
            meshes = sorted(
                {c.geometry.filename for lk in robot.links for c in lk.collisions if isinstance(c.geometry, Mesh)}
            )
            theirs = [m for m in meshes if not m.lower().endswith((".stl", ".obj")) or not m.startswith(own)]
            why = f"collision mesh(es) {', '.join(theirs) or ', '.join(meshes)} not STL or OBJ files of this package"
            raise InputError([_refused(robot, why)])
        mesh.set("file", f"../{rel}")
    return etree.tostring(root, encoding="unicode")


def _by_content(by_source: dict[str, str]) -> dict[str, str]:
    """sha256 of each own STL or OBJ file -> its package path, each file read once."""
    out: dict[str, str] = {}
    for source, rel in by_source.items():
        if rel.lower().endswith((".stl", ".obj")):
            try:
                with open(source, "rb") as f:
                    out.setdefault(hashlib.sha256(f.read()).hexdigest(), rel)
            except OSError:
                continue
    return out


def _with_header(text: str, changes: list[str]) -> str:
    lines = ["What descgen's conversion from the URDF changed or added (descgen/render/mjcf.py):"]
    lines += [f"- {c}" for c in changes] or ["- nothing"]
    comment = "\n".join(lines)
    while "--" in comment:  # an XML comment may not hold "--" (a name may)
        comment = comment.replace("--", "- -")
    head, sep, rest = text.partition("\n")
    if head.startswith("<mujoco"):
        return f"<!--\n{comment}\n-->\n{text}"
    return f"{head}{sep}<!--\n{comment}\n-->\n{rest}"


def _refused(robot: Robot, why: str) -> Finding:
    return GEN096.finding(
        f"hardware:=mujoco: {why}",
        "mujoco_ros2_control reads the MJCF file as it is: give STL or OBJ collision meshes of this package, and a "
        "model MuJoCo compiles (descgen simulate SPEC shows why it does not)",
        f"robot:{robot.name}",
        robot.where,
    )
