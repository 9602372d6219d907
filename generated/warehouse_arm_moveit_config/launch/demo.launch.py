# generated from specs/warehouse_arm.yaml by descgen — do not edit
# descgen spec-sha256=a090534ba3656e64ca8562c70afd09b4bc66cfc532123f14d6c9a57d5118efac content-sha256=d9a44373a59011fe6a00f386d86a18eebb5a677e125ad0dac39db87226abcebf
from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_demo_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder(
        "warehouse_arm", package_name="warehouse_arm_moveit_config"
    ).to_moveit_configs()
    return generate_demo_launch(moveit_config)
