"""Controller manager, controllers and the read-update-write loop (see system.py for sources).

Controllers (ros2_controllers, Jazzy):
- joint_state_broadcaster publishes /joint_states from *state* interfaces only;
- joint_trajectory_controller starts from the current state and, for position-only points,
  interpolates linearly between them; it commands positions and publishes its desired state;
- diff_drive_controller turns a twist into wheel velocities (v -/+ w s/2) / r and
  integrates odometry from the wheels' position states.

Limits: a command outside its interface's min/max (the joint's URDF limits) is rejected
before write() and logged with joint, value, limit and time; it is clipped only when the
joint's policy is ``clip``, and then the proposed and applied values are logged. (Jazzy
itself enforces nothing unless ``enforce_command_limits`` is set; the spec's limit policy
(C06 on the example) asks for this.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from descgen.commands.control.system import (
    ACTIVE,
    INACTIVE,
    UNCONFIGURED,
    Hardware,
    Node,
    ResourceManager,
    Trace,
)


@dataclass
class Point:
    time: float
    positions: tuple[float, ...]


class Controller(Node):
    def __init__(self, name: str, type_: str, params: dict[str, Any], trace: Trace) -> None:
        super().__init__(name, "controller", trace)
        self.type = type_
        self.params = params

    def claims(self) -> list[str]:
        return []

    def update(self, cm: ControllerManager, t: float, dt: float) -> None:
        return


class JointStateBroadcaster(Controller):
    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.published: list[tuple[float, dict[str, float]]] = []

    def update(self, cm: ControllerManager, t: float, dt: float) -> None:
        # measured state only: state interfaces, never commands
        self.published.append((t, {j.name: j.states.get("position", math.nan) for j in cm.hardware.joints}))


class JointTrajectoryController(Controller):
    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.joints = [str(j) for j in self.params.get("joints", [])]
        self.points: list[Point] = []
        self.start: tuple[float, ...] | None = None
        self.t0 = 0.0
        self.desired: dict[str, float] = {}

    def claims(self) -> list[str]:
        return [f"{j}/{i}" for j in self.joints for i in self.params.get("command_interfaces", ["position"])]

    def follow(self, points: list[Point], t0: float) -> None:
        self.points, self.t0, self.start = points, t0, None

    def update(self, cm: ControllerManager, t: float, dt: float) -> None:
        if self.start is None:  # the trajectory starts from where the joints are
            self.start = tuple(cm.state(j, "position") for j in self.joints)
        elapsed = t - self.t0
        previous = Point(0.0, self.start)
        target = self.start
        for p in self.points:
            if elapsed <= p.time:
                span = p.time - previous.time
                a = 1.0 if span <= 0 else (elapsed - previous.time) / span
                target = tuple(x + a * (y - x) for x, y in zip(previous.positions, p.positions, strict=True))
                break
            previous, target = p, p.positions
        for name, value in zip(self.joints, target, strict=True):
            self.desired[name] = value
            cm.command(self.name, name, "position", value)


class DiffDriveController(Controller):
    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.left = [str(x) for x in self.params.get("left_wheel_names", [])]
        self.right = [str(x) for x in self.params.get("right_wheel_names", [])]
        self.twist = (0.0, 0.0)
        self.pose = [0.0, 0.0, 0.0]
        self.last: dict[str, float] = {}

    def claims(self) -> list[str]:
        return [f"{w}/velocity" for w in self.left + self.right]

    def update(self, cm: ControllerManager, t: float, dt: float) -> None:
        r = float(self.params.get("wheel_radius", 0.1))
        s = float(self.params.get("wheel_separation", 0.5))
        v, w = self.twist
        for wheel in self.left:
            cm.command(self.name, wheel, "velocity", (v - w * s / 2) / r)
        for wheel in self.right:
            cm.command(self.name, wheel, "velocity", (v + w * s / 2) / r)
        # odometry from the wheels' position states (what the hardware reports)
        pos = {n: cm.state(n, "position") for n in self.left + self.right}
        if self.last:
            dl = sum(pos[n] - self.last[n] for n in self.left) / max(1, len(self.left)) * r
            dr = sum(pos[n] - self.last[n] for n in self.right) / max(1, len(self.right)) * r
            d, dth = (dl + dr) / 2, (dr - dl) / s
            self.pose[0] += d * math.cos(self.pose[2] + dth / 2)
            self.pose[1] += d * math.sin(self.pose[2] + dth / 2)
            self.pose[2] += dth
        self.last = pos


class GripperActionController(Controller):
    """position_controllers/GripperActionController and parallel_gripper_action_controller:
    one ``joint``; a goal (``~/gripper_cmd``) is a single target position, commanded as is on
    every update until the next goal (gripper_action_controller_impl.hpp,
    parallel_gripper_action_controller_impl.hpp). A trajectory file's points are successive
    goals: point i is sent when point i-1's time has passed and must be reached by its own
    time, so tracking is judged at the points' times only (``settles``)."""

    settles = True

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        joint = self.params.get("joint")
        self.joints = [str(joint)] if joint else []
        self.points: list[Point] = []
        self.t0 = 0.0
        self.desired: dict[str, float] = {}

    def claims(self) -> list[str]:
        return [f"{j}/position" for j in self.joints]

    def follow(self, points: list[Point], t0: float) -> None:
        self.points, self.t0 = points, t0

    def update(self, cm: ControllerManager, t: float, dt: float) -> None:
        if not self.joints or not self.points:
            return
        elapsed = t - self.t0
        goal = next((p for p in self.points if elapsed <= p.time), self.points[-1])
        self.desired[self.joints[0]] = goal.positions[0]
        cm.command(self.name, self.joints[0], "position", goal.positions[0])


# by full type first (position_controllers/ holds both a group and a gripper controller), then package
TYPES: dict[str, type[Controller]] = {
    "position_controllers/GripperActionController": GripperActionController,
    "parallel_gripper_action_controller/GripperActionController": GripperActionController,
}

KINDS = {
    "joint_state_broadcaster": JointStateBroadcaster,
    "joint_trajectory_controller": JointTrajectoryController,
    "diff_drive_controller": DiffDriveController,
}


@dataclass
class LimitEvent:
    time: float
    joint: str
    interface: str
    value: float
    limit: float
    applied: float | None  # None: rejected


@dataclass
class ControllerManager:
    hardware: Hardware
    update_rate: float
    trace: Trace
    controllers: dict[str, Controller] = field(default_factory=dict)
    rejected: list[LimitEvent] = field(default_factory=list)
    clipped: list[LimitEvent] = field(default_factory=list)
    proposed: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.resources = ResourceManager(self.trace)
        self.by_name = {j.name: j for j in self.hardware.joints}

    # -- interfaces ---------------------------------------------------------------------

    def state(self, joint: str, interface: str) -> float:
        return self.by_name[joint].states.get(interface, math.nan)

    def command(self, controller: str, joint: str, interface: str, value: float) -> None:
        key = f"{joint}/{interface}"
        if self.resources.owner.get(key) != controller:
            return  # only the claiming controller writes a command interface
        self.proposed[key] = value

    # -- lifecycle ------------------------------------------------------------------------

    def start_hardware(self) -> None:
        self.hardware.on_init()
        self.hardware.on_configure()
        self.hardware.on_activate()

    def spawn(self, name: str, type_: str, params: dict[str, Any], activate: bool = True) -> Controller:
        cls = TYPES.get(type_) or KINDS.get(type_.split("/")[0], Controller)
        c = cls(name, type_, params, self.trace)
        self.controllers[name] = c
        c.transition("load", "on_init", UNCONFIGURED)
        c.transition("configure", "on_configure", INACTIVE)
        if activate:
            self.activate(name)
        return c

    def activate(self, name: str) -> bool:
        c = self.controllers[name]
        for key in c.claims():
            joint, _, iface = key.partition("/")
            if joint not in self.by_name or iface not in self.by_name[joint].commands:
                self.trace.add(
                    event="claim",
                    controller=name,
                    interface=key,
                    result="FAILURE",
                    detail=f"command interface '{key}' is not exported by the hardware",
                )
                self.resources.release(name)
                return c.transition("activate", "on_activate", ACTIVE, ok=False)
            if self.resources.claim(name, key) is not None:
                self.resources.release(name)
                self.trace.add(
                    event="switch",
                    controller=name,
                    result="FAILURE",
                    detail=f"Resource conflict for controller '{name}'",
                )
                return c.transition("activate", "on_activate", ACTIVE, ok=False)
        return c.transition("activate", "on_activate", ACTIVE)

    def deactivate(self, name: str) -> None:
        self.controllers[name].transition("deactivate", "on_deactivate", INACTIVE)
        self.resources.release(name)

    # -- the loop -------------------------------------------------------------------------

    def step(self, t: float) -> None:
        dt = 1.0 / self.update_rate
        self.trace.time = t
        self.hardware.read(dt)
        self.proposed = {}
        for c in self.controllers.values():
            if c.state == ACTIVE:
                c.update(self, t, dt)
        self._enforce_limits(t)
        if self.hardware.state == ACTIVE:
            self.hardware.write()

    def _enforce_limits(self, t: float) -> None:
        for key, value in self.proposed.items():
            joint, _, iface = key.partition("/")
            j = self.by_name[joint]
            lo, hi = j.limits.get(iface, (None, None))
            limit = hi if hi is not None and value > hi else lo if lo is not None and value < lo else None
            if limit is None:
                j.commands[iface] = value
                continue
            if j.policy == "clip":
                j.commands[iface] = limit
                self.clipped.append(LimitEvent(t, joint, iface, value, limit, limit))
                self.trace.add(
                    event="limit",
                    joint=joint,
                    interface=iface,
                    proposed=value,
                    applied=limit,
                    limit=limit,
                    action="clipped",
                )
            else:
                self.rejected.append(LimitEvent(t, joint, iface, value, limit, None))
                self.trace.add(
                    event="limit",
                    joint=joint,
                    interface=iface,
                    proposed=value,
                    limit=limit,
                    action="rejected",
                    kept=j.commands[iface],
                )
