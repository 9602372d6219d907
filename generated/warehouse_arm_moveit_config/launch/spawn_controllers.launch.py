# generated from specs/warehouse_arm.yaml by descgen — do not edit
# descgen spec-sha256=a090534ba3656e64ca8562c70afd09b4bc66cfc532123f14d6c9a57d5118efac content-sha256=fdde43e3bdba4f288df9e26fad0bd66df7d091c4cf87cd03f32c5c250d7bbcd4
from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_spawn_controllers_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder(
        "warehouse_arm", package_name="warehouse_arm_moveit_config"
    ).to_moveit_configs()
    return generate_spawn_controllers_launch(moveit_config)
