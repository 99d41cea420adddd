"""Bus load: the frame-length formula against a bit-level CAN 2.0B frame model (an independent
oracle), and the shipped protocol's figures against the document's own message list."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest
from canspec.ir import busload

# --- an independent model of a CAN 2.0B data frame, bit by bit --------------------------------

def bits(value: int, width: int) -> list[int]:
    return [(value >> i) & 1 for i in range(width - 1, -1, -1)]


def crc15(stream: list[int]) -> int:
    """CAN CRC-15, polynomial x^15+x^14+x^10+x^8+x^7+x^4+x^3+1 (0x4599), as in ISO 11898-1."""
    crc = 0
    for b in stream:
        nxt = b ^ ((crc >> 14) & 1)
        crc = (crc << 1) & 0x7FFF
        if nxt:
            crc ^= 0x4599
    return crc


def stuffed_region(frame_id: int, data: bytes, extended: bool) -> list[int]:
    """SOF through CRC: the part of a frame bit stuffing applies to (dominant = 0)."""
    if extended:
        head = [0] + bits(frame_id >> 18, 11) + [1, 1] + bits(frame_id & 0x3FFFF, 18) + [0, 0, 0]  # SOF ID-A SRR IDE ID-B RTR r1 r0
    else:
        head = [0] + bits(frame_id, 11) + [0, 0, 0]  # SOF ID RTR IDE r0
    head += bits(len(data), 4)
    for byte in data:
        head += bits(byte, 8)
    return head + bits(crc15(head), 15)


def stuff(stream: list[int]) -> list[int]:
    """Insert a complement bit after every 5 equal bits (stuff bits count towards the next run)."""
    out: list[int] = []
    run_bit, run = None, 0
    for b in stream:
        out.append(b)
        run = run + 1 if b == run_bit else 1
        run_bit = b
        if run == 5:
            out.append(1 - b)
            run_bit, run = 1 - b, 1
    return out


def frame_length(frame_id: int, data: bytes, extended: bool = True) -> int:
    trailer = 1 + 2 + 7 + 3  # CRC delimiter, ACK slot + delimiter, EOF, interframe space
    return len(stuff(stuffed_region(frame_id, data, extended))) + trailer


# --- the formula -----------------------------------------------------------------------------

def test_published_worst_case_lengths():
    # Davis et al. 2007: 8-byte frames take at most 135 bits (11-bit ID) and 160 bits (29-bit ID).
    assert busload.frame_bits(8, extended=False) == 135
    assert busload.frame_bits(8, extended=True) == 160


@pytest.mark.parametrize("extended", [False, True])
@pytest.mark.parametrize("dlc", range(9))
def test_unstuffed_length_matches_the_frame_model(dlc, extended):
    frame_id = 0x1801B0A0 if extended else 0x123
    region = stuffed_region(frame_id, bytes(dlc), extended)
    assert len(region) == busload.STUFFED_CONTROL_BITS[extended] + 8 * dlc
    assert busload.frame_bits(dlc, extended, stuffing=False) == len(region) + busload.UNSTUFFED_TRAILER_BITS


@pytest.mark.parametrize("length", [5, 6, 9, 10, 53, 54, 117, 118])
def test_stuff_term_is_attained_by_the_worst_pattern(length):
    # 00000 1111 0000 1111 ...: every stuff bit starts a run the next 4 bits complete.
    pattern = [0] * 5
    while len(pattern) < length:
        pattern += [1 - pattern[-1]] * 4
    pattern = pattern[:length]
    assert len(stuff(pattern)) - length == (length - 1) // 4


@pytest.mark.parametrize("dlc", range(9))
def test_no_real_frame_exceeds_the_bound(dlc):
    rng = random.Random(dlc)
    worst = busload.frame_bits(dlc, True)
    for frame_id in (0x18FFAF00, 0x1801B0A0, 0x00000000, 0x1FFFFFFF, 0x0C000000):
        for fill in (0x00, 0xFF, 0x55, 0xF0, 0x0F):
            assert frame_length(frame_id, bytes([fill]) * dlc) <= worst
        for _ in range(200):
            assert frame_length(frame_id, bytes(rng.randrange(256) for _ in range(dlc))) <= worst


def test_vector_frames_stay_within_the_bound(vectors):
    for case in vectors["cases"]:
        assert frame_length(case["frame_id"], bytes.fromhex(case["data"])) <= busload.frame_bits(8, True)


# --- the shipped protocol ----------------------------------------------------------------------

# From the document's message list (section 2): 6 frames every 20 ms, 6 every 50 ms, 12 every
# 100 ms, and the 3-frame VIN message every 500 ms; 160 bits each at worst.
EXPECTED_BITS_PER_S = 6 * 160 * 50 + 6 * 160 * 20 + 12 * 160 * 10 + 3 * 160 * 2  # 87 360
EXPECTED_BY_SENDER = {
    "Wire_Car_ECU": 2 * 8000 + 3200 + 5 * 1600,  # EPS state, driving state; vehicle state 1; states 2-5 + fault
    "AUTOCAR": 2 * 8000 + 3200 + 1600,
    "R_GATE": 2 * 8000 + 3200 + 1600,
    "RC": 3 * 3200 + 1600,  # Tele EPS/speed/control 1 at 50 ms, control 2 at 100 ms
    "ALL": 960 + 4 * 1600,  # VIN (3 frames / 500 ms) and the four ultrasonic radar messages
}


def test_total_load_of_the_shipped_protocol(can):
    load = busload.bus_load(can)
    assert load.bitrate == 250_000
    assert load.bits_per_s == EXPECTED_BITS_PER_S == 87_360
    assert load.load == Fraction(87_360, 250_000)
    assert load.headroom == 1 - Fraction(87_360, 250_000)
    assert load.frames_per_s == 6 * 50 + 6 * 20 + 12 * 10 + 3 * 2
    assert load.bits_per_s_best == load.frames_per_s * 131


def test_load_per_sender(can):
    load = busload.bus_load(can)
    got = {s.sender: s.bits_per_s for s in load.senders}
    assert got == EXPECTED_BY_SENDER
    assert sum(got.values()) == EXPECTED_BITS_PER_S


def test_multiframe_message_counts_every_frame(can):
    ml = busload.message_load(can.message("device_id"), can.bus.bitrate)
    assert ml.frames_per_cycle == 3 and ml.frames_per_s == 6 and ml.bits_per_s == 960
