"""Transforms through time: a tf2-faithful buffer, and audits of recorded transforms."""
