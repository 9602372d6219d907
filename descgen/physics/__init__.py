"""Pure functions of a Robot: kinematics (numpy and plain-float), mimic joints, inertia, extents,
who publishes each frame, known poses, the self-collision matrix and the motion sweep, the
groups MoveIt plans with, which joints ros2_control claims."""
