"""Vector BLF → frame columns in bulk. python-can's BLFReader builds a Message per frame (the
bottleneck); this reader walks the objects of many decompressed log containers in one light loop
(position, header version, type) and reads every field with NumPy at those offsets. It reads
exactly what python-can's BLFReader reads (the same object types, fields, time stamps and
channel numbers; tests/logs compares the two): CAN_MESSAGE/2, CAN_ERROR_EXT, CAN_FD_MESSAGE and
CAN_FD_MESSAGE_64; other objects are skipped."""

from __future__ import annotations

import datetime
import struct
import zlib
from collections.abc import Iterator
from typing import IO

import numpy as np

from canspec.ir.ids import MAX_EXTENDED_ID
from canspec.logs import frames as fr
from canspec.logs.candump import DATA, ERROR, MAX_DATA, REMOTE

FILE_HEADER = struct.Struct("<4sLBBBBBBBBQQLL8H8H")
OBJ_BASE = struct.Struct("<4sHHLL")
CONTAINER = struct.Struct("<H6xL4x")
FD_64 = struct.Struct("<BBBBLLLLLLLHBBL")
CAN_MESSAGE, LOG_CONTAINER, CAN_ERROR_EXT, CAN_MESSAGE2, CAN_FD_MESSAGE, CAN_FD_MESSAGE_64 = 1, 10, 73, 86, 100, 101
FRAME_TYPES = frozenset((CAN_MESSAGE, CAN_ERROR_EXT, CAN_MESSAGE2, CAN_FD_MESSAGE, CAN_FD_MESSAGE_64))
NO_COMPRESSION, ZLIB_DEFLATE = 0, 2
CAN_MSG_EXT, REMOTE_FLAG = 0x80000000, 0x80
BUFFER_BYTES = 8 << 20  # decompressed objects per bulk step


class BlfError(ValueError):
    pass


def _start_time(header: tuple[int, ...]) -> float:
    """The file header's start SYSTEMTIME as a POSIX time stamp (UTC; 0 when invalid)."""
    y, mo, _, d, h, mi, s, ms = header[14:22]
    try:
        return datetime.datetime(y, mo, d, h, mi, s, ms * 1000, tzinfo=datetime.timezone.utc).timestamp()
    except ValueError:
        return 0.0


def read_blf(stream: IO[bytes]) -> Iterator[tuple[fr.Batch, int, list[tuple[int, str]]]]:
    """(batch, objects walked, problems as (record, text)) per bulk step. A file that ends inside
    an object, or an object that claims more bytes than follow, is one problem (the frames before
    it are read): python-can drops the rest silently."""
    head = stream.read(FILE_HEADER.size)
    if len(head) < FILE_HEADER.size:
        raise BlfError("truncated BLF file header")
    header = FILE_HEADER.unpack(head)
    if header[1] < FILE_HEADER.size:
        raise BlfError(f"BLF file header of {header[1]} bytes (at least {FILE_HEADER.size})")
    stream.read(header[1] - FILE_HEADER.size)
    start = _start_time(header)
    pending, size, tail, record, at = [], 0, b"", 0, header[1]
    while True:
        base = stream.read(OBJ_BASE.size)
        cut = skipped = ""  # why the file stops here; why a container's frames are not read
        if base:
            if len(base) < OBJ_BASE.size or base[:4] != b"LOBJ":
                raise BlfError("expected a BLF object ('LOBJ') in the file")
            _, _, _, obj_size, obj_type = OBJ_BASE.unpack(base)
            cut, body = _body(stream, obj_size, at)
            if obj_type == LOG_CONTAINER and len(body) >= CONTAINER.size:
                method, _ = CONTAINER.unpack_from(body)
                if method in (NO_COMPRESSION, ZLIB_DEFLATE):
                    pending.append(body[CONTAINER.size:] if method == NO_COMPRESSION else zlib.decompressobj().decompress(body[CONTAINER.size:]))
                    size += len(pending[-1])
                else:  # python-can skips it silently
                    skipped = f"the BLF log container at byte {at} has unknown compression method {method} (0 none, 2 zlib); its frames are not read"
            at += obj_size + obj_size % 4
            if size < BUFFER_BYTES and not cut and not skipped:
                continue
        buf = tail + b"".join(pending)  # a problem flushes the buffer first, so it is placed after the frames before it
        pending, size = [], 0
        batch, consumed = _objects(buf, start, record)
        tail = buf[consumed:]
        record += len(batch)
        # the end of the file, or an object longer than a bulk step (a bad size: memory would grow to it)
        lost = cut or _incomplete(tail, not base or len(tail) > BUFFER_BYTES)
        yield batch, len(batch), [(record + 1, problem) for problem in (skipped, lost) if problem]
        if not base or lost:
            return


def _body(stream: IO[bytes], obj_size: int, at: int) -> tuple[str, bytes]:
    """(why the file stops at this object, or ""; the object's bytes after its base header)."""
    if obj_size < OBJ_BASE.size:  # python-can fails on a negative read; the next object cannot be found
        return f"the BLF object at byte {at} claims {obj_size} bytes, less than its {OBJ_BASE.size}-byte header; the rest of the file is not read", b""
    body = stream.read(obj_size - OBJ_BASE.size)
    stream.read(obj_size % 4)
    if len(body) < obj_size - OBJ_BASE.size:
        return f"truncated BLF file: it ends inside the object at byte {at} ({obj_size - OBJ_BASE.size - len(body)} of its {obj_size} bytes missing)", body
    return "", body


def _incomplete(tail: bytes, final: bool) -> str:
    """What is wrong with the object left over at the start of `tail` once nothing more comes ("" if
    nothing: up to 8 bytes of padding)."""
    found = tail.find(b"LOBJ", 0, 8)
    if not final or found < 0:
        return ""
    if len(tail) - found < OBJ_BASE.size:
        return f"a BLF object header is cut short; the rest of the file ({len(tail)} bytes) is not read"
    claimed = OBJ_BASE.unpack_from(tail, found)[3]
    return f"a BLF object claims {claimed} bytes but {len(tail) - found} follow; the rest of the file ({len(tail)} bytes) is not read"


def _walk(buf: bytes) -> tuple[list[int], list[int], list[int], list[int], int]:
    """Positions, header versions, types and sizes of the frame objects, and where the first
    incomplete object starts (python-can's walk: the next object starts within 8 bytes)."""
    positions: list[int] = []
    versions: list[int] = []
    types: list[int] = []
    sizes: list[int] = []
    unpack, n, pos = OBJ_BASE.unpack_from, len(buf), 0
    while True:
        found = buf.find(b"LOBJ", pos, pos + 8)
        if found < 0:
            if pos + 8 > n:
                return positions, versions, types, sizes, pos
            raise BlfError("could not find the next BLF object")
        if found + OBJ_BASE.size > n:
            return positions, versions, types, sizes, pos
        _, _, version, obj_size, obj_type = unpack(buf, found)
        if obj_size < OBJ_BASE.size:
            raise BlfError(f"BLF object of {obj_size} bytes")
        if found + obj_size > n:
            return positions, versions, types, sizes, pos
        if obj_type in FRAME_TYPES and version in (1, 2):
            positions.append(found)
            versions.append(version)
            types.append(obj_type)
            sizes.append(obj_size)
        pos = found + obj_size


def _uint(b: np.ndarray, at: np.ndarray, nbytes: int) -> np.ndarray:
    """Little-endian unsigned integers of `nbytes` bytes at byte offsets `at`."""
    cells = b[at[:, None] + np.arange(nbytes)].astype(np.uint64)
    return np.bitwise_or.reduce(cells << (np.arange(nbytes, dtype=np.uint64) * np.uint64(8)), axis=1, initial=np.uint64(0))


BYTE_MASKS = np.array([(1 << 8 * k) - 1 for k in range(8)] + [2**64 - 1], dtype=np.uint64)


def _objects(buf: bytes, start: float, first: int) -> tuple[fr.Batch, int]:
    positions, versions, types, sizes, consumed = _walk(buf)
    b = np.frombuffer(buf + bytes(96), dtype=np.uint8)  # spare bytes: fixed-width reads past a short object stay in bounds
    p, v, t = (np.array(x, dtype=np.int64) for x in (positions, versions, types))
    d = p + OBJ_BASE.size + np.where(v == 1, 16, 24)  # the object's own fields
    ten_us = _uint(b, p + 16, 4) == 1
    timestamp = _uint(b, p + 24, 8).astype(np.float64) * np.where(ten_us, 1e-5, 1e-9) + start
    # the channel: 16 bits, but 8 in a CAN_FD_MESSAGE_64 (its DLC follows)
    channel = np.where(t == CAN_FD_MESSAGE_64, b[d], _uint(b, d, 2)).astype(np.int64) - 1
    classic, error, fd = np.isin(t, (CAN_MESSAGE, CAN_MESSAGE2)), t == CAN_ERROR_EXT, t == CAN_FD_MESSAGE
    flags = b[d + 2]
    frame_id = _uint(b, np.where(error, d + 16, d + 4), 4)
    length = np.where(classic, np.minimum(b[d + 3], 8), np.where(fd, np.minimum(b[d + 14], MAX_DATA), 0)).astype(np.int64)
    remote = (classic | fd) & (flags & REMOTE_FLAG > 0)
    word = _uint(b, np.where(fd, d + 20, d + 8), 8)
    kind = np.where(error, ERROR, np.where(remote, REMOTE, DATA)).astype(np.uint8)
    fd_flags = np.where(fd, b[d + 13] & 7, 0).astype(np.uint8)  # EDL, BRS, ESI: frames.FD, BRS, ESI
    long64 = {}
    for i in np.flatnonzero(t == CAN_FD_MESSAGE_64).tolist():
        frame_id[i], kind[i], fd_flags[i], payload = _fd64(buf, positions[i], int(d[i]), sizes[i])
        length[i], word[i] = len(payload), int.from_bytes(payload[:8], "little")
        if len(payload) > 8:
            long64[i] = payload
    length = np.where(kind == DATA, length, 0)
    word = np.where(kind == DATA, word & BYTE_MASKS[np.minimum(length, 8)], np.uint64(0))
    names, codes = np.unique(channel, return_inverse=True)
    batch = fr.Batch(
        timestamp, codes.astype(np.int32), (frame_id & np.uint64(MAX_EXTENDED_ID)).astype(np.uint32), (frame_id & np.uint64(CAN_MSG_EXT)) > 0,
        kind, length.astype(np.uint8), word, np.arange(first + 1, first + len(p) + 1, dtype=np.int64), fd_flags,
        channels=tuple(str(c) for c in names.tolist()), data=_fd_data(b, d, fd & (length > 8), length, long64),
    )
    return batch, consumed


def _fd_data(b: np.ndarray, d: np.ndarray, long_fd: np.ndarray, length: np.ndarray, long64: dict[int, bytes]) -> np.ndarray | None:
    """The data matrix of the frames longer than 8 bytes (None when there are none): CAN_FD_MESSAGE's
    64-byte field at +20, cut at its valid bytes; CAN_FD_MESSAGE_64's bytes as read."""
    if not long_fd.any() and not long64:
        return None
    data = np.zeros((len(d), MAX_DATA), np.uint8)
    rows = np.flatnonzero(long_fd)
    cells = b[(d[rows] + 20)[:, None] + np.arange(MAX_DATA)]
    data[rows] = np.where(np.arange(MAX_DATA) < length[rows][:, None], cells, 0)
    for i, payload in long64.items():
        data[i, : len(payload)] = np.frombuffer(payload, np.uint8)
    return data


def _fd64(buf: bytes, pos: int, at: int, obj_size: int) -> tuple[int, int, int, bytes]:
    """(id, kind, FD/BRS/ESI flags, data) of a CAN_FD_MESSAGE_64, as python-can reads it (data cut at 64 bytes)."""
    _, _, valid, _, can_id, _, fd_flags, _, _, _, _, _, _, ext_offset, _ = FD_64.unpack_from(buf, at)
    header_size = int.from_bytes(buf[pos + 4: pos + 6], "little")
    field = min(valid, (ext_offset or obj_size) - header_size - FD_64.size)
    data = buf[at + FD_64.size: at + FD_64.size + max(field, 0)].ljust(valid, b"\0")
    kind = REMOTE if fd_flags & 0x0010 else DATA
    return can_id, kind, (fd_flags >> 12) & 7, data[:MAX_DATA]
