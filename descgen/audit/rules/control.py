"""CTRL: the ros2_control block and controllers agree with the joints."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator

from ...findings import Finding
from ...model import Controller, Robot
from ..registry import at, rule


def claims(c: Controller) -> list[tuple[str, str]]:
    """(joint, command interface) pairs a controller claims when active (Jazzy ros2_controllers)."""
    t = c.type.split("/")[0]
    if t == "joint_trajectory_controller":
        return [(str(j), str(i)) for j in _list(c.param("joints")) for i in _list(c.param("command_interfaces"))]
    if t == "diff_drive_controller":
        wheels = [*_list(c.param("left_wheel_names")), *_list(c.param("right_wheel_names"))]
        return [(str(w), "velocity") for w in wheels]
    if t == "forward_command_controller" or t.endswith("forward_controller"):
        iface = c.param("interface_name")
        return [(str(j), str(iface)) for j in _list(c.param("joints"))]
    return []


def state_reads(c: Controller) -> list[tuple[str, str]]:
    t = c.type.split("/")[0]
    if t == "joint_trajectory_controller":
        return [(str(j), str(i)) for j in _list(c.param("joints")) for i in _list(c.param("state_interfaces"))]
    if t == "diff_drive_controller":
        if c.param("open_loop") is True:
            return []
        iface = "velocity" if c.param("position_feedback") is False else "position"
        wheels = [*_list(c.param("left_wheel_names")), *_list(c.param("right_wheel_names"))]
        return [(str(w), iface) for w in wheels]
    return []


def _list(v: object) -> list[object]:
    if isinstance(v, list | tuple):
        return list(v)
    return [] if v is None else [v]


@rule("CTRL001", "control-joint-not-in-urdf", "error")
def control_joint_not_in_urdf(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a ros2_control joint that is not a moving URDF joint.
    ## Why is this bad?
    ros2_control fails to load: "Joint 'x' not found in URDF" / "Fixed joints do not make
    sense in ros2_control".
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is None:
            yield at(
                "CTRL001",
                cj,
                f"ros2_control joint '{cj.name}' is not a URDF joint",
                "fix the name",
                subject=f"ros2_control:{cj.name}",
            )
        elif j.type == "fixed":
            yield at(
                "CTRL001",
                cj,
                f"ros2_control joint '{cj.name}' is fixed",
                "remove it from ros2_control",
                subject=f"ros2_control:{cj.name}",
            )


@rule("CTRL002", "controller-interface-missing", "error")
def controller_interface_missing(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a controller that claims a command interface or reads a state interface the
    hardware does not export.
    ## Why is this bad?
    The controller fails to activate; on the robot nothing moves and nothing says why
    until someone reads the controller_manager log.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    cmd = {(cj.name, i.name) for cj in rc.joints for i in cj.command}
    state = {(cj.name, i.name) for cj in rc.joints for i in cj.state}
    for c in rc.controllers:
        for joint, iface in claims(c):
            if (joint, iface) not in cmd:
                yield at(
                    "CTRL002",
                    c,
                    f"controller '{c.name}' claims '{joint}/{iface}', which the hardware does not export",
                    f"add command: [{iface}] to ros2_control joint '{joint}', or fix the controller",
                    subject=f"controller:{c.name}",
                )
        for joint, iface in state_reads(c):
            if (joint, iface) not in state:
                yield at(
                    "CTRL002",
                    c,
                    f"controller '{c.name}' reads state '{joint}/{iface}', which the hardware does not export",
                    f"add state: [{iface}] to ros2_control joint '{joint}'",
                    subject=f"controller:{c.name}",
                )


@rule("CTRL003", "no-joint-state-broadcaster", "warning")
def no_joint_state_broadcaster(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a ros2_control setup with controllers but no joint_state_broadcaster.
    ## Why is this bad?
    Nothing publishes measured joint states, so robot_state_publisher shows no motion,
    or something else fills /joint_states with commands.
    """
    rc = robot.ros2_control
    if rc is None or not rc.controllers:
        return
    if not any(c.type.startswith("joint_state_broadcaster/") for c in rc.controllers):
        yield at(
            "CTRL003",
            rc,
            "no joint_state_broadcaster among the controllers",
            "add joint_state_broadcaster/JointStateBroadcaster",
            subject="ros2_control",
        )


@rule("CTRL004", "interface-claimed-twice", "warning")
def interface_claimed_twice(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a command interface that two controllers claim.
    ## Why is this bad?
    Command interfaces are exclusive: the second controller fails to activate
    ("Resource conflict"). Fine only when they are alternatives never active together.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    owners: dict[tuple[str, str], list[str]] = defaultdict(list)
    for c in rc.controllers:
        for key in claims(c):
            owners[key].append(c.name)
    for (joint, iface), names in owners.items():
        if len(names) > 1:
            c = next(x for x in rc.controllers if x.name == names[1])
            yield at(
                "CTRL004",
                c,
                f"'{joint}/{iface}' is claimed by {', '.join(names)}",
                "give each command interface one controller, or activate them exclusively",
                subject=f"controller:{c.name}",
            )


@rule("CTRL005", "control-joint-listed-twice", "error")
def control_joint_listed_twice(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds a joint listed twice in the ros2_control block.
    ## Why is this bad?
    Interfaces get exported twice and the resource manager refuses the duplicate keys.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    seen: set[str] = set()
    for cj in rc.joints:
        if cj.name in seen:
            yield at(
                "CTRL005",
                cj,
                f"joint '{cj.name}' is listed twice in ros2_control",
                "merge the entries",
                subject=f"ros2_control:{cj.name}",
            )
        seen.add(cj.name)


@rule("CTRL006", "diff-drive-geometry-disagrees", "error")
def diff_drive_geometry_disagrees(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Derives `wheel_separation` and `wheel_radius` from the wheel joints and wheel
    geometry, and flags a diff_drive_controller whose values disagree (or whose wheels
    cannot give them).
    ## Why is this bad?
    Odometry scales with both: a radius typed twice and changed once makes the robot
    believe it drove further than it did, and the map smears.
    """
    from ...derive import diff_drive_geometry

    rc = robot.ros2_control
    if rc is None:
        return
    for c in rc.controllers:
        if not c.type.startswith("diff_drive_controller/"):
            continue
        geo = diff_drive_geometry(robot, c)
        for problem in geo.problems:
            yield at(
                "CTRL006",
                c,
                f"controller '{c.name}': {problem}",
                "fix the wheel joints or their collision geometry",
                subject=f"controller:{c.name}",
            )
        for key, derived in (("wheel_separation", geo.wheel_separation), ("wheel_radius", geo.wheel_radius)):
            given = c.param(key)
            if given is None or derived is None:
                continue
            if not isinstance(given, int | float) or abs(float(given) - derived) > 1e-9 * max(1.0, abs(derived)):
                yield at(
                    "CTRL006",
                    c,
                    f"controller '{c.name}' {key} is {given} but the URDF gives {derived:.9g} m",
                    f"remove {key} from the spec: descgen derives it from the URDF",
                    subject=f"controller:{c.name}",
                )


@rule("CTRL007", "update-rate-not-whole", "error")
def update_rate_not_whole(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Checks the controller_manager update rate is a whole number of Hz.
    ## Why is this bad?
    `update_rate` is an integer parameter; a fractional value fails to load.
    """
    rc = robot.ros2_control
    if rc is not None and rc.update_rate is not None and not float(rc.update_rate).is_integer():
        yield at(
            "CTRL007",
            rc,
            f"update_rate {rc.update_rate:g} Hz is not a whole number",
            "write e.g. 100 Hz",
            subject="ros2_control",
        )


@rule("CTRL008", "command-limit-beyond-urdf", "error")
def command_limit_beyond_urdf(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Compares each command interface's `min`/`max` with the joint's URDF limits (position
    with lower/upper, velocity and effort with their limits).
    ## Why is this bad?
    ros2_control uses them to tighten the URDF limits; wider values are ignored on new
    releases and trusted on older ones, so a command beyond the joint's range reaches the
    hardware.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is None or j.limit is None:
            continue
        lm = j.limit
        for iface in cj.command:
            if iface.name == "position" and j.type in ("revolute", "prismatic"):
                lo, hi = lm.lower, lm.upper
            elif iface.name == "velocity" and lm.velocity is not None:
                lo, hi = -abs(lm.velocity), abs(lm.velocity)
            elif iface.name == "effort" and lm.effort is not None:
                lo, hi = -abs(lm.effort), abs(lm.effort)
            else:
                continue
            tol = 1e-9
            if iface.max is not None and hi is not None and iface.max > hi + tol:
                yield at(
                    "CTRL008",
                    cj,
                    f"'{cj.name}/{iface.name}' command max {iface.max:.6g} is beyond the URDF limit {hi:.6g}",
                    "make the command limit equal to or inside the joint limit",
                    subject=f"ros2_control:{cj.name}",
                )
            if iface.min is not None and lo is not None and iface.min < lo - tol:
                yield at(
                    "CTRL008",
                    cj,
                    f"'{cj.name}/{iface.name}' command min {iface.min:.6g} is beyond the URDF limit {lo:.6g}",
                    "make the command limit equal to or inside the joint limit",
                    subject=f"ros2_control:{cj.name}",
                )


@rule("CTRL009", "controller-names-unknown-joint", "error")
def controller_names_unknown_joint(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Finds controllers whose joint lists (`joints`, `left_wheel_names`, `right_wheel_names`)
    name joints the URDF does not have.
    ## Why is this bad?
    The controller fails to configure on the robot; nothing moves.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    for c in rc.controllers:
        for key in ("joints", "left_wheel_names", "right_wheel_names"):
            for name in _list(c.param(key)):
                if robot.joint(str(name)) is None:
                    yield at(
                        "CTRL009",
                        c,
                        f"controller '{c.name}' {key} names '{name}', which is not a URDF joint",
                        "fix the joint name",
                        subject=f"controller:{c.name}",
                    )


@rule("CTRL010", "broadcaster-fed-from-commands", "error")
def broadcaster_fed_from_commands(robot: Robot) -> Iterator[Finding]:
    """## What it does
    Flags a joint_state_broadcaster whose `interfaces` or `map_interface_to_joint_state`
    names an interface the hardware exports only as a command interface.
    ## Why is this bad?
    /joint_states then carries what was commanded, robot_state_publisher turns it into tf,
    and the operator display animates commands as if they were measured motion.
    """
    rc = robot.ros2_control
    if rc is None:
        return
    commands = {i.name for cj in rc.joints for i in cj.command}
    states = {i.name for cj in rc.joints for i in cj.state}
    for c in rc.controllers:
        if not c.type.startswith("joint_state_broadcaster/"):
            continue
        named = [str(x) for x in _list(c.param("interfaces"))]
        mapping = c.param("map_interface_to_joint_state")
        if isinstance(mapping, tuple):
            named += [str(v) for _, v in mapping]
        for iface in named:
            if iface in commands and iface not in states:
                yield at(
                    "CTRL010",
                    c,
                    f"'{c.name}' publishes '{iface}', which the hardware exports only as a command interface",
                    "broadcast state interfaces only; publish desired values on their own topic",
                    subject=f"controller:{c.name}",
                )
