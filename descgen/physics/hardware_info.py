"""What Jazzy's ros2_control component parser reads from a ``<ros2_control>`` joint
(hardware_interface/src/component_parser.cpp at the jazzy branch, parse_component_from_xml;
docs/ros2_control_jazzy.md).

The audit rules (CTRL040-043) and the control model (HardwareInfo.mimic_joints) both ask
here, so they agree on which joints Jazzy treats as mimic joints.
"""

from __future__ import annotations

from descgen.core.model import ControlJoint, Robot


def mimic_attribute(cj: ControlJoint) -> bool | None:
    """The ``mimic`` attribute as Jazzy's parse_bool reads it: true/false in any case; None
    when absent (NOT_SET). Anything else throws std::invalid_argument (CTRL043)."""
    if cj.mimic is None:
        return None
    return {"true": True, "false": False}.get(cj.mimic.lower())  # parse_bool lowercases, never strips


def valid_mimic_attribute(cj: ControlJoint) -> bool:
    """False when parse_bool would throw: the attribute is set and is neither true nor false."""
    return cj.mimic is None or cj.mimic.lower() in ("true", "false")


def active_mimic(robot: Robot, cj: ControlJoint) -> bool:
    """Jazzy treats a ros2_control joint as a mimic joint when its URDF joint has <mimic>
    and the attribute is not false."""
    j = robot.joint(cj.name)
    return j is not None and j.mimic is not None and valid_mimic_attribute(cj) and mimic_attribute(cj) is not False
