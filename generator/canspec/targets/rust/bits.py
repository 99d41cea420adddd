"""Bit expressions over the frame word, in either byte order and for CAN FD frames.

A classic frame (at most 8 bytes) is held as one little-endian `u64` (`self.bits`): an Intel
field is `(bits >> word_shift) & mask`, a Motorola one the same over `bits.swap_bytes()` (the
frame read big-endian), its shift moved up by the bytes the frame lacks to 8 — unless it lies in
one byte, where the orders agree and no swap is needed. A classic frame whose fields each lie in one
byte or are whole Intel bytes, and read cheaper so (layout.py), is held as its bytes: a field is its
byte indexed, or its bytes as one integer. An FD
frame is held as its bytes: a field is read from its first byte as the narrowest integer (u8 …
u128) that holds the bytes it lies in, in its own order (`Place`): a flag costs a byte load, not an
8-byte load and a byte swap. Each
expression is written for its exact widths, so no cast is a no-op and no mask or shift is an
identity (clippy rejects both).
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.render.literals import RUST

WORD_BITS = 64
WORD_MASK = (1 << WORD_BITS) - 1
CLASSIC_BYTES = 8  # a classic frame fits the u64 frame word
WINDOW_BYTES = (1, 2, 4, 8, 16)  # the integers an FD frame's field is read as


@dataclass(frozen=True)
class Place:
    """Where the generated code finds a field: the integer `read` of `bits` bits holds it at bits
    [shift, shift + length). `window`: (first byte, window bytes, "le"/"be") for an FD frame's
    bytes, None for the classic frame word (`swapped`: read big-endian by `swap_bytes`)."""

    read: str
    bits: int
    shift: int
    swapped: bool = False
    window: tuple[int, str] | None = None


def place(sig: ir.Signal, dlc: int, held_as_bytes: bool) -> Place:
    """The field's place in a message of `dlc` bytes, held as its bytes or as the frame word."""
    first, last = min(s.byte for s in sig.segments), max(s.byte for s in sig.segments)
    if dlc <= CLASSIC_BYTES and held_as_bytes and first == last:  # the byte, a load LLVM keeps narrow
        return Place(f"self.bytes[{first}]", 8, sig.segments[0].byte_shift, window=(first, "le"))
    if dlc <= CLASSIC_BYTES and held_as_bytes:  # whole Intel bytes (layout.py): one narrow load, as LLVM combines them
        read = f"u{sig.length}::from_le_bytes([{', '.join(f'self.bytes[{i}]' for i in range(first, last + 1))}])"
        return Place(read, sig.length, 0, window=(first, "bytes"))
    if not held_as_bytes:
        if not sig.is_big_endian:
            return Place("self.bits", WORD_BITS, sig.word_shift)
        if first == last:  # within one byte the orders agree: no byte swap
            return Place("self.bits", WORD_BITS, 8 * first + sig.segments[0].byte_shift)
        return Place("self.bits.swap_bytes()", WORD_BITS, sig.word_shift + 8 * (CLASSIC_BYTES - dlc), swapped=True)
    size = next(n for n in WINDOW_BYTES if n > last - first)  # the narrowest integer that holds the field's bytes
    lsb = sig.segments[0]  # least significant value bits first
    order = "be" if sig.is_big_endian and size > 1 else "le"
    shift = 8 * (first + size - 1 - lsb.byte) + lsb.byte_shift if sig.is_big_endian else 8 * (lsb.byte - first) + lsb.byte_shift
    read = f"u{8 * size}::from_{order}_bytes(fd::window::<{size}>(&self.bytes, {first}))"
    return Place(read, 8 * size, shift, window=(first, order))


def frame_mask(sig: ir.Signal) -> int:
    """The field's bits in the frame read as one little-endian integer (any length, either order)."""
    out = 0
    for seg in sig.segments:
        out |= seg.mask << (8 * seg.byte)
    return out


def byte_masks(mask: int, dlc: int) -> str:
    """A little-endian frame mask as a Rust `[u8; dlc]` literal."""
    return "[" + ", ".join(RUST.hex((mask >> (8 * i)) & 0xFF, 2) for i in range(dlc)) + "]"


def int_type(bits: int, signed: bool) -> str:
    return f"{'i' if signed else 'u'}{bits}"


def raw_type(sig: ir.Signal) -> str:
    return int_type(sig.storage_bits, sig.signed)


def cast(expr: str, from_type: str, to_type: str) -> str:
    """`expr` (of `from_type`, an operand: a name or parenthesized) as `to_type`."""
    return expr if from_type == to_type else f"{expr} as {to_type}"


def _intel(sig: ir.Signal, word: str) -> Place:
    assert not sig.is_big_endian, "a Motorola field needs its place (bits.place)"
    return Place(word, WORD_BITS, sig.word_shift)


def unpack_expr(sig: ir.Signal, word: str = "self.bits", at: Place | None = None) -> str:
    """The raw value of `sig` as its storage type, from its place (default: bits `word_shift`
    up of the little-endian word `word`)."""
    at = at or _intel(sig, word)
    ty, width, shift, word = raw_type(sig), at.bits, at.shift, at.read
    if sig.signed:
        # Move the field to the top, then an arithmetic shift back sign-extends it.
        left, right = width - shift - sig.length, width - sig.length
        moved = f"({word} << {left})" if left else word
        value = f"({moved} as i{width}) >> {right}" if right else f"{moved} as i{width}"
        return value if ty == f"i{width}" else f"({value}) as {ty}"
    value = f"{word} >> {shift}" if shift else word
    # The cast truncates to the storage width, and the shift empties the bits above the word's top.
    if sig.length != sig.storage_bits and shift + sig.length < width:
        value = f"({value}) & {RUST.integer(sig.mask)}" if shift else f"{value} & {RUST.integer(sig.mask)}"
    if ty == f"u{width}":
        return value
    return f"({value}) as {ty}" if value != word else f"{word} as {ty}"


def pack_expr(sig: ir.Signal, var: str, at: Place | None = None) -> str:
    """The field's bits in place in its word, from `var` (a raw value that fits the field)."""
    at = at or _intel(sig, "self.bits")
    width, shift = at.bits, at.shift
    if sig.signed:
        value = f"{var} as u{width}" if sig.length == width else f"({var} as u{width} & {RUST.integer(sig.mask)})"
    elif sig.storage_bits == width:
        value = var
    else:
        value = f"u{width}::from({var})"
    return f"{value} << {shift}" if shift else value


def _operand(expr: str) -> str:
    """`expr` as the receiver of a method call: parenthesized unless it is one term already."""
    depth = 0
    for i, c in enumerate(expr):
        depth += {"(": 1, ")": -1}.get(c, 0)
        if depth == 0 and c in " )" and i < len(expr) - 1:  # a top-level operator, or a group that ends early
            return f"({expr})"
    return expr


def store_stmt(sig: ir.Signal, var: str = "value", at: Place | None = None) -> str:
    """The statement that replaces the field in the frame with `var`."""
    at = at or _intel(sig, "self.bits")
    packed = pack_expr(sig, var, at)
    in_word = sig.mask << at.shift
    if at.read.startswith("self.bytes["):
        return f"{at.read} = {packed};" if in_word == 0xFF else f"{at.read} = ({at.read} & {RUST.integer(0xFF ^ in_word)}) | {packed};"
    if at.window is not None and at.window[1] == "bytes":  # the field is the whole window
        first = at.window[0]
        return f"self.bytes[{first}..{first + at.bits // 8}].copy_from_slice(&{_operand(packed)}.to_le_bytes());"
    if at.window is not None:
        first, order = at.window
        full = (1 << at.bits) - 1
        word = packed if in_word == full else f"({at.read} & {RUST.integer(full ^ in_word)}) | {packed}"
        return f"let word = {word};\nfd::put_window(&mut self.bytes, {first}, word.to_{order}_bytes());"
    if at.swapped:
        packed = f"{_operand(packed)}.swap_bytes()"
        in_word = frame_mask(sig)
    if in_word == WORD_MASK:
        return f"self.bits = {packed};"
    return f"self.bits = (self.bits & {RUST.integer(WORD_MASK ^ in_word)}) | {packed};"


def outside_expr(var: str, lo: int | None, hi: int | None) -> str | None:
    """`var` outside [lo, hi]; a None bound is implied by the type. None when never."""
    if lo is None and hi is None:
        return None
    if lo is None:
        return f"{var} > {RUST.integer(hi)}"  # type: ignore[arg-type]
    if hi is None:
        return f"{var} < {RUST.integer(lo)}"
    if lo == hi:
        return f"{var} != {RUST.integer(lo)}"
    return f"!({RUST.integer(lo)}..={RUST.integer(hi)}).contains(&{var})"


def type_bounds(ty: str) -> tuple[int, int]:
    bits = int(ty[1:])
    return (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if ty[0] == "i" else (0, (1 << bits) - 1)


def _bounds(lo: int, hi: int, ty: str) -> tuple[int | None, int | None]:
    """Drop bounds the type already implies (clippy rejects `x >= 0` on unsigned)."""
    type_lo, type_hi = type_bounds(ty)
    return (None if lo <= type_lo else lo), (None if hi >= type_hi else hi)


def misfit_expr(sig: ir.Signal, var: str = "value", ty: str | None = None) -> str | None:
    """`var` (of `ty`, default the storage type) does not fit the field's bits; None when every
    value of the type fits."""
    return outside_expr(var, *_bounds(sig.raw_type_min, sig.raw_type_max, ty or raw_type(sig)))


def refused_expr(sig: ir.Signal, var: str = "value", ty: str | None = None) -> str | None:
    """A raw `var` (of `ty`, default the storage type) a physical encode may not produce:
    neither a special value nor within the documented range (for signals set by raw value:
    integers and enums). None: never."""
    lo, hi = sig.raw_min, sig.raw_max
    outside = outside_expr(var, *_bounds(lo, hi, ty or raw_type(sig)))
    if outside is None:
        return None
    return " && ".join([*(f"{var} != {RUST.integer(s.raw)}" for s in sig.specials if not lo <= s.raw <= hi), outside])
