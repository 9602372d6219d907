"""The ``<ros2_control>`` blocks of a robot as the templates write them: per block its
hardware (every variant in the Xacro), joints with their interface params, sensors and gpios."""

from __future__ import annotations

from typing import Any

from descgen.core.model import HardwareBlock, Robot, Ros2Control
from descgen.physics import derive
from descgen.render.formatting import xacro_text
from descgen.render.views import name_writer


def in_block(rc: Ros2Control, block: HardwareBlock, owner: str) -> bool:
    """Whether a joint/sensor/gpio whose block is ``owner`` belongs to ``block``. With one
    block everything does (a model built by hand may leave ``block`` empty)."""
    return len(rc.hardware_blocks()) == 1 or owner == block.name


def control_blocks(robot: Robot, xacro: bool) -> list[dict[str, Any]]:
    """One entry per block, in document order; free text escaped for the template family."""
    rc = robot.ros2_control
    if rc is None:
        return []
    text = xacro_text if xacro else str
    shown = name_writer(robot, xacro)  # the Xacro writes the prefix as its argument
    frames = {lk.name for lk in robot.links} if robot.prefix is not None and xacro else set()

    def params(items: tuple[tuple[str, str], ...]) -> list[tuple[str, str]]:
        # a param naming one of the robot's frames (a sensor's frame_id) takes the prefix argument too
        return [(k, shown(v) if v in frames else text(v)) for k, v in items]

    block_of = {cj.name: cj.block for cj in rc.joints}
    joints = derive.interfaces_with_limits(robot)
    out = []
    for b in rc.hardware_blocks():
        out.append(
            {
                "name": shown(b.name),
                "type": b.type,
                "is_async": b.is_async,
                "rw_rate": b.rw_rate,
                "thread_priority": b.thread_priority,
                "group": b.group,
                "plugin": b.plugin,
                "params": params(b.params),
                # the Xacro chooses the hardware with hardware:=; a URDF is the default variant
                "variants": [{"name": v.name, "plugin": v.plugin, "params": params(v.params)} for v in b.variants]
                if xacro
                else [],
                "joints": [(shown(n), c, st) for n, c, st in joints if in_block(rc, b, block_of.get(n, ""))],
                # shown name -> the joint's name (the initial_positions file's key)
                "raw": {shown(n): n for n, _, _ in joints},
                "sensors": [
                    {"name": shown(c.name), "state": c.state, "params": params(c.params)}
                    for c in rc.sensors
                    if in_block(rc, b, c.block)
                ],
                "gpios": [
                    {"name": shown(g.name), "command": g.command, "state": g.state, "params": params(g.params)}
                    for g in rc.gpios
                    if in_block(rc, b, g.block)
                ],
                "joint_params": {shown(cj.name): params(cj.params) for cj in rc.joints if cj.params},
            }
        )
    return out


def control_depends(rc: Ros2Control) -> list[str]:
    """exec_depends for the hardware plugins of every block and variant: mock_components lives
    in hardware_interface; a gazebo variant needs gz_ros2_control (its GazeboSimSystem and the
    gz_ros2_control-system sim plugin), as ros2_control_demos example_9's package.xml declares.
    A vendor's plugin is not a dependency: the driver depends on the description, not the
    reverse (ur_description does not depend on ur_robot_driver)."""
    plugins = [p for b in rc.hardware_blocks() for p in (b.plugin, *(v.plugin for v in b.variants))]
    out = []
    if any(p.startswith("mock_components/") for p in plugins):
        out.append("hardware_interface")
    if any(p.startswith("gz_ros2_control/") for p in plugins):
        out.append("gz_ros2_control")
    if any(p.startswith("mujoco_ros2_control/") for p in plugins):
        out.append("mujoco_ros2_control")  # its plugin and the ros2_control_node control.launch.py starts
    return out
