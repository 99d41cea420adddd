"""Bit layout of Intel (little-endian) signals: per-byte segments, storage widths."""

from __future__ import annotations

from canspec.ir import Segment


def segments(start: int, length: int) -> tuple[Segment, ...]:
    """Split an Intel signal starting at `start` (bit 0 = LSB of byte 0) into byte segments."""
    out = []
    bit, taken = start, 0
    while taken < length:
        byte, shift = divmod(bit, 8)
        width = min(8 - shift, length - taken)
        out.append(Segment(byte=byte, byte_shift=shift, width=width, value_shift=taken, mask=((1 << width) - 1) << shift))
        bit += width
        taken += width
    return tuple(out)


def storage_bits(length: int) -> int:
    """Narrowest standard integer width holding `length` bits."""
    for bits in (8, 16, 32, 64):
        if length <= bits:
            return bits
    raise ValueError(f"signal of {length} bits does not fit 64 bits")
