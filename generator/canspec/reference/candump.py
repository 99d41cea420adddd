"""candump log lines → frames. Accepted forms (SocketCAN can-utils):

    (1700000000.123456) can0 1806A0B0#0011223344556677   candump -L / log file
    1806A0B0#0011223344556677                             bare cansend form
    can0  1806A0B0   [8]  00 11 22 33 44 55 66 77         candump default output

`ID##<flags><data>` (CAN FD) is read as data; remote frames (`ID#R`) are refused.
"""

from __future__ import annotations

from typing import NamedTuple

MAX_DATA = 64
EXTENDED_ID_DIGITS = 8  # 29-bit IDs are written with 8 hex digits, 11-bit ones with 3


class LineError(ValueError):
    pass


class Frame(NamedTuple):
    timestamp: str | None
    channel: str | None
    frame_id: int
    extended: bool
    data: bytes


HEX_DIGITS = frozenset("0123456789abcdefABCDEF")


def _parse_id(text: str) -> tuple[int, bool]:
    if not text or not HEX_DIGITS.issuperset(text):  # int() alone would take "-1", "0x1F", "1_0"
        raise LineError(f"frame ID {text!r} is not hexadecimal")
    value = int(text, 16)
    extended = len(text) > 3
    if value > (0x1FFFFFFF if extended else 0x7FF):
        raise LineError(f"frame ID {text} does not fit {'29' if extended else '11'} bits")
    return value, extended


def _parse_data(text: str) -> bytes:
    if text[:1] == "#":  # CAN FD: one flags digit, then the data
        text = text[2:]
    if text[:1] in ("R", "r"):
        raise LineError("remote frame (no data)")
    try:
        data = bytes.fromhex(text.replace(".", ""))
    except ValueError:
        raise LineError(f"data {text!r} is not an even number of hex digits") from None
    if len(data) > MAX_DATA:
        raise LineError(f"{len(data)} data bytes (at most {MAX_DATA})")
    return data


def _parse_compact(text: str, timestamp: str | None, channel: str | None) -> Frame:
    hash_at = text.find("#")
    if hash_at <= 0:
        raise LineError(f"expected ID#DATA, got {text!r}")
    frame_id, extended = _parse_id(text[:hash_at])
    return Frame(timestamp, channel, frame_id, extended, _parse_data(text[hash_at + 1:]))


def parse_line(line: str) -> Frame | None:
    """The frame on a line; None for a blank or comment line; LineError when it is malformed."""
    tokens = line.split()
    if not tokens or tokens[0].startswith(("#", ";")):
        return None
    first = tokens[0]
    if first.startswith("("):
        if not first.endswith(")") or len(tokens) < 3:
            raise LineError("expected '(TIMESTAMP) CHANNEL ID#DATA'")
        return _parse_compact(tokens[2], first[1:-1], tokens[1])
    if len(tokens) == 1:
        return _parse_compact(first, None, None)
    if len(tokens) >= 3 and tokens[2].startswith("[") and tokens[2].endswith("]"):
        frame_id, extended = _parse_id(tokens[1])
        try:
            dlc = int(tokens[2][1:-1])
        except ValueError:
            raise LineError(f"length {tokens[2]!r} is not a number") from None
        data = _parse_data("".join(tokens[3:]))
        if len(data) != dlc:
            raise LineError(f"length [{dlc}] but {len(data)} data bytes")
        return Frame(None, first, frame_id, extended, data)
    raise LineError("not a candump line (expected '(TIMESTAMP) CHANNEL ID#DATA' or 'ID#DATA')")
