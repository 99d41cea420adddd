"""candump text → frame columns in bulk: the `-L` log form (`(TS) CHANNEL ID#DATA[ R|T]`, what
`candump -l` records and most tools write) is taken apart with NumPy over a whole chunk of
bytes — no Python work per line. Every line that is not exactly that form (other candump
forms, remote, error and CAN FD frames, malformed lines) goes to the exact line reader
(candump.parse_line), so the result is the same as reading every line with it."""

from __future__ import annotations

import numpy as np

from canspec.reference import frames as fr
from canspec.reference.candump import LineError, parse_line

HEX = np.full(256, 255, dtype=np.uint8)
for _i, _c in enumerate(b"0123456789abcdef"):
    HEX[_c] = _i
for _i, _c in enumerate(b"ABCDEF"):
    HEX[_c] = 10 + _i
MAX_TIME, MAX_CHANNEL = 24, 8  # longer time stamps / channel names take the line reader
SP, HASH, LPAREN, RPAREN, NL, CR = (ord(c) for c in " #()\n\r")


def _next(positions: np.ndarray, after: np.ndarray) -> np.ndarray:
    """For each index in `after`, the first position at or after it (len(buf) + 1 past the end)."""
    k = np.searchsorted(positions, after)
    return np.append(positions, np.iinfo(np.int64).max)[k]


def _gather(b: np.ndarray, start: np.ndarray, length: np.ndarray, width: int, zero: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Bytes [start, start+length) of each row in `width` columns (zero-padded unless `zero` is
    False: then cells past the length hold whatever follows); and the valid-cell mask. `b` ends
    in at least `width` spare bytes."""
    width = min(width, int(length.max(initial=0)))
    cells = b[start[:, None] + np.arange(width, dtype=np.int64)]
    valid = np.arange(width) < length[:, None]
    if zero:
        cells *= valid
    return cells, valid


def _hex_value(cells: np.ndarray, valid: np.ndarray, length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Hex digits (most significant first) → uint64, and whether every digit was hex."""
    nib = HEX[cells]
    ok = np.all((nib < 16) | ~valid, axis=1)
    shift = (length[:, None] - 1 - np.arange(cells.shape[1])) * 4
    value = np.where(valid & ok[:, None], nib.astype(np.uint64) << np.maximum(shift, 0).astype(np.uint64), np.uint64(0))
    return np.bitwise_or.reduce(value, axis=1, initial=np.uint64(0)), ok


def _data_word(cells: np.ndarray, valid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Up to 16 hex digits (byte 0 first) → the little-endian frame word."""
    nib = HEX[cells]
    ok = np.all((nib < 16) | ~valid, axis=1)
    nib = np.where(valid, nib, 0).astype(np.uint64)
    byte = (nib[:, 0::2] << np.uint64(4)) | nib[:, 1::2]
    return np.bitwise_or.reduce(byte << (np.arange(byte.shape[1], dtype=np.uint64) * np.uint64(8)), axis=1, initial=np.uint64(0)), ok


def _channels(b: np.ndarray, start: np.ndarray, length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Channel names (up to 8 bytes, read as one integer each) → distinct names and codes."""
    cells, _ = _gather(b, start, length, MAX_CHANNEL)
    packed = np.zeros((len(start), MAX_CHANNEL), np.uint8)
    packed[:, : cells.shape[1]] = cells
    key = packed.view("<u8").ravel()
    if len(key) and np.all(key == key[0]):  # the usual log: one channel
        names, codes = key[:1], np.zeros(len(key), np.int64)
    else:
        names, codes = np.unique(key, return_inverse=True)
    return names.view(f"S{MAX_CHANNEL}"), codes


def _fast(b: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Which lines are plain `-L` form, and their columns."""
    close = _next(np.flatnonzero(b == RPAREN), starts)
    spaces = np.flatnonzero(b == SP)
    ok = (b[starts] == LPAREN) & (close < ends - 1)
    close = np.where(ok, close, starts)
    ok &= b[np.minimum(close + 1, len(b) - 1)] == SP
    chan_end = _next(spaces, close + 2)
    hash_at = _next(np.flatnonzero(b == HASH), chan_end)
    data_end = np.minimum(_next(spaces, hash_at), ends)
    tail = ends - data_end
    ok &= (chan_end < hash_at) & (hash_at < ends) & ((tail == 0) | ((tail == 2) & np.isin(b[np.minimum(data_end + 1, len(b) - 1)], (ord("R"), ord("T")))))
    id_len, data_len, ts_len, ch_len = hash_at - chan_end - 1, data_end - hash_at - 1, close - starts - 1, chan_end - close - 2
    ok &= ((id_len == 3) | (id_len == 8)) & (data_len % 2 == 0) & (data_len <= 16) & (ts_len > 0) & (ts_len <= MAX_TIME) & (ch_len > 0) & (ch_len <= MAX_CHANNEL)
    rows = np.flatnonzero(ok)
    cells, valid = _gather(b, chan_end[rows] + 1, id_len[rows], 8, zero=False)
    frame_id, id_ok = _hex_value(cells, valid, id_len[rows])
    extended = id_len[rows] == 8
    id_ok &= frame_id <= np.where(extended, 0x1FFFFFFF, 0x7FF)  # error frames (CAN_ERR_FLAG) take the line reader
    cells, valid = _gather(b, hash_at[rows] + 1, data_len[rows], 16, zero=False)
    word, data_ok = _data_word(cells, valid)
    cells, valid = _gather(b, starts[rows] + 1, ts_len[rows], MAX_TIME)
    digit = (cells >= 48) & (cells <= 57)
    dots = np.sum(cells == 46, axis=1)
    ts_ok = np.all(digit | (cells == 46) | ~valid, axis=1) & (dots <= 1) & np.any(digit, axis=1)
    good = id_ok & data_ok & ts_ok
    rows, ok[:] = rows[good], False
    ok[rows] = True
    timestamp = np.ascontiguousarray(cells[good]).view(f"S{cells.shape[1]}").ravel().astype(np.float64) if cells.size else np.zeros(len(rows))
    names, codes = _channels(b, close[rows] + 2, ch_len[rows])
    return ok, {
        "timestamp": timestamp, "channel": codes.astype(np.int32), "channels": tuple(n.decode("latin-1") for n in names),
        "frame_id": frame_id[good].astype(np.uint32), "extended": extended[good], "dlc": (data_len[rows] // 2).astype(np.uint8), "word": word[good],
    }


def read_chunk(buf: bytes, first_line: int) -> tuple[fr.Batch, list[tuple[int, str]], int]:
    """The frames of complete lines in `buf` (numbered from `first_line`), the malformed lines
    as (line, message), and the number of lines."""
    b = np.frombuffer(buf, dtype=np.uint8)
    nl = np.flatnonzero(b == NL)
    if len(b) and b[-1] != NL:
        nl = np.append(nl, len(b))
    starts = np.concatenate(([0], nl[:-1] + 1)).astype(np.int64)
    ends = nl.astype(np.int64)
    if len(b):
        ends = ends - ((ends > starts) & (b[np.maximum(ends - 1, 0)] == CR))
    ok, cols = _fast(np.concatenate((b, np.full(MAX_TIME + 2, NL, np.uint8))), starts, ends) if len(starts) else (np.zeros(0, bool), None)
    fast_lines = np.flatnonzero(ok) + first_line
    fast = fr.Batch(
        cols["timestamp"], cols["channel"], cols["frame_id"], cols["extended"], np.zeros(len(fast_lines), np.uint8),
        cols["dlc"], cols["word"], fast_lines, channels=cols["channels"],
    ) if cols else fr.Batch.empty()
    slow, slow_lines, problems = [], [], []
    for i in np.flatnonzero(~ok).tolist():
        text = buf[starts[i]:ends[i]].decode("utf-8", errors="replace")
        try:
            frame = parse_line(text)
        except LineError as exc:
            problems.append((first_line + i, f"malformed line: {exc}: {text.strip()[:80]!r}"))
            continue
        if frame is not None:
            slow.append(frame)
            slow_lines.append(first_line + i)
    if not slow:
        return fast, problems, len(starts)
    both = fr.concat([fast, fr.from_frames(slow, slow_lines)])
    return both.take(np.argsort(both.line, kind="stable")), problems, len(starts)
