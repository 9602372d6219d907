"""Jinja2 templates for every output file (shipped in the wheel as ``descgen.templates``).

A team can override any of them by file name with ``descgen generate --templates DIR``.
"""
