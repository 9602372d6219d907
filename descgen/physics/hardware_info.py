"""What Jazzy's ros2_control component parser reads from a ``<ros2_control>`` joint
(hardware_interface/src/component_parser.cpp at the jazzy branch, parse_component_from_xml;
docs/ros2_control_jazzy.md).

The audit rules (CTRL040-043) and the control model (HardwareInfo.mimic_joints) both ask
here, so they agree on which joints Jazzy treats as mimic joints.
"""

from __future__ import annotations

from descgen.core.model import ControlJoint, Robot

# what get_attribute_value strips before parse_bool lowercases (component_parser.cpp, jazzy
# since hardware_interface 4.43.0; docs/ros2_control_parser_jazzy.md)
WHITESPACE = " \t\n\r\f\v"


def parsed_bool(text: str) -> bool | None:
    """A boolean attribute as Jazzy reads it: stripped, then true/false in any case; None for
    anything else (parse_bool throws std::invalid_argument)."""
    return {"true": True, "false": False}.get(text.strip(WHITESPACE).lower())


def mimic_attribute(cj: ControlJoint) -> bool | None:
    """The ``mimic`` attribute as Jazzy's parse_bool reads it; None when absent (NOT_SET) or
    not a boolean, which throws (CTRL043)."""
    return None if cj.mimic is None else parsed_bool(cj.mimic)


def valid_mimic_attribute(cj: ControlJoint) -> bool:
    """False when parse_bool would throw: the attribute is set and is neither true nor false."""
    return cj.mimic is None or parsed_bool(cj.mimic) is not None


def active_mimic(robot: Robot, cj: ControlJoint) -> bool:
    """Jazzy treats a ros2_control joint as a mimic joint when its URDF joint has <mimic>
    and the attribute is not false."""
    j = robot.joint(cj.name)
    return j is not None and j.mimic is not None and valid_mimic_attribute(cj) and mimic_attribute(cj) is not False
