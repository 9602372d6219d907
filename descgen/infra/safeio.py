"""Reading a file the user named without hanging, exhausting memory or crashing.

A path on the command line may name a FIFO (a read blocks forever), a device
(``/dev/zero`` never ends), a folder, a 1 GB file or a name longer than the OS allows.
So the file's type and size are checked before it is read, it is opened with
``O_NONBLOCK`` (a FIFO swapped in after the check cannot block the open), its type is
checked again on the open descriptor, and at most ``limit + 1`` bytes are read. Every
``OSError`` becomes an :class:`InputError` (exit 2, one located line), never a traceback.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from descgen.codes import Code
from descgen.codes.read import READ001, READ040, READ041, READ044
from descgen.core.findings import InputError, Where
from descgen.core.record import record

MIB = 1024 * 1024
MAX_DESCRIPTION_BYTES = 64 * MIB  # URDF, SRDF, Xacro, controllers YAML: the largest real ones are a few MB
_CHUNK = 1 * MIB


@record
class Codes:
    """The finding codes a reader reports; the spec loader keeps its YAML codes."""

    unreadable: Code = READ001
    not_regular: Code = READ040
    too_large: Code = READ041


READ_CODES = Codes()


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def _error(code: Code, message: str, hint: str, shown: str) -> InputError:
    return InputError([code.finding(message, hint, "file", Where(shown))])


def _unreadable(exc: OSError | ValueError, codes: Codes, shown: str) -> InputError:
    if isinstance(exc, FileNotFoundError):
        return _error(codes.unreadable, "file not found", "check the path", shown)
    # ValueError: a NUL byte in the path; OSError: ENAMETOOLONG, EACCES, ELOOP, EIO, ...
    reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
    return _error(codes.unreadable, f"cannot read the file: {reason}", "check the path and its permissions", shown)


def _not_regular(mode: int, what: str, codes: Codes, shown: str) -> InputError:
    kind = _kind(mode)
    message = f"is {kind}, not a regular file" if kind.startswith("a ") else f"is {kind}"
    return _error(codes.not_regular, message, f"name the {what} file itself", shown)


def _too_large(size: int, what: str, limit: int, codes: Codes, shown: str) -> InputError:
    return _error(
        codes.too_large,
        f"file is {size / 1e6:.1f} MB; a {what} file is at most {limit / MIB:g} MiB",
        "is this the right file?",
        shown,
    )


def read_bounded(
    path: Path,
    what: str,
    limit: int = MAX_DESCRIPTION_BYTES,
    *,
    display: str | None = None,
    codes: Codes = READ_CODES,
) -> bytes:
    """The bytes of the regular file ``path`` (``what`` names it in messages: "URDF").

    Raises :class:`InputError` for anything that is not a readable regular file of at most
    ``limit`` bytes, before reading it where possible."""
    shown = display if display is not None else str(path)
    check_file(path, what, limit, display=shown, codes=codes)
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        fd = os.open(path, flags)
    except (OSError, ValueError) as exc:
        raise _unreadable(exc, codes, shown) from None
    try:
        now = os.fstat(fd)  # the file may have been swapped since the stat above
        if not stat.S_ISREG(now.st_mode):
            raise _not_regular(now.st_mode, what, codes, shown)
        data = _read_at_most(fd, limit + 1)
    except OSError as exc:
        raise _unreadable(exc, codes, shown) from None
    finally:
        os.close(fd)
    if len(data) > limit:  # it grew after the stat
        raise _too_large(len(data), what, limit, codes, shown)
    return data


def check_file(
    path: Path,
    what: str,
    limit: int = MAX_DESCRIPTION_BYTES,
    *,
    display: str | None = None,
    codes: Codes = READ_CODES,
) -> None:
    """Refuse (InputError) what :func:`read_bounded` would refuse, from ``stat`` alone: for a
    file that another library opens itself (xacro)."""
    shown = display if display is not None else str(path)
    try:
        st = os.stat(path)  # follows symlinks: a link to a regular file is fine
    except (OSError, ValueError) as exc:
        raise _unreadable(exc, codes, shown) from None
    if not stat.S_ISREG(st.st_mode):
        raise _not_regular(st.st_mode, what, codes, shown)
    if st.st_size > limit:
        raise _too_large(st.st_size, what, limit, codes, shown)


def _read_at_most(fd: int, n: int) -> bytes:
    chunks: list[bytes] = []
    left = n
    while left > 0:
        chunk = os.read(fd, min(_CHUNK, left))
        if not chunk:
            break
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def read_head(path: Path, n: int) -> bytes:
    """The first ``n`` bytes of a regular file, or b"" when it is not one or cannot be read
    (for guessing a file's kind; the real read reports the problem)."""
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return b""
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOCTTY", 0))
    except (OSError, ValueError):
        return b""
    try:
        return _read_at_most(fd, n) if stat.S_ISREG(os.fstat(fd).st_mode) else b""
    except OSError:
        return b""
    finally:
        os.close(fd)


# --- folders the user named, and the files written for them -------------------------------------


def within(path: str, folder: str) -> bool:
    """Whether the real path ``path`` is ``folder`` or below it (both real, absolute); the
    separator matters: ``/a/pkg_evil`` is not inside ``/a/pkg``."""
    return path == folder or path.startswith(folder.rstrip("/") + "/")


def inside(path: Path, folder: Path) -> bool:
    """Whether ``path``, every symbolic link resolved, lies inside ``folder`` (also resolved):
    a link out of a folder the user named is not in it, a link within it is. False for a path
    that cannot be resolved (a NUL byte, a link loop)."""
    try:
        return within(os.path.realpath(path), os.path.realpath(folder))
    except (OSError, ValueError):
        return False


def refuse_outside(path: Path, folder: Path, what: str, *, code: Code, display: str | None = None) -> None:
    """InputError ``code`` when ``path`` (links resolved) leaves ``folder``: a file of a folder
    the user named is read only when it is really in that folder (docs/security.md)."""
    if inside(path, folder):
        return
    shown = display if display is not None else str(path)
    raise _error(
        code,
        f"the {what} is a symbolic link out of {folder}; only files inside it are read",
        f"copy the file into {folder} instead of linking to it",
        shown,
    )


def read_in_folder(
    path: Path,
    folder: Path,
    what: str,
    limit: int = MAX_DESCRIPTION_BYTES,
    *,
    code: Code = READ044,
    display: str | None = None,
    codes: Codes = READ_CODES,
) -> bytes:
    """:func:`read_bounded` for a file of a folder the user named (``--moveit-config``, a
    template folder): refused (``code``) when a link takes it out of ``folder``. The real path
    is what is opened, so the file checked is the file read."""
    shown = display if display is not None else str(path)
    refuse_outside(path, folder, what, code=code, display=shown)
    try:
        real = Path(os.path.realpath(path))
    except (OSError, ValueError) as exc:
        raise _unreadable(exc, codes, shown) from None
    return read_bounded(real, what, limit, display=shown, codes=codes)


def public_mode() -> int:
    """The mode a file created with ``open()`` gets under this process's umask (0o644 under the
    usual 022): for a file made with ``mkstemp`` (0o600) that users and their tools must read.
    Linux states the umask in /proc; setting it to read it back would race other threads' files."""
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as fh:
            mask = next(int(line.split()[1], 8) for line in fh if line.startswith("Umask:"))
    except (OSError, StopIteration, ValueError, IndexError):
        mask = os.umask(0o022)
        os.umask(mask)
    return 0o666 & ~mask


def output_kind(path: Path) -> str | None:
    """What stands at an output path that must not be replaced: "a symbolic link", "a FIFO
    (named pipe)", "a directory", ... ; None when nothing is there or a regular file is (the
    one kind ``--force`` may replace). ``lstat``: a link is never followed."""
    try:
        st = os.lstat(path)
    except (OSError, ValueError):  # nothing there (or no way there): the write itself reports why
        return None
    if stat.S_ISLNK(st.st_mode):
        return "a symbolic link"
    if stat.S_ISREG(st.st_mode):
        return None
    return _kind(st.st_mode)


def safe_file_name(name: str, suffix: str = "") -> str:
    """A file name for a joint, link or robot name (``name`` + ``suffix``) that is one plain
    component: a name of letters, digits, ``_``, ``-`` and ``.`` (not starting with ``.`` or
    ``-``) is kept as it is; any other (``a/../../x``, ``..``, a non-ASCII or over-long one) is
    written as its safe characters and a hash of the whole name, so two names never share a file
    and no name becomes a path."""
    import hashlib
    import re

    if re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.\-]{0,99}", name) and ".." not in name:
        return name + suffix
    plain = re.sub(r"[^A-Za-z0-9_\-]+", "_", name)[:60].strip("_-") or "name"
    digest = hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:12]
    return f"{plain}~{digest}{suffix}"


def output_file(folder: Path, name: str) -> Path:
    """``folder / name`` for a file descgen writes, checked after resolution: ``name`` is one
    component (no ``/``, not ``.`` or ``..``) and the result, links resolved, is in ``folder``.
    ValueError otherwise: a caller passes names through :func:`safe_file_name` first, so this is
    the last line, never the user's message."""
    if not name or "/" in name or "\x00" in name or name in (".", ".."):
        raise ValueError(f"not a plain file name: {name!r}")
    target = folder / name
    if not inside(target.parent, folder) or os.path.islink(target):
        raise ValueError(f"{target} is not inside {folder}")
    return target
