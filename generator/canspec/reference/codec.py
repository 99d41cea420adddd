"""The reference codec, read straight from the IR: raw pack/unpack, the XOR checksum, physical
conversion with the range rules, and per-message decoders compiled for `canspec decode`. It
produces the shared test vectors; the generated C, Python and Rust code must agree with it bit
for bit (cantools, reading the generated DBC, checks it independently).

A frame (up to 64 bytes) is handled as one integer, the frame word, read in the order of each
field: every field is `(v & word_mask) >> word_shift` of the little-endian word (Intel) or of the
big-endian one (Motorola), sign-extended with `sign_bit`; a float field's raw value is its bit
pattern, and its physical value the float those bits hold.

A multiplexed message (ir/mux.py) decodes to its multiplexers' values and the fields of the page
they select, and nothing of the other pages: the multiplexer values in the decoded form say which
page it holds. Packing writes the selected page's fields only (the other bits 0) and refuses a
field of another page."""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import bits_of_float, exact, float_of_bits, round_half_away


class CodecError(ValueError):
    pass


def frame_word(data: bytes | bytearray) -> int:
    return int.from_bytes(data, "little")


def raw_value(sig: ir.Signal, v: int, big: int | None = None) -> int:
    """The raw value of a field in the frame word `v` (little-endian) or, for a Motorola field,
    `big` (the same bytes read big-endian: big_word)."""
    word = v if not sig.is_big_endian else big
    if word is None:
        raise ValueError(f"{sig.name}: a Motorola field needs the big-endian frame word")
    return (((word & sig.word_mask) >> sig.word_shift) ^ sig.sign_bit) - sig.sign_bit


def big_word(v: int, dlc: int) -> int:
    """The big-endian frame word of the little-endian one `v` of a dlc-byte frame."""
    return int.from_bytes(v.to_bytes(dlc, "little"), "big")


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
    """Raw values → frame bytes. Missing signals are 0, reserved bits 0, checksum computed. In a
    multiplexed message the multiplexers' values in `raw` (missing: 0) select the fields written;
    a field of another page is an error."""
    v = big = 0
    for sig in _present(msg, raw):
        value = raw.get(sig.name, 0)
        if not sig.raw_type_min <= value <= sig.raw_type_max:
            raise CodecError(f"{msg.name}.{sig.name}: raw {value} does not fit {sig.length} bits ({sig.raw_type_min}..{sig.raw_type_max})")
        if sig.is_big_endian:
            big |= (value << sig.word_shift) & sig.word_mask
        else:
            v |= (value << sig.word_shift) & sig.word_mask
    if big:
        v |= int.from_bytes(big.to_bytes(msg.dlc, "big"), "little")
    if fill_checksum and msg.checksum is not None:
        v = (v & ~(0xFF << 8 * msg.checksum.byte)) | xor_checksum(msg, v) << 8 * msg.checksum.byte
    return v.to_bytes(msg.dlc, "little")


def _present(msg: ir.Message, raw: dict[str, int]) -> tuple[ir.Signal, ...]:
    if not msg.is_multiplexed:
        return msg.data_signals
    present = msg.present(raw)
    names = {s.name for s in present}
    stray = [s.name for s in msg.data_signals if s.name in raw and s.name not in names]
    if stray:
        selected = ", ".join(f"{m.name}={raw.get(m.name, 0)}" for m in msg.multiplexers if m.name in names)
        raise CodecError(f"{msg.name}: {', '.join(stray)} not on the page {selected} selects")
    return present


def unpack(msg: ir.Message, data: bytes | bytearray) -> dict[str, int]:
    """Frame bytes → raw values of every data signal the frame holds (in a multiplexed message: the
    multiplexers and the fields of the pages they select)."""
    if len(data) < msg.dlc:
        raise CodecError(f"{msg.name}: frame has {len(data)} bytes, needs {msg.dlc}")
    v = frame_word(data[: msg.dlc])
    big = int.from_bytes(data[: msg.dlc], "big")
    if not msg.is_multiplexed:
        return {sig.name: raw_value(sig, v, big) for sig in msg.data_signals}
    values = {m.name: raw_value(m, v, big) for m in msg.multiplexers}
    return {sig.name: raw_value(sig, v, big) for sig in msg.present(values)}


def to_raw(sig: ir.Signal, physical: float | str | Fraction) -> int:
    """Physical → raw with the shared rules: round half away from zero; outside the
    documented range (unless it is a special value) or not encodable is an error."""
    if sig.is_float:
        return float_raw(sig, physical)
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


def float_raw(sig: ir.Signal, physical: float | str | Fraction) -> int:
    """A float field's bit pattern: the value rounded to the format (binary32: to nearest). NaN and
    ±Inf pass where no range is documented; a finite value must lie in the range (the format's
    finite range without one)."""
    try:
        x = float(physical)
    except (ValueError, TypeError, OverflowError):
        raise CodecError(f"{sig.name}: {physical!r} is not a number") from None
    finite = math.isfinite(x)
    if (finite and not sig.accept_min <= Fraction(x) <= sig.accept_max) or (not finite and sig.doc_min is not None):
        raise CodecError(f"{sig.name}: {physical} is outside the allowed range [{float(sig.check_min):g}, {float(sig.check_max):g}]")
    return bits_of_float(x, sig.length)


def physical_value(sig: ir.Signal, raw: int) -> float | int | Fraction:
    """A field's physical value: exact (Fraction, int) for an integer field, the float for a float one."""
    return float_of_bits(raw, sig.length) if sig.is_float else sig.physical(raw)


# --- decoding many frames fast (`canspec decode`) ----------------------------------------------

TABLE_BITS = 10  # unsigned fields up to this wide get the text of every raw value precomputed


def physical_number(sig: ir.Signal, raw: int) -> float | int:
    """The physical value as a Python number: exact int arithmetic for integer scaling, doubles
    (raw * factor + offset, as every generated language computes them) otherwise."""
    if sig.is_float:
        return float_of_bits(raw, sig.length)
    if sig.is_integer:
        return raw * int(sig.factor) + int(sig.offset)
    return raw * float(sig.factor) + float(sig.offset)


def value_text(sig: ir.Signal, raw: int) -> str:
    """A value as printed: its label, or the number in the signal's precision."""
    label = sig.label_of(raw)
    if label is not None:
        return label.name
    phys = physical_number(sig, raw)
    if sig.is_float:
        return repr(phys)  # the shortest text that reads back to the same float (nan, inf, -0.0)
    return f"{phys:.{sig.decimals}f}" if sig.decimals else str(phys)


def signal_text(sig: ir.Signal, raw: int) -> str:
    """`name=value[ unit]` as the text output prints it."""
    text = value_text(sig, raw)
    return f"{sig.name}={text} {sig.unit}" if sig.unit and sig.label_of(raw) is None else f"{sig.name}={text}"


def text_decoder(msg: ir.Message) -> Callable[[int], str]:
    """A function from the frame word to the text line's fields, compiled once per message:
    straight-line code, with a precomputed text per raw value for narrow fields; a multiplexed
    message prints its multiplexers and the selected pages' fields."""
    if msg.is_multiplexed:
        return _page_text_decoder(msg)
    env: dict[str, object] = {"signal_text": signal_text}
    pieces = []
    for i, s in enumerate(msg.data_signals):
        raw = f"(({'b' if s.is_big_endian else 'v'} >> {s.word_shift}) & {s.mask})"
        if s.sign_bit:
            raw = f"(({raw} ^ {s.sign_bit}) - {s.sign_bit})"
        if s.is_float:
            env[f"S{i}"] = s
            pieces.append(f"signal_text(S{i}, {raw})")
        elif not s.sign_bit and s.length <= TABLE_BITS:
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
    big = f"    b = int.from_bytes(v.to_bytes({msg.dlc}, 'little'), 'big')\n" if msg.has_big_endian else ""
    exec(f"def fields(v):\n{big}    return {body}\n", env, namespace)  # noqa: S102 - source built from the IR's numbers and identifiers
    return namespace["fields"]  # type: ignore[return-value]


def _page_text_decoder(msg: ir.Message) -> Callable[[int], str]:
    """text_decoder for a multiplexed message: the fields unpack finds for the frame's pages."""
    by_name = {s.name: s for s in msg.data_signals}

    def fields(v: int) -> str:
        raws = unpack(msg, v.to_bytes(msg.dlc, "little"))
        return ", ".join(signal_text(by_name[name], raw) for name, raw in raws.items())

    return fields
