# generated from specs/warehouse_arm.yaml by descgen — do not edit
# descgen spec-sha256=a090534ba3656e64ca8562c70afd09b4bc66cfc532123f14d6c9a57d5118efac content-sha256=7d8f739283f84e358ec65f63868f48d28fce95fd539a44285633699b2fb5d71b
"""Run warehouse_arm on ros2_control (mock_components/GenericSystem): robot_state_publisher,
ros2_control_node and the controller spawners."""

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
    controllers = PathJoinSubstitution([share, "config", "ros2_controllers.yaml"])
    # Jazzy: controller_manager reads the URDF from the robot_description topic that
    # robot_state_publisher publishes.
    nodes = [
        hardware,
        Node(
            package="robot_state_publisher",
            executable="robot_state_publisher",
            parameters=[{"robot_description": robot_description}],
        ),
        Node(
            package="controller_manager",
            executable="ros2_control_node",
            parameters=[controllers],
            output="both",
        ),
    ]
    nodes.append(
        Node(
            package="controller_manager",
            executable="spawner",
            arguments=["joint_state_broadcaster", "--controller-manager", "/controller_manager"],
        )
    )
    nodes.append(
        Node(
            package="controller_manager",
            executable="spawner",
            arguments=["diff_drive_controller", "--controller-manager", "/controller_manager"],
        )
    )
    nodes.append(
        Node(
            package="controller_manager",
            executable="spawner",
            arguments=["arm_controller", "--controller-manager", "/controller_manager"],
        )
    )
    return LaunchDescription(nodes)
