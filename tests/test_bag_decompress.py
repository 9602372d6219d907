"""A compressed recording inflates to its bound, never to whatever it holds (descgen/infra/bag_decompress.py).

Honest recordings compressed each way rosbag2 compresses them (MCAP chunks, each message, the
whole file) audit exactly as the same recording uncompressed does (the oracle: tf-audit of the
plain recording). Hostile ones, a few kilobytes of zstd holding hundreds of megabytes, are
refused with BAG001 while the audit's peak memory (tracemalloc) stays a small fraction of the
payload; each test first shows that the payload really inflates to that much.
"""

from __future__ import annotations

import os
import struct
import tracemalloc
from pathlib import Path
from typing import Any

import lz4.frame
import pytest
import yaml
from backports import zstd
from rosbags.rosbag2 import CompressionFormat, CompressionMode, Reader, ReaderError, StoragePlugin, Writer, storage_mcap
from rosbags.typesys import Stores, get_typestore

from descgen.audit.spec import load_spec
from descgen.commands.tf import bagaudit, scenario
from descgen.core.findings import InputError
from descgen.infra import bag_decompress

from .conftest import EXAMPLE

ROBOT = load_spec(EXAMPLE).robot
TS = get_typestore(Stores.ROS2_JAZZY)
MIB = 1 << 20
BOMB = 256 * MIB  # what each hostile payload inflates to
SKIPPABLE = 0x184D2A50  # a zstd skippable frame's magic: decoders pass over its content


@pytest.fixture(scope="module")
def plain(tmp_path_factory: pytest.TempPathFactory) -> Path:
    bag = tmp_path_factory.mktemp("plain") / "bag"
    scenario.write(ROBOT, bag, scenario.FAULTS, duration=3.0)
    return bag


def _convert(src: Path, dst: Path, mode: CompressionMode, pad: int = 0) -> None:
    """``src`` written again by rosbags with ``mode`` compression (what ``ros2 bag convert`` does);
    ``pad`` bytes of incompressible data on one more topic make the first chunk large."""
    with Reader(src) as reader:
        conns = list(reader.connections)
        msgs = list(reader.messages())
    writer = Writer(dst, version=8, storage_plugin=StoragePlugin.MCAP)
    writer.set_compression(mode, CompressionFormat.ZSTD)
    with writer:
        new = {c.id: writer.add_connection(c.topic, c.msgtype, typestore=TS) for c in conns}
        if pad:
            filler = writer.add_connection("/filler", "std_msgs/msg/String", typestore=TS)
            text = os.urandom(pad // 2).hex().encode()  # compresses about 2:1 only
            writer.write(filler, msgs[0][1], b"\x00\x01\x00\x00" + struct.pack("<I", pad + 1) + text + b"\x00")
        for c, t, raw in msgs:
            writer.write(new[c.id], t, raw)


def _outcomes(bag: Path) -> tuple[Any, ...]:
    rep = bagaudit.audit(bag, "odom", max_age_ns=100_000_000, keep_results=True)
    return rep.lookups, dict(rep.counts), rep.results


@pytest.mark.parametrize("mode", [CompressionMode.STORAGE, CompressionMode.MESSAGE, CompressionMode.FILE])
def test_an_honest_compressed_recording_audits_as_the_uncompressed_one(
    plain: Path, tmp_path: Path, mode: CompressionMode
) -> None:
    bag = tmp_path / "bag"
    _convert(plain, bag, mode)
    meta = yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    stored = b"".join(p.read_bytes() for p in bag.iterdir() if p.name != "metadata.yaml")
    if mode == CompressionMode.STORAGE:  # the chunks say zstd; the file is plain MCAP
        assert meta["compression_mode"] == "" and b"zstd" in stored
    else:
        assert meta["compression_mode"] == mode.name.lower() and meta["compression_format"] == "zstd"
    expected = _outcomes(plain)
    assert expected[0] > 50 and set(expected[1]) > {"ok"}  # the planted faults give more than ok
    assert _outcomes(bag) == expected


def _peak(fn: Any) -> tuple[int, Any]:
    tracemalloc.start()
    try:
        try:
            result: Any = fn()
        except Exception as exc:  # the outcome is what the test checks
            result = exc
        return tracemalloc.get_traced_memory()[1], result
    finally:
        tracemalloc.stop()


def _bomb(size: int) -> bytes:
    payload = zstd.compress(bytes(size), level=19)
    assert len(payload) < 64 * 1024  # a few kilobytes on disk
    return payload


def _chunk_bomb(src: Path, dst: Path) -> None:
    """``src`` with zstd chunks, its first chunk's records replaced by a zstd frame of BOMB
    zero bytes (then a skippable frame, so the record keeps its length and every offset of
    the file's index stays right) and its CRC cleared; its declared size is left as it was."""
    _convert(src, dst, CompressionMode.STORAGE, pad=200_000)
    (mcap,) = dst.glob("*.mcap")
    data = bytearray(mcap.read_bytes())
    at = 8  # past the magic; then records: opcode (1 byte), length (u64), body
    while data[at] != 0x06:  # the first chunk record
        at += 9 + struct.unpack_from("<Q", data, at + 1)[0]
    body = at + 9
    declared = struct.unpack_from("<QQQI", data, body)[2]
    (name_len,) = struct.unpack_from("<I", data, body + 28)
    assert data[body + 32 : body + 32 + name_len] == b"zstd"
    size_at = body + 32 + name_len
    (compressed,) = struct.unpack_from("<Q", data, size_at)
    bomb = _bomb(BOMB)
    skip = compressed - len(bomb) - 8
    assert skip >= 0, "the chunk compresses to less than the bomb"
    filler = bomb + struct.pack("<II", SKIPPABLE, skip) + bytes(skip)
    data[size_at + 8 : size_at + 8 + compressed] = filler
    struct.pack_into("<I", data, body + 24, 0)  # no CRC: the bound, not the checksum, must stop it
    mcap.write_bytes(bytes(data))
    assert declared < 8 * MIB and len(zstd.decompress(filler)) == BOMB  # the premise


def test_a_chunk_holding_far_more_than_it_declares_is_refused_without_inflating_it(plain: Path, tmp_path: Path) -> None:
    bag = tmp_path / "bag"
    _chunk_bomb(plain, bag)
    peak, outcome = _peak(lambda: bagaudit.audit(bag, "odom"))
    assert isinstance(outcome, InputError), outcome
    (f,) = outcome.findings
    assert f.code == "BAG001" and "size mismatch" in f.message
    assert peak < 32 * MIB, f"{peak / MIB:.0f} MiB"


def test_a_chunk_declaring_more_than_the_bound_is_refused_before_inflating() -> None:
    bag_decompress.install()
    small = zstd.compress(b"x" * 100)
    assert storage_mcap.DECOMPRESSORS["zstd"](small, 100) == b"x" * 100
    assert storage_mcap.DECOMPRESSORS["lz4"](lz4.frame.compress(b"y" * 100), 100) == b"y" * 100
    with pytest.raises(ReaderError, match="at most 256 MiB"):
        storage_mcap.DECOMPRESSORS["zstd"](small, bag_decompress.MAX_CHUNK_BYTES + 1)
    with pytest.raises(ReaderError, match="at most 256 MiB"):
        storage_mcap.DECOMPRESSORS["lz4"](lz4.frame.compress(b"y"), bag_decompress.MAX_CHUNK_BYTES + 1)


def test_an_lz4_chunk_is_cut_at_one_byte_past_its_declared_size() -> None:
    bag_decompress.install()
    payload = lz4.frame.compress(bytes(64 * MIB))
    peak, out = _peak(lambda: storage_mcap.DECOMPRESSORS["lz4"](payload, 1000))
    assert out == bytes(1001)  # rosbags then refuses the chunk for the length mismatch
    assert peak < 4 * MIB


@pytest.mark.parametrize("codec", ["zstd", "lz4"])
def test_a_large_declared_size_reserves_nothing(codec: str) -> None:
    """A tiny frame declaring 200 MiB: the output grows with what inflates, in steps."""
    bag_decompress.install()
    payload = zstd.compress(b"z" * 1000) if codec == "zstd" else lz4.frame.compress(b"z" * 1000)
    peak, out = _peak(lambda: storage_mcap.DECOMPRESSORS[codec](payload, 200 * MIB))
    assert out == b"z" * 1000
    assert peak < 16 * MIB, f"{peak / MIB:.0f} MiB"


def test_a_chunk_of_too_many_frames_is_refused() -> None:
    skippable = struct.pack("<II", SKIPPABLE, 0)
    fine = zstd.compress(b"q") + skippable * (bag_decompress.MAX_FRAMES - 1)
    assert zstd.decompress(fine) == b"q" == bag_decompress.zstd_at_most(fine, 100)
    with pytest.raises(ReaderError, match="zstd frames"):
        bag_decompress.zstd_at_most(fine + skippable, 100)


@pytest.mark.parametrize(("size", "refused"), [(100, False), (101, True)])
def test_the_file_bound_is_exact(size: int, refused: bool) -> None:
    """As rosbags copies a compressed file out (shutil.copyfileobj): a file of exactly the
    bound passes, one byte more does not."""
    import io
    import shutil

    src = bag_decompress._AtMost(io.BytesIO(bytes(size)), bag_decompress._Budget(100))
    if refused:
        with pytest.raises(ReaderError, match="more than"):
            shutil.copyfileobj(src, io.BytesIO(), 7)
    else:
        shutil.copyfileobj(src, io.BytesIO(), 7)
        assert bag_decompress._AtMost(io.BytesIO(bytes(size)), bag_decompress._Budget(100)).read() == bytes(size)


def test_chunks_held_at_once_beyond_the_bound_are_refused_before_inflating(
    plain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Six 16 MiB chunks of one instant: rosbags' merge inflates all six before the first
    message. Each is within the chunk bound; together they are over a 32 MiB live bound, and
    the chunk index says so before anything is inflated."""
    bag = tmp_path / "bag"
    with Reader(plain) as reader:
        conns = list(reader.connections)
        msgs = list(reader.messages())
    writer = Writer(bag, version=8, storage_plugin=StoragePlugin.MCAP)
    writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    big = b"\x00\x01\x00\x00" + struct.pack("<I", 16 * MIB + 1) + bytes(16 * MIB) + b"\x00"
    with writer:
        new = {c.id: writer.add_connection(c.topic, c.msgtype, typestore=TS) for c in conns}
        filler = writer.add_connection("/filler", "std_msgs/msg/String", typestore=TS)
        for _ in range(6):
            writer.write(filler, msgs[0][1], big)
        for c, t, raw in msgs:
            writer.write(new[c.id], t, raw)
    expected = _outcomes(plain)
    assert _outcomes(bag) == expected  # within the default bound: audited as the plain one
    monkeypatch.setattr(bag_decompress, "MAX_LIVE_BYTES", 32 * MIB)
    peak, outcome = _peak(lambda: bagaudit.audit(bag, "odom"))
    assert isinstance(outcome, InputError), outcome
    (f,) = outcome.findings
    assert f.code == "BAG001" and "overlap in time" in f.message
    assert peak < 8 * MIB, f"{peak / MIB:.0f} MiB"


def test_control_evidence_is_read_within_the_bound(plain: Path, tmp_path: Path) -> None:
    """`check` reads the committed control recording back (descgen/commands/control/evidence_check.py):
    a bomb there is refused as one in tf-audit."""
    from descgen.commands.control import evidence_check

    bag = tmp_path / "bag"
    _chunk_bomb(plain, bag)
    peak, outcome = _peak(lambda: evidence_check._messages(bag))
    assert isinstance(outcome, ValueError) and "size mismatch" in str(outcome), outcome
    assert peak < 32 * MIB, f"{peak / MIB:.0f} MiB"


@pytest.mark.parametrize(
    ("frames", "expected"),
    [
        ([b"a" * 1000, b"b" * 10], b"a" * 1000 + b"b" * 10),  # every frame, as zstd.decompress
        ([b"c" * 5], b"c" * 5),
    ],
)
def test_zstd_at_most_reads_every_frame_as_zstd_decompress(frames: list[bytes], expected: bytes) -> None:
    data = b"".join(zstd.compress(f) for f in frames) + struct.pack("<II", SKIPPABLE, 4) + b"pad!"
    assert zstd.decompress(data) == expected  # the oracle
    assert bag_decompress.zstd_at_most(data, 10**6) == expected
    assert bag_decompress.zstd_at_most(data, 7) == expected[:7]


def test_truncated_zstd_is_refused() -> None:
    data = zstd.compress(bytes(range(256)) * 100)
    with pytest.raises(ReaderError, match="ends before"):
        bag_decompress.zstd_at_most(data[: len(data) // 2], 10**6)


def _with_compression_mode(bag: Path, mode: str) -> None:
    meta_file = bag / "metadata.yaml"
    meta = yaml.safe_load(meta_file.read_text())
    info = meta["rosbag2_bagfile_information"]
    info["compression_mode"], info["compression_format"] = mode, "zstd"
    meta_file.write_text(yaml.safe_dump(meta))


def test_a_message_inflating_past_the_bound_is_refused(
    plain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A ``message``-compressed recording whose first message is a bomb (rosbags inflated each
    message with no limit)."""
    monkeypatch.setattr(bag_decompress, "MAX_MESSAGE_BYTES", 8 * MIB)
    bag = tmp_path / "bag"
    with Reader(plain) as reader:
        conns = list(reader.connections)
        msgs = list(reader.messages())
    bomb = _bomb(BOMB)
    with Writer(bag, version=8, storage_plugin=StoragePlugin.MCAP) as writer:
        new = {c.id: writer.add_connection(c.topic, c.msgtype, typestore=TS) for c in conns}
        for i, (c, t, raw) in enumerate(msgs):
            writer.write(new[c.id], t, bomb if i == 0 else zstd.compress(raw))
    _with_compression_mode(bag, "message")
    peak, outcome = _peak(lambda: bagaudit.audit(bag, "odom"))
    assert isinstance(outcome, InputError), outcome
    (f,) = outcome.findings
    assert f.code == "BAG001" and "inflates to more than 8 MiB" in f.message
    assert peak < 32 * MIB, f"{peak / MIB:.0f} MiB"


def test_the_files_of_one_recording_share_the_bound(
    plain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Two compressed files of 5 MiB each under an 8 MiB bound: each alone is within it, the
    recording is not (rosbags inflates every file before it opens any)."""
    monkeypatch.setattr(bag_decompress, "MAX_FILE_BYTES", 8 * MIB)
    bag = tmp_path / "bag"
    _convert(plain, bag, CompressionMode.FILE, pad=5 * MIB)  # one more message of 5 MiB
    (stored,) = bag.glob("*.zstd")
    assert 5 * MIB < len(zstd.decompress(stored.read_bytes())) < 6 * MIB
    one = bagaudit.audit(bag, "odom")  # within the bound alone
    second = stored.with_name("second_" + stored.name)
    second.write_bytes(stored.read_bytes())
    meta_file = bag / "metadata.yaml"
    meta = yaml.safe_load(meta_file.read_text())
    info = meta["rosbag2_bagfile_information"]
    info["relative_file_paths"] = [*info["relative_file_paths"], second.name]
    info["files"] = [*info["files"], {**info["files"][0], "path": second.name}]
    meta_file.write_text(yaml.safe_dump(meta))
    with pytest.raises(InputError) as refused:
        bagaudit.audit(bag, "odom")
    (f,) = refused.value.findings
    assert one.lookups and f.code == "BAG001" and "inflate to more than 8 MiB" in f.message


def test_a_file_inflating_past_the_bound_is_refused(
    plain: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A ``file``-compressed recording whose storage file is a bomb: rosbags inflated it into a
    temporary folder, to whatever size, before opening it."""
    monkeypatch.setattr(bag_decompress, "MAX_FILE_BYTES", 8 * MIB)
    bag = tmp_path / "bag"
    _convert(plain, bag, CompressionMode.FILE)
    (stored,) = bag.glob("*.zstd")
    real = zstd.decompress(stored.read_bytes())
    stored.write_bytes(zstd.compress(real + bytes(BOMB), level=19))
    peak, outcome = _peak(lambda: bagaudit.audit(bag, "odom"))
    assert isinstance(outcome, InputError), outcome
    (f,) = outcome.findings
    assert f.code == "BAG001" and "inflate to more than 8 MiB" in f.message
    assert peak < 32 * MIB, f"{peak / MIB:.0f} MiB"
