"""CAN FD frame lengths (ISO 11898-1:2015): the data lengths a frame can carry and the 4-bit DLC
code that announces each on the wire."""

from __future__ import annotations

FD_LENGTHS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64)  # index = DLC code
CLASSIC_MAX = 8


def dlc_code(length: int) -> int:
    """The DLC field's value for a frame of `length` data bytes."""
    return FD_LENGTHS.index(length)


def padded_length(length: int) -> int:
    """The smallest frame length holding `length` bytes (an FD frame pads to the next length)."""
    return next(n for n in FD_LENGTHS if n >= length)
