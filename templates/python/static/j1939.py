"""J1939 29-bit identifiers (SAE J1939-21): priority(3) EDP(1) DP(1) PF(8) PS(8) SA(8).
PF < 240 is PDU1 (PS is the destination address), PF >= 240 is PDU2 (broadcast, PS is a
group extension and part of the PGN)."""

from __future__ import annotations

from typing import NamedTuple

__all__ = ["PDU2_MIN_PF", "J1939Id", "compose", "decompose"]

PDU2_MIN_PF = 240


class J1939Id(NamedTuple):
    priority: int
    edp: int
    dp: int
    pf: int
    ps: int
    sa: int
    pgn: int
    da: int | None  # destination address (PDU1); None for broadcast PDU2

    @property
    def is_pdu2(self) -> bool:
        return self.pf >= PDU2_MIN_PF


def decompose(frame_id: int) -> J1939Id:
    """The J1939 fields of a 29-bit frame ID."""
    if not 0 <= frame_id <= 0x1FFFFFFF:
        raise ValueError(f"frame ID 0x{frame_id:X} is not a 29-bit identifier")
    pf = (frame_id >> 16) & 0xFF
    ps = (frame_id >> 8) & 0xFF
    pdu2 = pf >= PDU2_MIN_PF
    edp = (frame_id >> 25) & 1
    dp = (frame_id >> 24) & 1
    pgn = (edp << 17) | (dp << 16) | (pf << 8) | (ps if pdu2 else 0)
    return J1939Id((frame_id >> 26) & 7, edp, dp, pf, ps, frame_id & 0xFF, pgn, None if pdu2 else ps)


def compose(priority: int, pgn: int, sa: int, da: int | None = None) -> int:
    """A 29-bit frame ID from priority, PGN, source address and (PDU1 only) destination address."""
    if not 0 <= priority <= 7:
        raise ValueError(f"priority {priority} is outside 0..7")
    if not 0 <= pgn <= 0x3FFFF:
        raise ValueError(f"PGN 0x{pgn:X} is outside 0..0x3FFFF")
    if not 0 <= sa <= 0xFF or (da is not None and not 0 <= da <= 0xFF):
        raise ValueError("addresses are 0..255")
    pf = (pgn >> 8) & 0xFF
    if pf < PDU2_MIN_PF:
        pgn = (pgn & 0x3FF00) | (0xFF if da is None else da)
    elif da is not None:
        raise ValueError(f"PGN 0x{pgn:X} is a broadcast (PDU2) group: it has no destination address")
    return (priority << 26) | (pgn << 8) | sa
