"""descgen: robot descriptions from measured specs, proven before they are written."""

__version__ = "0.1.0"
