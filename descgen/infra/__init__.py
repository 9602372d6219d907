"""Machinery, not robotics: bounded and safe file I/O (safeio.py), the YAML reader with
positions, the result and evidence caches, their one key scheme (keys.py) and stat index
(stat_index.py), worker processes, progress and interruption handling."""
