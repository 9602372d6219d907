"""``descgen tf-scenario``: a short rosbag2 recording of a spec's robot, with planted faults.

What a running robot would record (docs/reference/robot_state_publisher.md, ros2_control.md,
rosbag2.md): robot_state_publisher's fixed joints once on /tf_static, joint_state_broadcaster's
/joint_states at the controller rate and robot_state_publisher's /tf for the movable joints
stamped with them, diff_drive_controller's odom -> base frame on /tf, and camera headers
(sensor_msgs/CameraInfo) in the camera's optical frame. Log time = stamp + a small delay.

Faults (each applied inside a time window so a test can check the right messages fail):
- ``camera-future``: camera stamps 300 ms ahead of the clock, in [2 s, 3 s);
- ``odom-gap``: no odometry transform in [4 s, 5 s);
- ``unknown-frame``: camera frame_id not in the tree, in [6 s, 7 s).
"""

from __future__ import annotations

import heapq
import math
import shutil
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from descgen.codes import Code
from descgen.codes.command import UNIT021
from descgen.codes.recording import BAG003, BAG011
from descgen.commands.tf.buffer import quat_from_matrix
from descgen.core.findings import InputError, Where
from descgen.core.model import ONE_DOF, WITH_LIMITS, Robot
from descgen.physics import mimic
from descgen.physics.kinematics import joint_transform

FAULTS = ("camera-future", "odom-gap", "unknown-frame")
WINDOWS = {"camera-future": (2.0, 3.0), "odom-gap": (4.0, 5.0), "unknown-frame": (6.0, 7.0)}
NS = 1_000_000_000
# a scenario is a short test recording: at least a few controller cycles, and short enough
# to be written in seconds (ten minutes is ~60 000 messages per topic)
MIN_DURATION_S = 0.1
MAX_DURATION_S = 600.0
START_NS = 1_700_000_000 * NS  # a fixed epoch by default: recordings are reproducible


def _refuse(code: Code, out: Path, message: str, hint: str = "choose another --out") -> InputError:
    return InputError([code.finding(message, hint, "option", Where(str(out)))])


def check_out(out: Path) -> None:
    """``out`` must be a new folder in an existing, writable folder."""
    if out.exists() or out.is_symlink():
        raise _refuse(BAG003, out, f"{out} exists; a recording is written to a new folder")
    parent = out.parent
    if not parent.is_dir():
        what = "is not a folder" if parent.exists() else "does not exist"
        raise _refuse(BAG011, out, f"cannot write {out}: {parent} {what}")


@dataclass(frozen=True)
class Plan:
    rate_hz: float
    odom: tuple[str, str] | None  # (odom frame, base frame)
    camera_frame: str | None


def plan(robot: Robot) -> Plan:
    rc = robot.ros2_control
    rate = float(rc.update_rate) if rc and rc.update_rate else 100.0
    odom = None
    for c in rc.controllers if rc else ():
        if c.type.startswith("diff_drive_controller/") and c.param("enable_odom_tf", True) is not False:
            odom = (str(c.param("odom_frame_id", "odom")), str(c.param("base_frame_id", "base_link")))
    camera = next((s.optical_frame or s.link for s in robot.sensors if s.type == "camera"), None)
    return Plan(rate, odom, camera)


def joint_values(robot: Robot, t: float) -> dict[str, float]:
    """A slow, smooth motion inside every driving joint's limits; mimic joints follow their
    leaders (GenericSystem computes their state, robot_state_publisher their transform)."""
    out: dict[str, float] = {}
    for i, j in enumerate(robot.joints):
        if j.type == "continuous":
            out[j.name] = 2.0 * t
        elif j.type in WITH_LIMITS and j.limit and j.limit.lower is not None and j.limit.upper is not None:
            mid, amp = (j.limit.lower + j.limit.upper) / 2, (j.limit.upper - j.limit.lower) / 4
            out[j.name] = mid + amp * math.sin(0.5 * t + i)
    return mimic.resolve(robot, out)


def write(
    robot: Robot,
    out: Path,
    faults: tuple[str, ...] = (),
    duration: float = 10.0,
    storage: str = "mcap",
    start_ns: int = START_NS,
    description: str | None = None,
) -> dict[str, int]:
    """Write the recording to the new folder ``out``, whole or not at all (it is written
    beside ``out`` and renamed into place); returns message counts per topic. It starts at
    ``start_ns`` (ns since the epoch); ``description``, a URDF, is recorded on
    /robot_description as robot_state_publisher latches it."""
    check_out(out)
    if not MIN_DURATION_S <= duration <= MAX_DURATION_S:  # the library is called directly too
        raise _refuse(
            UNIT021,
            out,
            f"duration {duration:g} s is outside {MIN_DURATION_S:g} s to {MAX_DURATION_S:g} s",
            "give a shorter or longer --duration",
        )
    try:
        staging = Path(tempfile.mkdtemp(prefix=f".{out.name}.", dir=out.parent))
    except OSError as exc:
        raise _refuse(BAG011, out, f"cannot write in {out.parent}: {exc.strerror or exc}") from None
    from rosbags.rosbag2 import WriterError

    try:
        counts = _write(robot, staging / out.name, faults, duration, storage, start_ns, description)
        (staging / out.name).rename(out)
    except (OSError, WriterError) as exc:  # disk full, permissions, out created meanwhile
        raise _refuse(BAG011, out, f"cannot write {out}: {getattr(exc, 'strerror', None) or exc}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return counts


def _write(
    robot: Robot,
    out: Path,
    faults: tuple[str, ...],
    duration: float,
    storage: str,
    start: int,
    description: str | None,
) -> dict[str, int]:
    from rosbags.interfaces import Qos, QosDurability, QosHistory, QosLiveliness, QosReliability, QosTime
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    types: dict[str, Any] = dict(ts.types)
    time_, header_ = types["builtin_interfaces/msg/Time"], types["std_msgs/msg/Header"]
    vec_, quat_ = types["geometry_msgs/msg/Vector3"], types["geometry_msgs/msg/Quaternion"]
    transform_, stamped_ = types["geometry_msgs/msg/Transform"], types["geometry_msgs/msg/TransformStamped"]
    tf_message_, joint_state_ = types["tf2_msgs/msg/TFMessage"], types["sensor_msgs/msg/JointState"]
    camera_info_, roi_ = types["sensor_msgs/msg/CameraInfo"], types["sensor_msgs/msg/RegionOfInterest"]
    string_ = types["std_msgs/msg/String"]

    def stamp(ns: int) -> Any:
        return time_(sec=ns // NS, nanosec=ns % NS)

    def tf(parent: str, child: str, ns: int, m: np.ndarray) -> Any:
        q = quat_from_matrix(m[:3, :3])
        return stamped_(
            header=header_(stamp=stamp(ns), frame_id=parent),
            child_frame_id=child,
            transform=transform_(
                translation=vec_(x=float(m[0, 3]), y=float(m[1, 3]), z=float(m[2, 3])),
                rotation=quat_(x=q[0], y=q[1], z=q[2], w=q[3]),
            ),
        )

    p = plan(robot)
    latched = Qos(
        QosHistory.KEEP_LAST,
        1,
        QosReliability.RELIABLE,
        QosDurability.TRANSIENT_LOCAL,
        QosTime(0, 0),
        QosTime(0, 0),
        QosLiveliness.AUTOMATIC,
        QosTime(0, 0),
        False,
    )
    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    counts: dict[str, int] = {}
    fixed = [j for j in robot.joints if j.type == "fixed" and j.parent and j.child]
    movable = [j for j in robot.joints if j.type in ONE_DOF and j.parent and j.child]
    period = int(NS / p.rate_hz)
    steps = int(duration * p.rate_hz)

    # Events are made lazily and merged by (log time, order of making): the same order a
    # stable sort of them all would give, without holding a long recording in memory.
    def static_events() -> Iterator[Event]:
        if description is not None:  # robot_state_publisher latches it before its first transforms
            yield (start + 500_000, -1, "/robot_description", string_(data=description), "std_msgs/msg/String")
        msg = tf_message_(transforms=[tf(j.parent or "", j.child or "", start, joint_transform(j)) for j in fixed])
        yield (start + 1_000_000, 0, "/tf_static", msg, "tf2_msgs/msg/TFMessage")

    def controller_events() -> Iterator[Event]:
        pending: list[Event] = []  # at rates above 1 kHz a step's /tf is logged after the next /joint_states
        for k in range(steps):
            yield from _ready(pending, start + k * period + 1_000_000)
            for e in controller_step(k):
                heapq.heappush(pending, e)
        yield from _ready(pending, None)

    def controller_step(k: int) -> list[Event]:
        out: list[Event] = []
        ns = start + k * period
        t = k / p.rate_hz
        q = joint_values(robot, t)
        names = [j.name for j in movable]
        out.append(
            (
                ns + 1_000_000,
                1 + 2 * k,
                "/joint_states",
                joint_state_(
                    header=header_(stamp=stamp(ns), frame_id=""),
                    name=names,
                    position=np.array([q.get(n, 0.0) for n in names]),
                    velocity=np.zeros(len(names)),
                    effort=np.zeros(0),
                ),
                "sensor_msgs/msg/JointState",
            )
        )
        transforms = [tf(j.parent or "", j.child or "", ns, joint_transform(j, q.get(j.name, 0.0))) for j in movable]
        in_gap = "odom-gap" in faults and WINDOWS["odom-gap"][0] <= t < WINDOWS["odom-gap"][1]
        if p.odom is not None and k % 2 == 0 and not in_gap:  # odometry at half the rate, driving a circle
            m = np.eye(4)
            m[:2, 3] = (math.sin(0.2 * t), 1 - math.cos(0.2 * t))
            c, s = math.cos(0.2 * t), math.sin(0.2 * t)
            m[:2, :2] = ((c, -s), (s, c))
            transforms.append(tf(p.odom[0], p.odom[1], ns, m))
        out.append((ns + 2_000_000, 2 + 2 * k, "/tf", tf_message_(transforms=transforms), "tf2_msgs/msg/TFMessage"))
        return out

    def camera_events() -> Iterator[Event]:
        if p.camera_frame is None:
            return
        cam_period = NS // 30
        for k in range(int(duration * 30)):
            ns = start + k * cam_period + 5_000_000  # exposure time; arrives 20 ms later
            t = (ns - start) / NS
            frame, stamped = p.camera_frame, ns
            if "camera-future" in faults and WINDOWS["camera-future"][0] <= t < WINDOWS["camera-future"][1]:
                stamped = ns + 300_000_000
            if "unknown-frame" in faults and WINDOWS["unknown-frame"][0] <= t < WINDOWS["unknown-frame"][1]:
                frame = "camera_optical"
            info = camera_info_(
                header=header_(stamp=stamp(stamped), frame_id=frame),
                height=480,
                width=640,
                distortion_model="plumb_bob",
                d=np.zeros(5),
                k=np.zeros(9),
                r=np.zeros(9),
                p=np.zeros(12),
                binning_x=0,
                binning_y=0,
                roi=roi_(x_offset=0, y_offset=0, height=0, width=0, do_rectify=False),
            )
            yield (ns + 20_000_000, 1 + 2 * steps + k, "/camera/camera_info", info, "sensor_msgs/msg/CameraInfo")

    def events() -> Iterator[Event]:
        return heapq.merge(static_events(), controller_events(), camera_events())

    # connections in the order of each topic's first message: the first few events say it
    topics = {"/tf_static"} | ({"/joint_states", "/tf"} if steps else set())
    topics |= {"/robot_description"} if description is not None else set()
    topics |= {"/camera/camera_info"} if p.camera_frame is not None and int(duration * 30) else set()
    first: dict[str, str] = {}
    for _, _, topic, _, msgtype in events():
        first.setdefault(topic, msgtype)
        if len(first) == len(topics):
            break
    with Writer(out, version=9, storage_plugin=plugin) as w:
        conns = {}
        for topic, msgtype in first.items():
            qos = (latched,) if topic in ("/tf_static", "/robot_description") else ()
            conns[topic] = w.add_connection(topic, msgtype, typestore=ts, offered_qos_profiles=qos)
        for log_ns, _, topic, msg, msgtype in events():
            w.write(conns[topic], log_ns, ts.serialize_cdr(msg, msgtype))
            counts[topic] = counts.get(topic, 0) + 1
    return counts


Event = tuple[int, int, str, Any, str]  # log ns, order of making, topic, message, type


def _ready(pending: list[Event], before: int | None) -> Iterator[Event]:
    """Pop the heap's events logged before ``before`` (None: all), oldest first."""
    while pending and (before is None or pending[0][0] < before):
        yield heapq.heappop(pending)
