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
All arithmetic is exact (Fraction) so the published figures never depend on float rounding.
Event-driven messages have no rate to count: they are left out of the figures and listed apart.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from canspec import ir

STUFFED_CONTROL_BITS = {False: 34, True: 54}  # g, by is_extended
UNSTUFFED_TRAILER_BITS = 13  # CRC delimiter 1 + ACK 2 + EOF 7 + interframe space 3


def frame_bits(dlc: int, extended: bool = True, stuffing: bool = True) -> int:
    """Length on the bus of one data frame, interframe space included; worst case when stuffing."""
    g = STUFFED_CONTROL_BITS[extended]
    stuffed_region = g + 8 * dlc
    stuff = (stuffed_region - 1) // 4 if stuffing else 0
    return stuffed_region + UNSTUFFED_TRAILER_BITS + stuff


@dataclass(frozen=True)
class MessageLoad:
    message: ir.Message
    frames_per_cycle: int  # a multi-frame message sends all its frames every cycle (worst case)
    bits_min: int  # frame length without stuff bits
    bits_max: int  # worst-case frame length
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


def message_load(msg: ir.Message, bitrate: int) -> MessageLoad:
    assert msg.cycle_ms is not None, "an event-driven message has no rate"
    frames = msg.multiframe.frames if msg.multiframe is not None else 1
    frames_per_s = Fraction(1000 * frames, msg.cycle_ms)
    worst = frame_bits(msg.dlc, msg.is_extended)
    bits_per_s = frames_per_s * worst
    return MessageLoad(msg, frames, frame_bits(msg.dlc, msg.is_extended, stuffing=False), worst, frames_per_s, bits_per_s,
                       bits_per_s / bitrate)


def bus_load(can: ir.CanProtocol) -> BusLoad:
    rate = can.bus.bitrate
    loads = tuple(message_load(m, rate) for m in can.messages if m.is_cyclic)
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
    return BusLoad(rate, loads, tuple(senders), events, sum((ml.frames_per_s for ml in loads), Fraction(0)), total, best, total / rate,
                   1 - total / rate)
