"""The MoveIt config package ``<robot>_moveit_config`` (docs/moveit_config.md).

``derive`` computes what the package states from the robot (planning joints and their
limits, the controllers MoveIt drives, initial positions), ``render`` writes its files,
``proof`` reads them back. Nothing here is imported by the description package's path, so a
spec without ``moveit:`` costs nothing.
"""
