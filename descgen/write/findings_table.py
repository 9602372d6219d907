"""The findings table file (``tf-audit --out findings.parquet``): the one place it is written.

Written whole or not at all: row groups go to a temporary file beside it as each recording is
done, and the file is renamed into place only when every recording is in. An existing file is
replaced only with ``--force`` and only when it is a regular file (never a link, folder or device).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any

from descgen.codes.recording import BAG015
from descgen.core.findings import InputError, Where
from descgen.infra.safeio import output_kind, public_mode


def _refuse(path: Path, message: str, hint: str = "choose another --out") -> InputError:
    return InputError([BAG015.finding(message, hint, "option", Where(str(path)))])


def check_out(path: Path, force: bool) -> None:
    """Refuse, before any work, an --out that would not be written (exit 2)."""
    kind = output_kind(path)
    if kind is not None:
        raise _refuse(path, f"--out names {kind}; the table is written only as a regular file")
    if path.exists() and not force:
        raise _refuse(path, f"{path} exists", "choose another --out, or replace it with --force")
    if not path.parent.is_dir():
        raise _refuse(path, f"cannot write {path}: {path.parent} is not a folder")
    if not os.access(path.parent, os.W_OK):
        raise _refuse(path, f"cannot write in {path.parent}: permission denied")


def pyarrow_modules() -> tuple[Any, Any]:
    """pyarrow and pyarrow.parquet, or BAG015 saying how to install them."""
    try:
        import pyarrow
        import pyarrow.parquet as pq
    except ImportError:
        raise InputError(
            [
                BAG015.finding(
                    "--out writes Parquet with pyarrow, which is not installed",
                    "pip install 'descgen[fleet]'",
                    "option",
                    Where("--out"),
                )
            ]
        ) from None
    return pyarrow, pq


class TableFile:
    """``with TableFile(path, schema, force) as f: f.write(table)``; in place when the block ends
    without an error, gone otherwise."""

    def __init__(self, path: Path, schema: Any, force: bool) -> None:
        self.path, self.schema, self.force = path, schema, force
        self.tmp: Path | None = None
        self.writer: Any = None

    def __enter__(self) -> TableFile:
        _, pq = pyarrow_modules()
        check_out(self.path, self.force)
        try:
            fd, tmp = tempfile.mkstemp(prefix=f".{self.path.name}.", dir=self.path.parent)
            os.close(fd)
            self.tmp = Path(tmp)
            self.writer = pq.ParquetWriter(tmp, self.schema, compression="zstd")
        except OSError as exc:
            if self.tmp is not None:
                self.tmp.unlink(missing_ok=True)
            raise _refuse(self.path, f"cannot write {self.path}: {exc.strerror or exc}") from None
        return self

    def write(self, table: Any) -> None:
        if not table.num_rows:
            return
        try:
            self.writer.write_table(table)
        except OSError as exc:  # disk full, a file too large
            raise _refuse(self.path, f"cannot write {self.path}: {exc.strerror or exc}") from None

    def __exit__(self, kind: object, exc: object, tb: object) -> None:
        assert self.tmp is not None
        try:
            self.writer.close()
            if kind is None:
                os.chmod(self.tmp, public_mode())
                check_out(self.path, self.force)  # something swapped in while the audit ran
                os.replace(self.tmp, self.path)
        except OSError as err:
            raise _refuse(self.path, f"cannot write {self.path}: {err.strerror or err}") from None
        finally:
            self.tmp.unlink(missing_ok=True)
