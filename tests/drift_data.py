"""Test data for ``descgen drift``: recordings of a robot whose true kinematics differ from its URDF.

An independent oracle: the true poses come from pinocchio's forward kinematics of a *planted*
URDF, never from descgen's own kinematics, so a test can check that drift finds what was planted.

- :func:`plant` adds calibration errors to joint origins (``xyz``/``rpy``) of a URDF text;
- :class:`Truth` is the planted robot, with joint zero offsets: a joint that reports ``q`` is
  really at ``q + offset``, so the true pose is pinocchio's FK at ``q_reported + offset``;
- :func:`samples` makes a :class:`Recording`: the reported joint values along a smooth
  excitation, and a tracker's (noisy) pose of a frame relative to a base link;
- :func:`write_csv` and :func:`write_bag` write it as a CSV table or a rosbag2 recording.

Time is float seconds from ``T0`` (1 700 000 000 s, so stamps look real); the excitation itself
is evaluated at ``t - T0`` so that its sines keep their precision.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin
from lxml import etree

T0 = 1_700_000_000.0  # s: the first sample's time
T0_NS = 1_700_000_000 * 1_000_000_000
LOG_DELAY_NS = 2_000_000  # log time = stamp + 2 ms
COMPONENTS = ("x", "y", "z", "roll", "pitch", "yaw")
MOVING_TYPES = ("revolute", "prismatic", "continuous")
JOINT_STATE = "sensor_msgs/msg/JointState"
POSE_TYPES = ("geometry_msgs/msg/PoseStamped", "geometry_msgs/msg/TransformStamped")
_PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97)


# --- URDF ---------------------------------------------------------------------------------------


def _parse(urdf_text: str) -> Any:
    parser = etree.XMLParser(resolve_entities=False, remove_blank_text=False)
    return etree.fromstring(urdf_text.encode("utf-8"), parser)


def _joints(root: Any) -> list[Any]:
    """The robot's own ``<joint>`` elements (not those of ``<ros2_control>`` or ``<transmission>``)."""
    return list(root.iterchildren("joint"))


def _floats(text: str | None, count: int = 3) -> list[float]:
    if text is None or not text.split():
        return [0.0] * count
    values = [float(v) for v in text.split()]
    if len(values) != count:
        raise ValueError(f"expected {count} numbers, got {text!r}")
    return values


def plant(urdf_text: str, origins: Mapping[tuple[str, str], float]) -> str:
    """``urdf_text`` with ``value`` ADDED to component ``component`` of joint ``joint``'s
    ``<origin>`` for each ``(joint, component): value`` of ``origins``; component is one of
    x, y, z (m), roll, pitch, yaw (rad); a missing ``<origin>`` or attribute counts as 0. The
    changed attributes are written in full with repr() precision; nothing else changes."""
    if not origins:
        return urdf_text
    root = _parse(urdf_text)
    by_name = {j.get("name"): j for j in _joints(root)}
    for (joint, component), value in origins.items():
        if joint not in by_name:
            raise KeyError(f"no joint {joint!r} in the URDF")
        if component not in COMPONENTS:
            raise ValueError(f"component {component!r} is not one of {', '.join(COMPONENTS)}")
        element = by_name[joint]
        origin = element.find("origin")
        if origin is None:
            origin = etree.SubElement(element, "origin")
        index = COMPONENTS.index(component)
        attr, index = ("xyz", index) if index < 3 else ("rpy", index - 3)
        numbers = _floats(origin.get(attr))
        numbers[index] += float(value)
        origin.set(attr, " ".join(repr(v) for v in numbers))
    return etree.tostring(root.getroottree(), encoding="unicode")  # comments kept, XML declaration dropped


@dataclass(frozen=True)
class _JointInfo:
    name: str
    type: str
    lower: float
    upper: float
    mimic: tuple[str, float, float] | None  # (master joint, multiplier, offset)


def _joint_infos(root: Any) -> list[_JointInfo]:
    out = []
    for j in _joints(root):
        kind = j.get("type", "")
        limit = j.find("limit")
        if kind == "continuous":
            lower, upper = -math.pi, math.pi
        elif kind in ("revolute", "prismatic") and limit is not None:
            lower, upper = float(limit.get("lower", "0")), float(limit.get("upper", "0"))
        else:
            lower, upper = 0.0, 0.0
        m = j.find("mimic")
        mimic = None
        if m is not None:
            mimic = (m.get("joint", ""), float(m.get("multiplier", "1")), float(m.get("offset", "0")))
        out.append(_JointInfo(j.get("name", ""), kind, lower, upper, mimic))
    return out


def root_link(urdf_text: str) -> str:
    """The URDF's root link: the one link that is no joint's child."""
    root = _parse(urdf_text)
    children = {c.get("link") for j in _joints(root) for c in j.iterchildren("child")}
    roots = [link.get("name") for link in root.iterchildren("link") if link.get("name") not in children]
    if len(roots) != 1:
        raise ValueError(f"the URDF has {len(roots)} root links: {roots}")
    return str(roots[0])


def moving_joints(urdf_text: str) -> tuple[str, ...]:
    """Every revolute, prismatic or continuous joint that is not a mimic, in document order."""
    return tuple(j.name for j in _joint_infos(_parse(urdf_text)) if j.type in MOVING_TYPES and j.mimic is None)


# --- the truth ----------------------------------------------------------------------------------


class Truth:
    """The real robot: pinocchio's model of a (planted) URDF text, fixed base, and joint zero
    offsets (rad for revolute and continuous, m for prismatic): a joint reporting ``q`` is at
    ``q + offset``. A mimic joint follows its master's TRUE value (``multiplier * (q_master +
    offset_master) + mimic offset``), plus its own offset in ``offsets`` if it has one. Joints
    given no value are at 0 (reported)."""

    def __init__(self, urdf_text: str, offsets: Mapping[str, float] | None = None, base: str | None = None) -> None:
        self.model = pin.buildModelFromXML(urdf_text)  # mimic joints as plain joints: set below
        self.data = self.model.createData()
        self.base = base if base is not None else root_link(urdf_text)
        self.offsets = dict(offsets or {})
        infos = {j.name: j for j in _joint_infos(_parse(urdf_text))}
        # pinocchio joint 0 is "universe"; the others are the URDF's moving joints
        self._slots: dict[str, tuple[int, int]] = {}
        for jid in range(1, self.model.njoints):
            joint = self.model.joints[jid]
            name = str(self.model.names[jid])
            if joint.nq not in (1, 2) or name not in infos:
                raise ValueError(f"joint {name!r} ({joint.shortname()}) is not revolute, prismatic or continuous")
            self._slots[name] = (joint.idx_q, joint.nq)
        for name in self.offsets:
            if name not in self._slots:
                raise KeyError(f"offset for {name!r}, which is no moving joint of the URDF")
        self._mimics = {name: infos[name].mimic for name in self._slots if infos[name].mimic is not None}
        self._base_id = self._frame_id(self.base)

    def _frame_id(self, link: str) -> int:
        if not self.model.existFrame(link, pin.BODY):
            raise KeyError(f"no link {link!r} in the URDF")
        return int(self.model.getFrameId(link, pin.BODY))

    def true_values(self, reported: Mapping[str, float]) -> dict[str, float]:
        """Each moving joint's true value, from the reported values (missing: 0)."""
        unknown = set(reported) - set(self._slots)
        if unknown:
            raise KeyError(f"no moving joints {sorted(unknown)} in the URDF")
        true = {n: float(reported.get(n, 0.0)) + self.offsets.get(n, 0.0) for n in self._slots if n not in self._mimics}
        for name, mimic in self._mimics.items():
            assert mimic is not None
            master, multiplier, offset = mimic
            true[name] = multiplier * true[master] + offset + self.offsets.get(name, 0.0)
        return true

    def configuration(self, reported: Mapping[str, float]) -> np.ndarray:
        """pinocchio's q for the reported values: continuous joints as (cos q, sin q)."""
        q = pin.neutral(self.model)
        for name, value in self.true_values(reported).items():
            index, nq = self._slots[name]
            if nq == 1:
                q[index] = value
            else:
                q[index], q[index + 1] = math.cos(value), math.sin(value)
        return q

    def placement(self, frame: str, reported: Mapping[str, float]) -> pin.SE3:
        """The true placement of link ``frame`` in the base link: oMf_base^-1 * oMf_frame."""
        frame_id = self._frame_id(frame)
        pin.framesForwardKinematics(self.model, self.data, self.configuration(reported))
        return self.data.oMf[self._base_id].actInv(self.data.oMf[frame_id])

    def pose(self, frame: str, reported: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
        """(position (3,), quaternion x, y, z, w (4,) with w >= 0) of ``frame`` in the base."""
        m = self.placement(frame, reported)
        return np.array(m.translation, dtype=float), quat_xyzw(m.rotation)


def quat_xyzw(rotation: np.ndarray) -> np.ndarray:
    """The unit quaternion (x, y, z, w) of a rotation matrix, sign chosen so that w >= 0."""
    q = np.array(pin.Quaternion(np.asarray(rotation, dtype=float)).coeffs(), dtype=float)
    q /= np.linalg.norm(q)
    return -q if q[3] < 0 else q


# --- recordings ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Recording:
    """A tracked frame's pose and the reported joint values at times ``t`` (float seconds).

    ``q`` are the REPORTED joint values (no offsets); ``xyz``/``quat_xyzw`` the measured pose
    (truth plus noise) of ``frame`` in ``base``; ``xyz_true``/``quat_xyzw_true`` the noise-free
    truth; ``q_at(t)`` the reported joint trajectory at any absolute times ``t`` (shape (N, J))."""

    joint_names: tuple[str, ...]
    t: np.ndarray
    q: np.ndarray
    xyz: np.ndarray
    quat_xyzw: np.ndarray
    frame: str
    base: str
    q_at: Callable[[np.ndarray], np.ndarray]
    xyz_true: np.ndarray
    quat_xyzw_true: np.ndarray


def _trajectory(
    infos: Mapping[str, _JointInfo], joints: Sequence[str], moving: Iterable[str], phases: np.ndarray
) -> Callable[[np.ndarray], np.ndarray]:
    """q(t) = mid + 0.8 * half_range * sin(2 pi f_k (t - T0) + phase_k) for the moving joints,
    f_k = 0.05 (1 + sqrt(p_k)) Hz with p_k the k-th prime; the others at 0 clipped into limits."""
    moving = set(moving)
    mids = np.array([(infos[n].lower + infos[n].upper) / 2 for n in joints])
    halves = np.array([(infos[n].upper - infos[n].lower) / 2 if n in moving else 0.0 for n in joints])
    rest = np.array([0.0 if n in moving else min(max(0.0, infos[n].lower), infos[n].upper) for n in joints])
    is_moving = np.array([n in moving for n in joints], dtype=bool)
    freqs = np.array([0.05 * (1 + math.sqrt(_PRIMES[k % len(_PRIMES)])) for k in range(len(joints))])

    def q_at(t: np.ndarray) -> np.ndarray:
        tau = np.asarray(t, dtype=float).reshape(-1, 1) - T0
        wave = mids + 0.8 * halves * np.sin(2 * math.pi * freqs * tau + phases)
        return np.where(is_moving, wave, rest)

    return q_at


def samples(
    urdf_text: str,
    frame: str,
    *,
    base: str | None = None,
    offsets: Mapping[str, float] | None = None,
    origins: Mapping[tuple[str, str], float] | None = None,
    joints: Sequence[str] | None = None,
    n: int = 400,
    seed: int = 0,
    moving: Iterable[str] | None = None,
    noise_m: float = 0.0,
    noise_rad: float = 0.0,
    duration_s: float = 40.0,
    switch: tuple[float, Mapping[str, float] | None, Mapping[tuple[str, str], float] | None] | None = None,
) -> Recording:
    """A recording of ``frame``'s pose in ``base`` (default: the root link) while ``joints``
    (default :func:`moving_joints`) move: ``n`` samples evenly over [0, duration_s) from ``T0``.
    The truth is the URDF with ``origins`` planted and joint zero ``offsets``; from
    ``switch = (t_switch_s, offsets2, origins2)`` on (``t - T0 >= t_switch_s``) it is the URDF with
    ``origins2`` and ``offsets2`` instead (each None meaning none). Measured position = truth +
    N(0, noise_m) per axis; measured rotation = truth * exp(N(0, noise_rad) per axis).
    Random draws, in order: the phases (J), position noise (n, 3), rotation noise (n, 3)."""
    root = _parse(urdf_text)
    infos = {j.name: j for j in _joint_infos(root)}
    names = tuple(joints) if joints is not None else moving_joints(urdf_text)
    for name in names:
        if name not in infos or infos[name].type not in MOVING_TYPES:
            raise KeyError(f"{name!r} is no revolute, prismatic or continuous joint of the URDF")
    moving_set = set(names) if moving is None else set(moving)
    if not moving_set <= set(names):
        raise KeyError(f"moving joints {sorted(moving_set - set(names))} are not among the joints")
    base = base if base is not None else root_link(urdf_text)
    rng = np.random.default_rng(seed)
    phases = rng.uniform(0.0, 2 * math.pi, len(names))
    q_at = _trajectory(infos, names, moving_set, phases)
    t = T0 + duration_s * np.arange(n) / n
    q = q_at(t)

    truth = Truth(plant(urdf_text, origins or {}), offsets, base)
    after = None
    if switch is not None:
        t_switch, offsets2, origins2 = switch
        after = (t_switch, Truth(plant(urdf_text, origins2 or {}), offsets2, base))
    xyz_true = np.zeros((n, 3))
    quat_true = np.zeros((n, 4))
    rot_true = np.zeros((n, 3, 3))
    for k in range(n):
        model = after[1] if after is not None and t[k] - T0 >= after[0] else truth
        m = model.placement(frame, dict(zip(names, q[k].tolist(), strict=True)))
        xyz_true[k] = m.translation
        rot_true[k] = m.rotation
        quat_true[k] = quat_xyzw(m.rotation)
    xyz = xyz_true + rng.normal(0.0, noise_m, (n, 3))
    rotvec = rng.normal(0.0, noise_rad, (n, 3))
    quat = np.array([quat_xyzw(rot_true[k] @ pin.exp3(rotvec[k])) for k in range(n)]).reshape(n, 4)
    return Recording(names, t, q, xyz, quat, frame, base, q_at, xyz_true, quat_true)


# --- files --------------------------------------------------------------------------------------


def write_csv(path: str | Path, rec: Recording, with_quaternion: bool = True) -> None:
    """``time,<joints...>,x,y,z[,qx,qy,qz,qw]``: one row per sample, numbers with repr() precision."""
    header = ["time", *rec.joint_names, "x", "y", "z"] + (["qx", "qy", "qz", "qw"] if with_quaternion else [])
    lines = [",".join(header)]
    for k in range(len(rec.t)):
        row = [rec.t[k], *rec.q[k], *rec.xyz[k]] + (list(rec.quat_xyzw[k]) if with_quaternion else [])
        lines.append(",".join(repr(float(v)) for v in row))
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")


def stamp_ns(t: float) -> int:
    """A time in float seconds as integer nanoseconds (``t - T0`` is exact in floating point)."""
    return T0_NS + round((float(t) - T0) * 1e9)


def write_bag(
    path: str | Path,
    rec: Recording,
    pose_topic: str = "/tracker/pose",
    msgtype: str = "geometry_msgs/msg/PoseStamped",
    joint_rate_hz: float | None = None,
    storage: str = "mcap",
) -> dict[str, int]:
    """A rosbag2 recording (a new folder ``path``; storage ``mcap`` or ``sqlite3``) of ``rec``:
    ``/joint_states`` (sensor_msgs/msg/JointState) and ``pose_topic`` (``msgtype``: PoseStamped
    in ``rec.base``, or TransformStamped ``rec.base`` -> ``rec.frame``). Joint states share the
    pose samples' stamps, or, with ``joint_rate_hz``, lie on their own grid from ``T0`` at that
    rate up to one step past the last pose sample (a reader must interpolate). Log time =
    stamp + 2 ms; messages in log-time order, joint states before a pose at equal log times.
    Returns the number of messages per topic."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore

    if msgtype not in POSE_TYPES:
        raise ValueError(f"msgtype {msgtype!r} is not one of {', '.join(POSE_TYPES)}")
    if storage not in ("mcap", "sqlite3"):
        raise ValueError(f"storage {storage!r} is not mcap or sqlite3")
    store = getattr(Stores, "ROS2_JAZZY", Stores.ROS2_HUMBLE)
    ts = get_typestore(store)
    types: dict[str, Any] = dict(ts.types)
    time_, header_ = types["builtin_interfaces/msg/Time"], types["std_msgs/msg/Header"]
    joint_state_ = types[JOINT_STATE]

    def header(ns: int, frame_id: str) -> Any:
        return header_(stamp=time_(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000), frame_id=frame_id)

    def pose_msg(ns: int, k: int) -> Any:
        x, y, z = (float(v) for v in rec.xyz[k])
        qx, qy, qz, qw = (float(v) for v in rec.quat_xyzw[k])
        if msgtype == "geometry_msgs/msg/PoseStamped":
            pose = types["geometry_msgs/msg/Pose"](
                position=types["geometry_msgs/msg/Point"](x=x, y=y, z=z),
                orientation=types["geometry_msgs/msg/Quaternion"](x=qx, y=qy, z=qz, w=qw),
            )
            return types[msgtype](header=header(ns, rec.base), pose=pose)
        transform = types["geometry_msgs/msg/Transform"](
            translation=types["geometry_msgs/msg/Vector3"](x=x, y=y, z=z),
            rotation=types["geometry_msgs/msg/Quaternion"](x=qx, y=qy, z=qz, w=qw),
        )
        return types[msgtype](header=header(ns, rec.base), child_frame_id=rec.frame, transform=transform)

    def joint_msg(ns: int, q: np.ndarray) -> Any:
        return joint_state_(
            header=header(ns, ""),
            name=list(rec.joint_names),
            position=np.asarray(q, dtype=np.float64),
            velocity=np.zeros(0),
            effort=np.zeros(0),
        )

    # (log time, 0 for joint states / 1 for poses, index, topic, message, type)
    events: list[tuple[int, int, int, str, Any, str]] = []
    pose_ns = [stamp_ns(t) for t in rec.t]
    for k, ns in enumerate(pose_ns):
        events.append((ns + LOG_DELAY_NS, 1, k, pose_topic, pose_msg(ns, k), msgtype))
    if joint_rate_hz is None:
        joint_ns, joint_q = pose_ns, rec.q
    else:
        last = (pose_ns[-1] - T0_NS) / 1e9 if pose_ns else 0.0
        steps = math.floor(last * joint_rate_hz) + 2 if pose_ns else 0
        joint_ns = [T0_NS + round(k * 1e9 / joint_rate_hz) for k in range(steps)]
        joint_q = rec.q_at(np.array([T0 + (ns - T0_NS) / 1e9 for ns in joint_ns]))
    for k, ns in enumerate(joint_ns):
        events.append((ns + LOG_DELAY_NS, 0, k, "/joint_states", joint_msg(ns, joint_q[k]), JOINT_STATE))
    events.sort(key=lambda e: e[:3])

    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    counts: dict[str, int] = {}
    with Writer(Path(path), version=9, storage_plugin=plugin) as w:
        conns: dict[str, Any] = {}
        for log_ns, _, _, topic, msg, kind in events:
            if topic not in conns:
                conns[topic] = w.add_connection(topic, kind, typestore=ts)
            w.write(conns[topic], log_ns, ts.serialize_cdr(msg, kind))
            counts[topic] = counts.get(topic, 0) + 1
    return counts
