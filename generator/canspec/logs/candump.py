"""candump text → frames, one line at a time (the exact reader; `logfast.py` reads the common
`-L` form in bulk and hands every other line to this one). Accepted (SocketCAN can-utils):

    (1700000000.123456) can0 1806A0B0#0011223344556677 [R|T]   candump -L / -l log file
    1806A0B0#0011223344556677                                  bare cansend form
    can0  1806A0B0   [8]  00 11 22 33 44 55 66 77              candump default output
    (1700000000.123456)  can0  1806A0B0   [8]  00 11 ...       -ta, -td, -tz (time as written)
    (2023-11-14 22:13:20.123456)  can0  1806A0B0   [8]  ...    -tA (local time)
    (1700000000.123456)  can0  RX - -  1806A0B0   [8]  ...     -x (direction and FD flags)
    can0  1806A0B0  [12]  00 11 ...   /   1806A0B0##1<data>    CAN FD (`##` + a flags digit:
                                                               1 BRS, 2 ESI; then the data)

Remote frames (`ID#R`, `remote request`) and error frames (the ID carries CAN_ERR_FLAG,
0x20000000) are frames of their own kind; trailing `'ascii'` (-a) and error text (-e) are ignored.
"""

from __future__ import annotations

import re
from datetime import datetime
from typing import NamedTuple

from canspec.ir.ids import max_id

MAX_DATA = 64
ERR_FLAG = 0x20000000  # linux/can.h CAN_ERR_FLAG: candump prints it as part of an error frame's ID
DATA, REMOTE, ERROR = 0, 1, 2  # frame kinds
FD_FLAG, BRS_FLAG, ESI_FLAG = 1, 2, 4  # Frame.flags (frames.FD, BRS, ESI)


class LineError(ValueError):
    pass


class Frame(NamedTuple):
    timestamp: float | None  # seconds as written (None: the line has none)
    channel: str | None
    frame_id: int
    extended: bool
    data: bytes
    kind: int = DATA
    flags: int = 0  # CAN FD: frames.FD | BRS | ESI


HEX_DIGITS = frozenset("0123456789abcdefABCDEF")
TIME_CHARS = frozenset("0123456789.")
# can-utils lib.c: `R`, then an optional DLC digit (9..F: a raw DLC, 8 bytes), candump's own 8_9..8_F form too
REMOTE_DLC = re.compile(r"([0-9A-Fa-f]|8_[9A-Fa-f])?")


def parse_id(text: str) -> tuple[int, bool, int]:
    """(id, extended, kind): 8 digits are a 29-bit ID (or an error frame's class), else 11-bit."""
    if not text or not HEX_DIGITS.issuperset(text):  # int() alone would take "-1", "0x1F", "1_0"
        raise LineError(f"frame ID {text!r} is not hexadecimal")
    value = int(text, 16)
    extended = len(text) > 3
    if extended and value & ERR_FLAG and value < 2 * ERR_FLAG:
        return value & ~ERR_FLAG, True, ERROR
    if value > max_id(extended):
        raise LineError(f"frame ID {text} does not fit {'29' if extended else '11'} bits")
    return value, extended, DATA


def _hex_bytes(text: str) -> bytes:
    try:
        data = bytes.fromhex(text)
    except ValueError:
        raise LineError(f"data {text!r} is not an even number of hex digits") from None
    if len(data) > MAX_DATA:
        raise LineError(f"{len(data)} data bytes (at most {MAX_DATA})")
    return data


def _seconds(text: str) -> bool:
    return bool(text) and TIME_CHARS.issuperset(text) and text.count(".") <= 1 and text != "."


def parse_time(text: str) -> float:
    """A candump time stamp: seconds (`-ta/-td/-tz`, log files) or a local date and time (`-tA`)."""
    if _seconds(text):
        return float(text)
    try:
        return datetime.strptime(text, "%Y-%m-%d %H:%M:%S.%f").timestamp()
    except ValueError:
        pass
    if text[:1] == "-" and _seconds(text[1:]):  # candump never writes one: a damaged or hand-made log
        raise LineError(f"time stamp ({text}) is negative (refused)")
    raise LineError(f"time stamp ({text}) is not a number")


def _compact(text: str, timestamp: float | None, channel: str | None) -> Frame:
    hash_at = text.find("#")
    if hash_at <= 0:
        raise LineError(f"expected ID#DATA, got {text!r}")
    frame_id, extended, kind = parse_id(text[:hash_at])
    data = text[hash_at + 1:]
    flags = 0
    if data[:1] == "#":  # CAN FD: one flags digit (linux/can.h CANFD_BRS 1, CANFD_ESI 2), then the data
        if len(data) < 2 or data[1] not in HEX_DIGITS:
            raise LineError(f"CAN FD frame {text!r}: expected a flags digit after '##'")
        flags = FD_FLAG | (BRS_FLAG if int(data[1], 16) & 1 else 0) | (ESI_FLAG if int(data[1], 16) & 2 else 0)
        data = data[2:]
    elif data[:1] in ("R", "r"):
        if not REMOTE_DLC.fullmatch(data[1:]):
            raise LineError(f"remote frame {text!r}: expected nothing, one DLC digit (0-F) or 8_9..8_F after 'R'")
        return Frame(timestamp, channel, frame_id, extended, b"", REMOTE)
    return Frame(timestamp, channel, frame_id, extended, _hex_bytes(data.replace(".", "")), kind, flags)


def _bracketed(tokens: list[str], at: int, timestamp: float | None) -> Frame:
    """candump's screen form: CHANNEL [RX - -] ID [LEN] BYTES... (tokens[at] is `[LEN]`)."""
    if at < 2:
        raise LineError("expected 'CHANNEL ID [LEN] DATA'")
    frame_id, extended, kind = parse_id(tokens[at - 1])
    try:
        dlc = int(tokens[at][1:-1])
    except ValueError:
        raise LineError(f"length {tokens[at]!r} is not a number") from None
    rest = tokens[at + 1:]
    if rest[:2] == ["remote", "request"]:
        return Frame(timestamp, tokens[0], frame_id, extended, b"", REMOTE)
    if len(rest) < dlc:
        raise LineError(f"length [{dlc}] but {len(rest)} data bytes")
    if any(len(t) != 2 for t in rest[:dlc]):
        raise LineError(f"data {' '.join(rest[:dlc])!r} is not hex bytes")
    # candump prints a CAN FD frame's length with two digits ([08], [12]); -x adds B (BRS) / E (ESI)
    marks = tokens[1: at - 1]
    flags = FD_FLAG | (BRS_FLAG if "B" in marks else 0) | (ESI_FLAG if "E" in marks else 0) if len(tokens[at]) == 4 or dlc > 8 else 0
    return Frame(timestamp, tokens[0], frame_id, extended, _hex_bytes("".join(rest[:dlc])), kind, flags)


def parse_line(line: str) -> Frame | None:
    """The frame on a line; None for a blank or comment line; LineError when it is malformed."""
    text = line.strip()
    if not text or text[0] in "#;":
        return None
    timestamp = None
    if text[0] == "(":
        close = text.find(")")
        if close < 0:
            raise LineError("expected '(TIMESTAMP) CHANNEL ID#DATA'")
        timestamp = parse_time(text[1:close])
        text = text[close + 1:]
    tokens = text.split()
    at = next((i for i, t in enumerate(tokens) if t[:1] == "[" and t[-1:] == "]"), -1)
    if at >= 0:
        return _bracketed(tokens, at, timestamp)
    if timestamp is not None:
        if len(tokens) < 2 or len(tokens) > 3 or tokens[2:] not in ([], ["R"], ["T"]):
            raise LineError("expected '(TIMESTAMP) CHANNEL ID#DATA'")
        return _compact(tokens[1], timestamp, tokens[0])
    if len(tokens) == 1:
        return _compact(tokens[0], None, None)
    raise LineError("not a candump line (expected '(TIMESTAMP) CHANNEL ID#DATA' or 'ID#DATA')")
