"""Descriptions descgen did not write, read as ROS reads them: URDF, Xacro (sandboxed), SRDF,
controllers YAML, a MoveIt config package; and description.py, the one loader every command that
takes "a description" uses (a spec, a URDF or a Xacro, with its SRDF and controllers)."""
