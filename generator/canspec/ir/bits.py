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


def raw_type_range(length: int, signed: bool) -> tuple[int, int]:
    if signed:
        return -(1 << (length - 1)), (1 << (length - 1)) - 1
    return 0, (1 << length) - 1


def bit_owner_map(fields: list[tuple[str, int, int]], frame_bits: int) -> list[str | None]:
    """For overlap checks: which field owns each bit (first claimant wins)."""
    owners: list[str | None] = [None] * frame_bits
    for name, start, length in fields:
        for bit in range(start, min(start + length, frame_bits)):
            if owners[bit] is None:
                owners[bit] = name
    return owners
