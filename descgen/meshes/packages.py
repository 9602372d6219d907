"""Where a ROS package named in ``package://`` or ``$(find)`` is: the one package resolver of
every command (docs/packages.md says the order once, for users).

The folders searched, first found wins, are:

1. the spec's ``package_paths:`` (a spec's commands only; relative to the spec),
2. ``--package-path DIR`` options, in the order given,
3. the sourced environment: each prefix of ``AMENT_PREFIX_PATH`` (its ``share/``, where an
   installed package lives and where ``ament_index`` finds it), then each folder of
   ``ROS_PACKAGE_PATH``,
4. for a description someone else wrote, its own package (descgen/meshes/paths.py).

:func:`search` composes 2 and 3; the spec's folders are put before them where the spec is
read (descgen/meshes/paths.py), so every command finds the same package for the same name.

In one folder a package, a folder whose package.xml gives the name (or, installed, that the
ament index of its ``share/`` lists), is found as ROS's tools lay it out: ``<folder>/<name>``
(a source tree or an install's ``share/``), the folder itself, a colcon install
(``<folder>/share/<name>`` merged, ``<folder>/<name>/share/<name>`` isolated), or below it in
a source workspace (``src/<repo>/<pkg>``, found by the name its package.xml gives, as colcon
crawls it: not below a package, nor into a folder with COLCON_IGNORE, AMENT_IGNORE or
CATKIN_IGNORE, nor hidden folders).

Its own small module so that resolving an audited URDF's ``package://`` meshes does not
import the Xacro reader (minidom, the sandboxed evaluator), which a plain URDF never needs.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

from descgen.infra.safeio import MIB, inside, read_head, within

_NAME = re.compile(r"<name>\s*([^<\s]+)\s*</name>")
_MANIFEST_BYTES = 1 * MIB  # the <name> of a package.xml is in its first lines; real ones are a few kB
_AMENT_MARKERS = Path("ament_index", "resource_index", "packages")
_IGNORE = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")
# a workspace crawl: src/<repo>/<group>/<pkg> is as deep as real workspaces go; a folder of
# thousands (a home folder given by mistake) is cut off rather than walked for minutes
CRAWL_DEPTH = 4
CRAWL_FOLDERS = 20_000
_PSEUDO = frozenset(("/proc", "/sys", "/dev", "/run"))
_crawled: dict[str, dict[str, Path]] = {}  # real folder -> package name -> folder, per process


def search(given: Sequence[Path], environ: Mapping[str, str]) -> tuple[Path, ...]:
    """The folders a command searches after a spec's own ``package_paths:``: ``given``
    (--package-path), then the sourced environment's (:func:`environment`), each once."""
    return tuple(dict.fromkeys([*given, *environment(environ)]))


def environment(environ: Mapping[str, str]) -> tuple[Path, ...]:
    """The package folders a sourced ROS environment names: ``<prefix>/share`` of every
    ``AMENT_PREFIX_PATH`` prefix (the overlay first, as ament_index searches them), then every
    ``ROS_PACKAGE_PATH`` folder. Entries that are not folders are skipped, as ROS skips them."""
    found: list[Path] = []
    for entry in environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep):
        if entry and os.path.isabs(entry) and os.path.isdir(os.path.join(entry, "share")):
            found.append(Path(entry) / "share")
    for entry in environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
        if entry and os.path.isabs(entry) and os.path.isdir(entry):
            found.append(Path(entry))
    return tuple(dict.fromkeys(found))


def find_package(name: str, package_paths: Sequence[Path]) -> Path | None:
    """The folder of package ``name`` in the first folder of ``package_paths`` that holds it
    (the layouts of the module's docstring), or None.

    Only what is really inside a folder counts (docs/security.md): a package folder or
    package.xml that is a link out of it is not found there. A package.xml is read like any
    input: a regular file, without blocking, at most 1 MiB (a FIFO or device names nothing)."""
    for folder in package_paths:
        found = _in_folder(name, folder)
        if found is not None:
            return found
    return None


def _in_folder(name: str, folder: Path) -> Path | None:
    # a package is a folder whose package.xml gives its name, or an installed one that the ament
    # index lists (ament_index_python's get_package_share_directory: the marker, then the folder of
    # that name), nothing less: a spec's package_paths: may lie outside the project, and
    # package://etc/passwd must not find /etc
    for candidate in (folder / name, folder, folder / "share" / name, folder / name / "share" / name):
        if manifest_name(candidate / "package.xml") == name and inside(candidate, folder):
            return candidate
    for share in (folder, folder / "share", folder / name / "share"):
        if (share / _AMENT_MARKERS / name).is_file() and (share / name).is_dir() and inside(share / name, folder):
            return share / name
    return _crawl(folder).get(name)


def _crawl(folder: Path) -> dict[str, Path]:
    """Package name -> folder of every package below ``folder`` (shallowest first, then by
    path), as colcon crawls a workspace; memoised per process."""
    try:
        real = os.path.realpath(folder)
    except (OSError, ValueError):
        return {}
    if real in _crawled:
        return _crawled[real]
    found: dict[str, Path] = {}
    level = [folder] if os.path.isdir(real) else []
    visited = 0
    for _ in range(CRAWL_DEPTH):
        deeper: list[Path] = []
        for parent in level:
            if visited > CRAWL_FOLDERS:
                break
            for child in _subfolders(parent):
                visited += 1
                if visited > CRAWL_FOLDERS:
                    break
                if os.path.realpath(child) in _PSEUDO:
                    continue  # no packages there, and reading them can be slow or endless
                if any((child / marker).exists() for marker in _IGNORE) or not inside(child, folder):
                    continue
                manifest = child / "package.xml"
                if manifest.is_file():
                    pkg = manifest_name(manifest)
                    if pkg is not None:
                        found.setdefault(pkg, child)
                    continue  # not below a package, as colcon
                deeper.append(child)
        level = deeper
    _crawled[real] = found
    return found


def _subfolders(parent: Path) -> list[Path]:
    try:
        with os.scandir(parent) as entries:
            names = sorted(e.name for e in entries if not e.name.startswith(".") and e.is_dir())
    except OSError:
        return []
    return [parent / n for n in names]


class Owners:
    """Which package an absolute path of this machine lies in, among the packages ``search``
    finds: the nearest folder above its real path holding a package.xml, when that name finds
    that very folder (what ``$(find)`` gave). Only folders inside ``search`` are looked at, so
    a path written in an input reads nothing else (the path is resolved first: ``..`` and
    links cannot walk out)."""

    def __init__(self, search: Sequence[Path]) -> None:
        self.search = list(search)
        self.roots = [os.path.realpath(f) for f in search]
        self.named: dict[str, str | None] = {}

    def _package(self, folder: str) -> str | None:
        if folder not in self.named:
            name = manifest_name(Path(folder) / "package.xml")
            found = find_package(name, self.search) if name else None
            self.named[folder] = name if found is not None and os.path.realpath(found) == folder else None
        return self.named[folder]

    def of(self, path: str) -> tuple[str, str, str] | None:
        """(package, its real folder, the path inside it) of an absolute ``path``, or None."""
        try:
            real = os.path.realpath(path)
        except (OSError, ValueError):
            return None
        inside = [r for r in self.roots if within(real, r)]
        if not inside:
            return None
        folder = real if os.path.isdir(real) else os.path.dirname(real)
        while any(within(folder, r) for r in inside):
            pkg = self._package(folder)
            if pkg is not None:
                return pkg, folder, real[len(folder) :].lstrip("/")
            if folder == os.path.dirname(folder):
                break
            folder = os.path.dirname(folder)
        return None


def package_roots(folder: Path) -> tuple[str, ...]:
    """The real folders a package's files may lie in: the package's own, and, for a colcon
    ``--symlink-install``, the source package its package.xml is a link to (its files are
    links into that folder; a link anywhere else still leaves the package)."""
    own = os.path.realpath(folder)
    manifest = os.path.join(folder, "package.xml")
    if not os.path.islink(manifest):
        return (own,)
    # the link must reach a package.xml giving the same name: a link to some other file
    # (or to / itself) does not widen what the package may read
    target = os.path.realpath(manifest)
    same = os.path.basename(target) == "package.xml" and manifest_name(Path(target)) == manifest_name(Path(manifest))
    return tuple(dict.fromkeys((own, os.path.dirname(target)))) if same else (own,)


def manifest_name(manifest: Path) -> str | None:
    """The ``<name>`` a package.xml gives, or None (no such regular file, no name)."""
    found = _NAME.search(read_head(manifest, _MANIFEST_BYTES).decode("utf-8", "replace"))
    return found.group(1) if found else None
