"""A model of ros2_control's behaviour on Jazzy, without ROS.

Facts encoded (docs/reference/ros2_control.md, with its sources):
- hardware components and controllers are lifecycle nodes: unconfigured (after on_init),
  inactive (on_configure), active (on_activate), finalized (on_shutdown); an ERROR from a
  callback or from read()/write() runs on_error (SUCCESS -> unconfigured, else finalized)
  (hardware_interface/src/hardware_component.cpp);
- unlisted hardware components are activated at startup (controller_manager parameter
  ``hardware_components_initial_state``); the spawner loads, configures and activates a
  controller (controller_manager/spawner.py);
- command interfaces are claimed exclusively by an active controller ("Command interface
  with key '...' is already claimed"; a switch reports "Resource conflict"); state
  interfaces are shared (hardware_interface/src/resource_manager.cpp); deactivating releases;
- every period: read() (hardware -> state interfaces, in inactive and active), update()
  of active controllers, write() (command interfaces -> hardware, active only)
  (controller_manager/src/ros2_control_node.cpp);
- mock_components/GenericSystem mirrors in read(): position command -> position state
  (+ position_state_following_offset), same-named states from same-named commands; a NaN
  command is ignored; an infinite one makes read() return ERROR; with calculate_dynamics a
  velocity command integrates into position (hardware_interface/src/mock_components/generic_system.cpp);
- at the end of every read(), GenericSystem sets each mimic joint's position state to
  ``offset + multiplier * position(leader)`` and its velocity and acceleration states to
  ``multiplier * leader's`` (its direct URDF ``<mimic>`` leader, in the order of the
  block's joints: a chain is not resolved first) (generic_system.cpp, "Update mimic joints").
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from descgen.codes.control import CTRL032
from descgen.core.findings import Finding, InputError, Where
from descgen.core.record import record

if TYPE_CHECKING:
    from descgen.core.model import Robot

UNCONFIGURED, INACTIVE, ACTIVE, FINALIZED = "unconfigured", "inactive", "active", "finalized"


@dataclass
class Trace:
    events: list[dict[str, Any]] = field(default_factory=list)
    time: float = 0.0

    def add(self, **event: Any) -> None:
        self.events.append({"t": round(self.time, 9), **event})


@dataclass
class Node:
    """A lifecycle node (hardware component or controller)."""

    name: str
    kind: str  # hardware | controller
    trace: Trace
    state: str = "unloaded"

    def transition(self, transition: str, callback: str, target: str, ok: bool = True) -> bool:
        before = self.state
        after = (
            target
            if ok
            else {
                "on_configure": UNCONFIGURED,
                "on_activate": INACTIVE,
                "on_deactivate": ACTIVE,
                "on_init": FINALIZED,
            }.get(callback, before)
        )
        self.state = after
        self.trace.add(
            event="transition",
            kind=self.kind,
            name=self.name,
            transition=transition,
            callback=callback,
            start=before,
            goal=target,
            result="SUCCESS" if ok else "FAILURE",
            state=after,
        )
        return ok

    def error(self, why: str) -> None:
        self.trace.add(event="error", kind=self.kind, name=self.name, detail=why)
        self.transition("error", "on_error", UNCONFIGURED)


@dataclass
class JointHw:
    name: str
    commands: dict[str, float]  # interface -> value
    states: dict[str, float]
    limits: dict[str, tuple[float | None, float | None]]  # command interface -> (min, max)
    policy: str = "reject"  # reject | clip


@record
class MimicHw:
    """HardwareInfo.mimic_joints: a joint whose states follow a leader in the same block."""

    joint: str
    leader: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass
class Plant:
    """How a joint really moves. ``mock``: GenericSystem's echo. ``sim``: a first-order lag
    with velocity and acceleration limits, noise, and optional planted faults."""

    kind: str = "mock"
    tau: float = 0.05
    noise: float = 0.0
    faults: dict[str, str] = field(default_factory=dict)  # joint -> stuck | offset | reversed
    offset: float = 0.1
    seed: int = 0


FAULT_KINDS = ("stuck", "offset", "reversed")


def plant_faults(items: Iterable[tuple[str, str]], plant: str, robot: Robot) -> dict[str, str]:
    """``--plant-fault JOINT:=KIND`` options, already read as (joint, kind) pairs of a known
    kind (``cli_types.plant_fault``), as ``{joint: kind}``, every one checked against the
    robot: a fault that is silently not planted would let a run pass that should fail."""
    found: list[Finding] = []
    faults: dict[str, str] = {}
    controlled = {j.name for j in robot.ros2_control.joints} if robot.ros2_control else set()

    def bad(message: str, hint: str) -> None:
        found.append(CTRL032.finding(message, hint, "option", Where("<command line>")))

    for joint, kind in items:
        shown = ascii(f"{joint}:={kind}")
        if joint not in controlled:
            bad(
                f"--plant-fault {shown}: {joint!a} is not a joint under ros2_control",
                "name one of " + ", ".join(sorted(controlled))
                if controlled
                else "the robot has no ros2_control joints",
            )
        elif joint in faults and faults[joint] != kind:
            bad(f"--plant-fault {shown}: {joint} already has the fault {faults[joint]}", "plant one fault per joint")
        else:
            faults[joint] = kind
    if faults and plant != "sim" and not found:
        bad(
            "--plant-fault needs --plant sim: the mock plant echoes commands, so a fault would not show",
            "add --plant sim",
        )
    if found:
        raise InputError(found)
    return faults


class Hardware(Node):
    def __init__(
        self, name: str, plugin: str, params: dict[str, str], joints: list[JointHw], trace: Trace, plant: Plant
    ) -> None:
        super().__init__(name, "hardware", trace)
        self.plugin = plugin
        self.params = params
        self.joints = joints
        self.plant = plant
        self.dynamics = params.get("calculate_dynamics", "false").lower() == "true"
        self.follow = float(params.get("position_state_following_offset", "0") or 0)
        self.actual: dict[str, float] = {}
        self.speed: dict[str, float] = {}
        self.rng = random.Random(plant.seed)
        self.vel_limit: dict[str, float] = {}
        self.mimics: list[MimicHw] = []

    @property
    def echoes_commands(self) -> bool:
        """GenericSystem without dynamics: the 'measured' state is the command, mirrored."""
        return self.plant.kind == "mock" and not self.dynamics

    def on_init(self) -> None:
        self.transition("create", "on_init", UNCONFIGURED)

    def on_configure(self) -> None:
        for j in self.joints:  # NaN states become 0; initial values are kept
            for k, v in j.states.items():
                if math.isnan(v):
                    j.states[k] = 0.0
            if "position" in j.states:
                j.states["position"] += self.follow if self.plant.kind == "mock" else 0.0
                self.actual[j.name] = j.states["position"]
            for k, v in j.commands.items():
                if math.isnan(v):
                    j.commands[k] = j.states.get(k, 0.0)
        self.transition("configure", "on_configure", INACTIVE)

    def on_activate(self) -> None:
        self.transition("activate", "on_activate", ACTIVE)

    def read(self, dt: float) -> None:
        if self.state not in (INACTIVE, ACTIVE):
            return
        for j in self.joints:
            if any(math.isinf(v) for v in j.commands.values()):
                self.error(f"infinite command on {j.name}: read() returned ERROR")
                return
            if self.plant.kind == "mock":
                self._mirror(j, dt)
            else:
                self._simulate(j, dt)
        self._follow_mimics()

    def _follow_mimics(self) -> None:
        """GenericSystem's "Update mimic joints" step, after every other state is set."""
        by_name = {j.name: j for j in self.joints}
        for mj in self.mimics:
            follower, leader = by_name[mj.joint], by_name[mj.leader]
            for k in ("position", "velocity", "acceleration"):
                if k in follower.states:
                    # get_state of an interface the leader lacks would throw; a missing one reads as 0 here
                    src = leader.states.get(k, 0.0)
                    follower.states[k] = (mj.offset if k == "position" else 0.0) + mj.multiplier * src

    def _mirror(self, j: JointHw, dt: float) -> None:
        pos = j.commands.get("position")
        if pos is not None and not math.isnan(pos) and "position" in j.states:
            j.states["position"] = pos + self.follow
        for k, v in j.commands.items():
            if k in j.states and k != "position" and not math.isnan(v):
                j.states[k] = v
        if self.dynamics and "velocity" in j.commands and "position" not in j.commands and "position" in j.states:
            j.states["position"] += j.commands["velocity"] * dt

    def _simulate(self, j: JointHw, dt: float) -> None:
        fault = self.plant.faults.get(j.name)
        x = self.actual.get(j.name, j.states.get("position", 0.0))
        v = self.speed.get(j.name, 0.0)
        vmax = self.vel_limit.get(j.name, math.inf)
        if "position" in j.commands:
            goal = j.commands["position"]
            if fault == "reversed":
                goal = -goal
            want = (goal - x) / max(self.plant.tau, dt)
        else:
            want = j.commands.get("velocity", 0.0) * (-1 if fault == "reversed" else 1)
        want = max(-vmax, min(vmax, want))
        amax = 10 * vmax if math.isfinite(vmax) else math.inf
        v = v + max(-amax * dt, min(amax * dt, want - v))
        if fault != "stuck":
            x += v * dt
        else:
            v = 0.0
        self.actual[j.name], self.speed[j.name] = x, v
        measured = x + (self.plant.offset if fault == "offset" else 0.0) + self.rng.gauss(0, self.plant.noise)
        if "position" in j.states:
            j.states["position"] = measured
        if "velocity" in j.states:
            j.states["velocity"] = v

    def write(self) -> None:
        return  # GenericSystem's write() does nothing; the plant reads commands in read()


class HardwareSet(Hardware):
    """Every hardware component of the description, one per ``<ros2_control>`` block, as the
    resource manager runs them (resource_manager.cpp): each is its own lifecycle node (its own
    transitions in the trace), each reads in turn, and only active non-sensor components are
    written (a sensor component has no write()). The controller manager sees the union of
    their joints; a mimic joint follows its leader inside its own component only."""

    def __init__(self, parts: list[Hardware], trace: Trace, plant: Plant) -> None:
        super().__init__("+".join(p.name for p in parts), "", {}, [j for p in parts for j in p.joints], trace, plant)
        self.parts = parts
        self.kinds: dict[str, str] = {}  # part name -> system | actuator | sensor

    @property
    def echoes_commands(self) -> bool:
        return all(p.echoes_commands for p in self.parts)

    def _sync(self) -> None:
        # the set is active while any component is: the loop then reads and writes, and each
        # component itself decides whether it takes part (as read()/write() check their state)
        states = {p.state for p in self.parts}
        self.state = ACTIVE if ACTIVE in states else next(iter(states), UNCONFIGURED)

    def on_init(self) -> None:
        for p in self.parts:
            p.on_init()
        self._sync()

    def on_configure(self) -> None:
        for p in self.parts:
            p.on_configure()
        self._sync()

    def on_activate(self) -> None:
        for p in self.parts:
            p.on_activate()
        self._sync()

    def read(self, dt: float) -> None:
        for p in self.parts:
            p.read(dt)
        self._sync()

    def write(self) -> None:
        for p in self.parts:
            if p.state == ACTIVE and self.kinds.get(p.name, "system") != "sensor":
                p.write()


class ResourceManager:
    """Exclusive command-interface claims (resource_manager.cpp)."""

    def __init__(self, trace: Trace) -> None:
        self.owner: dict[str, str] = {}
        self.trace = trace

    def claim(self, controller: str, key: str) -> str | None:
        holder = self.owner.get(key)
        if holder is not None:
            why = f"Command interface with key '{key}' is already claimed (by {holder})"
            self.trace.add(event="claim", controller=controller, interface=key, result="FAILURE", detail=why)
            return why
        self.owner[key] = controller
        self.trace.add(event="claim", controller=controller, interface=key, result="SUCCESS")
        return None

    def release(self, controller: str) -> None:
        for key in [k for k, c in self.owner.items() if c == controller]:
            del self.owner[key]
            self.trace.add(event="release", controller=controller, interface=key)
