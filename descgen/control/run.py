"""``descgen control``: load the generated ros2_control files, run a trajectory through the
read-update-write loop, and write what happened at the command/state boundary."""

from __future__ import annotations

import csv
import dataclasses
import io
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .. import units
from ..findings import Finding, InputError, Where
from ..model import Robot, Ros2Control
from ..readers.controllers import read_controllers_text
from ..readers.urdf import read_urdf_text
from ..readers.xacro_file import expand
from ..yamlsource import Document, load
from .manager import ControllerManager, JointTrajectoryController, Point
from .system import Hardware, JointHw, MimicHw, Plant, Trace

DEFAULT_TOLERANCE = {"prismatic": 0.01, "other": math.radians(3)}
# simulated time of one run (--duration and time_from_start): at least one cycle, and at most
# ten minutes, which the loop model runs in about a minute; longer is a typo, not a test
MIN_DURATION_S = 0.01
MAX_DURATION_S = 600.0
_KEYS = ("controller", "joints", "points")
_POINT_KEYS = ("time_from_start", "positions")


@dataclass
class Trajectory:
    controller: str
    joints: list[str]
    points: list[Point]
    where: Where = field(default_factory=lambda: Where("<trajectory>"))  # the file, for messages


class _Problems:
    """The findings of one trajectory file, each placed at its YAML node."""

    def __init__(self, doc: Document) -> None:
        self.doc = doc
        self.found: list[Finding] = []

    def __call__(
        self, where: tuple[str | int, ...], message: str, hint: str, code: str = "CTRL020", key: bool = False
    ) -> None:
        self.found.append(Finding(code, "error", message, hint, "trajectory", self.doc.where(where, key=key)))


def read_trajectory(path: Path, robot: Robot) -> Trajectory:
    """A trajectory file (controller, joints, points of time_from_start and positions), checked
    so that a run can neither crash on it nor pass without running anything."""
    doc = load(path)
    data = doc.data
    bad = _Problems(doc)
    if not isinstance(data, dict):
        bad((), "a trajectory is a mapping (controller, joints, points)", "see the README")
        raise InputError(bad.found)
    for k in data:
        if k not in _KEYS:
            bad((k,), f"unknown key {k!a}", f"a trajectory has {', '.join(_KEYS)}", key=True)
    controller = data.get("controller")
    if not isinstance(controller, str) or not controller:
        bad(("controller",), "controller: expected the name of a joint_trajectory_controller", "e.g. arm_controller")
    joints = _joints(data, robot, bad)
    points = _points(data, joints, robot, bad)
    if bad.found:
        raise InputError(bad.found)
    return Trajectory(str(controller), joints or [], points, doc.where(()))


def _joints(data: dict[str, Any], robot: Robot, bad: _Problems) -> list[str] | None:
    raw = data.get("joints")
    if not isinstance(raw, list) or not raw:
        bad(("joints",), "joints: expected a non-empty list of joint names", "e.g. joints: [elbow_joint]", "CTRL030")
        return None
    ok = True
    for i, name in enumerate(raw):
        if not isinstance(name, str):
            bad(("joints", i), f"joints: {name!a} is not a joint name", "write the joint's name")
            ok = False
        elif robot.joint(name) is None:
            bad(("joints", i), f"unknown joint {name!a}", "name a joint of the robot")
        elif raw.index(name) != i:
            bad(("joints", i), f"joint {name!a} is listed twice", "list each joint once")
    return [str(j) for j in raw] if ok else None


def _points(data: dict[str, Any], joints: list[str] | None, robot: Robot, bad: _Problems) -> list[Point]:
    raw = data.get("points")
    if raw is None or raw == []:
        bad(("points",), "the trajectory has no points: nothing would run", "add at least one point", "CTRL030")
        return []
    if not isinstance(raw, list):
        bad(("points",), "points: expected a list of points", "write points as a YAML list")
        return []
    points: list[Point] = []
    last: float | None = None
    for i, p in enumerate(raw):
        if not isinstance(p, dict):
            bad(("points", i), f"point {i + 1} is not a mapping", "write {time_from_start: ..., positions: [...]}")
            continue
        for k in p:
            if k not in _POINT_KEYS:
                bad(
                    ("points", i, k),
                    f"point {i + 1}: unknown key {k!a}",
                    "a point has time_from_start and positions",
                    key=True,
                )
        t = _time(p, i, bad)
        if t is not None and last is not None and t <= last:
            bad(
                ("points", i, "time_from_start"),
                f"point {i + 1}: time_from_start {t:g} s is not after the previous point's {last:g} s",
                "list points in increasing time",
                "CTRL031",
            )
        last = t if t is not None else last
        values = _positions(p, i, joints, robot, bad)
        if t is not None and values is not None:
            points.append(Point(t, values))
    return points


def _time(p: dict[str, Any], i: int, bad: _Problems) -> float | None:
    if "time_from_start" not in p:
        bad(("points", i), f"point {i + 1} has no time_from_start", 'write e.g. time_from_start: "2 s"')
        return None
    try:
        return units.duration(p["time_from_start"], 0.0, MAX_DURATION_S)
    except units.QuantityError as exc:
        bad(("points", i, "time_from_start"), f"time_from_start: {exc.message}", exc.hint, exc.code)
        return None


def _positions(
    p: dict[str, Any], i: int, joints: list[str] | None, robot: Robot, bad: _Problems
) -> tuple[float, ...] | None:
    raw = p.get("positions")
    if not isinstance(raw, list):
        bad(("points", i, "positions"), f"point {i + 1}: positions must be a list", 'write e.g. positions: ["0 deg"]')
        return None
    if joints is None:
        return None
    if len(raw) != len(joints):
        bad(
            ("points", i, "positions"),
            f"{len(raw)} positions for {len(joints)} joints",
            "give one position per joint",
        )
        return None
    values = []
    for k, (name, value) in enumerate(zip(joints, raw, strict=True)):
        j = robot.joint(name)
        kind = "length" if j is not None and j.type == "prismatic" else "angle"
        try:
            values.append(units.to_si(value, kind))
        except units.QuantityError as exc:
            bad(("points", i, "positions", k), exc.message, exc.hint, exc.code)
    return tuple(values) if len(values) == len(joints) else None


@dataclass
class Outcome:
    cm: ControllerManager
    rows: list[tuple[float, str, float, float, float]] = field(default_factory=list)  # t, joint, desired, cmd, meas
    tracking: dict[str, float] = field(default_factory=dict)
    tolerance: dict[str, float] = field(default_factory=dict)

    @property
    def echo(self) -> bool:
        return self.cm.hardware.echoes_commands

    def findings(self) -> list[Finding]:
        """What the run showed at the command/state boundary, as findings."""
        out = []
        for j, e in self.tracking.items():
            if e > self.tolerance[j]:
                out.append(
                    Finding(
                        "CTRL011",
                        "error",
                        f"joint '{j}' tracking error reached {e:.4g} (tolerance "
                        f"{self.tolerance[j]:.4g}): the measured state does not follow the command",
                        "check the joint's direction, encoder offset and whether it moves at all",
                        f"joint:{j}",
                    )
                )
        for ev in self.cm.rejected[:1]:
            out.append(
                Finding(
                    "CTRL012",
                    "error",
                    f"{len(self.cm.rejected)} command(s) rejected by limits; first: "
                    f"{ev.joint}/{ev.interface} = {ev.value:.6g} beyond {ev.limit:.6g} at {ev.time:.2f} s",
                    "keep the trajectory inside the joint limits",
                    f"joint:{ev.joint}",
                )
            )
        for n, c in self.cm.controllers.items():
            if c.state != "active":
                out.append(
                    Finding(
                        "CTRL013",
                        "error",
                        f"controller '{n}' never became active (state {c.state})",
                        "see lifecycle.md for the failed transition or claim",
                        f"controller:{n}",
                    )
                )
        if self.echo:
            out.append(
                Finding(
                    "CTRL014",
                    "info",
                    "the measured state is the mock hardware echoing the command",
                    "this run does not verify motion; use --plant sim or real hardware",
                    "hardware",
                )
            )
        return out

    def verdict(self) -> dict[str, Any]:
        failed = [j for j, e in self.tracking.items() if e > self.tolerance[j]]
        inactive = [n for n, c in self.cm.controllers.items() if c.state != "active"]
        return {
            "rejected": [
                {"joint": e.joint, "interface": e.interface, "time": e.time, "value": e.value, "limit": e.limit}
                for e in self.cm.rejected
            ],
            "clipped": [
                {
                    "joint": e.joint,
                    "interface": e.interface,
                    "time": e.time,
                    "proposed": e.value,
                    "applied": e.applied,
                    "limit": e.limit,
                }
                for e in self.cm.clipped
            ],
            "tracking": self.tracking,
            "tolerance": self.tolerance,
            "tracking_failed": failed,
            "controllers_not_active": inactive,
            "state_echoes_command": self.echo,
            "note": (
                "the 'measured' state is mock_components/GenericSystem mirroring the command: this is not "
                "verified motion"
            )
            if self.echo
            else "measured state comes from the simulated plant",
            "ok": not failed and not self.cm.rejected and not inactive,
            "findings": [f.as_dict() for f in self.findings()],
        }


def find_package(spec: Path, robot: Robot, given: Path | None) -> Path:
    """The generated package: ``given`` is the package itself or the output root holding it
    (what ``generate --out`` was given); without it, the default output root. Nothing found
    is an input error that says where it looked."""
    from ..generate import default_out
    from ..render.context import package_name

    name = package_name(robot)
    root = given if given is not None else default_out(spec)
    tried = [root, root / name] if given is not None else [root / name]
    needed = (Path("config") / "ros2_controllers.yaml", Path("urdf") / f"{robot.name}.ros2_control.xacro")
    for folder in tried:
        if all((folder / rel).is_file() for rel in needed):
            return folder
    looked = " or ".join(str(f) for f in tried)
    raise InputError(
        [
            Finding(
                "CTRL021",
                "error",
                f"no generated package of '{robot.name}' at {looked} "
                f"(it needs {needed[0].as_posix()} and {needed[1].as_posix()})",
                f"run descgen generate {spec}"
                + (f" --out {given}" if given is not None else "")
                + ", or pass --package with the folder generate --out wrote",
                "option" if given is not None else "file",
                Where(str(tried[-1])),
            )
        ]
    )


def load_system(package: Path, robot: Robot, plant: Plant) -> ControllerManager:
    """The hardware and controllers as the generated files describe them."""
    xacro = package / "urdf" / f"{robot.name}.ros2_control.xacro"
    model, _ = read_urdf_text(expand(xacro, str(xacro)), str(xacro))
    rc = model.ros2_control
    if rc is None:
        raise InputError(
            [Finding("CTRL021", "error", f"{xacro} has no <ros2_control> block", "generate first", "file")]
        )
    controllers, rate, _ = read_controllers_text(
        (package / "config" / "ros2_controllers.yaml").read_text(), str(package / "config" / "ros2_controllers.yaml")
    )
    _refuse_like_jazzy(robot, rc, xacro)
    trace = Trace()
    policies = {cj.name: cj.on_limit for cj in robot.ros2_control.joints} if robot.ros2_control else {}
    joints = []
    for cj in rc.joints:
        joints.append(
            JointHw(
                cj.name,
                {i.name: math.nan for i in cj.command},
                {i.name: math.nan if i.initial_value is None else i.initial_value for i in cj.state},
                {i.name: (i.min, i.max) for i in cj.command},
                policies.get(cj.name, "reject"),
            )
        )
    hw = Hardware(rc.name, rc.plugin, dict(rc.params), joints, trace, plant)
    hw.mimics = mimic_joints(robot, rc)
    for j in robot.joints:
        if j.limit is not None and j.limit.velocity:
            hw.vel_limit[j.name] = abs(j.limit.velocity)
    cm = ControllerManager(hw, rate or 100.0, trace)
    cm.start_hardware()
    for c in controllers:
        cm.spawn(c.name, c.type, {k: _plain(v) for k, v in c.params})
    return cm


def _refuse_like_jazzy(robot: Robot, rc: Ros2Control, xacro: Path) -> None:
    """What Jazzy's component parser throws on (mimic rules, CTRL040-043), as an input error:
    the real controller_manager would load no hardware at all."""
    from ..audit import run as run_rules

    model = dataclasses.replace(robot, ros2_control=dataclasses.replace(rc, controllers=()))
    refused = [f for f in run_rules(model, codes=MIMIC_CODES) if f.severity == "error"]
    if refused:
        raise InputError(refused)


MIMIC_CODES = ("CTRL040", "CTRL041", "CTRL042", "CTRL043")


def mimic_joints(robot: Robot, rc: Ros2Control) -> list[MimicHw]:
    """HardwareInfo.mimic_joints as Jazzy's parser fills it: every ros2_control joint whose
    URDF joint has <mimic> and whose mimic attribute is not false, in block order."""
    from ..audit.rules.control import active_mimic

    out = []
    for cj in rc.joints:
        j = robot.joint(cj.name)
        if j is not None and j.mimic is not None and active_mimic(robot, cj):
            out.append(MimicHw(cj.name, j.mimic.joint, j.mimic.multiplier, j.mimic.offset))
    return out


def _plain(v: object) -> object:
    if isinstance(v, tuple) and v and all(isinstance(x, tuple) and len(x) == 2 for x in v):
        return {str(k): _plain(x) for k, x in v}
    if isinstance(v, tuple):
        return [_plain(x) for x in v]
    return v


def run(package: Path, robot: Robot, trajectory: Trajectory, duration: float | None, plant: Plant) -> Outcome:
    cm = load_system(package, robot, plant)
    jtc = cm.controllers.get(trajectory.controller)
    if not isinstance(jtc, JointTrajectoryController):
        raise InputError(
            [
                Finding(
                    "CTRL022",
                    "error",
                    f"no joint_trajectory_controller named '{trajectory.controller}' in the controllers file",
                    "name the arm's controller",
                    "trajectory",
                    trajectory.where,
                )
            ]
        )
    foreign = [j for j in trajectory.joints if j not in jtc.joints]
    if foreign or not trajectory.points:
        raise InputError(
            [
                Finding(
                    "CTRL033" if foreign else "CTRL030",
                    "error",
                    f"controller '{trajectory.controller}' does not command {', '.join(foreign)}"
                    if foreign
                    else "the trajectory has no points: nothing would run",
                    f"its joints are {', '.join(jtc.joints)}" if foreign else "add at least one point",
                    "trajectory",
                    trajectory.where,
                )
            ]
        )
    end = duration if duration is not None else trajectory.points[-1].time + 1.0
    dt = 1.0 / cm.update_rate
    # the goal is given in the trajectory's joint order; the controller has its own
    order = {n: i for i, n in enumerate(trajectory.joints)}
    points = [
        Point(p.time, tuple(p.positions[order[j]] if j in order else math.nan for j in jtc.joints))
        for p in trajectory.points
    ]
    cm.step(0.0)  # one cycle so the controller sees measured state before the goal arrives
    jtc.follow(points, 0.0)
    out = Outcome(cm)
    kinds = {j.name: j.type for j in robot.joints}
    for name in jtc.joints:
        out.tracking[name] = 0.0
        out.tolerance[name] = DEFAULT_TOLERANCE["prismatic" if kinds.get(name) == "prismatic" else "other"]
    for k in range(1, round(end * cm.update_rate) + 1):
        t = k * dt
        cm.step(t)
        for name in jtc.joints:
            desired = jtc.desired.get(name, math.nan)
            commanded = cm.by_name[name].commands.get("position", math.nan)
            measured = cm.state(name, "position")
            out.rows.append((t, name, desired, commanded, measured))
            if not math.isnan(desired) and not math.isnan(measured):
                out.tracking[name] = max(out.tracking[name], abs(desired - measured))
    return out


def write_evidence(out: Outcome, folder: Path, robot: Robot) -> list[str]:
    """lifecycle.jsonl/.md, interfaces.md, desired_vs_measured.csv, plots, MCAP, verdict.json."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:  # a file in the way, no permission
        raise InputError(
            [
                Finding(
                    "CTRL034",
                    "error",
                    f"cannot create the evidence folder {folder}: {exc.strerror or exc}",
                    "choose another --out",
                    "option",
                    Where(str(folder)),
                )
            ]
        ) from None
    cm = out.cm
    written = []

    def put(name: str, text: str) -> None:
        (folder / name).write_text(text, encoding="utf-8")
        written.append(name)

    put("lifecycle.jsonl", "".join(json.dumps(e, sort_keys=True) + "\n" for e in cm.trace.events))
    lines = [
        "# ros2_control lifecycle and claims, in order",
        "",
        "| t (s) | event | who | detail |",
        "|---|---|---|---|",
    ]
    for e in cm.trace.events:
        who = e.get("name") or e.get("controller") or e.get("joint", "")
        detail = ", ".join(f"{k}={v}" for k, v in e.items() if k not in ("t", "event", "name", "controller", "kind"))
        lines.append(f"| {e['t']:.2f} | {e['event']} | {who} | {detail} |")
    put("lifecycle.md", "\n".join(lines) + "\n")
    cmds = [f"{j.name}/{i}" for j in cm.hardware.joints for i in j.commands]
    states = [f"{j.name}/{i}" for j in cm.hardware.joints for i in j.states]
    text = [
        "# Interfaces and controllers (as `ros2 control list_hardware_interfaces` / `list_controllers`)",
        "",
        "```",
        "command interfaces",
    ]
    text += [f"\t{k} [available] [{'claimed' if k in cm.resources.owner else 'unclaimed'}]" for k in cmds]
    text += ["state interfaces"] + [f"\t{k}" for k in states] + ["```", "", "```"]
    text += [f"{n:<26} {c.type:<55} {c.state}" for n, c in cm.controllers.items()] + ["```", ""]
    put("interfaces.md", "\n".join(text))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["time_s", "joint", "desired", "commanded", "measured", "error"])
    for t, name, d, c, m in out.rows:
        w.writerow([f"{t:.3f}", name, f"{d:.9g}", f"{c:.9g}", f"{m:.9g}", f"{d - m:.9g}"])
    put("desired_vs_measured.csv", buf.getvalue())
    put("verdict.json", json.dumps(out.verdict(), indent=2) + "\n")
    written += _plots(out, folder)
    written += _recording(out, folder)
    return written


def _plots(out: Outcome, folder: Path) -> list[str]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    names = []
    for joint in out.tracking:
        rows = [r for r in out.rows if r[1] == joint]
        fig, ax = plt.subplots(figsize=(7, 3.2))
        ax.plot([r[0] for r in rows], [r[2] for r in rows], label="desired (controller)")
        ax.plot([r[0] for r in rows], [r[3] for r in rows], "--", label="commanded (after limits)")
        ax.plot([r[0] for r in rows], [r[4] for r in rows], label="measured (state interface)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("position (SI: m or rad)")
        ax.set_title(f"{joint}: " + ("state echoes the command (mock)" if out.echo else "simulated plant"))
        ax.legend(fontsize=7)
        fig.tight_layout()
        name = f"{joint}.png"
        fig.savefig(folder / name, dpi=80)
        plt.close(fig)
        names.append(name)
    return names


def _recording(out: Outcome, folder: Path) -> list[str]:
    import shutil

    import numpy as np
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    types: dict[str, Any] = dict(ts.types)
    js, header, time_ = (
        types["sensor_msgs/msg/JointState"],
        types["std_msgs/msg/Header"],
        types["builtin_interfaces/msg/Time"],
    )
    bag = folder / "control_run"
    shutil.rmtree(bag, ignore_errors=True)
    start = 1_700_000_000 * 1_000_000_000
    by_time: dict[float, list[tuple[str, float, float]]] = {}
    for t, name, d, _, m in out.rows:
        by_time.setdefault(t, []).append((name, d, m))
    with Writer(bag, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        measured = w.add_connection("/joint_states", "sensor_msgs/msg/JointState", typestore=ts)
        desired = w.add_connection("/arm_controller/desired_state", "sensor_msgs/msg/JointState", typestore=ts)
        for t, entries in sorted(by_time.items()):
            ns = start + round(t * 1e9)
            stamp = time_(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)
            names = [e[0] for e in entries]
            for conn, values in ((measured, [e[2] for e in entries]), (desired, [e[1] for e in entries])):
                msg = js(
                    header=header(stamp=stamp, frame_id=""),
                    name=names,
                    position=np.array(values),
                    velocity=np.zeros(0),
                    effort=np.zeros(0),
                )
                w.write(conn, ns, ts.serialize_cdr(msg, "sensor_msgs/msg/JointState"))
    return ["control_run/"]
