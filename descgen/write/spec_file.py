"""A spec file written whole or not at all (``import -o``, ``descgen fix``): the one place a spec
is written. Only a regular file is ever replaced, never a link, FIFO, device or folder."""

from __future__ import annotations

from pathlib import Path

from descgen.codes.importer import IMP033, IMP034
from descgen.core.findings import InputError, Where
from descgen.infra.safeio import public_mode


def refuse_unsafe_output(path: Path) -> None:
    """IMP033 (exit 2) when ``-o`` names a symbolic link, FIFO, device, socket or folder:
    import writes a spec as a regular file, and ``--force`` replaces only a regular file. Run
    as root, replacing a device (``-o /dev/null``) would break the machine; replacing a link
    would not write where it points, and writing through it would write where nobody asked."""
    from descgen.infra.safeio import output_kind

    kind = output_kind(path)
    if kind is not None:
        raise InputError(
            [
                IMP033.finding(
                    f"-o names {kind}, not a regular file; import writes a spec only as a regular file "
                    "and never replaces anything else (--force included)",
                    "name a new file, or a regular file with --force",
                    "option",
                    Where(str(path)),
                )
            ]
        )


def write_spec(path: Path, text: str) -> None:
    """Write the spec whole or not at all: a temporary file beside it, then a rename. What the
    rename replaces is checked first (only a regular file, never a link, FIFO or device)."""
    import os
    import tempfile

    refuse_unsafe_output(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    except OSError as exc:  # a file in the way of the folder, no permission, a read-only disk
        raise InputError(
            [
                IMP034.finding(
                    f"cannot write the spec there: {exc.strerror or exc}",
                    "choose another -o file",
                    "option",
                    Where(str(path)),
                )
            ]
        ) from None
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        # mkstemp's file is private: a new spec gets what open() would give, a replaced one keeps its mode
        os.chmod(tmp, path.stat().st_mode & 0o7777 if path.is_file() else public_mode())
        refuse_unsafe_output(path)  # swapped in while the spec was written
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
