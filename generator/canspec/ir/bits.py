"""Bit layout of signals in either byte order: the bits a field occupies, per-byte segments, its
place in the frame word, storage widths.

One numbering of a frame's bits serves both orders, the DBC's: bit `8 × byte + k` is bit k (0 the
least significant) of data byte `byte`. An Intel (little_endian) field's `start` is its least
significant bit and the field runs upward, into the next byte's low bits. A Motorola (big_endian)
field's `start` is its most significant bit and the field runs downward, from a byte's bit 0 into
the next byte's bit 7 ("sawtooth"), so its more significant bytes come first in the frame.
"""

from __future__ import annotations

from canspec.ir.model import Segment

LITTLE, BIG = "little_endian", "big_endian"


def positions(start: int, length: int, byte_order: str) -> tuple[int, ...]:
    """The frame bits of value bits 0 (LSB) .. length - 1 (MSB)."""
    if byte_order == LITTLE:
        return tuple(range(start, start + length))
    out, bit = [], start
    for _ in range(length):  # MSB first, then reversed
        out.append(bit)
        bit = bit - 1 if bit % 8 else bit + 15
    return tuple(reversed(out))


def fits(start: int, length: int, byte_order: str, frame_bytes: int) -> bool:
    """Whether every bit of the field lies in a frame of `frame_bytes` bytes."""
    if start < 0 or length < 1:
        return False
    return all(p < 8 * frame_bytes for p in positions(start, length, byte_order))


def lsb(start: int, length: int, byte_order: str) -> int:
    return positions(start, length, byte_order)[0]


def segments(start: int, length: int, byte_order: str = LITTLE) -> tuple[Segment, ...]:
    """The field's share of each frame byte, least significant value bits first: within a byte,
    value bits rise with the byte's bits in either order."""
    out: list[Segment] = []
    for value_bit, pos in enumerate(positions(start, length, byte_order)):
        byte, shift = divmod(pos, 8)
        last = out[-1] if out else None
        if last is not None and last.byte == byte and last.byte_shift + last.width == shift:
            out[-1] = _segment(byte, last.byte_shift, last.width + 1, last.value_shift)
        else:
            out.append(_segment(byte, shift, 1, value_bit))
    return tuple(out)


def _segment(byte: int, shift: int, width: int, value_shift: int) -> Segment:
    return Segment(byte=byte, byte_shift=shift, width=width, value_shift=value_shift, mask=((1 << width) - 1) << shift)


def word_shift(start: int, length: int, byte_order: str, frame_bytes: int) -> int:
    """Where the field's LSB lies in the frame word: the frame's bytes read as one integer, little-
    endian for an Intel field and big-endian for a Motorola one, in which either field is contiguous."""
    if byte_order == LITTLE:
        return start
    byte, bit = divmod(lsb(start, length, byte_order), 8)
    return 8 * (frame_bytes - 1 - byte) + bit


def describe(start: int, length: int, byte_order: str) -> str:
    """Where a field lies, byte by byte, most significant first: 'byte 0 bits 3..0, byte 1 bits 7..4'."""
    parts = []
    for seg in reversed(segments(start, length, byte_order)):
        hi, lo = seg.byte_shift + seg.width - 1, seg.byte_shift
        parts.append(f"byte {seg.byte} bit {lo}" if hi == lo else f"byte {seg.byte} bits {hi}..{lo}")
    return ", ".join(parts)


def storage_bits(length: int) -> int:
    """Narrowest standard integer width holding `length` bits."""
    for bits in (8, 16, 32, 64):
        if length <= bits:
            return bits
    raise ValueError(f"signal of {length} bits does not fit 64 bits")
