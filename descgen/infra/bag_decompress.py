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
- the compressed files of one recording are inflated to at most :data:`MAX_FILE_BYTES` in all;
- a recording whose chunks, by their index, would be held inflated at the same time beyond
  :data:`MAX_LIVE_BYTES` is refused before any is inflated (rosbags merges the chunks of a file
  by time and holds each from its first message to its last);
- a chunk or message of more than :data:`MAX_FRAMES` zstd frames is refused (rosbags writes one
  a chunk; each further frame costs a copy of the rest of the input).

Output is produced in steps of :data:`STEP` bytes, so no bound is reserved up front.
:func:`open_reader` is the one way descgen opens a recording.

What goes over is a ``ReaderError`` (BAG001 for tf-audit; descgen/commands/tf/bagaudit.py). The bounds
are far above what rosbag2 writes: its MCAP chunks are about 1 MB (``chunk_size`` defaults to
768 KiB; the zstd presets use 4 MiB) and a message is one sensor sample.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

MIB = 1 << 20
MAX_CHUNK_BYTES = 256 * MIB
MAX_MESSAGE_BYTES = 256 * MIB
MAX_FILE_BYTES = 16 * 1024 * MIB
MAX_LIVE_BYTES = 1024 * MIB
MAX_FRAMES = 256
STEP = 8 * MIB

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


def open_reader(bag: Path) -> Any:
    """rosbags' ``Reader`` of the rosbag2 folder ``bag``, opened with the bounds installed and
    checked against its chunk index; the caller closes it. rosbags' own errors pass through."""
    from rosbags.rosbag2 import Reader

    install()
    _FILES[0] = _Budget(MAX_FILE_BYTES)  # one recording's compressed files share one bound
    reader = Reader(bag)
    reader.open()
    try:
        inner = reader.storage  # a rosbag2 folder's reader, holding one storage reader a file
        for storage in getattr(inner, "storages", None) or [inner]:
            _check_live(getattr(storage, "chunks", ()))  # an MCAP file's chunk index (sqlite3 has none)
    except Exception:
        reader.close()
        raise
    return reader


def _check_live(chunks: Any) -> None:
    """Refuse chunks that would be held inflated at the same time beyond MAX_LIVE_BYTES:
    each from its first message time to its last (both included), as the merge holds them."""
    events = []
    for c in chunks:
        events.append((c.message_start_time, 0, c.uncompressed_size))
        events.append((c.message_end_time, 1, -c.uncompressed_size))
    live = 0
    for _, _, size in sorted(events):  # a start before an end at the same time: both are held
        live += size
        if live > MAX_LIVE_BYTES:
            raise _error(
                f"the recording's chunks overlap in time so that more than {MAX_LIVE_BYTES // MIB} MiB of them "
                "would be held inflated at once (`ros2 bag convert` it into time-ordered chunks)"
            )


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
    never more than ``limit`` bytes are inflated, and at most MAX_FRAMES frames read."""
    zstd = _zstd_module()
    out: list[bytes] = []
    room = limit
    rest = data
    frames = 0
    while rest and room > 0:
        frames += 1
        if frames > MAX_FRAMES:
            raise _error(f"more than {MAX_FRAMES} zstd frames in one chunk or message")
        d = zstd.ZstdDecompressor()
        room = _one_frame(d, rest, room, out)
        if not d.eof:
            if room > 0:  # wanted more and the input ended: what zstd.decompress refuses too
                raise _error("zstd data ends before its frame does")
            break
        rest = d.unused_data
    return b"".join(out)


def _one_frame(d: Any, data: bytes, room: int, out: list[bytes]) -> int:
    """Inflate one frame of ``data`` with the decompressor ``d`` (zstd's or lz4's, which share
    this interface) into ``out``, in steps of at most STEP bytes, until the frame ends, the
    input runs out or ``room`` is used up; the room left."""
    feed = data
    while room > 0 and not d.eof:
        part: bytes = d.decompress(feed, max_length=min(room, STEP))
        feed = b""
        out.append(part)
        room -= len(part)
        if not part and d.needs_input:
            break
    return room


def _zstd_module() -> Any:
    """The zstd module rosbags itself uses (the standard library's from Python 3.14)."""
    from rosbags.rosbag2 import storage_mcap

    return getattr(storage_mcap, "zstd")  # noqa: B009  (not re-exported; the module rosbags imported)


def lz4_at_most(data: bytes, limit: int) -> bytes:
    """``lz4.frame.decompress(data)`` (the first frame, as rosbags reads it) cut at ``limit`` bytes."""
    from lz4.frame import LZ4FrameDecompressor  # type: ignore[import-untyped]

    d = LZ4FrameDecompressor()
    out: list[bytes] = []
    room = _one_frame(d, data, limit, out)
    if not d.eof and room > 0:
        raise _error("lz4 data ends before its frame does")
    return b"".join(out)


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
        return _AtMost(self._module.open(file, mode), _FILES[0])


class _Budget:
    """What the compressed files of one recording may still inflate to."""

    def __init__(self, limit: int) -> None:
        self.left = limit
        self.limit = limit


_FILES = [_Budget(MAX_FILE_BYTES)]  # the recording open_reader is opening


class _AtMost:
    """A decompressing file that refuses to give more than its budget has left."""

    def __init__(self, inner: Any, budget: _Budget) -> None:
        self._inner = inner
        self._budget = budget

    def __enter__(self) -> _AtMost:
        return self

    def __exit__(self, *exc: object) -> None:
        self._inner.close()

    def close(self) -> None:
        self._inner.close()

    def read(self, size: int | None = -1) -> bytes:
        if size is None or size < 0:  # all of it, in steps, each counted
            parts = []
            while part := self.read(STEP):
                parts.append(part)
            return b"".join(parts)
        budget = self._budget
        data: bytes = self._inner.read(min(size, budget.left + 1))
        budget.left -= len(data)
        if budget.left < 0:
            raise _error(f"the recording's compressed files inflate to more than {budget.limit // MIB} MiB")
        return data
