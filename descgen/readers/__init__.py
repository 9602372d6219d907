"""Readers of descriptions descgen did not write: URDF, Xacro, SRDF, controllers YAML."""
