# generated from specs/warehouse_arm.yaml by descgen — do not edit
# descgen spec-sha256=a090534ba3656e64ca8562c70afd09b4bc66cfc532123f14d6c9a57d5118efac content-sha256=b70401d93074ee78b25a914763571f30d9e74e8369738daebfbff3b4fe7475e2
from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_rsp_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder(
        "warehouse_arm", package_name="warehouse_arm_moveit_config"
    ).to_moveit_configs()
    return generate_rsp_launch(moveit_config)
