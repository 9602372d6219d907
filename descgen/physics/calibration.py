"""What a calibration means for a joint: the one place a correction becomes an origin.

A joint's calibration has two parts (docs/calibration.md):

- an origin correction, added to the nominal origin's components (x, y, z, roll, pitch, yaw),
  the parameterisation of UR's kinematics file and of ``descgen drift``'s parameters
  ``joint:<name>:origin.<x|y|z|roll|pitch|yaw>``;
- a zero offset: the joint reports q and is at q + offset (``joint:<name>:offset``). URDF has no
  field for it, so it is written into the origin, origin * motion(offset), which gives the same
  pose of the child for every q: origin * motion(offset) * motion(q) = origin * motion(q + offset).

A sensor's mount replaces its joint's origin (a hand-eye result is a whole pose).
"""

from __future__ import annotations

from dataclasses import replace

from descgen.core.model import Joint, JointCalibration, KnownPose, Pose, Robot, Vec3

ORIGIN_COMPONENTS = ("x", "y", "z", "roll", "pitch", "yaw")


def calibrated_origin(joint: Joint, nominal: Pose, offset: float, dxyz: Vec3, drpy: Vec3) -> Pose:
    """The origin of ``joint`` as measured: ``nominal`` plus the correction, then the offset.
    Without an offset the components are summed exactly as written (a vendor's file of whole
    origins round-trips to the last bit)."""
    xyz = (nominal.xyz[0] + dxyz[0], nominal.xyz[1] + dxyz[1], nominal.xyz[2] + dxyz[2])
    rpy = (nominal.rpy[0] + drpy[0], nominal.rpy[1] + drpy[1], nominal.rpy[2] + drpy[2])
    if offset == 0.0:
        return Pose(xyz, rpy)
    # numpy only here: the known poses (physics/poses.py) read this module on check's fast path
    from descgen.physics.kinematics import motion
    from descgen.physics.transforms import matrix_rpy, pose_matrix

    t = pose_matrix(xyz, rpy) @ motion(joint, offset)
    return Pose((float(t[0, 3]), float(t[1, 3]), float(t[2, 3])), matrix_rpy(t[:3, :3]))


def nominal_origin(joint: Joint, calibrated: Pose, entry: JointCalibration) -> Pose:
    """The inverse of :func:`calibrated_origin`: the nominal origin that ``entry``'s corrections
    turn into ``calibrated`` (for a sensor mount, which replaces the origin, the entry's own)."""
    if entry.sensor is not None:
        return entry.nominal
    xyz, rpy = calibrated.xyz, calibrated.rpy
    if entry.offset != 0.0:
        import numpy as np

        from descgen.physics.kinematics import motion
        from descgen.physics.transforms import matrix_rpy, pose_matrix

        t = pose_matrix(xyz, rpy) @ np.linalg.inv(motion(joint, entry.offset))
        xyz, rpy = (float(t[0, 3]), float(t[1, 3]), float(t[2, 3])), matrix_rpy(t[:3, :3])
    d, r = entry.dxyz, entry.drpy
    return Pose((xyz[0] - d[0], xyz[1] - d[1], xyz[2] - d[2]), (rpy[0] - r[0], rpy[1] - r[1], rpy[2] - r[2]))


def with_joint(robot: Robot, old: Joint, new: Joint) -> Robot:
    """``robot`` with ``old`` replaced by ``new`` (a planted fault), the calibration layer kept
    consistent: a calibrated joint's nominal origin moves with its calibrated one, so a pose
    judged against the nominal model sees the fault too."""
    joints = tuple(new if j is old else j for j in robot.joints)
    layer = tuple(
        replace(e, calibrated=new.origin, nominal=nominal_origin(new, new.origin, e)) if e.joint == old.name else e
        for e in robot.calibration
    )
    return replace(robot, joints=joints, calibration=layer)


def nominal(robot: Robot) -> Robot:
    """``robot`` without its calibration layer: every calibrated joint at its nominal origin."""
    if not robot.calibration:
        return robot
    back = {e.joint: e.nominal for e in robot.calibration}
    joints = tuple(replace(j, origin=back[j.name]) if j.name in back else j for j in robot.joints)
    return replace(robot, joints=joints, calibration=())


def for_pose(robot: Robot, pose: KnownPose) -> Robot:
    """The robot a known pose is judged against: as calibrated, or nominal for a pose that says so."""
    return nominal(robot) if pose.nominal else robot


def correction_size(joint: Joint, entry: JointCalibration) -> tuple[float, float]:
    """How far the calibration moves (m) and turns (rad) ``joint``'s child frame at q = 0."""
    import math

    from descgen.physics.kinematics import joint_transform

    nominal = joint_transform(replace(joint, origin=entry.nominal))
    calibrated = joint_transform(replace(joint, origin=entry.calibrated))
    shift = float(math.dist(nominal[:3, 3], calibrated[:3, 3]))
    rel = nominal[:3, :3].T @ calibrated[:3, :3]
    return shift, math.acos(max(-1.0, min(1.0, (float(rel.trace()) - 1.0) / 2.0)))


def parameter(joint: str, what: str) -> str:
    """A calibration parameter's public name: ``joint:<name>:offset`` or ``joint:<name>:origin.<c>``."""
    return f"joint:{joint}:{what}" if what == "offset" else f"joint:{joint}:origin.{what}"


def split_parameter(name: str) -> tuple[str, str] | None:
    """(joint, ``offset`` or an origin component) of a parameter name; None if it is not one."""
    if not name.startswith("joint:"):
        return None
    joint, sep, what = name[len("joint:") :].rpartition(":")
    if not sep or not joint:
        return None
    if what == "offset":
        return joint, what
    if what.startswith("origin.") and what[len("origin.") :] in ORIGIN_COMPONENTS:
        return joint, what[len("origin.") :]
    return None


__all__ = [
    "ORIGIN_COMPONENTS",
    "calibrated_origin",
    "correction_size",
    "for_pose",
    "nominal",
    "nominal_origin",
    "parameter",
    "split_parameter",
    "with_joint",
]
