# generated from specs/warehouse_arm.yaml by descgen — do not edit
# descgen spec-sha256=a090534ba3656e64ca8562c70afd09b4bc66cfc532123f14d6c9a57d5118efac content-sha256=3327c247c0acb006314dbd881a8ff89b91db36e1763a29f0d9c78a41f50f51ab
"""Show warehouse_arm in RViz: robot_state_publisher, joint_state_publisher_gui, rviz2."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare("warehouse_arm_description")
    xacro_file = PathJoinSubstitution([share, "urdf", "warehouse_arm.urdf.xacro"])
    # hardware:=NAME goes to xacro, which selects that variant's <hardware> plugin (see the Xacro)
    hardware = DeclareLaunchArgument(
        "hardware",
        default_value="mock",
        choices=["mock", "gazebo", "real"],
        description="the ros2_control hardware the robot description selects",
    )
    robot_description = ParameterValue(
        Command([FindExecutable(name="xacro"), " ", xacro_file, " hardware:=", LaunchConfiguration("hardware")]),
        value_type=str,
    )
    rviz_config = PathJoinSubstitution([share, "rviz", "warehouse_arm.rviz"])
    return LaunchDescription(
        [
            hardware,
            Node(
                package="robot_state_publisher",
                executable="robot_state_publisher",
                parameters=[{"robot_description": robot_description}],
            ),
            Node(package="joint_state_publisher_gui", executable="joint_state_publisher_gui"),
            Node(package="rviz2", executable="rviz2", arguments=["-d", rviz_config]),
        ]
    )
