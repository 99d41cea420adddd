"""Worst-case CAN bus load of a protocol: frame lengths with bit stuffing, per message, per sender.

Frame length (Davis, Burns, Bril, Lukkien, "Controller Area Network (CAN) schedulability analysis:
Refuted, revisited and revised", Real-Time Systems 35(3):239-272, 2007 — the worst-case frame
transmission time C_m of their CAN model, in bits):

    C = g + 8n + 13 + floor((g + 8n - 1) / 4)   bits

n data bytes; g = 34 control bits exposed to stuffing for an 11-bit ID (SOF, ID, RTR, IDE, r0,
DLC, CRC) and 54 for a 29-bit ID (SOF, 11-bit base ID, SRR, IDE, 18-bit extension, RTR, r1, r0,
DLC, CRC); 13 bits that are never stuffed (CRC delimiter, ACK slot and delimiter, 7-bit EOF,
3-bit interframe space); the floor term is the most stuff bits the stuffed region can need
(one after the first 5 equal bits, then one per 4 bits). 8 bytes, 29-bit ID: 160 bits.

CAN FD frames (ISO 11898-1:2015, FD base and extended format, the ISO CRC with its stuff count)
take two bit rates: the arbitration phase at the bus's nominal bitrate and, with bit-rate
switching (BRS), the data phase at `bus.data_bitrate`. In bits, n data bytes:

    A = 17 (11-bit ID: SOF, ID 11, RRS, IDE, FDF, res, BRS)
        36 (29-bit ID: SOF, base ID 11, SRR, IDE, ID extension 18, RRS, FDF, res, BRS)
    D = 5 + 8n (ESI, DLC 4, data): dynamically stuffed together with A, as one run
    S = floor((A + D - 1) / 4) dynamic stuff bits at worst (Davis's bound over SOF..data), of which
        S_A = floor((A - 2) / 4) come before the end of BRS (after bit 5, 9, ... of the frame)
    F = 4 + c + ceil((4 + c) / 4): stuff count (3-bit Gray code + parity), the c = 17-bit CRC
        (n <= 16) or 21-bit CRC (n > 16), and the fixed stuff bits (one before the stuff count,
        then one after every 4 bits): 27 or 32, whatever the data
    nominal bits = A + S_A + 13 (CRC delimiter, ACK slot and delimiter, EOF 7, interframe space 3)
    data-phase bits = D + S - S_A + F

BRS and the CRC delimiter each straddle a switch of the bit rate (at their sample points); both are
counted at the nominal rate, so the figure is an upper bound. Without BRS every bit goes at the
nominal rate. A frame's length is stated in nominal bit times (nominal + data-phase bits ×
bitrate / data_bitrate) so one load = bits per second / bitrate serves classic and FD frames. The
field lengths are ISO 11898-1:2015's FD frame formats with the ISO CRC field (stuff count, CRC-17 /
CRC-21, fixed stuff bits), as Vector's CAN FD course describes them
(https://elearning.vector.com/mod/page/view.php?id=369 and id=1651: the CRC field starts with a
stuff bit, then one after every 4 bits; no dynamic stuffing after the data field) and as public CAN
FD bus-load calculators count them. Worked example: 64 bytes, 11-bit ID, BRS, 500 kbit/s / 2
Mbit/s: at most 33 nominal + 679 data-phase bits = 202.75 nominal bit times (405.5 µs).

All arithmetic is exact (Fraction) so the published figures never depend on float rounding.
Event-driven messages have no rate to count: they are left out of the figures and listed apart.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from canspec import ir

STUFFED_CONTROL_BITS = {False: 34, True: 54}  # g, by is_extended
UNSTUFFED_TRAILER_BITS = 13  # CRC delimiter 1 + ACK 2 + EOF 7 + interframe space 3


FD_ARBITRATION_BITS = {False: 17, True: 36}  # A: SOF .. BRS, by is_extended
FD_CONTROL_BITS = 5  # ESI + DLC, sent in the data phase before the data
STUFF_COUNT_BITS = 4  # 3-bit Gray-coded count of the dynamic stuff bits + parity


def frame_bits(dlc: int, extended: bool = True, stuffing: bool = True) -> int:
    """Length on the bus of one classic data frame, interframe space included; worst case when stuffing."""
    g = STUFFED_CONTROL_BITS[extended]
    stuffed_region = g + 8 * dlc
    stuff = (stuffed_region - 1) // 4 if stuffing else 0
    return stuffed_region + UNSTUFFED_TRAILER_BITS + stuff


def fd_crc_bits(dlc: int) -> int:
    """CRC-17 up to 16 data bytes, CRC-21 above."""
    return 17 if dlc <= 16 else 21


def fd_crc_field_bits(dlc: int) -> int:
    """Stuff count, CRC sequence and their fixed stuff bits (one before the stuff count, one after every 4 bits)."""
    sequence = STUFF_COUNT_BITS + fd_crc_bits(dlc)
    return sequence + -(-sequence // 4)


@dataclass(frozen=True)
class FdFrameBits:
    """One CAN FD frame's bits: those at the nominal bitrate and those of the data phase."""

    nominal: int
    data: int

    def nominal_times(self, brs: bool, bitrate: int, data_bitrate: int | None) -> Fraction:
        """The frame's duration in nominal bit times: the data phase is faster with BRS."""
        if brs and data_bitrate:
            return self.nominal + Fraction(self.data * bitrate, data_bitrate)
        return Fraction(self.nominal + self.data)


def fd_frame_bits(dlc: int, extended: bool = True, stuffing: bool = True) -> FdFrameBits:
    """Length on the bus of one CAN FD data frame, split by phase; worst case when stuffing."""
    a, d = FD_ARBITRATION_BITS[extended], FD_CONTROL_BITS + 8 * dlc
    stuff, stuff_a = ((a + d - 1) // 4, (a - 2) // 4) if stuffing else (0, 0)
    return FdFrameBits(a + stuff_a + UNSTUFFED_TRAILER_BITS, d + stuff - stuff_a + fd_crc_field_bits(dlc))


def fd_formula_facts() -> dict[str, int]:
    """The FD formula's constants, for the handbook's statement of it."""
    return {"a_standard": FD_ARBITRATION_BITS[False], "a_extended": FD_ARBITRATION_BITS[True], "control": FD_CONTROL_BITS,
            "stuff_count": STUFF_COUNT_BITS, "crc_short": fd_crc_field_bits(16), "crc_long": fd_crc_field_bits(64),
            "example_nominal": fd_frame_bits(64, False).nominal, "example_data": fd_frame_bits(64, False).data}


@dataclass(frozen=True)
class MessageLoad:
    message: ir.Message
    frames_per_cycle: int  # a multi-frame message sends all its frames every cycle (worst case)
    bits_min: int | Fraction  # frame length without stuff bits (an FD frame's: in nominal bit times)
    bits_max: int | Fraction  # worst-case frame length
    phases: FdFrameBits | None  # an FD frame's worst-case bits per phase (None: a classic frame)
    frames_per_s: Fraction
    bits_per_s: Fraction  # worst case
    load: Fraction  # share of the bit rate, 0..1


@dataclass(frozen=True)
class SenderLoad:
    sender: str
    messages: tuple[MessageLoad, ...]
    frames_per_s: Fraction
    bits_per_s: Fraction
    load: Fraction


@dataclass(frozen=True)
class BusLoad:
    bitrate: int
    data_bitrate: int | None  # CAN FD data phase (frames with BRS)
    messages: tuple[MessageLoad, ...]  # the cyclic messages, document order
    senders: tuple[SenderLoad, ...]  # in node order, then "ALL"
    event_driven: tuple[ir.Message, ...]  # not counted: sent on change or on request, at no fixed rate
    frames_per_s: Fraction
    bits_per_s: Fraction
    bits_per_s_best: Fraction  # the same traffic with no stuff bits at all
    load: Fraction
    headroom: Fraction  # 1 - load

    @property
    def load_best(self) -> Fraction:
        return self.bits_per_s_best / self.bitrate

    @property
    def spare_bits_per_s(self) -> Fraction:
        return self.bitrate - self.bits_per_s


def message_bits(msg: ir.Message, bitrate: int, data_bitrate: int | None, stuffing: bool = True) -> int | Fraction:
    """One frame of `msg` in nominal bit times: a classic frame's bits, an FD frame's two phases."""
    if not msg.is_fd:
        return frame_bits(msg.dlc, msg.is_extended, stuffing)
    return fd_frame_bits(msg.dlc, msg.is_extended, stuffing).nominal_times(msg.brs, bitrate, data_bitrate)


def message_load(msg: ir.Message, bitrate: int, data_bitrate: int | None = None) -> MessageLoad:
    assert msg.cycle_ms is not None, "an event-driven message has no rate"
    frames = msg.multiframe.frames if msg.multiframe is not None else 1
    frames_per_s = Fraction(1000 * frames, msg.cycle_ms)
    worst = message_bits(msg, bitrate, data_bitrate)
    bits_per_s = frames_per_s * worst
    phases = fd_frame_bits(msg.dlc, msg.is_extended) if msg.is_fd else None
    return MessageLoad(msg, frames, message_bits(msg, bitrate, data_bitrate, stuffing=False), worst, phases, frames_per_s, bits_per_s,
                       bits_per_s / bitrate)


def bus_load(can: ir.CanProtocol) -> BusLoad:
    rate, data_rate = can.bus.bitrate, can.bus.data_bitrate
    loads = tuple(message_load(m, rate, data_rate) for m in can.messages if m.is_cyclic)
    order = [n.name for n in can.nodes]
    order += sorted({m.sender for m in can.messages} - set(order))
    senders = []
    for name in order:
        mine = tuple(ml for ml in loads if ml.message.sender == name)
        if mine:
            bps = sum((ml.bits_per_s for ml in mine), Fraction(0))
            senders.append(SenderLoad(name, mine, sum((ml.frames_per_s for ml in mine), Fraction(0)), bps, bps / rate))
    total = sum((ml.bits_per_s for ml in loads), Fraction(0))
    best = sum((ml.frames_per_s * ml.bits_min for ml in loads), Fraction(0))
    events = tuple(m for m in can.messages if not m.is_cyclic)
    return BusLoad(rate, data_rate, loads, tuple(senders), events, sum((ml.frames_per_s for ml in loads), Fraction(0)), total, best, total / rate,
                   1 - total / rate)
