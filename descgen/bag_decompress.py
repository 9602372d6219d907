"""Decompression of recordings with a bound: what rosbags inflates is never larger than declared.

A rosbag2 recording is data from someone else (docs/security.md), and rosbags (0.11) inflates
whatever it is given, all at once: an MCAP chunk (zstd or lz4) is decompressed whole before its
length is compared with the size the chunk declares; a message of a ``compression_mode: message``
recording is decompressed with no limit; a ``compression_mode: file`` recording is inflated into a
temporary folder before it is opened. A few kilobytes of zstd can hold gigabytes of zeros, so a
hostile or damaged recording could exhaust the memory or the disk of the machine auditing it.

:func:`install` replaces those three decompressors, in rosbags' modules, by bounded ones:

- a chunk is inflated to at most one byte more than it declares, and a chunk declaring more
  than :data:`MAX_CHUNK_BYTES` is refused before anything is inflated (rosbags then reports
  the length mismatch as it always did; honest chunks give the same bytes as before);
- a message is inflated to at most :data:`MAX_MESSAGE_BYTES`;
- a compressed file is inflated to at most :data:`MAX_FILE_BYTES`.

What goes over is a ``ReaderError`` (BAG001 for tf-audit; descgen/tf/bagaudit.py). The bounds
are far above what rosbag2 writes: its MCAP chunks are about 1 MB (``chunk_size`` defaults to
768 KiB; the zstd presets use 4 MiB) and a message is one sensor sample.
"""

from __future__ import annotations

import threading
from typing import Any

MIB = 1 << 20
MAX_CHUNK_BYTES = 256 * MIB
MAX_MESSAGE_BYTES = 256 * MIB
MAX_FILE_BYTES = 16 * 1024 * MIB

_LOCK = threading.Lock()
_INSTALLED: list[bool] = []


def install() -> None:
    """Put the bounded decompressors in rosbags' reader modules (once per process; idempotent)."""
    with _LOCK:
        if _INSTALLED:
            return
        from rosbags.rosbag2 import reader, storage_mcap

        storage_mcap.DECOMPRESSORS["zstd"] = _zstd_chunk
        storage_mcap.DECOMPRESSORS["lz4"] = _lz4_chunk
        setattr(reader, "zstd", _BoundedZstd(getattr(reader, "zstd")))  # noqa: B009, B010  (not re-exported)
        _INSTALLED.append(True)


def _error(message: str) -> Exception:
    from rosbags.rosbag2 import ReaderError

    return ReaderError(message)


def _declared(size: int) -> int:
    """The most a chunk declaring ``size`` bytes is inflated to: one byte more tells a chunk
    that holds more than it says (rosbags refuses it for the mismatch)."""
    if not 0 <= size <= MAX_CHUNK_BYTES:
        raise _error(
            f"an MCAP chunk declares {size / MIB:.0f} MiB uncompressed; descgen reads chunks of at most "
            f"{MAX_CHUNK_BYTES // MIB} MiB (re-record with a smaller chunk_size, or `ros2 bag convert` the recording)"
        )
    return size + 1


def zstd_at_most(data: bytes, limit: int) -> bytes:
    """``zstd.decompress(data)`` (every frame, skippable frames too) cut at ``limit`` bytes:
    never more than ``limit`` bytes are inflated."""
    zstd = _zstd_module()
    out: list[bytes] = []
    room = limit
    rest = data
    while rest and room > 0:
        d = zstd.ZstdDecompressor()
        part = d.decompress(rest, max_length=room)
        out.append(part)
        room -= len(part)
        if not d.eof:
            if room > 0:  # wanted more and the input ended: what zstd.decompress refuses too
                raise _error("zstd data ends before its frame does")
            break
        rest = d.unused_data
    return b"".join(out)


def _zstd_module() -> Any:
    """The zstd module rosbags itself uses (the standard library's from Python 3.14)."""
    from rosbags.rosbag2 import storage_mcap

    return getattr(storage_mcap, "zstd")  # noqa: B009  (not re-exported; the module rosbags imported)


def lz4_at_most(data: bytes, limit: int) -> bytes:
    """``lz4.frame.decompress(data)`` (the first frame, as rosbags reads it) cut at ``limit`` bytes."""
    from lz4.frame import LZ4FrameDecompressor  # type: ignore[import-untyped]

    d = LZ4FrameDecompressor()
    out: bytes = d.decompress(data, max_length=limit)
    if not d.eof and len(out) < limit:
        raise _error("lz4 data ends before its frame does")
    return out


def _zstd_chunk(data: bytes, size: int) -> bytes:
    return zstd_at_most(data, _declared(size))


def _lz4_chunk(data: bytes, size: int) -> bytes:
    return lz4_at_most(data, _declared(size))


class _BoundedZstd:
    """Stands for the ``zstd`` module in rosbags' reader: ``decompress`` (one message of a
    ``message``-compressed recording) and ``open`` (a ``file``-compressed one) are bounded;
    anything else is the module's own."""

    def __init__(self, module: Any) -> None:
        self._module = module

    def __getattr__(self, name: str) -> Any:
        return getattr(self._module, name)

    def decompress(self, data: bytes) -> bytes:
        out = zstd_at_most(data, MAX_MESSAGE_BYTES + 1)
        if len(out) > MAX_MESSAGE_BYTES:
            raise _error(f"a compressed message inflates to more than {MAX_MESSAGE_BYTES // MIB} MiB")
        return out

    def open(self, file: Any, mode: str = "rb") -> _AtMost:
        return _AtMost(self._module.open(file, mode), MAX_FILE_BYTES)


class _AtMost:
    """A decompressing file that refuses to give more than ``limit`` bytes in all."""

    def __init__(self, inner: Any, limit: int) -> None:
        self._inner = inner
        self._left = limit
        self._limit = limit

    def __enter__(self) -> _AtMost:
        return self

    def __exit__(self, *exc: object) -> None:
        self._inner.close()

    def close(self) -> None:
        self._inner.close()

    def read(self, size: int = -1) -> bytes:
        want = self._left + 1 if size is None or size < 0 or size > self._left else size
        data: bytes = self._inner.read(want)
        self._left -= len(data)
        if self._left < 0:
            raise _error(f"a compressed recording file inflates to more than {self._limit // MIB} MiB")
        return data

    def readinto(self, buffer: Any) -> int:
        data = self.read(len(buffer))
        buffer[: len(data)] = data
        return len(data)
