"""Where generated files are written: a package switched as a whole, never file by file.

A spec with ``moveit:`` has two packages; both are built before either is switched
(:func:`write_packages`), so a failure while building changes neither, and a switch that fails
puts the first back; only a run killed between the two switches (two renames) leaves the new
description beside the old MoveIt package, which ``check`` reports as stale.

The complete new package (the old one's files, minus ours that changed or went stale, plus the
new files) is built in a scratch folder ``<out>/.descgen-new-*`` on the same file system, then
swapped with the package folder in one step (Linux ``renameat2(RENAME_EXCHANGE)``), or where that
is missing by two renames through ``.descgen-old-*``. A reader sees the old set or the new set,
never a mix. A run killed or failing at any point leaves at worst scratch folders, which the
next run removes (putting back a package that was moved aside and not replaced) before it writes.

The package folder must not be, nor hold, a link or a special file: generate and check
refuse it before reading or writing anything (GEN040-GEN043), so nothing is read or written
outside the output root.
"""

from __future__ import annotations

import contextlib
import ctypes
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

from descgen.codes import Code
from descgen.codes.generate import GEN040, GEN041, GEN042, GEN043, GEN044
from descgen.core.findings import Finding, InputError, Where, errors
from descgen.core.model import Robot
from descgen.infra import interruptions
from descgen.infra.safeio import read_bounded
from descgen.meshes.paths import MAX_MESH_BYTES, MESH_FOLDER, own_meshes
from descgen.render import header
from descgen.spec.files import default_out


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


# --- the robot's own meshes: copied byte for byte, their hashes in a manifest -----------------------

# Binary files carry no header, so the package records what generate copied: check compares
# copies and sources, generate tells a copy edited in the package from a changed source, and a
# mesh no longer used is removed like any file descgen no longer generates.
MANIFEST = f"{MESH_FOLDER}/meshes.sha256"
_MANIFEST_LINE = re.compile(r"([0-9a-f]{64})  (\S.*)")


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def mesh_copies(robot: Robot, root: Path) -> dict[str, tuple[Path, bytes]]:
    """Package path -> (source, bytes) of every mesh to copy, each read with a bound."""
    return {
        rel: (src, read_bounded(src, "mesh", MAX_MESH_BYTES, display=shown_source(src, root)))
        for rel, src in sorted(own_meshes(robot).items())
    }


def shown_source(src: Path, root: Path) -> str:
    try:
        return src.relative_to(root.resolve().parent).as_posix()
    except ValueError:
        return str(src)


def manifest(meshes: dict[str, tuple[Path, bytes]]) -> str:
    lines = ["# sha256 of every mesh generate copied here, as `sha256sum -c` reads it from the package folder"]
    lines += [f"{sha256(data)}  {rel}" for rel, (_, data) in meshes.items()]
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


def hand_edited(package_dir: Path, files: dict[str, str], meshes: Mapping[str, tuple[Path, bytes]] = {}) -> list[str]:
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
        now = sha256(read_bounded(target, "mesh", MAX_MESH_BYTES))
        if now != sha256(data) and now != recorded.get(rel):
            edited.append(rel)
    return edited


# What generate owns; other commands may add their own evidence to the package.
_OWN_DIRS = {"urdf", "srdf", "config", "launch", "rviz", "package.xml", "CMakeLists.txt", MESH_FOLDER}
_OWN_FILES: set[str] = {"evidence/known_poses.md", "evidence/frames.md", "evidence/frames.dot"}


def ours(package_dir: Path) -> list[str]:
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


def _refusal(code: Code, message: str, hint: str, path: Path) -> Finding:
    return code.finding(message, hint, f"file:{path.name}", Where(str(path)))


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
                GEN041, f"the package folder {package_dir} is a symbolic link (to {target})", _LINK_HINT, package_dir
            )
        ]
    if not package_dir.is_dir():
        return [
            _refusal(
                GEN041,
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
                    found.append(_refusal(GEN040, what, _LINK_HINT, path))
                elif entry.is_dir(follow_symlinks=False):
                    pending.append(path)
                elif not entry.is_file(follow_symlinks=False):
                    what = f"{rel} in {package_dir.name} is not a regular file (a FIFO, socket or device)"
                    found.append(_refusal(GEN043, what, "remove it from the package folder", path))
    return sorted(found, key=lambda f: f.where.file)


def refuse_unsafe(package_dir: Path) -> None:
    """Raise InputError when the package folder is a link, or holds a link or a special file."""
    found = _unsafe_entries(package_dir)
    if found:
        raise InputError(found)


def output_root(spec: Path, out_root: Path | None) -> Path | None:
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
                    GEN042,
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
                        GEN044,
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
    out.removed = [rel for rel in ours(package_dir) if rel not in files]
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
            [_refusal(GEN042, f"the output root {root} is not a folder", "name a folder with --out", root)]
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
