"""J1939 29-bit identifier fields (SAE J1939-21): P(3) EDP(1) DP(1) PF(8) PS(8) SA(8)."""

from __future__ import annotations

from canspec.ir import J1939Id
from canspec.ir.ids import MAX_EXTENDED_ID

PDU2_MIN_PF = 240  # PF >= 240: broadcast, PS is a group extension
GLOBAL_ADDRESS = 0xFF  # the destination "every node" of a PDU1 group
ID_MASK = MAX_EXTENDED_ID  # a J1939 identifier is a 29-bit one
PRIORITY_SHIFT = 26
PRIORITY_MASK = 0x7 << PRIORITY_SHIFT  # the 3 priority bits in the identifier


def decompose(frame_id: int) -> J1939Id:
    priority = (frame_id & PRIORITY_MASK) >> PRIORITY_SHIFT
    edp = (frame_id >> 25) & 0x1
    dp = (frame_id >> 24) & 0x1
    pf = (frame_id >> 16) & 0xFF
    ps = (frame_id >> 8) & 0xFF
    sa = frame_id & 0xFF
    pdu2 = pf >= PDU2_MIN_PF
    pgn = (edp << 17) | (dp << 16) | (pf << 8) | (ps if pdu2 else 0)
    return J1939Id(priority, edp, dp, pf, ps, sa, pgn, None if pdu2 else ps, pdu2, f"0x{pgn:05X}")


def compose(priority: int, pgn: int, sa: int, da: int | None = None) -> int:
    """29-bit ID from priority, PGN, source and (for PDU1) destination address."""
    pf = (pgn >> 8) & 0xFF
    if pf < PDU2_MIN_PF:
        pgn = (pgn & 0x3FF00) | ((da if da is not None else GLOBAL_ADDRESS) & 0xFF)
    return ((priority << PRIORITY_SHIFT) & PRIORITY_MASK) | ((pgn & 0x3FFFF) << 8) | (sa & 0xFF)
