"""An installed distribution's version without importing ``importlib.metadata``.

``importlib.metadata`` costs ~25 ms of imports (email, zipfile, csv, ...) in a process that
needs none of them; every ``check`` asks for the versions of the tools its cached results
depend on (evidence_hash.versions), and validate and check must not pay that (issue 17).
The common case is a wheel install: one ``<name>-<version>.dist-info`` folder in a
``sys.path`` entry, its METADATA starting with the header. That case is read here; anything
else (an egg, a zip, two candidates in one folder, no header Version) answers None and the
caller asks ``importlib.metadata``, which stays the reference (tests/test_dist_version.py
compares the two on every installed distribution).
"""

from __future__ import annotations

import os
import re
import sys

_SEPARATORS = re.compile(r"[-_.]+")
_SUFFIXES = (".dist-info", ".egg-info", ".egg")  # what importlib.metadata reads in a folder


def _normal(name: str) -> str:
    """PEP 503 normalisation, as importlib.metadata compares names (``PyYAML`` == ``pyyaml``)."""
    return _SEPARATORS.sub("-", name).lower()


def _name_of(entry: str) -> str:
    """The normalised distribution name of ``foo-1.0.dist-info``, ``foo.egg-info``, ``foo-1.0-py3.11.egg``."""
    return _normal(entry[: entry.rfind(".")].split("-", 1)[0])


def installed_version(dist: str) -> str | None:
    """The ``Version:`` of ``dist`` as importlib.metadata would find it first (the first
    ``sys.path`` entry that holds it), or None when this scan cannot tell for sure."""
    wanted = _normal(dist)
    for entry in sys.path:
        try:
            names = os.listdir(entry or ".")
        except FileNotFoundError:
            continue
        except OSError:
            return None  # a zip (importlib.metadata looks inside) or an unreadable folder
        found = [n for n in names if n.lower().endswith(_SUFFIXES) and _name_of(n) == wanted]
        if not found:
            continue
        if len(found) != 1 or not found[0].endswith(".dist-info"):
            return None
        try:
            with open(os.path.join(entry or ".", found[0], "METADATA"), "rb") as f:
                head = f.read(8192).decode("utf-8", "replace")
        except OSError:
            return None
        for line in head.replace("\r\n", "\n").split("\n"):
            if not line:
                return None  # end of the header, no Version
            if line[:8].lower() == "version:":
                return line[8:].strip() or None
        return None
    return None
