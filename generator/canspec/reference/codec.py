"""The reference codec, read straight from the IR: raw pack/unpack, the XOR checksum, physical
conversion with the range rules, and per-message decoders compiled for `canspec decode`. It
produces the shared test vectors; the generated C, Python and Rust code must agree with it bit
for bit (cantools, reading the generated DBC, checks it independently).

A frame of up to 8 bytes is handled as one little-endian integer `v` (the frame word): every
field of an Intel-order message is `(v & word_mask) >> start`, sign-extended with `sign_bit`."""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import exact, round_half_away


class CodecError(ValueError):
    pass


def frame_word(data: bytes | bytearray) -> int:
    return int.from_bytes(data, "little")


def raw_value(sig: ir.Signal, v: int) -> int:
    """The raw value of a field in the frame word `v`."""
    return (((v & sig.word_mask) >> sig.start) ^ sig.sign_bit) - sig.sign_bit


def xor_checksum(msg: ir.Message, v: int) -> int:
    """The XOR of the bytes the message's checksum covers, from the frame word."""
    assert msg.checksum is not None
    c, x = v & msg.checksum.cover_mask, 0
    while c:
        x ^= c & 0xFF
        c >>= 8
    return x


def checksum_ok(msg: ir.Message, data: bytes | bytearray) -> bool:
    return msg.checksum is None or data[msg.checksum.byte] == xor_checksum(msg, frame_word(data))


def pack(msg: ir.Message, raw: dict[str, int], *, fill_checksum: bool = True) -> bytes:
    """Raw values → frame bytes. Missing signals are 0, reserved bits 0, checksum computed."""
    v = 0
    for sig in msg.data_signals:
        value = raw.get(sig.name, 0)
        if not sig.raw_type_min <= value <= sig.raw_type_max:
            raise CodecError(f"{msg.name}.{sig.name}: raw {value} does not fit {sig.length} bits ({sig.raw_type_min}..{sig.raw_type_max})")
        v |= (value << sig.start) & sig.word_mask
    if fill_checksum and msg.checksum is not None:
        v = (v & ~(0xFF << 8 * msg.checksum.byte)) | xor_checksum(msg, v) << 8 * msg.checksum.byte
    return v.to_bytes(msg.dlc, "little")


def unpack(msg: ir.Message, data: bytes | bytearray) -> dict[str, int]:
    """Frame bytes → raw values of every data signal."""
    if len(data) < msg.dlc:
        raise CodecError(f"{msg.name}: frame has {len(data)} bytes, needs {msg.dlc}")
    v = frame_word(data[: msg.dlc])
    return {sig.name: raw_value(sig, v) for sig in msg.data_signals}


def to_raw(sig: ir.Signal, physical: float | str | Fraction) -> int:
    """Physical → raw with the shared rules: round half away from zero; outside the
    documented range (unless it is a special value) or not encodable is an error."""
    try:
        value = exact(physical)
    except (ValueError, ArithmeticError, TypeError):
        raise CodecError(f"{sig.name}: {physical!r} is not a finite number") from None
    # the rounded value must fit, not q: a decoded value at the field's end (5 bits, 31 × 0.1 -
    # 0.05 = 3.0500000000000003 in doubles) lies a hair beyond it and rounds back into it
    raw = round_half_away((value - sig.offset) / sig.factor)
    if not sig.raw_type_min <= raw <= sig.raw_type_max:
        raise CodecError(f"{sig.name}: {physical} does not fit the {sig.length}-bit field")
    if any(s.raw == raw for s in sig.specials):
        return raw
    if not sig.accept_min <= value <= sig.accept_max or not sig.raw_min <= raw <= sig.raw_max:
        raise CodecError(f"{sig.name}: {physical} is outside the allowed range [{float(sig.phys_min):g}, {float(sig.phys_max):g}]")
    return raw


# --- decoding many frames fast (`canspec decode`) ----------------------------------------------

TABLE_BITS = 10  # unsigned fields up to this wide get the text of every raw value precomputed


def physical_number(sig: ir.Signal, raw: int) -> float | int:
    """The physical value as a Python number: exact int arithmetic for integer scaling, doubles
    (raw * factor + offset, as every generated language computes them) otherwise."""
    if sig.is_integer:
        return raw * int(sig.factor) + int(sig.offset)
    return raw * float(sig.factor) + float(sig.offset)


def value_text(sig: ir.Signal, raw: int) -> str:
    """A value as printed: its label, or the number in the signal's precision."""
    label = sig.label_of(raw)
    if label is not None:
        return label.name
    phys = physical_number(sig, raw)
    return f"{phys:.{sig.decimals}f}" if sig.decimals else str(phys)


def signal_text(sig: ir.Signal, raw: int) -> str:
    """`name=value[ unit]` as the text output prints it."""
    text = value_text(sig, raw)
    return f"{sig.name}={text} {sig.unit}" if sig.unit and sig.label_of(raw) is None else f"{sig.name}={text}"


def text_decoder(msg: ir.Message) -> Callable[[int], str]:
    """A function from the frame word to the text line's fields, compiled once per message:
    straight-line code, with a precomputed text per raw value for narrow fields."""
    env: dict[str, object] = {"signal_text": signal_text}
    pieces = []
    for i, s in enumerate(msg.data_signals):
        raw = f"((v >> {s.start}) & {s.mask})"
        if s.sign_bit:
            raw = f"(({raw} ^ {s.sign_bit}) - {s.sign_bit})"
        if not s.sign_bit and s.length <= TABLE_BITS:
            env[f"T{i}"] = tuple(signal_text(s, r) for r in range(s.mask + 1))
            pieces.append(f"T{i}[{raw}]")
        elif s.labels or (not s.is_integer and not s.decimals):
            env[f"S{i}"] = s
            pieces.append(f"signal_text(S{i}, {raw})")
        else:
            unit = f" {s.unit}" if s.unit else ""
            spec = f".{s.decimals}f" if s.decimals else "d"
            factor, offset = (int(s.factor), int(s.offset)) if s.is_integer else (float(s.factor), float(s.offset))
            pattern = f"{s.name}=%{spec}{unit}".replace("%", "%%").replace(f"%%{spec}", f"%{spec}", 1)
            pieces.append(f"{pattern!r} % ({raw} * {factor!r} + {offset!r})")
    body = f"', '.join(({', '.join(pieces)},))" if pieces else "''"
    namespace: dict[str, object] = {}
    exec(f"def fields(v):\n    return {body}\n", env, namespace)  # noqa: S102 - source built from the IR's numbers and identifiers
    return namespace["fields"]  # type: ignore[return-value]
