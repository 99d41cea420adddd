"""Reference codec over the IR: raw pack/unpack, XOR checksum, physical conversion with the
range rules. It produces the shared test vectors and backs `canspec decode`; the generated
C, Python and Rust code must agree with it bit for bit (cantools checks it independently)."""

from __future__ import annotations

from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import exact, round_half_away


class CodecError(ValueError):
    pass


def xor_checksum(msg: ir.Message, data: bytes | bytearray) -> int:
    assert msg.checksum is not None
    value = 0
    for b in msg.checksum.covers:
        value ^= data[b]
    return value


def pack(msg: ir.Message, raw: dict[str, int], *, fill_checksum: bool = True) -> bytes:
    """Raw values → frame bytes. Missing signals are 0, reserved bits 0, checksum computed."""
    buf = bytearray(msg.dlc)
    for sig in msg.data_signals:
        value = raw.get(sig.name, 0)
        if not sig.raw_type_min <= value <= sig.raw_type_max:
            raise CodecError(f"{msg.name}.{sig.name}: raw {value} does not fit {sig.length} bits ({sig.raw_type_min}..{sig.raw_type_max})")
        value &= sig.mask
        for seg in sig.segments:
            buf[seg.byte] |= ((value >> seg.value_shift) & ((1 << seg.width) - 1)) << seg.byte_shift
    if fill_checksum and msg.checksum is not None:
        buf[msg.checksum.byte] = xor_checksum(msg, buf)
    return bytes(buf)


def unpack(msg: ir.Message, data: bytes) -> dict[str, int]:
    """Frame bytes → raw values of every data signal."""
    if len(data) < msg.dlc:
        raise CodecError(f"{msg.name}: frame has {len(data)} bytes, needs {msg.dlc}")
    out = {}
    for sig in msg.data_signals:
        value = 0
        for seg in sig.segments:
            value |= ((data[seg.byte] >> seg.byte_shift) & ((1 << seg.width) - 1)) << seg.value_shift
        if sig.signed and value >> (sig.length - 1):
            value -= 1 << sig.length
        out[sig.name] = value
    return out


def checksum_ok(msg: ir.Message, data: bytes) -> bool:
    return msg.checksum is None or data[msg.checksum.byte] == xor_checksum(msg, data)


def to_raw(sig: ir.Signal, physical: float | str | Fraction) -> int:
    """Physical → raw with the shared rules: round half away from zero; outside the
    documented range (unless it is a special value) or not encodable is an error."""
    try:
        value = exact(physical)
    except (ValueError, ArithmeticError, TypeError):
        raise CodecError(f"{sig.name}: {physical!r} is not a finite number") from None
    q = (value - sig.offset) / sig.factor
    if not sig.raw_type_min <= q <= sig.raw_type_max:
        raise CodecError(f"{sig.name}: {physical} does not fit the {sig.length}-bit field")
    raw = round_half_away(q)
    if any(s.raw == raw for s in sig.specials):
        return raw
    if not sig.accept_min <= value <= sig.accept_max or not sig.raw_min <= raw <= sig.raw_max:
        raise CodecError(
            f"{sig.name}: {physical} is outside the allowed range [{float(sig.phys_min):g}, {float(sig.phys_max):g}]"
        )
    return raw


def to_physical(sig: ir.Signal, raw: int) -> Fraction:
    return raw * sig.factor + sig.offset
