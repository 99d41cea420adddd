"""Bit expressions over the frame word.

Frames are handled as one little-endian `u64` (`self.bits`): every signal is Intel order, so
a signal is `(bits >> start) & mask` — one shift and one mask, whatever bytes it spans. Each
expression is written for its exact widths, so no cast is a no-op and no mask or shift is an
identity (clippy rejects both).
"""

from __future__ import annotations

from canspec import ir
from canspec.render.literals import RUST

WORD_BITS = 64
WORD_MASK = (1 << WORD_BITS) - 1


def int_type(bits: int, signed: bool) -> str:
    return f"{'i' if signed else 'u'}{bits}"


def raw_type(sig: ir.Signal) -> str:
    return int_type(sig.storage_bits, sig.signed)


def cast(expr: str, from_type: str, to_type: str) -> str:
    """`expr` (of `from_type`, an operand: a name or parenthesized) as `to_type`."""
    return expr if from_type == to_type else f"{expr} as {to_type}"


def unpack_expr(sig: ir.Signal, word: str = "self.bits") -> str:
    """The raw value of `sig` from the frame word, as its storage type."""
    ty = raw_type(sig)
    if sig.signed:
        # Move the field to the top, then an arithmetic shift back sign-extends it.
        left, right = WORD_BITS - sig.start - sig.length, WORD_BITS - sig.length
        moved = f"({word} << {left})" if left else word
        value = f"({moved} as i64) >> {right}" if right else f"{moved} as i64"
        return value if ty == "i64" else f"({value}) as {ty}"
    value = f"{word} >> {sig.start}" if sig.start else word
    # The cast truncates to the storage width, and the shift empties the bits above the word's top.
    if sig.length != sig.storage_bits and sig.start + sig.length < WORD_BITS:
        value = f"({value}) & {RUST.integer(sig.mask)}" if sig.start else f"{value} & {RUST.integer(sig.mask)}"
    if ty == "u64":
        return value
    return f"({value}) as {ty}" if value != word else f"{word} as {ty}"


def pack_expr(sig: ir.Signal, var: str) -> str:
    """The field's bits in place in the frame word, from `var` (a raw value that fits the field)."""
    if sig.signed:
        value = f"{var} as u64" if sig.length == WORD_BITS else f"({var} as u64 & {RUST.integer(sig.mask)})"
    elif sig.storage_bits == WORD_BITS:
        value = var
    else:
        value = f"u64::from({var})"
    return f"{value} << {sig.start}" if sig.start else value


def store_stmt(sig: ir.Signal, var: str = "value") -> str:
    """`self.bits` with the field replaced by `var`."""
    if sig.word_mask == WORD_MASK:
        return f"self.bits = {pack_expr(sig, var)};"
    return f"self.bits = (self.bits & {RUST.integer(WORD_MASK ^ sig.word_mask)}) | {pack_expr(sig, var)};"


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
