# generated from specs/warehouse_arm.yaml by descgen — do not edit
# descgen spec-sha256=a090534ba3656e64ca8562c70afd09b4bc66cfc532123f14d6c9a57d5118efac content-sha256=b4e2c41759e9d76760c22ece6f2f5ac8a264609eb86c932cee7325f7ad690859
from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_move_group_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder(
        "warehouse_arm", package_name="warehouse_arm_moveit_config"
    ).to_moveit_configs()
    return generate_move_group_launch(moveit_config)
