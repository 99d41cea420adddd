"""Bus logs → batches of frame columns (frames.Batch), read in bounded chunks so memory does not
grow with the log. Formats: candump (every output form, in bulk: candump_bulk), Vector BLF (in bulk:
blf_bulk), Vector ASC and PEAK TRC through python-can's readers, ASAM MF4 through asammdf (whole
columns of the bus-logging groups at once); CAN FD records in every format (up to 64 bytes, the
FD/BRS/ESI flags). Picked by extension (`.gz` too) or by name; `-` is
stdin (text forms). A file that cannot be read, or is not in its format, raises InputError with
one line saying what is wrong."""

from __future__ import annotations

import gc
import gzip
import io
import os
import sys
import zlib
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import IO, Any

import numpy as np

from canspec.ir.ids import MAX_EXTENDED_ID
from canspec.logs import frames as fr
from canspec.logs.candump import DATA, ERROR, REMOTE
from canspec.logs.candump_bulk import read_chunk
from canspec.logs.pycan import trc_version_problem

FORMATS = ("candump", "asc", "blf", "trc", "mf4")
EXTENSIONS = {".log": "candump", ".candump": "candump", ".txt": "candump", ".asc": "asc", ".blf": "blf", ".trc": "trc", ".mf4": "mf4"}
TEXT_FORMATS = ("candump", "asc", "trc")
MAGIC = {"blf": b"LOGG", "mf4": b"MDF     "}
UTF8_BOM = b"\xef\xbb\xbf"
# UTF-32 first: its little-endian mark FF FE 00 00 starts with UTF-16's FF FE
WIDE_BOMS = ((b"\xff\xfe\0\0", "UTF-32"), (b"\0\0\xfe\xff", "UTF-32"), (b"\xff\xfe", "UTF-16"), (b"\xfe\xff", "UTF-16"))
CHUNK_BYTES = 2 << 20  # candump text per bulk step (bounds the working memory)
MF4_CHUNK = 1 << 20  # records per asammdf read (about 90 MiB of 64-byte data records)


class InputError(Exception):
    """The input cannot be read at all (missing, unreadable, not in its format)."""


@dataclass
class Chunk:
    batch: fr.Batch
    problems: list[tuple[int, str]] = field(default_factory=list)  # (line or record, message)
    lines: int = 0  # lines (text) or records read
    position: int | None = None  # bytes of the file read so far (None: stdin), for progress


def detect_format(path: str, forced: str | None) -> str:
    if forced:
        return forced
    if path == "-":
        return "candump"
    stem = path[:-3] if path.lower().endswith(".gz") else path
    ext = os.path.splitext(stem)[1].lower()
    if ext not in EXTENSIONS:
        raise InputError(f"unknown log extension {ext or '(none)'!r}; name the format with --input-format {{{','.join(FORMATS)}}}")
    return EXTENSIONS[ext]


def _open(path: str) -> tuple[IO[bytes], IO[bytes] | None]:
    """The (decompressed) byte stream and the file under it."""
    if path == "-":
        return sys.stdin.buffer, None
    try:
        if os.path.isdir(path):
            raise InputError("is a directory")
        raw = open(path, "rb")  # noqa: SIM115 - closed by the caller
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}") from None
    if path.lower().endswith(".gz"):
        return gzip.open(raw), raw  # type: ignore[return-value]
    return raw, raw


def _head(stream: IO[bytes], fmt: str) -> bytes:
    """The first bytes, checked against the format; the caller re-reads them (all but a UTF-8 byte
    order mark, read past here)."""
    try:
        head = stream.peek(4096)[:4096] if hasattr(stream, "peek") else b""
    except (OSError, EOFError, gzip.BadGzipFile) as exc:
        raise InputError(f"cannot read: {exc}") from None
    if not head:
        raise InputError("empty input")
    magic = MAGIC.get(fmt)
    if magic is not None and not head.startswith(magic):
        raise InputError(f"not a {fmt.upper()} file (no {magic.decode().strip()!r} signature at the start)")
    for bom, unicode in WIDE_BOMS if fmt in TEXT_FORMATS else ():
        if head.startswith(bom):  # the readers take ASCII-compatible text only
            raise InputError(f"the file is {unicode} text (byte order mark {bom.hex(' ').upper()}); re-save it as UTF-8 or ASCII")
    if fmt in TEXT_FORMATS and head.startswith(UTF8_BOM):  # Windows editors write one; it is not part of the first line
        stream.read(len(UTF8_BOM))
        head = head[len(UTF8_BOM):]
    if fmt in TEXT_FORMATS and (b"\0" in head or head.startswith((b"LOGG", b"MDF "))):
        raise InputError(f"binary data, not a {fmt} text log (name the format with --input-format)")
    if fmt == "asc" and not any(line.strip().lower().startswith((b"date", b"base")) for line in head.splitlines()[:20]):
        raise InputError("not a Vector ASC log (no 'date' or 'base' header line)")
    if fmt == "trc" and not head.lstrip().startswith(b";"):
        raise InputError("not a PEAK TRC log (no ';' header)")
    if fmt == "trc" and (problem := trc_version_problem(head)):
        raise InputError(problem)
    return head


def read_log(path: str, fmt: str | None = None) -> Iterator[Chunk]:
    """The log's frames, chunk by chunk (`fmt` None: from the extension). InputError before the
    first chunk when the input cannot be read or is not in its format."""
    stream, raw = _open(path)
    try:
        fmt = detect_format(path, fmt)
    except InputError:
        if raw is not None:
            raw.close()
        raise
    if not hasattr(stream, "peek"):
        stream = io.BufferedReader(stream)  # type: ignore[arg-type]
    try:
        _head(stream, fmt)
        reader = {"candump": _candump, "mf4": _binary(_mf4), "blf": _binary(_blf)}.get(fmt, _python_can)
        for chunk in reader(stream, fmt):
            chunk.position = raw.tell() if raw is not None and not raw.closed else None
            yield chunk
    except (OSError, EOFError, gzip.BadGzipFile, ValueError, zlib.error) as exc:
        raise InputError(f"cannot read: {exc}") from None
    finally:
        if raw is not None:
            stream.close()
            raw.close()


def input_size(path: str) -> int | None:
    try:
        return None if path == "-" else os.path.getsize(path)
    except OSError:
        return None


def _candump(stream: IO[bytes], fmt: str) -> Iterator[Chunk]:
    line, rest = 1, b""
    while True:
        block = stream.read(CHUNK_BYTES)
        data = rest + block
        cut = data.rfind(b"\n") + 1 if block else len(data)
        if cut == 0 and block:
            rest = data
            continue
        rest = data[cut:]
        if data[:cut]:
            batch, problems, lines = read_chunk(data[:cut], line)
            yield Chunk(batch, problems, lines)
            line += lines
        if not block:
            return


def _binary(reader: Any) -> Any:
    """A binary reader whose file is damaged: asammdf and the BLF reader fail in their own ways
    (MdfException, zlib.error, struct.error, ...). Before the first record it is not a readable file
    (InputError); after, the records read so far count and the rest is one problem, as for a text log."""

    def guarded(stream: IO[bytes], fmt: str) -> Iterator[Chunk]:
        records = 0
        unraisable = sys.unraisablehook  # asammdf's MDF4.__del__ fails again on a half-opened file: not the user's concern
        sys.unraisablehook = lambda _: None
        try:
            for chunk in reader(stream, fmt):
                records += chunk.lines
                yield chunk
        except (InputError, ImportError):  # a missing reader is the extra to install (cli.py names it), not a damaged file
            raise
        except Exception as exc:  # noqa: BLE001 - whatever the reader raised on damaged data
            what = f"{type(exc).__name__}: {str(exc).strip()}"
            if not records:
                raise InputError(f"not a readable {fmt.upper()} file ({what})") from None
            yield Chunk(fr.from_frames([], []), [(records + 1, f"unreadable {fmt.upper()} record ({what}); the rest of the file is not read")])
        finally:
            gc.collect()
            sys.unraisablehook = unraisable

    return guarded


def _blf(stream: IO[bytes], fmt: str) -> Iterator[Chunk]:
    from canspec.logs.blf_bulk import read_blf

    for batch, objects, problems in read_blf(stream):
        yield Chunk(batch, problems, objects)


def _python_can(stream: IO[bytes], fmt: str) -> Iterator[Chunk]:
    """ASC and TRC through python-can (logs/pycan.py)."""
    from canspec.logs.pycan import Unreadable, read_text

    try:
        for batch, problems, lines in read_text(stream, fmt):
            yield Chunk(batch, problems, lines)
    except Unreadable as exc:
        raise InputError(str(exc)) from None


MF4_GROUPS = {"CAN_DataFrame": DATA, "CAN_RemoteFrame": REMOTE, "CAN_ErrorFrame": ERROR}


def _mf4(stream: IO[bytes], fmt: str) -> Iterator[Chunk]:
    """ASAM MF4 bus logging: the CAN_DataFrame / _RemoteFrame / _ErrorFrame channel groups read
    as whole columns by asammdf, MF4_CHUNK records at a time."""
    from asammdf import MDF

    # process_bus_logging=False: asammdf would otherwise decode every frame on opening (0.2 s per
    # million records) for the DBC-less bus views canspec never asks for.
    failed = ""
    try:
        mdf = MDF(io.BytesIO(stream.read()) if not stream.seekable() else stream, process_bus_logging=False)
    except Exception as exc:  # noqa: BLE001 - a damaged file; raised below, once the half-opened MDF is gone with `exc`
        failed = f"{type(exc).__name__}: {str(exc).strip()}"
    if failed:
        gc.collect()
        raise InputError(f"not a readable MF4 file ({failed})")
    start = mdf.header.start_time.timestamp()
    record = 0
    try:
        for gi, group in enumerate(mdf.groups):
            for ch in group.channels:
                kind = MF4_GROUPS.get(ch.name)
                if kind is None:
                    continue
                total = group.channel_group.cycles_nr
                for offset in range(0, total, MF4_CHUNK):
                    sig = mdf.get(ch.name, group=gi, record_offset=offset, record_count=min(MF4_CHUNK, total - offset), raw=True)
                    yield Chunk(_mf4_columns(sig, ch.name, kind, start, record), [], len(sig.timestamps))
                    record += len(sig.timestamps)
    finally:
        mdf.close()


BYTE_MASKS = np.array([(1 << 8 * k) - 1 for k in range(8)] + [2**64 - 1], dtype=np.uint64)  # the first k bytes of a word


def _mf4_data(s: Any, name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray]:
    """(length, word, data, flags) of data frames: DataBytes is as wide as the group's longest frame."""
    dlc = s[f"{name}.DataLength"].astype(np.uint8)
    raw = s[f"{name}.DataBytes"]
    if raw.shape[1] >= 8:
        cells = np.ascontiguousarray(raw[:, :8])
    else:
        cells = np.zeros((len(dlc), 8), np.uint8)
        cells[:, : raw.shape[1]] = raw
    word = cells.view("<u8").ravel() & BYTE_MASKS[np.minimum(dlc, 8)]
    data = None
    if raw.shape[1] > 8 and (dlc > 8).any():
        data = np.where(np.arange(raw.shape[1]) < dlc[:, None], raw, 0).astype(np.uint8)
    flags = np.zeros(len(dlc), np.uint8)
    if f"{name}.EDL" in s.dtype.names and s[f"{name}.EDL"].any():  # BRS and ESI exist only on FD frames
        for field_name, bit in (("EDL", fr.FD), ("BRS", fr.BRS), ("ESI", fr.ESI)):
            flags |= np.where(s[f"{name}.{field_name}"] != 0, bit, 0).astype(np.uint8)
    return dlc, word, data, flags


def _mf4_columns(sig: Any, name: str, kind: int, start: float, first: int) -> fr.Batch:
    s = sig.samples
    n = len(s)
    data = None
    if kind == DATA:
        dlc, word, data, flags = _mf4_data(s, name)
    else:
        dlc, word, flags = np.zeros(n, np.uint8), np.zeros(n, np.uint64), np.zeros(n, np.uint8)
    bus = s[f"{name}.BusChannel"]
    if n and np.all(bus == bus[0]):  # the usual log: one channel
        channels, codes = bus[:1], np.zeros(n, np.int32)
    else:
        channels, codes = np.unique(bus, return_inverse=True)
    return fr.Batch(
        sig.timestamps.astype(np.float64) + start, codes.astype(np.int32), s[f"{name}.ID"].astype(np.uint32) & np.uint32(MAX_EXTENDED_ID),
        s[f"{name}.IDE"].astype(bool), np.full(n, kind, np.uint8), dlc, word,
        np.arange(first + 1, first + n + 1, dtype=np.int64), flags, channels=tuple(str(c) for c in channels.tolist()), data=data,
    )
