"""Compile the robot with MuJoCo and report what it refuses and what it changes silently.

MuJoCo stops at its first error. To report every refused body in one run, a refused body's
inertials are replaced by a harmless stand-in and the model compiled again, so MuJoCo itself
stays the judge of each refusal. What it changes without a word (fused fixed links,
discarded visuals, mass from geometry, unlimited joints) is read from the compiled model.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from descgen.codes.simulate import SIM001, SIM002, SIM003, SIM004, SIM005, SIM006, SIM007
from descgen.core.findings import Finding
from descgen.core.model import WITH_LIMITS, Inertia, Inertial, Robot
from descgen.render.mujoco_urdf import Emitted

_ELEMENT = re.compile(r"Element name '([^']*)'")
_STANDIN = Inertial(1.0, inertia=Inertia(1e-3, 0.0, 0.0, 1e-3, 0.0, 1e-3))
MAX_RETRIES = 64  # refused bodies reported in one run; a bound on the work for a hostile description

Spec = Any  # mujoco.MjSpec (the package ships no type information)
Customise = Callable[[Spec], None]


@dataclass
class Compiled:
    spec: Spec | None  # None: MuJoCo refused the model
    model: Any  # mujoco.MjModel
    findings: list[Finding]


def _refusal(robot: Robot, message: str) -> tuple[Finding, str | None]:
    """The finding for MuJoCo's error ``message`` and the body it names (None: none named)."""
    found = _ELEMENT.search(message)
    body = found.group(1) if found else None
    link = robot.link(body) if body else None
    first = message.strip().splitlines()[0] if message.strip() else "no message"
    subject, where = (link.subject, link.where) if link is not None else (f"robot:{robot.name}", robot.where)
    welded = sorted(robot.body_of(body) - {body}) if body else []
    with_links = f" (with the fused link(s) {', '.join(welded)})" if welded else ""
    if "mjMINVAL" in message:
        return SIM001.finding(
            f"MuJoCo refuses body {body}{with_links}: {first}",
            "give every moving link a positive mass and a positive-definite inertia",
            subject,
            where,
        ), body
    if "A + B >= C" in message:
        return SIM002.finding(
            f"MuJoCo refuses body {body}{with_links}: {first}",
            "principal moments must satisfy A + B >= C; recompute the tensor",
            subject,
            where,
        ), body
    return SIM003.finding(
        f"MuJoCo refused the model: {' '.join(message.split())}", "fix the element named", subject, where
    ), None


def _stand_in(robot: Robot, body: str) -> Robot:
    """``robot`` with every inertial of ``body`` (and the links fused into it) harmless."""
    names = robot.body_of(body)
    links = tuple(dataclasses.replace(lk, inertial=_STANDIN) if lk.name in names else lk for lk in robot.links)
    return dataclasses.replace(robot, links=links)


def compile_robot(robot: Robot, emit: Callable[[Robot], Emitted], customise: Customise) -> Compiled:
    """MuJoCo's model of ``robot``: its refusals, or the compiled spec after ``customise``."""
    import mujoco

    found: list[Finding] = []
    current = robot
    for _ in range(MAX_RETRIES):
        emitted = emit(current)
        try:
            spec = mujoco.MjSpec.from_string(emitted.text, assets=emitted.assets)
            customise(spec)
            model = spec.compile()
        except (ValueError, RuntimeError, mujoco.FatalError) as exc:
            f, body = _refusal(robot, str(exc))
            found.append(f)
            if body is None or robot.link(body) is None:
                return Compiled(None, None, found)
            current = _stand_in(current, body)
            continue
        if found:  # refusals were reported; the stand-ins make the compiled model no proof
            return Compiled(None, None, found)
        return Compiled(spec, model, emitted.findings)
    return Compiled(None, None, found)


def silent_changes(robot: Robot, model: Any) -> list[Finding]:
    """What MuJoCo changed without a word, read from the compiled ``model``."""
    import mujoco

    bodies = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) for b in range(model.nbody)}
    return [
        *_fused(robot, bodies),
        *_visuals(robot),
        *_mass_from_geometry(robot, model, bodies),
        *_unlimited(robot, model),
    ]


def _fused(robot: Robot, bodies: set[str | None]) -> list[Finding]:
    gone = [lk for lk in robot.links if lk.name not in bodies]
    if not gone:
        return []
    names = ", ".join(lk.name for lk in gone)
    return [
        SIM004.finding(
            f"{len(gone)} link(s) on fixed joints are merged into their parent body: {names}",
            'expected for frames; add <mujoco><compiler fusestatic="false"/></mujoco> if a consumer needs them '
            "as bodies",
            f"robot:{robot.name}",
            robot.where,
        )
    ]


def _visuals(robot: Robot) -> list[Finding]:
    count = sum(len(lk.visuals) for lk in robot.links)
    if not count:
        return []
    bare = [lk.name for lk in robot.links if lk.visuals and not lk.collisions]
    also = f"; link(s) with visuals but no collision are invisible there: {', '.join(bare)}" if bare else ""
    return [
        SIM005.finding(
            f"MuJoCo discards all {count} visual(s) and shows the collision shapes{also}",
            'add <mujoco><compiler discardvisual="false"/></mujoco> to see the visuals in MuJoCo',
            f"robot:{robot.name}",
            robot.where,
        )
    ]


def _mass_from_geometry(robot: Robot, model: Any, bodies: set[str | None]) -> list[Finding]:
    """Links without an inertial but with collision shapes: MuJoCo's mass of their body minus
    the declared masses fused into it is the mass it made up."""
    import mujoco

    out = []
    for lk in robot.links:
        if lk.inertial is not None or not lk.collisions:
            continue
        owner = next((n for n in _fused_into(robot, lk.name) if n in bodies), None)
        if owner is None:
            continue
        b = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, owner)
        declared = sum((x.inertial.mass or 0.0) for n in robot.body_of(owner) if (x := robot.link(n)) and x.inertial)
        extra = float(model.body_mass[b]) - declared
        where_to = "" if owner == lk.name else f" (fused into {owner})"
        out.append(
            SIM006.finding(
                f"link {lk.name} has no <inertial>; MuJoCo gives it {extra:.6g} kg from its collision shapes "
                f"at 1000 kg/m^3{where_to}, urdfdom and RViz treat it as massless",
                "give the link an <inertial> with its measured mass",
                lk.subject,
                lk.where,
            )
        )
    return out


def _fused_into(robot: Robot, link: str) -> list[str]:
    """``link`` and its ancestors over fixed joints, nearest first (the body it ends up in)."""
    out = [link]
    while (j := robot.parent_joint(out[-1])) is not None and j.type == "fixed" and j.parent and j.parent not in out:
        out.append(j.parent)
    return out


def _unlimited(robot: Robot, model: Any) -> list[Finding]:
    import mujoco

    out = []
    for j in robot.joints:
        lm = j.limit
        if j.type not in WITH_LIMITS or lm is None:
            continue
        one_bound = (lm.lower is None) != (lm.upper is None)
        inverted = lm.lower is not None and lm.upper is not None and lm.lower > lm.upper
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, j.name)
        if not (one_bound or inverted) or jid < 0 or model.jnt_limited[jid]:
            continue
        why = f"lower {j.show(lm.lower or 0.0)} > upper {j.show(lm.upper or 0.0)}" if inverted else "only one bound"
        out.append(
            SIM007.finding(
                f"joint {j.name}: {why}; MuJoCo makes the joint unlimited (sdformat swaps the bounds instead)",
                "write both bounds with lower <= upper",
                j.subject,
                lm.where if lm.where.line else j.where,
            )
        )
    return out
