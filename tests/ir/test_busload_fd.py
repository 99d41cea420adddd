"""CAN FD bus load: the two-phase frame length against a bit-level model of an ISO 11898-1:2015 FD
frame (an independent oracle: the frame built bit by bit, dynamically stuffed from SOF to the end of
the data, the CRC field with its stuff count and fixed stuff bits), figures worked out by hand for
three frames, and the FD fixture's load against its own message list."""

from __future__ import annotations

import random
from fractions import Fraction
from pathlib import Path

import pytest
from canspec.ir import busload
from canspec.ir.fd import FD_LENGTHS, dlc_code
from canspec.pipeline import compile_spec

FIXTURE = Path(__file__).resolve().parents[1] / "fixtures" / "valid" / "motorola_fd_float.yaml"


def bits(value: int, width: int) -> list[int]:
    return [(value >> i) & 1 for i in range(width - 1, -1, -1)]


def arbitration(frame_id: int, extended: bool, brs: bool) -> list[int]:
    """SOF .. BRS (dominant = 0): RRS and res dominant, FDF recessive."""
    if extended:
        return [0] + bits(frame_id >> 18, 11) + [1, 1] + bits(frame_id & 0x3FFFF, 18) + [0, 1, 0, int(brs)]  # SRR IDE ID-B RRS FDF res BRS
    return [0] + bits(frame_id, 11) + [0, 0, 1, 0, int(brs)]  # RRS IDE FDF res BRS


def dynamic_stuff(stream: list[int]) -> list[bool]:
    """Per bit sent, whether it is a stuff bit: a complement after 5 equal bits, none after the last bit
    (the CRC field's first fixed stuff bit follows the data field)."""
    out: list[bool] = []
    run_bit, run = None, 0
    for i, b in enumerate(stream):
        out.append(False)
        run = run + 1 if b == run_bit else 1
        run_bit = b
        if run == 5 and i < len(stream) - 1:
            out.append(True)
            run_bit, run = 1 - b, 1
    return out


def crc_field(length: int, stuff_bits: int) -> int:
    """Bits of the CRC field before its delimiter: a fixed stuff bit, then one after every 4 bits of
    the stuff count (Gray code of the count mod 8, parity) and the CRC sequence."""
    gray = (stuff_bits % 8) ^ ((stuff_bits % 8) >> 1)
    sequence = bits(gray, 3) + [gray.bit_count() % 2] + [0] * (17 if length <= 16 else 21)  # the CRC's value never matters
    sent = 0
    for i, _ in enumerate(sequence):
        sent += 1 + (i % 4 == 0)  # the fixed stuff bit before bits 0, 4, 8, ...
    return sent


def frame(frame_id: int, data: bytes, extended: bool, brs: bool, stuffing: bool = True) -> tuple[int, int]:
    """(bits at the nominal rate, bits of the data phase) of one FD frame, the phase switching after BRS
    and back at the CRC delimiter (counted at the nominal rate, with ACK, EOF and the interframe space)."""
    arb = arbitration(frame_id, extended, brs)
    stream = arb + [0] + bits(dlc_code(len(data)), 4) + [b for byte in data for b in bits(byte, 8)]  # ESI DLC data
    flags = dynamic_stuff(stream) if stuffing else [False] * len(stream)
    real, nominal = 0, 0
    for is_stuff in flags:  # every bit up to and including BRS is sent at the nominal rate
        if real == len(arb):
            break
        nominal += 1
        real += not is_stuff
    data_phase = len(flags) - nominal + crc_field(len(data), sum(flags))
    return nominal + 1 + 2 + 7 + 3, data_phase


@pytest.mark.parametrize("extended", [False, True])
@pytest.mark.parametrize("length", FD_LENGTHS)
def test_unstuffed_length_matches_the_frame_model(length, extended):
    fb = busload.fd_frame_bits(length, extended, stuffing=False)
    assert (fb.nominal, fb.data) == frame(0x1801B0A0 if extended else 0x123, bytes(length), extended, True, stuffing=False)


@pytest.mark.parametrize("extended", [False, True])
@pytest.mark.parametrize("length", FD_LENGTHS)
def test_no_real_frame_exceeds_the_bound_in_either_phase(length, extended):
    rng = random.Random(length * 2 + extended)
    worst = busload.fd_frame_bits(length, extended)
    ids = (0x1FFFFFFF, 0x00000000, 0x0C000000, 0x18FFAF00) if extended else (0x000, 0x7FF, 0x555, 0x0F0)
    most = (0, 0)
    for frame_id in ids:
        payloads = [bytes([fill]) * length for fill in (0x00, 0xFF, 0x55, 0xF0, 0x0F, 0x87)] + [rng.randbytes(length) for _ in range(100)]
        for data in payloads:
            nominal, data_phase = frame(frame_id, data, extended, True)
            assert nominal <= worst.nominal and nominal + data_phase <= worst.nominal + worst.data
            most = max(most, (nominal, data_phase))
    assert most[0] >= worst.nominal - 2  # the bound is near what frames reach (an all-zero ID stuffs the arbitration phase fully)


def test_fixed_bits_of_the_crc_field():
    # stuff count 4 + CRC + fixed stuff bits: ceil(21 / 4) = 6 with CRC-17, ceil(25 / 4) = 7 with CRC-21
    assert [busload.fd_crc_field_bits(n) for n in (0, 8, 12, 16, 20, 64)] == [27, 27, 27, 27, 32, 32]


# Worked by hand from the field lengths (ISO 11898-1:2015), A = 17 / 36 arbitration bits up to BRS:
#  64 bytes, 11-bit, BRS: D = 5 + 512 = 517; dynamic stuff floor((17 + 517 - 1) / 4) = 133, 3 of them
#    before BRS (after bits 5, 9, 13); nominal 17 + 3 + 13 = 33; data 517 + 130 + 4 + 21 + 7 = 679.
#  12 bytes, 11-bit, no BRS: D = 101; stuff floor(117 / 4) = 29, 3 before BRS; 33 and 101 + 26 + 27 = 154.
#  16 bytes, 29-bit, BRS: D = 133; stuff floor(168 / 4) = 42, floor(34 / 4) = 8 before BRS;
#    nominal 36 + 8 + 13 = 57; data 133 + 34 + 4 + 17 + 6 = 194.
HAND = [(64, False, (33, 679)), (12, False, (33, 154)), (16, True, (57, 194))]


@pytest.mark.parametrize(("length", "extended", "expected"), HAND)
def test_hand_computed_frames(length, extended, expected):
    fb = busload.fd_frame_bits(length, extended)
    assert (fb.nominal, fb.data) == expected


def test_hand_computed_frame_times():
    # 500 kbit/s nominal, 2 Mbit/s data: 33 × 2 µs + 679 × 0.5 µs = 405.5 µs = 202.75 nominal bit times
    assert busload.fd_frame_bits(64, False).nominal_times(True, 500_000, 2_000_000) == Fraction(81100, 400) == Fraction(811, 4)
    assert busload.fd_frame_bits(12, False).nominal_times(False, 500_000, 2_000_000) == 187  # no BRS: all nominal
    assert busload.fd_frame_bits(16, True).nominal_times(True, 500_000, 2_000_000) == 57 + Fraction(194, 4)


def test_the_fd_fixture_load():
    """motorola_fd_float: a classic 8-byte frame every 10 ms (135 bits), the 64-byte BRS frame every
    50 ms (811/4 nominal bit times) and the 12-byte frame without BRS every 100 ms (187 bits)."""
    can = compile_spec(FIXTURE).spec.can
    load = busload.bus_load(can)
    assert (load.bitrate, load.data_bitrate) == (500_000, 2_000_000)
    assert [ml.bits_max for ml in load.messages] == [135, Fraction(811, 4), 187]
    assert load.bits_per_s == 100 * 135 + 20 * Fraction(811, 4) + 10 * 187 == Fraction(19425)
    assert load.load == Fraction(19425, 500_000)
    # without stuff bits: 111; 30 + (517 + 32) / 4; 30 + 101 + 27
    assert load.bits_per_s_best == 100 * 111 + 20 * (30 + Fraction(549, 4)) + 10 * 158
