"""Mesh files: where a ``package://`` or relative path points (paths.py, packages.py), what is
measured in one (load.py, facts.py) and the persistent cache of those measurements (cache.py)."""
