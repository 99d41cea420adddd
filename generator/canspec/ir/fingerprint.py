"""Per-message layout fingerprint: a 32-bit hash of everything that decides the bytes on the
wire (like MAVLink's CRC_EXTRA). Names and descriptions do not count; layout, scaling,
signedness, ID, DLC, checksum and counter roles do."""

from __future__ import annotations

import hashlib


def layout_fingerprint(frame_id: int, dlc: int, fields: list[tuple[str, int, int, bool, str, str]], fd: bool = False) -> int:
    """`fields`: (role, start, length, signed, factor_text, offset_text) for every non-reserved signal."""
    parts = [f"id={frame_id:08X}", f"dlc={dlc}"] + (["fd"] if fd else [])
    parts += [
        f"{role}:{start}:{length}:{'s' if signed else 'u'}:{factor}:{offset}"
        for role, start, length, signed, factor, offset in sorted(fields, key=lambda f: f[1])
    ]
    return int.from_bytes(hashlib.sha256(";".join(parts).encode()).digest()[:4], "big")
