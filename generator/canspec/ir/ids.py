"""CAN identifiers: the largest 11-bit and 29-bit ID, and how an ID is written in text."""

from __future__ import annotations

MAX_STANDARD_ID = 0x7FF  # 11-bit identifier
MAX_EXTENDED_ID = 0x1FFFFFFF  # 29-bit identifier
DBC_EXTENDED_FLAG = 0x80000000  # a DBC writes a 29-bit ID with bit 31 set


def max_id(extended: bool) -> int:
    return MAX_EXTENDED_ID if extended else MAX_STANDARD_ID


def id_text(frame_id: int, extended: bool) -> str:
    """"0x1801B0A0" (29-bit, eight digits) / "0x123" (11-bit, three digits)."""
    return f"0x{frame_id:08X}" if extended else f"0x{frame_id:03X}"
