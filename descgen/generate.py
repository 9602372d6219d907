"""``generate`` and ``check``: render the package, prove it, then write it (all or nothing)
or compare it with what is committed.

A spec with ``moveit:`` has a second package, ``<robot>_moveit_config`` (descgen/moveit/),
beside the description package. Both are built before either is switched
(:func:`write_packages`), so a failure while building changes neither, and a switch that fails
puts the first back; only a run killed between the two switches (two renames) leaves the new
description beside the old MoveIt package, which ``check`` reports as stale.

This module is where generated files are written (:func:`write_package`). The package is
switched as a whole, never file by file: the complete new package (the old one's files,
minus ours that changed or went stale, plus the new files) is built in a scratch folder
``<out>/.descgen-new-*`` on the same file system, then swapped with the package folder in
one step (Linux ``renameat2(RENAME_EXCHANGE)``), or where that is missing by two renames
through ``.descgen-old-*``. A reader sees the old set or the new set, never a mix. A run
killed or failing at any point leaves at worst scratch folders, which the next run removes
(putting back a package that was moved aside and not replaced) before it writes.

The package folder must not be, nor hold, a link or a special file: generate and check
refuse it before reading or writing anything (GEN040-GEN043), so nothing is read or written
outside the output root.
"""

from __future__ import annotations

import contextlib
import ctypes
import difflib
import errno
import functools
import hashlib
import os
import posixpath
import re
import secrets
import shutil
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import cast

from . import checks, interruptions
from .findings import Finding, InputError, Where, errors
from .mesh_paths import MAX_MESH_BYTES, MESH_FOLDER, own_meshes, spec_folder
from .model import Robot
from .render import header, render_package
from .render.context import package_name
from .safeio import read_bounded
from .spec import load_spec


@dataclass(frozen=True)
class Plan:
    robot: Robot
    files: dict[str, str]  # the rendered text files, the mesh manifest among them
    package_dir: Path
    findings: tuple[Finding, ...]  # warnings from the spec, errors and warnings from the checks
    # the robot's own meshes: package path -> (source file beside the spec, its bytes)
    meshes: dict[str, tuple[Path, bytes]] = field(default_factory=dict)
    # the MoveIt config package (spec ``moveit:``): its files and folder; empty and None without it
    moveit_files: dict[str, str] = field(default_factory=dict)
    moveit_dir: Path | None = None
    # each proof's findings by its name (checks.CHECKS order): the evidence page shows them
    proofs: tuple[tuple[str, tuple[Finding, ...]], ...] = ()

    def content(self) -> dict[str, str | bytes]:
        """Every file generate writes: the text files and the mesh copies."""
        every: dict[str, str | bytes] = {**self.files, **{rel: data for rel, (_, data) in self.meshes.items()}}
        return dict(sorted(every.items()))


@dataclass
class Outcome:
    findings: list[Finding] = field(default_factory=list)
    written: list[str] = field(default_factory=list)
    unchanged: list[str] = field(default_factory=list)
    removed: list[str] = field(default_factory=list)
    diff: str = ""

    @property
    def failed(self) -> bool:
        return bool(errors(self.findings))


def default_out(spec: Path) -> Path:
    """``generated/`` beside ``specs/`` (or beside the spec when it is not in a specs folder)."""
    parent = spec.resolve().parent
    return parent.parent / "generated" if parent.name == "specs" else parent / "generated"


def spec_display(spec: Path, out_root: Path) -> str:
    """How the header names the spec: relative to the project (the folder holding the
    output root), so it is the same from any working directory and on any machine."""
    try:
        return spec.resolve().relative_to(out_root.resolve().parent).as_posix()
    except ValueError:
        return spec.name


def plan(
    spec: Path,
    out_root: Path | None = None,
    templates: Path | None = None,
    package_paths: Sequence[Path] = (),
    thorough: bool = False,
    show_progress: bool = False,
) -> Plan:
    """Load, render and prove one spec. Raises InputError for invalid input.

    ``templates`` (--templates) overrides the folder the spec records (``templates:``); that
    one renders sandboxed, since the spec is someone else's data. ``package_paths``
    (--package-path) are searched for ``package://`` meshes after the spec's ``package_paths:``.
    ``show_progress``: a collision matrix's samples drawn on a terminal."""
    root = out_root or default_out(spec)
    loaded = load_spec(spec, package_paths=package_paths)
    robot = loaded.robot
    recorded = loaded.spec.templates
    sandboxed = templates is None and recorded is not None
    if sandboxed and recorded is not None:
        templates = spec_folder(spec, recorded)  # validated by load_spec (SPEC064)
    shown = spec_display(spec, root)
    meshes = _mesh_copies(robot, root)
    if robot.semantic is not None and robot.semantic.collision_matrix is not None:
        # the matrix needs the URDF (rendered alone first: the rest would be rendered again), and
        # the SRDF and its evidence need the matrix
        urdf = f"urdf/{robot.name}.urdf"
        robot = _with_matrix(
            robot,
            render_package(robot, shown, templates, sandboxed, only={urdf}),
            meshes,
            root / package_name(robot),
            show_progress,
        )
    files = render_package(robot, shown, templates, sandboxed)
    if meshes:
        files[MANIFEST] = header.add(MANIFEST, _manifest(meshes), shown, robot.spec_hash or "0" * 64)
    package_dir = root / package_name(robot)
    proofs = checks.run_named(files, robot, package_dir, thorough)  # by name for the evidence page
    found = [*loaded.findings, *(f for _, done in proofs for f in done)]
    moveit_files: dict[str, str] = {}
    moveit_dir = None
    if robot.moveit is not None:
        from .moveit import proof
        from .moveit.render import moveit_package_name, render

        moveit_dir = root / moveit_package_name(robot)
        moveit_files = render(robot, files, shown, templates, sandboxed)
        found += proof.check(moveit_files, robot, moveit_dir, files)
    return Plan(robot, dict(sorted(files.items())), package_dir, tuple(found), meshes, moveit_files, moveit_dir, proofs)


def _with_matrix(
    robot: Robot, files: Mapping[str, str], meshes: dict[str, tuple[Path, bytes]], pkg: Path, show_progress: bool
) -> Robot:
    """The robot with its sampled self-collision matrix, taken from the committed SRDF when
    that records the same input hash (so ``check`` does not sample again)."""
    from dataclasses import replace

    from . import collision

    sem = robot.semantic
    assert sem is not None and sem.collision_matrix is not None
    srdf = pkg / "srdf" / f"{robot.name}.srdf"
    committed = None
    if srdf.is_file() and not srdf.is_symlink():
        try:
            committed = read_bounded(srdf, "SRDF").decode("utf-8", errors="replace")
        except InputError:
            committed = None  # unreadable: sample again, check reports the file
    matrix = collision.compute(
        robot,
        files[f"urdf/{robot.name}.urdf"],
        {rel: data for rel, (_, data) in meshes.items()},
        pkg.name,
        sem.collision_matrix,
        committed,
        show_progress,
    )
    from .sweep import evidence as sweep_evidence

    out = replace(robot, semantic=replace(sem, matrix=matrix))
    sweep_evidence.reuse_committed(out, pkg)  # check: the committed sweep's collision runs, when still valid
    return out


# --- the robot's own meshes: copied byte for byte, their hashes in a manifest -----------------------

# Binary files carry no header, so the package records what generate copied: check compares
# copies and sources, generate tells a copy edited in the package from a changed source, and a
# mesh no longer used is removed like any file descgen no longer generates.
MANIFEST = f"{MESH_FOLDER}/meshes.sha256"
_MANIFEST_LINE = re.compile(r"([0-9a-f]{64})  (\S.*)")


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _mesh_copies(robot: Robot, root: Path) -> dict[str, tuple[Path, bytes]]:
    """Package path -> (source, bytes) of every mesh to copy, each read with a bound."""
    return {
        rel: (src, read_bounded(src, "mesh", MAX_MESH_BYTES, display=_shown_source(src, root)))
        for rel, src in sorted(own_meshes(robot).items())
    }


def _shown_source(src: Path, root: Path) -> str:
    try:
        return src.relative_to(root.resolve().parent).as_posix()
    except ValueError:
        return str(src)


def _manifest(meshes: dict[str, tuple[Path, bytes]]) -> str:
    lines = ["# sha256 of every mesh generate copied here, as `sha256sum -c` reads it from the package folder"]
    lines += [f"{_sha256(data)}  {rel}" for rel, (_, data) in meshes.items()]
    return "\n".join(lines) + "\n"


def _recorded_meshes(package_dir: Path) -> dict[str, str]:
    """Package path -> sha256 of the meshes the package's manifest says generate copied.
    The manifest is in the output folder, so only paths inside ``meshes/`` are believed."""
    target = package_dir / MANIFEST
    if not target.is_file() or target.is_symlink():
        return {}
    text = read_bounded(target, "mesh manifest").decode("utf-8", "replace")
    out: dict[str, str] = {}
    for line in text.splitlines():
        m = _MANIFEST_LINE.fullmatch(line)
        if m is None:
            continue
        rel = PurePosixPath(m.group(2))
        if rel.parts[:1] == (MESH_FOLDER,) and ".." not in rel.parts and not rel.is_absolute():
            out[rel.as_posix()] = m.group(1)
    return out


def _hand_edited(package_dir: Path, files: dict[str, str], meshes: Mapping[str, tuple[Path, bytes]] = {}) -> list[str]:
    """Files we would overwrite that are not as descgen wrote them: a text file whose content
    no longer matches its header, a mesh copy that is neither the new bytes nor what the
    manifest recorded (edited in the package, or someone else's file)."""
    edited = []
    for rel in files:
        target = package_dir / rel
        if not target.is_file():
            continue
        stamp = header.read(target.read_text(encoding="utf-8", errors="replace"))
        if stamp is None or stamp.hand_edited:
            edited.append(rel)
    recorded = _recorded_meshes(package_dir) if meshes else {}
    for rel, (_, data) in meshes.items():
        target = package_dir / rel
        if not target.is_file():
            continue
        now = _sha256(read_bounded(target, "mesh", MAX_MESH_BYTES))
        if now != _sha256(data) and now != recorded.get(rel):
            edited.append(rel)
    return edited


# What generate owns; other commands may add their own evidence to the package.
_OWN_DIRS = {"urdf", "srdf", "config", "launch", "rviz", "package.xml", "CMakeLists.txt", MESH_FOLDER}
_OWN_FILES: set[str] = {"evidence/known_poses.md", "evidence/frames.md", "evidence/frames.dot"}


def _ours(package_dir: Path) -> list[str]:
    """Files of the package that ``generate`` wrote earlier: those carrying its header, and
    the mesh copies its manifest lists."""
    found: list[str] = []
    if not package_dir.is_dir():
        return found
    for p in sorted(package_dir.rglob("*")):
        rel = p.relative_to(package_dir).as_posix()
        # only where generate writes, so other commands' (possibly large) evidence is not read
        if p.is_file() and not p.is_symlink() and (rel.split("/")[0] in _OWN_DIRS or rel in _OWN_FILES):
            try:
                with open(p, "rb") as fh:  # the head only: a mesh may be large and is not text
                    head = fh.read(600).decode("utf-8", errors="ignore")
            except OSError:
                continue
            if header.MARK in head:
                found.append(rel)
    copies = [rel for rel in _recorded_meshes(package_dir) if (package_dir / rel).is_file()]
    return sorted({*found, *copies})


def _refusal(code: str, message: str, hint: str, path: Path) -> Finding:
    return Finding(code, "error", message, hint, f"file:{path.name}", Where(str(path)))


_LINK_HINT = (
    "replace the link with a real file or folder (or delete it: generate recreates its own files); "
    "descgen never writes or reads through links in its output"
)


def _unsafe_entries(package_dir: Path) -> list[Finding]:
    """Links and special files in the package, found without following any link.

    A link could make generate write (or check read and print) a file outside the output
    root; a FIFO or device would hang or flood the copy of the user's files."""
    if not os.path.lexists(package_dir):
        return []
    if package_dir.is_symlink():
        target = os.readlink(package_dir)
        return [
            _refusal(
                "GEN041", f"the package folder {package_dir} is a symbolic link (to {target})", _LINK_HINT, package_dir
            )
        ]
    if not package_dir.is_dir():
        return [
            _refusal(
                "GEN041",
                f"the package folder {package_dir} exists but is not a folder",
                "move that file away; generate writes a folder there",
                package_dir,
            )
        ]
    found: list[Finding] = []
    pending = [package_dir]
    while pending:
        with os.scandir(pending.pop()) as entries:
            for entry in entries:
                path = Path(entry.path)
                rel = path.relative_to(package_dir).as_posix()
                if entry.is_symlink():
                    what = f"{rel} in {package_dir.name} is a symbolic link (to {os.readlink(path)})"
                    found.append(_refusal("GEN040", what, _LINK_HINT, path))
                elif entry.is_dir(follow_symlinks=False):
                    pending.append(path)
                elif not entry.is_file(follow_symlinks=False):
                    what = f"{rel} in {package_dir.name} is not a regular file (a FIFO, socket or device)"
                    found.append(_refusal("GEN043", what, "remove it from the package folder", path))
    return sorted(found, key=lambda f: f.where.file)


def refuse_unsafe(package_dir: Path) -> None:
    """Raise InputError when the package folder is a link, or holds a link or a special file."""
    found = _unsafe_entries(package_dir)
    if found:
        raise InputError(found)


def _output_root(spec: Path, out_root: Path | None) -> Path | None:
    """``out_root``, after refusing a default output root that is a link.

    The default root comes from where the spec lies, so a checked-out ``generated`` link
    would send the package wherever its author chose; a root named with --out is the
    user's own choice and may be a link."""
    if out_root is not None:
        return out_root
    root = default_out(spec)
    if root.is_symlink():
        raise InputError(
            [
                _refusal(
                    "GEN042",
                    f"the output root {root} is a symbolic link (to {os.readlink(root)})",
                    "name the output folder with --out, or replace the link with a folder",
                    root,
                )
            ]
        )
    return root


# --- the switch: build the whole new package beside the old one, then swap folders ---

# Scratch folders in the output root, ".descgen-<state>-<package>-<random>". The state is in
# the name, and every change of state is one rename, so a killed run leaves names that say
# exactly what each folder holds:
#   new-   being built, or (after an exchange) the old package on its way out: always removed
#   old-   the complete old package, moved aside by the fallback switch: restored when the
#          package is missing (killed between the two renames), else removed
#   trash- being deleted: always removed
# (a folder is never "marked complete" by a file inside it, since that file would then
# appear in the package for a moment after the swap).
_SCRATCH = ".descgen-"
_AT_FDCWD = -100
_RENAME_EXCHANGE = 2


@functools.cache
def _renameat2() -> Callable[..., int] | None:
    """libc's renameat2 (glibc >= 2.28), or None on systems without it."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        fn = libc.renameat2
    except (AttributeError, OSError, TypeError):
        return None
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    return cast("Callable[..., int]", fn)


def exchange(a: Path, b: Path) -> bool:
    """Swap two folders in one step (Linux RENAME_EXCHANGE). False, with nothing changed,
    when the system or the file system cannot; other failures raise OSError."""
    fn = _renameat2()
    if fn is None:
        return False
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(a), None, str(b))


def _scratch_path(root: Path, state: str, package: str) -> Path:
    return root / f"{_SCRATCH}{state}-{package}-{secrets.token_hex(4)}"


def _remove(path: Path) -> None:
    """Delete a scratch entry; a link is unlinked, never followed."""
    if path.is_symlink() or not path.is_dir():
        with contextlib.suppress(FileNotFoundError):
            path.unlink()
    else:
        shutil.rmtree(path, ignore_errors=True)


def recover(root: Path) -> list[str]:
    """Clean what killed or failed runs left in the output root: a package moved aside and
    not replaced is put back; every other scratch folder is removed. Returns the names of
    the packages put back."""
    restored: list[str] = []
    if not root.is_dir():
        return restored
    for entry in sorted(root.iterdir()):
        if not entry.name.startswith(_SCRATCH):
            continue
        state, _, rest = entry.name[len(_SCRATCH) :].partition("-")
        package = rest.rpartition("-")[0]
        home = root / package
        if state == "old" and package and entry.is_dir() and not entry.is_symlink() and not os.path.lexists(home):
            os.rename(entry, home)
            restored.append(package)
        else:
            _remove(entry)
    return restored


@contextlib.contextmanager
def _locked(root: Path) -> Iterator[None]:
    """One writer per output root, so no run cleans up another's scratch folder (POSIX only)."""
    try:
        import fcntl
    except ImportError:  # Windows: no flock; runs must not overlap
        yield
        return
    fd = os.open(root, os.O_RDONLY)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise InputError(
                [
                    _refusal(
                        "GEN044",
                        f"another descgen run is writing into {root}",
                        "wait for it to finish, then run again",
                        root,
                    )
                ]
            ) from None
        yield
    finally:
        os.close(fd)  # closing releases the lock


def _fsync(path: Path) -> None:
    """Flush a folder's entries to disk (POSIX; a no-op where folders cannot be opened)."""
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _bytes(content: str | bytes) -> bytes:
    return content.encode("utf-8") if isinstance(content, str) else content


def _changes(package_dir: Path, files: Mapping[str, str | bytes]) -> Outcome:
    """Which files change, which stay, which of ours are no longer produced (compared as bytes)."""
    out = Outcome()
    for rel, content in files.items():
        target = package_dir / rel
        same = target.is_file() and target.read_bytes() == _bytes(content)
        (out.unchanged if same else out.written).append(rel)
    out.removed = [rel for rel in _ours(package_dir) if rel not in files]
    return out


def _copy_tree(src: Path, dst: Path, skip: set[str], rel: str = "") -> None:
    """Everything of the old package but ``skip``, hard-linked (the old inodes are never
    written again, so sharing them is safe and costs no space) or else copied; links are
    never followed."""
    with os.scandir(src) as entries:
        for entry in sorted(entries, key=lambda e: e.name):
            sub = f"{rel}{entry.name}"
            source, target = Path(entry.path), dst / entry.name
            if entry.is_symlink() or not (entry.is_dir(follow_symlinks=False) or entry.is_file(follow_symlinks=False)):
                refuse_unsafe(src)  # appeared since the check: refuse, naming it
            elif entry.is_dir(follow_symlinks=False):
                os.mkdir(target)
                shutil.copymode(source, target, follow_symlinks=False)
                _copy_tree(source, target, skip, f"{sub}/")
            elif sub not in skip:
                try:
                    os.link(source, target, follow_symlinks=False)
                except OSError:
                    shutil.copy2(source, target, follow_symlinks=False)


def _write(path: Path, content: str | bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "wb") as fh:  # text is written as UTF-8 with \n line ends, exactly as rendered
        fh.write(_bytes(content))
        fh.flush()
        os.fsync(fh.fileno())


def _build(new: Path, package_dir: Path, files: Mapping[str, str | bytes], out: Outcome) -> None:
    """The complete new package in ``new``: the old one's files (ours that changed or went
    stale left out, everyone else's kept), then the files that changed."""
    if package_dir.is_dir():
        shutil.copymode(package_dir, new)
        _copy_tree(package_dir, new, {*out.written, *out.removed})
    for rel in out.written:
        # a package path is made of names (the robot's, a mesh's): never one that leaves the package
        if posixpath.isabs(rel) or ".." in rel.split("/") or "\x00" in rel:
            raise ValueError(f"package path {rel!r} leaves the package")
        _write(new / rel, files[rel])
    _fsync(new)


def _switch(new: Path, package_dir: Path) -> Path | None:
    """Put ``new`` in the package's place; returns the folder now holding the old package.

    A reader sees the old folder or the new one, never a mix: one exchange where the system
    has it; else two renames, and a run killed between them leaves a complete
    ``.descgen-old-*`` that the next run puts back."""
    if not os.path.lexists(package_dir):
        os.rename(new, package_dir)
        return None
    if exchange(new, package_dir):
        return new
    old = _scratch_path(package_dir.parent, "old", package_dir.name)
    os.rename(package_dir, old)
    try:
        os.rename(new, package_dir)
    except BaseException:
        os.rename(old, package_dir)
        raise
    return old


def write_package(package_dir: Path, files: Mapping[str, str | bytes]) -> Outcome:
    """Switch the package to ``files`` as a whole: build the complete new package in a
    scratch folder in the output root, then swap the two folders (see :func:`_switch`).
    Files descgen wrote earlier and no longer produces are dropped; other files (evidence
    of other commands, the user's own) are carried over unchanged. Refuses (InputError)
    links and special files in the package before anything is written; cleans up after
    earlier killed runs first."""
    return write_packages([(package_dir, files)])[0]


def write_packages(packages: Sequence[tuple[Path, Mapping[str, str | bytes]]]) -> list[Outcome]:
    """:func:`write_package` for sibling packages of one output root (the description and its
    MoveIt config): every new package is built before any is switched, so a failure while
    building (a full disk) changes none of them; a switch that fails puts back the ones
    switched before it. Only a run killed between two switches leaves one package new and
    the other old, which ``check`` reports as stale."""
    for package_dir, files in packages:
        for rel in files:
            parts = PurePosixPath(rel).parts
            if not parts or PurePosixPath(rel).is_absolute() or ".." in parts:
                raise ValueError(f"not a path inside the package: {rel!r}")
        refuse_unsafe(package_dir)
    roots = {package_dir.parent for package_dir, _ in packages}
    if len(roots) != 1:
        raise ValueError("packages switched together share one output root")
    (root,) = roots
    if os.path.lexists(root) and not root.is_dir():
        raise InputError(
            [_refusal("GEN042", f"the output root {root} is not a folder", "name a folder with --out", root)]
        )
    root.mkdir(parents=True, exist_ok=True)
    with _locked(root):
        if recover(root):
            for package_dir, _ in packages:
                refuse_unsafe(package_dir)  # a package put back is checked like any other
        outs = [_changes(package_dir, files) for package_dir, files in packages]
        todo = [
            (package_dir, files, out)
            for (package_dir, files), out in zip(packages, outs, strict=True)
            if out.written or out.removed
        ]
        built: list[tuple[Path, Path]] = []  # (scratch folder, package folder)
        try:
            for package_dir, files, out in todo:
                new = _scratch_path(root, "new", package_dir.name)
                os.mkdir(new)
                built.append((new, package_dir))
                _build(new, package_dir, files, out)
        except BaseException:
            for new, _ in built:
                _remove(new)
            raise
        with interruptions.held():  # a Ctrl-C raised between two switches would part them
            olds = _switch_all(built)
        # the packages are switched: what is left is clean-up, which the next run's recover()
        # also does, so a failure here is no failure of the write
        with contextlib.suppress(OSError):
            _fsync(root)
            for old, package_dir in olds:
                if old is not None:
                    trash = _scratch_path(root, "trash", package_dir.name)
                    os.rename(old, trash)
                    _remove(trash)
    return outs


def _switch_all(built: list[tuple[Path, Path]]) -> list[tuple[Path | None, Path]]:
    """Switch every built package into place, in order; when one fails, the ones before it
    are switched back (their old folders are complete) and every scratch folder is removed.
    Two failures in a row (the switch and its undo) can leave them apart; ``check`` says so."""
    done: list[tuple[Path | None, Path]] = []
    try:
        for new, package_dir in built:
            done.append((_switch(new, package_dir), package_dir))
    except BaseException:
        for old, package_dir in reversed(done):
            _unswitch(old, package_dir, package_dir.parent)
        for new, _ in built[len(done) :]:
            _remove(new)
        raise
    return done


def _unswitch(old: Path | None, package_dir: Path, root: Path) -> None:
    """Undo :func:`_switch`: the old package (``old``; None when there was none) back in place,
    the new one moved aside in one rename, then removed."""
    aside = _scratch_path(root, "trash", package_dir.name)
    if old is None:
        os.rename(package_dir, aside)  # gone in one step, never half deleted in place
    elif exchange(old, package_dir):
        aside = old
    else:
        os.rename(package_dir, aside)
        os.rename(old, package_dir)
    _remove(aside)


def generate(
    spec: Path,
    out_root: Path | None = None,
    templates: Path | None = None,
    force: bool = False,
    package_paths: Sequence[Path] = (),
    show_progress: bool = False,
) -> Outcome:
    p = plan(spec, _output_root(spec, out_root), templates, package_paths, show_progress=show_progress)
    outcome = Outcome(findings=list(p.findings))
    if outcome.failed:
        return outcome
    refuse_unsafe(p.package_dir)  # before reading any file of the package
    if p.moveit_dir is not None:
        refuse_unsafe(p.moveit_dir)
    edited = [] if force else [(p.package_dir, rel) for rel in _hand_edited(p.package_dir, p.files, p.meshes)]
    if p.moveit_dir is not None and not force:
        edited += [(p.moveit_dir, rel) for rel in _hand_edited(p.moveit_dir, p.moveit_files)]
    if edited:
        for folder, rel in edited:
            how = (
                f"is neither its source nor what {MANIFEST} recorded"
                if folder == p.package_dir and rel in p.meshes
                else "its content no longer matches its header"
            )
            shown = rel if folder == p.package_dir else f"{folder.name}/{rel}"
            outcome.findings.append(
                Finding(
                    "GEN004",
                    "error",
                    f"{shown} was edited by hand ({how}); not overwritten",
                    "move the change into the spec or a template, or run with --force to discard it",
                    f"file:{shown}",
                    Where(str(folder / rel)),
                )
            )
        return outcome
    try:
        packages: list[tuple[Path, Mapping[str, str | bytes]]] = [(p.package_dir, p.content())]
        if p.moveit_dir is not None:  # built before either is switched (see the module docstring)
            packages.append((p.moveit_dir, dict(p.moveit_files)))
        written, *more = write_packages(packages)
        for second in more:
            assert p.moveit_dir is not None
            written.written += [f"{p.moveit_dir.name}/{rel}" for rel in second.written]
            written.unchanged += [f"{p.moveit_dir.name}/{rel}" for rel in second.unchanged]
            written.removed += [f"{p.moveit_dir.name}/{rel}" for rel in second.removed]
    except OSError as exc:  # a full disk, a read-only --out: the old package is still in place
        raise InputError(
            [
                Finding(
                    "GEN045",
                    "error",
                    f"could not write the package: {exc.strerror or exc}"
                    + (f": {exc.filename}" if exc.filename else ""),
                    "check free space and permissions of the output folder (--out); nothing was changed",
                    "file",
                    Where(str(p.package_dir)),
                )
            ]
        ) from None
    written.findings = outcome.findings
    draw_frames(p.package_dir)
    return written


def draw_frames(package_dir: Path) -> None:
    """evidence/frames.svg from frames.dot when Graphviz's dot is installed, and only when the
    svg does not already record this dot text and this dot (see frames_svg)."""
    from .frames_svg import draw

    draw(package_dir)


def check(
    spec: Path,
    out_root: Path | None = None,
    templates: Path | None = None,
    write_page: bool = False,
    package_paths: Sequence[Path] = (),
    thorough: bool = False,
) -> Outcome:
    """Regenerate in memory and compare with the files on disk; run every check. The evidence
    page (``descgen report``) is compared when it exists, and written with ``write_page``.
    ``thorough`` adds the slow-to-start proofs (checks.THOROUGH: yourdfpy)."""
    root = _output_root(spec, out_root)
    p = plan(spec, root, templates, package_paths, thorough)
    refuse_unsafe(p.package_dir)  # a link would let the diff print a file from elsewhere
    outcome = Outcome(findings=list(p.findings))
    diffs: list[str] = []
    _compare(p.package_dir, p.files, p.robot.spec_hash, "", set(p.meshes), outcome, diffs)
    outcome.findings += _stale_meshes(p)
    if p.moveit_dir is not None:  # the MoveIt package is compared like the description package
        refuse_unsafe(p.moveit_dir)
        _compare(p.moveit_dir, p.moveit_files, p.robot.spec_hash, f"{p.moveit_dir.name}/", set(), outcome, diffs)
    outcome.diff = "".join(diffs)
    outcome.findings += _stale_evidence(spec, p, root or default_out(spec), write_page)
    outcome.findings += _evidence_page(spec, p, root or default_out(spec), outcome, write_page)
    return outcome


def _compare(
    package_dir: Path,
    files: Mapping[str, str],
    spec_hash: str | None,
    prefix: str,
    other: set[str],
    outcome: Outcome,
    diffs: list[str],
) -> None:
    """Each rendered file against the one on disk (GEN004-GEN006, with a diff), and files of
    ours no longer rendered (GEN007; ``other`` are generated files compared elsewhere).
    ``prefix`` names the package in messages when it is not the description package."""
    for rel, fresh in files.items():
        shown = f"{prefix}{rel}"
        target = package_dir / rel
        where = Where(str(target))
        if not target.is_file():
            outcome.findings.append(
                Finding("GEN006", "error", f"{shown} is missing", "run descgen generate", f"file:{shown}", where)
            )
            continue
        current = target.read_text(encoding="utf-8", errors="replace")
        if current == fresh:
            continue
        stamp = header.read(current)
        if stamp is not None and stamp.hand_edited:
            what, hint, code = "was edited by hand", "move the change into the spec or a template", "GEN004"
        elif stamp is not None and stamp.spec_hash != spec_hash:
            what, hint, code = "is stale: the spec changed", "run descgen generate and commit the result", "GEN005"
        else:
            what, hint, code = (
                "is stale: templates or descgen changed",
                "run descgen generate and commit the result",
                "GEN005",
            )
        outcome.findings.append(Finding(code, "error", f"{shown} {what}", hint, f"file:{shown}", where))
        diffs.append(
            "".join(
                difflib.unified_diff(
                    current.splitlines(keepends=True),
                    fresh.splitlines(keepends=True),
                    fromfile=f"a/{shown}",
                    tofile=f"b/{shown}",
                )
            )
        )
    for rel in _ours(package_dir):
        if rel not in files and rel not in other:
            outcome.findings.append(
                Finding(
                    "GEN007",
                    "error",
                    f"{prefix}{rel} is no longer generated",
                    "run descgen generate",
                    f"file:{prefix}{rel}",
                    Where(str(package_dir / rel)),
                )
            )


def _evidence_page(spec: Path, p: Plan, root: Path, outcome: Outcome, write_page: bool) -> list[Finding]:
    """The evidence page rebuilt from the proofs just run: compared (GEN080), or written when
    asked and every proof passed (else GEN081: a page must not show a failed package as current)."""
    from . import evidence_page as page
    from . import pose_images

    if not write_page and not (p.package_dir / page.PAGE).is_file():
        return []
    shown = spec_display(spec, root)
    lines = page.check_lines(shown, outcome.findings, outcome.diff)
    meshes = {rel: data for rel, (_, data) in p.meshes.items()}
    key = page.input_key(spec, shown, p.files, meshes, p.package_dir, lines, len(p.content()))
    if not write_page and page.current(p.package_dir, key):  # built from these very inputs: not again
        return pose_images.stale(p.package_dir, p.robot)
    fresh = page.build(spec, shown, p.files, p.robot, p.package_dir, lines, len(p.content()), write_page, p.proofs, key)
    if not write_page:
        return page.stale(p.package_dir, fresh) + pose_images.stale(p.package_dir, p.robot)
    bad = page.failed_verdicts(fresh)
    if outcome.failed or bad:
        why = bad[0] if bad else "the package is stale or a check failed"
        return [
            Finding(
                "GEN081",
                "error",
                f"{page.PAGE} not written: {why}",
                "fix what check reports, then run descgen report again",
                f"file:{page.PAGE}",
                Where(str(p.package_dir / page.PAGE)),
            )
        ]
    outcome.written += pose_images.write(p.package_dir, p.robot)  # before the page that embeds them
    outcome.written.append(page.PAGE)
    page.write(p.package_dir, fresh)
    return []


def _stale_meshes(p: Plan) -> list[Finding]:
    """Every mesh copy compared byte for byte with its source beside the spec."""
    found: list[Finding] = []
    for rel, (src, data) in p.meshes.items():
        target = p.package_dir / rel
        where = Where(str(target))
        if not target.is_file():
            found.append(Finding("GEN006", "error", f"{rel} is missing", "run descgen generate", f"file:{rel}", where))
            continue
        now = read_bounded(target, "mesh", MAX_MESH_BYTES)
        if now != data:
            found.append(
                Finding(
                    "GEN060",
                    "error",
                    f"{rel} differs from its source {_shown_source(src, p.package_dir.parent)} "
                    f"(sha256 {_sha256(now)[:12]}... in the package, "
                    f"{_sha256(data)[:12]}... at the source)",
                    "run descgen generate and commit the result; to change a mesh, edit the file beside the spec",
                    f"file:{rel}",
                    where,
                )
            )
    return found


def _stale_evidence(spec: Path, p: Plan, root: Path, refresh: bool = False) -> list[Finding]:
    """The committed control evidence (written by ``descgen control``, not by generate) run
    again from what verdict.json records, and compared like a generated file."""
    from .control.evidence_check import check_evidence

    return check_evidence(p.package_dir, p.robot, spec_display(spec, root), refresh)
