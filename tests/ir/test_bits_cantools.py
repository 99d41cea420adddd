"""ir/bits.py against cantools' own bit numbering (the DBC convention canspec adopts): for random
(start, length, byte order, frame length) a one-signal message encoded by cantools gives the bytes
that positions(), segments() and word_shift() each place the value at, and cantools accepts the
field in the frame exactly when fits() says it lies inside."""

from __future__ import annotations

import cantools
from canspec.ir.bits import fits, positions, segments, word_shift
from canspec.ir.fd import FD_LENGTHS
from hypothesis import given, settings
from hypothesis import strategies as st


def cantools_message(start: int, length: int, order: str, dlc: int) -> cantools.database.can.Message:
    sig = cantools.database.can.Signal("f", start, length, byte_order=order, is_signed=False)
    return cantools.database.can.Message(0x123, "m", dlc, [sig], strict=True, is_fd=dlc > 8)


@st.composite
def fields(draw: st.DrawFn) -> tuple[int, int, str, int, int]:
    """A field that lies in its frame: (start, length, order, dlc, raw value)."""
    dlc = draw(st.sampled_from([n for n in FD_LENGTHS if n]))
    order = draw(st.sampled_from(["little_endian", "big_endian"]))
    length = draw(st.integers(1, min(64, 8 * dlc)))
    start = draw(st.integers(0, 8 * dlc - 1).filter(lambda s: fits(s, length, order, dlc)))
    raw = draw(st.integers(0, (1 << length) - 1))
    return start, length, order, dlc, raw


@settings(max_examples=300, deadline=None)
@given(fields())
def test_positions_segments_and_word_shift_match_cantools(field):
    start, length, order, dlc, raw = field
    data = cantools_message(start, length, order, dlc).encode({"f": raw}, scaling=False)

    by_positions = bytearray(dlc)
    for i, pos in enumerate(positions(start, length, order)):
        if raw >> i & 1:
            by_positions[pos // 8] |= 1 << (pos % 8)
    assert bytes(by_positions) == data

    by_segments = bytearray(dlc)
    for seg in segments(start, length, order):
        by_segments[seg.byte] |= ((raw >> seg.value_shift) & ((1 << seg.width) - 1)) << seg.byte_shift
    assert bytes(by_segments) == data

    word = "big" if order == "big_endian" else "little"
    shift = word_shift(start, length, order, dlc)
    assert (raw << shift).to_bytes(dlc, word) == data
    assert int.from_bytes(data, word) >> shift == raw


@settings(max_examples=300, deadline=None)
@given(st.sampled_from([n for n in FD_LENGTHS if n]), st.sampled_from(["little_endian", "big_endian"]), st.integers(0, 520), st.integers(1, 64))
def test_fits_is_what_cantools_accepts(dlc, order, start, length):
    try:
        cantools_message(start, length, order, dlc)
        accepted = True
    except cantools.database.errors.Error:
        accepted = False
    assert fits(start, length, order, dlc) == accepted, (start, length, order, dlc)
