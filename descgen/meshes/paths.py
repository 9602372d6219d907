"""Where a mesh reference points: the one resolver for specs and for audited descriptions.

A mesh is named either by a path relative to the file that references it (a spec, a URDF)
or by ``package://<pkg>/<path>``, found in the package paths. Both are held to the trust
boundary (docs/security.md): the file must lie inside the folder it is relative to (the
spec's folder, the audited description's package) or inside the package it names, after
symbolic links are resolved, so ``../../etc/passwd`` or a link out is refused; and it is
checked as a regular file of bounded size before anyone reads it.

For a spec, :func:`resolve_spec` does this at ``validate`` (a mesh that cannot be found is an
input error at the line of its reference) and renames the robot's own meshes (those named
relative to the spec) to ``package://<robot>_description/meshes/...``, where ``generate``
copies them; a mesh of another package stays a reference to it. The model records, for every
mesh filename, the file it resolved to (:attr:`descgen.core.model.Robot.mesh_files`), so every
command that loads the spec reads the same files.
"""

from __future__ import annotations

import os
import posixpath
import re
import stat
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from descgen.codes import Code
from descgen.codes.spec import SPEC060, SPEC061, SPEC062, SPEC063, SPEC064, SPEC065, SPEC066
from descgen.core.findings import Finding, Where
from descgen.core.model import Collision, Link, Mesh, MeshState, Robot, Visual
from descgen.core.record import record
from descgen.infra.safeio import MIB, within
from descgen.meshes.packages import Owners, find_package, manifest_name, package_roots

MAX_MESH_BYTES = 64 * MIB  # the largest meshes of real robots are a few MB; a CAD dump may be tens
PACKAGE_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_-]*")  # what $(find) accepts too
MESH_FOLDER = "meshes"


@record
class Resolved:
    """What one mesh reference points at. ``path`` is set when the file exists (state ok)."""

    state: MeshState  # ok | missing | escapes | unresolved
    path: Path | None = None
    package: str | None = None  # the package a package:// reference names
    problem: str | None = None  # why an existing path cannot be read: not a regular file, too large


def split_package_uri(name: str) -> tuple[str, str] | None:
    """(package, path inside it) of ``package://pkg/path``; None for any other name."""
    if not name.startswith("package://"):
        return None
    pkg, _, rest = name[len("package://") :].partition("/")
    return pkg, rest


def resolve(
    name: str,
    base: Path,
    root: Path,
    package_paths: Sequence[Path],
    packages: dict[str, Path | None] | None = None,
    folders: dict[str, str] | None = None,
    owners: Owners | None = None,
) -> Resolved:
    """Resolve ``name`` as written in a file whose folder is ``base``. A relative name must
    stay inside ``root``; a ``package://`` name inside its package, found in ``package_paths``
    (in order); an absolute one (``/...``, ``file:///...``) inside a package ``owners`` finds
    (none for a spec, which must work on any machine). ``packages`` memoises
    package name -> folder and ``folders`` a folder's real path across the calls of one
    description (searching the package paths and resolving every folder of a path again are
    most of the cost). Never raises for a bad name: a NUL byte, an over-long name or a link
    loop is a file that cannot be there."""
    try:
        return _resolve(
            name,
            base,
            root,
            package_paths,
            {} if packages is None else packages,
            {} if folders is None else folders,
            owners,
        )
    except (OSError, ValueError):
        return Resolved("missing")


def _resolve(
    name: str,
    base: Path,
    root: Path,
    package_paths: Sequence[Path],
    packages: dict[str, Path | None],
    folders: dict[str, str],
    owners: Owners | None = None,
) -> Resolved:
    uri = split_package_uri(name)
    package = None
    if uri is not None:
        package, rest = uri
        if package not in packages:
            found = find_package(package, package_paths) if PACKAGE_NAME.fullmatch(package) else None
            packages[package] = found.resolve() if found is not None else None
        folder = packages[package]
        if folder is None:
            return Resolved("unresolved", package=package)
        roots, target = package_roots(folder), _realpath(os.path.join(folder, rest), folders)
    elif name.startswith("file://") or os.path.isabs(name):  # Path(name).is_absolute(), without a Path
        # what a Xacro's file://$(find pkg)/meshes/... expands to: fine inside a folder the user
        # named (its package is there on any machine that expands it), refused anywhere else
        written = name[len("file://") :] if name.startswith("file://") else name
        owner = owners.of(written) if owners is not None and os.path.isabs(written) else None
        if owner is None:
            return Resolved("escapes")
        package = owner[0]
        roots, target = (owner[1],), os.path.realpath(written)
    else:
        roots, target = (_realpath(str(root), folders),), _realpath(os.path.join(base, name), folders)
    if not any(within(target, r) for r in roots):  # the real path: a link out is caught too
        return Resolved("escapes", package=package)
    try:
        st = os.stat(target)
    except FileNotFoundError:
        return Resolved("missing", package=package)
    problem = None
    if not stat.S_ISREG(st.st_mode):
        problem = "is not a regular file (a folder, FIFO or device)"
        return Resolved("missing", Path(target), package, problem)
    if st.st_size > MAX_MESH_BYTES:
        problem = f"is {st.st_size / 1e6:.1f} MB; a mesh is at most {MAX_MESH_BYTES // MIB} MiB"
    return Resolved("ok", Path(target), package, problem)


def _realpath(path: str, folders: dict[str, str]) -> str:
    """``os.path.realpath(path)`` (what ``Path.resolve()`` does) with the real path of its
    folder memoised in ``folders``: a description's meshes share a few folders, and realpath
    lstat()s every component of every path (~15 system calls a mesh). The last component is
    still looked at each time: only when it is a link is the whole path resolved again."""
    head, tail = os.path.split(path)
    if tail in ("", ".", ".."):
        return os.path.realpath(path)
    real_head = folders.get(head)
    if real_head is None:
        real_head = folders[head] = os.path.realpath(head)
    joined = os.path.join(real_head, tail)
    return os.path.realpath(joined) if os.path.islink(joined) else joined


# --- audited descriptions -------------------------------------------------------------------------


def package_root(start: Path) -> Path:
    """The nearest folder at or above ``start`` holding a package.xml, else ``start``."""
    for folder in (start, *start.parents):
        if (folder / "package.xml").is_file():
            return folder
    return start


def mesh_status(
    robot: Robot, description: Path, package_paths: Sequence[Path]
) -> tuple[dict[str, MeshState], dict[str, Path]]:
    """ok | missing | escapes | unresolved for every mesh filename of an audited description,
    and the file each found one is (for rules that read meshes). A relative name may not leave
    the description's package; ``package://`` is searched in ``package_paths``, then answered by
    the description's own package (the nearest folder above it holding a package.xml, by the
    name that file gives), and nowhere else: not the folders beside it (docs/security.md)."""
    return resolve_names(_mesh_names(robot), description, package_paths)


def resolve_names(
    names: Iterable[str], description: Path, package_paths: Sequence[Path]
) -> tuple[dict[str, MeshState], dict[str, Path]]:
    """:func:`mesh_status` for mesh filenames as written in ``description`` (the findings
    cache resolves the names it recorded again, descgen/audit/findings_cache.py)."""
    status: dict[str, MeshState] = {}
    files: dict[str, Path] = {}
    base = description.resolve().parent
    search = list(package_paths)
    root = package_root(base)  # once per description, not per mesh
    # an absolute mesh (file://$(find pkg)/... expanded) may lie in a package of the folders the
    # user named or in the description's own package, as RViz's resource_retriever reads it
    owners = Owners([*search, root])
    packages: dict[str, Path | None] = {}
    own: list[str | None] = []  # the own package's name, read once, only when a name needs it
    folders: dict[str, str] = {}
    for name in names:
        if name in status:
            continue
        uri = split_package_uri(name)
        if uri is not None and uri[0] not in packages and PACKAGE_NAME.fullmatch(uri[0]):
            # --package-path first, as ROS's overlays (the first found wins), then the own package
            found = find_package(uri[0], search)
            if found is None:
                if not own:
                    own.append(manifest_name(root / "package.xml"))
                found = root if own[0] == uri[0] else None
            packages[uri[0]] = found.resolve() if found is not None else None
        r = resolve(name, base, root, search, packages, folders, owners)
        status[name] = r.state
        if r.state == "ok" and r.path is not None:
            files[name] = r.path
    return status, files


def _mesh_names(robot: Robot) -> Iterator[str]:
    for lk in robot.links:
        for shape in lk.shapes():
            if isinstance(shape.geometry, Mesh):
                yield shape.geometry.filename


# --- specs ----------------------------------------------------------------------------------------


def project_root(spec: Path) -> Path:
    """The folder a spec's ``templates:`` may not leave: the project, i.e. the folder holding
    ``specs/`` (where ``generated/`` goes too), or the spec's own folder when it is not in a
    ``specs`` folder."""
    folder = spec.resolve().parent
    return folder.parent if folder.name == "specs" else folder


def spec_folder(spec: Path, written: str, key: str = "package_paths") -> Path | None:
    """A folder recorded in a spec (relative to it), resolved; None when it is absolute, is
    not a folder or (``templates``) leaves the project (resolve_spec reports why)."""
    return _folder(spec, written, key)[0]


def _folder(spec: Path, written: str, key: str) -> tuple[Path | None, str]:
    """A ``package_paths:`` entry may lie outside the project (a workspace beside it, as
    ``../../ws/src``): only packages are read there, each only inside itself (find_package,
    :func:`resolve`), so it points descgen at packages, not at the machine. Templates are
    code that renders the package, so they stay in the project."""
    try:
        if Path(written).is_absolute():
            return None, "is an absolute path; a spec records folders relative to itself, so it works on any machine"
        target = (spec.resolve().parent / written).resolve()
        if key == "templates" and not target.is_relative_to(project_root(spec)):
            return None, f"leaves the project folder {project_root(spec).name}/"
        if not target.is_dir():
            return None, "is not a folder"
    except (OSError, ValueError):
        return None, "is not a folder"
    return target, ""


def spec_file(spec: Path, written: str) -> tuple[Path | None, str]:
    """A spec file named by another spec (``compose:``), resolved, or why it cannot be used: it
    is relative to the naming spec and stays in the project, as templates do (it is read as data,
    but a spec pointing anywhere would let one spec read any YAML on the machine)."""
    try:
        if Path(written).is_absolute():
            return None, "is an absolute path; a spec names other files relative to itself, so it works on any machine"
        target = (spec.resolve().parent / written).resolve()
        if not target.is_relative_to(project_root(spec)):
            return None, f"leaves the project folder {project_root(spec).name}/"
        if not target.is_file():
            return None, "is not a file"
    except (OSError, ValueError):
        return None, "is not a file"
    return target, ""


def package_name(robot: Robot) -> str:
    """The generated package's name: the spec's ``package.name``, else ``<robot>_description``.
    The one place every output (package.xml, CMake, launch, ``package://``, ``$(find)``, the
    MoveIt package) takes it from."""
    return robot.package.name or f"{robot.name}_description"


def own_mesh_path(written: str, folder: str = "/spec") -> str:
    """Where a mesh named relative to the spec is copied in the package: ``meshes/`` plus the
    path as written (without a leading ``meshes/``, which would be doubled), normalised as a
    path inside the spec's ``folder``: ``../specs/base.stl`` written in specs/ is ``meshes/base.stl``,
    so a name never puts a copy outside ``meshes/`` (ValueError for one that would)."""
    inside = posixpath.normpath(posixpath.join(folder, written))
    rel = posixpath.relpath(inside, folder)
    if rel == "." or rel == ".." or rel.startswith("../"):
        raise ValueError(f"mesh path {written!r} leaves its folder")
    return rel if rel.startswith(f"{MESH_FOLDER}/") else f"{MESH_FOLDER}/{rel}"


def own_meshes(robot: Robot) -> dict[str, Path]:
    """Package path -> source file of every mesh that ``generate`` copies into the package."""
    prefix = f"package://{package_name(robot)}/"
    return {name[len(prefix) :]: Path(path) for name, path in robot.mesh_files if name.startswith(prefix)}


# a package a pass-through element names, as xacro and ROS write it: $(find pkg) (kept symbolic
# by import and evaluated by xacro at launch, descgen/spec/passthrough.py) and package://pkg/
PACKAGE_REF = re.compile(r"\$\(find ([A-Za-z0-9][A-Za-z0-9_-]*)\)|package://([A-Za-z0-9][A-Za-z0-9_-]*)/")


def named_packages(robot: Robot) -> list[str]:
    """Packages the robot names, in the order first named: those of its ``package://`` meshes,
    then those its pass-through elements name (a Gazebo plugin's ``$(find pkg)/config/...``)."""
    found: dict[str, None] = {}
    for name in _mesh_names(robot):
        if (uri := split_package_uri(name)) and PACKAGE_NAME.fullmatch(uri[0]):
            found.setdefault(uri[0])
    for xml in robot.passthrough:
        for ref in PACKAGE_REF.finditer(xml):
            found.setdefault(ref.group(1) or ref.group(2))
    return list(found)


def other_packages(robot: Robot) -> list[str]:
    """Packages the outputs reference, each an exec_depend (:func:`named_packages` but the own)."""
    return sorted(set(named_packages(robot)) - {package_name(robot)})


def _mesh_refs(spec: Any) -> Iterator[tuple[tuple[str | int, ...], str]]:
    """(YAML path of the filename, filename) of every mesh reference in a spec (a part's
    body once, however many instances it has)."""
    bodies: list[tuple[tuple[str | int, ...], Any]] = [(("links", i), lk) for i, lk in enumerate(spec.links)]
    bodies += [(("parts", i, "link"), part.link) for i, part in enumerate(spec.parts)]
    for path, body in bodies:
        for kind in ("visual", "collision"):
            for k, shape in enumerate(getattr(body, kind)):
                mesh = shape.geometry.mesh
                if mesh is not None:
                    yield (*path, kind, k, "geometry", "mesh", "filename"), mesh.filename


@record
class _Found:
    model_name: str
    path: Path
    dest: str | None  # package path of a copy (own meshes)


def resolve_spec(
    robot: Robot, spec: Any, where: Any, spec_path: Path, package_paths: Sequence[Path] = ()
) -> tuple[Robot, list[Finding]]:
    """Resolve every mesh of a validated spec (``spec``: the RobotSpec; ``where(path)``: the
    YAML position of a path). Returns the robot with its own meshes renamed into its package
    and :attr:`Robot.mesh_files` set, and an error finding for every reference, recorded
    folder or copy that cannot work."""
    problems: list[Finding] = []
    search: list[Path] = []
    for i, written in enumerate(getattr(spec, "package_paths", None) or []):
        folder, why = _folder(spec_path, written, "package_paths")
        if folder is None:
            problems.append(_folder_error(("package_paths", i), written, why, where))
        else:
            search.append(folder)
    templates = getattr(spec, "templates", None)
    if templates is not None:
        folder, why = _folder(spec_path, templates, "templates")
        if folder is None:
            problems.append(_folder_error(("templates",), templates, why, where))
    search += list(package_paths)
    base = spec_path.resolve().parent
    own = package_name(robot)
    for i, kept in enumerate(getattr(spec, "passthrough", None) or []):
        if any((ref.group(1) or ref.group(2)) == own for ref in PACKAGE_REF.finditer(kept.xml)):
            problems.append(
                _error(
                    SPEC066,
                    f"pass-through element {i + 1} names the generated package {own}",
                    "name the package that holds the file, or give the generated package another name "
                    "(package: {name: ...})",
                    where(("passthrough", i)),
                )
            )
    found: dict[str, _Found] = {}
    copies: dict[str, tuple[Path, str]] = {}
    for ypath, name in _mesh_refs(spec):
        at = where(ypath)
        uri = split_package_uri(name)
        if uri is not None and uri[0] == own:
            problems.append(_own_package(name, own, at))
            continue
        r = resolve(name, base, base, search)
        bad = _refusal(name, r, at, bool(search))
        if bad is not None:
            problems.append(bad)
            continue
        assert r.path is not None
        try:
            dest = own_mesh_path(name, base.as_posix()) if uri is None else None
        except ValueError:  # through a link inside the folder and back up past it: no copy could be named
            problems.append(_refusal(name, Resolved("escapes"), at, bool(search)) or _clash(name, name, name, at))
            continue
        if dest is not None:
            earlier = copies.setdefault(dest, (r.path, name))
            if earlier[0] != r.path:
                problems.append(_clash(name, earlier[1], dest, at))
                continue
        model_name = f"package://{own}/{dest}" if dest is not None else name
        found[name] = _Found(model_name, r.path, dest)
    return _renamed(robot, found), problems


def _renamed(robot: Robot, found: dict[str, _Found]) -> Robot:
    def shape(s: Visual | Collision) -> Visual | Collision:
        g = s.geometry
        if isinstance(g, Mesh) and g.filename in found:
            return replace(s, geometry=replace(g, filename=found[g.filename].model_name))
        return s

    def link(lk: Link) -> Link:
        visuals = tuple(shape(v) for v in lk.visuals)
        collisions = tuple(shape(c) for c in lk.collisions)
        return replace(lk, visuals=visuals, collisions=collisions)  # type: ignore[arg-type]

    files = {f.model_name: str(f.path) for f in found.values()}
    return replace(
        robot,
        links=tuple(link(lk) for lk in robot.links),
        mesh_files=tuple(sorted(files.items())),
        mesh_status=tuple((name, "ok") for name in sorted(files)),
    )


_HINT_FOLDER = (
    "write a path relative to the spec, e.g. meshes/base.stl, with the file beside the spec, "
    "or package://<pkg>/<path> with the package's folder under package_paths:"
)


def _refusal(name: str, r: Resolved, at: Where, have_paths: bool) -> Finding | None:
    """The error for a reference that cannot be used, or None."""
    if r.state == "ok" and r.problem is None:
        return None
    if r.state == "escapes":
        return _error(
            SPEC061,
            f"mesh '{name}' points outside the spec's folder and the package paths",
            "keep meshes inside the spec's folder (no '..' past it, no absolute path or file://, no link out) "
            "or in a package named with package://",
            at,
        )
    if r.state == "unresolved":
        where_ = (
            "which is in no folder of package_paths:, --package-path or the sourced environment"
            if have_paths
            else "but the spec records no package_paths:, no --package-path was given and no ROS workspace is "
            "sourced (AMENT_PREFIX_PATH, ROS_PACKAGE_PATH)"
        )
        return _error(
            SPEC062,
            f"mesh '{name}' names package '{r.package}', {where_}",
            f"pass --package-path DIR, DIR being the folder that holds {r.package}/ (to validate, generate and "
            "check alike), or record that folder relative to the spec under package_paths:, or fix the package name",
            at,
        )
    if r.problem is not None:
        return _error(SPEC063, f"mesh '{name}' {r.problem}", "name the mesh file itself", at)
    return _error(SPEC060, f"mesh '{name}' does not exist", _HINT_FOLDER, at)


def _own_package(name: str, own: str, at: Where) -> Finding:
    return _error(
        SPEC062,
        f"mesh '{name}' names the package descgen generates ({own}), which does not exist before it",
        "write the path relative to the spec (e.g. meshes/base.stl): generate copies it into the package; "
        f"or, if the mesh belongs to an existing package called {own}, give the generated package another "
        "name (package: {name: ...}) and pass --package-path",
        at,
    )


def _clash(name: str, other: str, dest: str, at: Where) -> Finding:
    return _error(
        SPEC065,
        f"mesh '{name}' and mesh '{other}' are different files but would both be copied to {dest}",
        "move one of them, or rename it",
        at,
    )


def _folder_error(ypath: tuple[str | int, ...], written: str, why: str, where: Any) -> Finding:
    key = "templates" if ypath[0] == "templates" else "package_paths"
    return _error(
        SPEC064,
        f"{key} entry '{written}' {why}",
        "name a folder relative to the spec, inside the project (the folder holding specs/)"
        if key == "templates"
        else "name a folder relative to the spec (it may lie outside the project, e.g. ../../ws/src), or pass "
        "--package-path DIR, or source the workspace",
        where(ypath),
    )


def _error(code: Code, message: str, hint: str, at: Where) -> Finding:
    return code.finding(message, hint, "spec", at)
