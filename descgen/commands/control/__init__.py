"""The command/state boundary: a model of ros2_control's lifecycle, claims and loop."""
