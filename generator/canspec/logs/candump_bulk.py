"""candump text → frame columns in bulk: the `-L` log form (`(TS) CHANNEL ID#DATA[ R|T]`, what
`candump -l` records and most tools write) and the screen forms (`[(TS)] CHANNEL [RX - -] ID
[N]  XX XX ...`: default, -ta/-td/-tz, -x) are taken apart with NumPy over a whole chunk of
bytes — no Python work per line. Every other line (-tA dates, remote, error and CAN FD frames,
malformed lines) goes to the exact line reader (candump.parse_line), so the result is the same
as reading every line with it."""

from __future__ import annotations

import numpy as np

from canspec.ir.ids import MAX_EXTENDED_ID, MAX_STANDARD_ID
from canspec.logs import frames as fr
from canspec.logs.candump import LineError, parse_line

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


def _prev(positions: np.ndarray, before: np.ndarray) -> np.ndarray:
    """For each index in `before`, the last position before it (-1 when there is none)."""
    return np.concatenate(([-1], positions))[np.searchsorted(positions, before)]


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


def _times(b: np.ndarray, start: np.ndarray, length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Time stamps (digits with at most one '.') → float64 (NaN where not such a number), and
    which were; what float() makes of the same text."""
    cells, valid = _gather(b, start, length, MAX_TIME)
    digit = (cells >= 48) & (cells <= 57)
    ok = np.all(digit | (cells == 46) | ~valid, axis=1) & (np.sum(cells == 46, axis=1) <= 1) & np.any(digit, axis=1) & (length <= MAX_TIME)
    out = np.full(len(start), np.nan)
    if cells.size:
        out[ok] = np.ascontiguousarray(cells[ok]).view(f"S{cells.shape[1]}").ravel().astype(np.float64)
    return out, ok


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
    ok &= (
        ((id_len == 3) | (id_len == 8)) & (data_len % 2 == 0) & (data_len <= 16) & (ts_len > 0) & (ts_len <= MAX_TIME) & (ch_len > 0) & (ch_len <= MAX_CHANNEL)
    )
    rows = np.flatnonzero(ok)
    cells, valid = _gather(b, chan_end[rows] + 1, id_len[rows], 8, zero=False)
    frame_id, id_ok = _hex_value(cells, valid, id_len[rows])
    extended = id_len[rows] == 8
    id_ok &= frame_id <= np.where(extended, MAX_EXTENDED_ID, MAX_STANDARD_ID)  # error frames (CAN_ERR_FLAG) take the line reader
    cells, valid = _gather(b, hash_at[rows] + 1, data_len[rows], 16, zero=False)
    word, data_ok = _data_word(cells, valid)
    timestamp, ts_ok = _times(b, starts[rows] + 1, ts_len[rows])
    good = id_ok & data_ok & ts_ok
    rows, ok[:] = rows[good], False
    ok[rows] = True
    timestamp = timestamp[good]
    names, codes = _channels(b, close[rows] + 2, ch_len[rows])
    return ok, {
        "timestamp": timestamp, "channel": codes.astype(np.int32), "channels": tuple(n.decode("latin-1") for n in names),
        "frame_id": frame_id[good].astype(np.uint32), "extended": extended[good], "dlc": (data_len[rows] // 2).astype(np.uint8), "word": word[good],
    }


def _screen(b: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Which lines are classic frames in candump's screen form, and their columns:
    `[(TS)] CHANNEL [anything] ID [N]  XX XX ...[ trailing text]`, bytes one space apart."""
    spaces, solid = np.flatnonzero(b == SP), np.flatnonzero(b != SP)
    last = len(b) - 1

    def at(i: np.ndarray) -> np.ndarray:
        return b[np.clip(i, 0, last)]

    first = _next(solid, starts)  # first non-space of the line
    timed = at(first) == LPAREN
    close = np.where(timed, _next(np.flatnonzero(b == RPAREN), first), first - 1)
    ok = (first < ends) & ~np.isin(at(first), (HASH, ord(";"))) & (close < ends)
    chan = _next(solid, close + 1)
    chan_end = _next(spaces, chan)
    lb = _next(np.flatnonzero(b == ord("[")), close + 1)  # the line's first '[' must open the `[N]` token
    rb = _next(np.flatnonzero(b == ord("]")), lb)
    # `[N]` only: candump writes a CAN FD frame's length with two digits (`[08]`), left to the line reader
    ok &= (lb < ends) & (rb < ends) & (rb - lb == 2) & (at(lb - 1) == SP) & ((rb + 1 == ends) | (at(rb + 1) == SP))
    lb, rb = np.where(ok, lb, 0), np.where(ok, rb, 0)
    id_end = _prev(solid, lb) + 1  # just past the ID token
    id_start = _prev(spaces, id_end) + 1
    id_len, ch_len = id_end - id_start, chan_end - chan
    ok &= (id_start > chan_end) & ((id_len == 3) | (id_len == 8)) & (ch_len > 0) & (ch_len <= MAX_CHANNEL)
    digits = at(lb + 1).astype(np.int64) - 48
    ok &= (digits >= 0) & (digits <= 8)
    data = _next(solid, rb + 1)
    data_end = data + 3 * digits - 1  # the last byte's end
    ok &= (digits == 0) | ((data_end <= ends) & ((data_end == ends) | (at(data_end) == SP)))
    rows = np.flatnonzero(ok)
    cells, valid = _gather(b, id_start[rows], id_len[rows], 8, zero=False)
    frame_id, good = _hex_value(cells, valid, id_len[rows])
    extended = id_len[rows] == 8
    good &= frame_id <= np.where(extended, MAX_EXTENDED_ID, MAX_STANDARD_ID)
    n = digits[rows]
    pairs = data[rows][:, None] + 3 * np.arange(8)
    valid = np.arange(8) < n[:, None]
    sep_ok = np.all((at(pairs + 2) == SP) | (np.arange(8) >= n[:, None] - 1), axis=1)
    cells = np.stack((at(pairs), at(pairs + 1)), axis=2).reshape(len(rows), 16)
    word, data_ok = _data_word(cells, np.repeat(valid, 2, axis=1))
    timestamp, ts_ok = _times(b, first[rows] + 1, close[rows] - first[rows] - 1)
    ts_ok |= ~timed[rows]
    good &= sep_ok & data_ok & ts_ok
    rows, ok[:] = rows[good], False
    ok[rows] = True
    names, codes = _channels(b, chan[rows], ch_len[rows])
    return ok, {
        "timestamp": timestamp[good], "channel": codes.astype(np.int32), "channels": tuple(n.decode("latin-1") for n in names),
        "frame_id": frame_id[good].astype(np.uint32), "extended": extended[good], "dlc": n[good].astype(np.uint8), "word": word[good],
    }


def _batch(cols: dict[str, np.ndarray], lines: np.ndarray) -> fr.Batch:
    return fr.Batch(cols["timestamp"], cols["channel"], cols["frame_id"], cols["extended"], np.zeros(len(lines), np.uint8),
                    cols["dlc"], cols["word"], lines, channels=cols["channels"])  # type: ignore[arg-type]


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
    padded = np.concatenate((b, np.full(MAX_TIME + 32, NL, np.uint8)))
    parts, ok = [], np.zeros(len(starts), bool)
    for reader in (_fast, _screen):
        todo = np.flatnonzero(~ok)
        if not len(todo):
            break
        hit, cols = reader(padded, starts[todo], ends[todo])
        if hit.any():
            parts.append(_batch(cols, todo[hit] + first_line))
            ok[todo[hit]] = True
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
    if slow:
        parts.append(fr.from_frames(slow, slow_lines))
    if len(parts) == 1:
        return parts[0], problems, len(starts)
    both = fr.concat(parts)
    return both.take(np.argsort(both.line, kind="stable")), problems, len(starts)
