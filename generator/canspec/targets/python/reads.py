"""Where decode reads a field from: the frame bytes it spans (`dN`), a 16-bit word of two of them (`hN`), or, for a
wider field of a CAN FD frame, a slice of its own bytes. The rest read the whole frame as one integer (fields.py)."""

from __future__ import annotations

from canspec import ir

MAX_BYTE_SPAN = 3  # bytes a field read from the frame's bytes may span: their combination stays a one-digit int (< 2^30)


def frame_bytes(sig: ir.Signal, frame_bits: int) -> tuple[tuple[int, int], ...] | None:
    """(frame byte, its left shift) of a non-float field that spans at most MAX_BYTE_SPAN bytes, else None:
    decode reads it from those bytes (`d3 | d4 << 8`, small ints), not from the frame word (nor, in a CAN FD
    frame, from a slice of its own bytes). The bytes are taken in the order of the field's word: a Motorola
    field's first byte is its highest."""
    if sig.is_float:
        return None
    lo, hi = sig.word_shift // 8, (sig.word_shift + sig.length - 1) // 8  # in the word, from its least significant byte
    if hi - lo >= MAX_BYTE_SPAN:
        return None
    last = frame_bits // 8 - 1
    return tuple((last - p if sig.is_big_endian else p, 8 * (p - lo)) for p in range(lo, hi + 1))


def _pair_shift(sig: ir.Signal, pair: int, order: str, frame_bits: int) -> int | None:
    """The shift of a field in the 16-bit word of frame bytes `pair`, `pair + 1` read in `order` ("<" or ">"), or
    None when it does not lie there in that order (a one-byte field lies in either order)."""
    parts = frame_bytes(sig, frame_bits)
    if parts is None or not {i for i, _ in parts} <= {pair, pair + 1}:
        return None
    if len(parts) == 2 and sig.is_big_endian != (order == ">"):
        return None
    low = parts[0][0]  # the field's least significant frame byte
    return 8 * (pair + 1 - low if order == ">" else low - pair) + sig.word_shift % 8


def checksums_every_byte(msg: ir.Message) -> bool:
    """The message's XOR checksum and the bytes it covers are the whole frame (its XOR is then 0 when intact)."""
    return msg.checksum is not None and set(msg.checksum.covers) | {msg.checksum.byte} == set(range(msg.dlc))


def word_pairs(msg: ir.Message) -> tuple[str, frozenset[int]]:
    """The 16-bit words decode reads whole (`hN`, N the first of their two frame bytes, by a struct `H` in the
    returned order), where it would otherwise join two bytes: each is a pair of bytes some field spans exactly and every
    field read from those bytes lies in, in the order of most such pairs. None where the checksum XORs every byte
    (decode reads them one by one)."""
    frame_bits = msg.dlc * 8
    if checksums_every_byte(msg):
        return "<", frozenset()
    readers = [s for s in msg.data_signals if frame_bytes(s, frame_bits) is not None]
    found: dict[str, set[int]] = {"<": set(), ">": set()}
    for order, pairs in found.items():
        for sig in readers:
            parts = frame_bytes(sig, frame_bits)
            pair = min(i for i, _ in parts) if parts is not None and len(parts) == 2 else None
            if pair is None or sig.is_big_endian != (order == ">"):
                continue
            touching = [s for s in readers if {i for i, _ in frame_bytes(s, frame_bits) or ()} & {pair, pair + 1}]
            if all(_pair_shift(s, pair, order, frame_bits) is not None for s in touching):
                pairs.add(pair)
    order = ">" if len(found[">"]) > len(found["<"]) else "<"
    return order, frozenset(found[order])


def pair_of(sig: ir.Signal, frame_bits: int, words: tuple[str, frozenset[int]]) -> tuple[int, int] | None:
    """The 16-bit word of `words` (word_pairs) a field is read from, if it is: its first frame byte, and the field's
    shift in it."""
    parts = frame_bytes(sig, frame_bits)
    if parts is None:
        return None
    order, pairs = words
    first = min(i for i, _ in parts)
    for p in (first, first - 1):
        shift = _pair_shift(sig, p, order, frame_bits) if p in pairs else None
        if shift is not None:
            return p, shift
    return None


def own_bytes(sig: ir.Signal, frame_bits: int) -> tuple[str, int, int]:
    """A field wider than MAX_BYTE_SPAN bytes of a CAN FD frame (more than 8 bytes) read from its own bytes, not from a
    word of up to 512 bits: (the integer of those bytes in the field's order, the field's shift in it, its bits)."""
    lo, hi = sig.word_shift // 8, (sig.word_shift + sig.length - 1) // 8
    last = frame_bits // 8 - 1
    at = [last - p if sig.is_big_endian else p for p in range(lo, hi + 1)]
    return f'_from_bytes(data[{min(at)}:{max(at) + 1}], "{sig.word_order}")', sig.word_shift - 8 * lo, 8 * len(at)
