"""Machinery, not robotics: bounded and safe file I/O (safeio.py), the YAML reader with
positions, the result and evidence caches and their keys, worker processes, progress and
interruption handling."""
