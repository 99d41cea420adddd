"""Physical ↔ raw in C: the double path and the integer-only (fixed-point) path of a signal.

The double encode is the shared rounding rule step for step (ir/encoding.py): q = (value -
offset) / factor, then `<prefix>_round_half_away(q)` (the 2^52 branch included). All but the
widest fields encode through the runtime's out-of-line `<prefix>_phys_*` functions with a
`<prefix>_phys_t` (offset, factor, accepted range) per signal, shared by the signals that agree
(model.py): each encoder is a call and the raw-range compares the accepted range leaves open, so
an image holds the rounding once however many signals it encodes, at every optimisation level.
The range check comes first and keeps q inside the rounding's domain [-2^63, 2^63), except where
the accepted range reaches 2^62 (`phys_round` checks q first there); every q beyond the field's
raw type rounds beyond its raw range, which the encoder compares. A field wider than 63 unsigned
bits rounds |q| with `<prefix>_round_abs` into a uint64_t inline, q first held inside the raw
type widened by one step.

The fixed encode rounds (F - fo) / ff half away from zero exactly, F = physical × 10^k, ff =
factor × 10^k, fo = offset × 10^k: on every decimal input and tie the result the double rule
gives within its tie guarantee (tested against the vectors). It divides by |ff| as a multiply
(divide.py), in 32-bit words where its numbers fit, else in 64-bit ones, exact for every numerator
that interval allows, and a 64-bit decode multiplies through `<prefix>_mul64`: no division and no
64-bit product, so no libgcc helper on Cortex-M0+ or M4. Every comparison whose outcome the
operand's type, or an earlier check, already decides is left out (compilers warn about it, and
MISRA C:2012 rule 14.3 forbids it): after the fixed encode's first check the value lies in a
known interval, and r, rounded monotonically from it, in one computed exactly here.

Conditions of more than one comparison parenthesise each (MISRA C:2012 rule 12.1).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import decimal_scaling, round_half_away
from canspec.render.literals import C
from canspec.targets.c import divide
from canspec.targets.c.names import CNames

INT_TYPES = ((32, "int32_t", -(2**31), 2**31 - 1), (64, "int64_t", -(2**63), 2**63 - 1))
U64_MAX = 2**64 - 1
INT64_MAX = 2**63 - 1
DOUBLE_EXACT = 2**53  # integers up to this magnitude are exact in a double
Q_SAFE = 2**62  # |q| below this: inside the rounding's domain [-2^63, 2^63) with every rounding error of its computation


def int_lit(value: int, bits: int, signed: bool) -> str:
    return C.integer(value, bits) if signed else C.unsigned(value, bits)


def _bound_terms(var: str, lo: int | None, hi: int | None, type_lo: int, type_hi: int, lit) -> list[str]:  # type: ignore[no-untyped-def]
    """C terms true when `var` (known to lie in [type_lo, type_hi]) is below lo or above hi;
    a bound that interval already keeps is left out."""
    low = f"{var} < {lit(lo)}" if lo is not None and lo > type_lo else ""
    high = f"{var} > {lit(hi)}" if hi is not None and hi < type_hi else ""
    return _either_side(var, lo, hi, low, high)


def _either_side(var: str, lo: int | None, hi: int | None, low: str, high: str) -> list[str]:
    """The terms `low` (var below lo) and `high` (above hi) that are needed. Where both are, around
    an interval wider than INT64_MAX (var an int64_t), one unsigned compare instead: the same test,
    in the form cppcheck 2.10's value flow does not misjudge (its interval arithmetic overflows
    there and reports the second compare as invariant, MISRA rule 14.3)."""
    if low and high and lo is not None and hi is not None and lo < 0 and hi - lo > INT64_MAX:
        return [f"((uint64_t){var} + {C.unsigned(-lo, 64)}) > {C.unsigned(hi - lo, 64)}"]
    return [t for t in (low, high) if t]


def any_of(terms: list[str]) -> str:
    """C condition true when any term is ("" for none); each comparison in parentheses where
    there are several (a `!(...)` term is one operand already)."""
    if len(terms) == 1:
        return terms[0]
    return " || ".join(t if t.startswith("!(") else f"({t})" for t in terms)


@dataclass(frozen=True)
class CRanges:
    """What encode checks after rounding: `r` a special value, else inside the documented range
    (`value`) and the encodable raw range (`r`)."""

    specials: str  # condition: r is one of the signal's special raw values ("" if it has none)
    outside: str  # condition: the value or r is out of range ("" if nothing can be)


@dataclass(frozen=True)
class CDouble:
    decode_pre: str  # `const double scaled = <this>;` before decode_expr, or ""
    decode_expr: str  # double from `raw` (and `scaled`)
    exact: bool  # every raw value is exact in a double
    phys: str  # initializer of its `<prefix>_phys_t`: offset, factor, accepted range, scaled ("" on the wide path)
    phys_name: str  # that descriptor's name: `<signal fn>_phys` (model.py: the first signal's where several share it)
    phys_local: bool  # defined in the encoder (no other signal has the same); else at file scope ...
    phys_defines: bool  # ... before this signal's encoder (the first signal that uses it)
    window_test: str  # the shared path: true (ERR_RANGE) where q is outside the rounding's domain ("" where the accepted range keeps it inside)
    special_test: str  # true where r rounds to a special value (OK), "" without them; then ...
    encode_test: str  # ... the accepted range and rounding (true: ERR_RANGE), a `<prefix>_phys_encode` call, ...
    encode_tail: str  # ... or where no compare is left after it, the rest of the encode: a `<prefix>_phys_encode_<type>` call
    ranges: CRanges  # what is checked after the first check (the shared path: the raw range the accepted one leaves open)
    # the wide unsigned path: a uint64_t field beyond 2^63
    wide_unsigned: bool
    refuse: str  # its first check (true: ERR_RANGE): q's rounding would leave the raw type widened by one step
    rounded: str  # r = |q| rounded (a negative q must round to 0)


@dataclass(frozen=True)
class CFixed:
    scale: int  # 10^k
    scale_lit: str
    type: str  # int32_t / int64_t / uint64_t
    decode_expr: str  # physical × scale from `raw` (or from `field`, which decode_pre sets)
    outside: str  # condition: the input lies beyond the raw type widened by one step ("" if its type keeps it inside)
    rounded: str  # r from `value`: (value - fo) / ff rounded half away from zero
    r_type: str
    ranges: CRanges
    note: str = ""  # comment beside `rounded`: the divisor and the multiply that divides by it
    decode_pre: tuple[str, ...] = ()  # statements before decode_expr: `field`, the argument as the field's bits


def _ranges(sig: ir.Signal, r_signed: bool, value_terms: list[str], r_reach: tuple[int, int] | None) -> CRanges:
    """`r_reach`: the interval r lies in wherever the value terms are false; None where they
    are always true (r is never compared)."""
    lit = (lambda v: C.integer(v, 64)) if r_signed else (lambda v: C.unsigned(v, 64))
    specials = any_of([f"r == {C.integer(sp.raw) if r_signed else C.unsigned(sp.raw)}" for sp in sig.specials])
    r_terms = _bound_terms("r", sig.raw_min, sig.raw_max, *r_reach, lit) if r_reach else []
    return CRanges(specials, any_of(value_terms + r_terms))


def _r_type_range(r_signed: bool) -> tuple[int, int]:
    return (-(2**63), 2**63 - 1) if r_signed else (0, U64_MAX)


def _fixed_ranges(sig: ir.Signal, r_signed: bool, scale: int, scaling: tuple[int, int], reach: tuple[int, int], lit) -> CRanges:  # type: ignore[no-untyped-def]
    """The fixed encode's range checks, given that `value` lies in `reach` after the first
    check: only the terms that can be true there. Where the value terms are false, value lies
    in their narrowed interval, and r = (value - fo) / ff rounded, monotonic in value, between
    the roundings of its ends."""
    ff, fo = scaling
    fmin, fmax = int(sig.check_min * scale), int(sig.check_max * scale)
    value_terms = _bound_terms("value", fmin, fmax, *reach, lit)
    lo, hi = max(reach[0], fmin), min(reach[1], fmax)
    ends = sorted(round_half_away(Fraction(v - fo, ff)) for v in (lo, hi))
    return _ranges(sig, r_signed, value_terms, (ends[0], ends[1]) if lo <= hi else None)


def double_path(names: CNames, sig: ir.Signal, fn: str, macro: str, force: bool) -> CDouble | None:
    """The double path of a data signal (C functions `fn`_*, macros `macro`_*): where its raw
    values are exact in a double, or `force`d."""
    exact = max(-sig.raw_type_min, sig.raw_type_max) <= DOUBLE_EXACT
    if not exact and not force:
        return None
    factor, offset = sig.factor, sig.offset
    # Two statements: compilers may contract `raw * f + o` in one expression into an FMA (clang
    # does when constant folding), which would round differently from the shared rule. The
    # constants are the signal's `_FACTOR` and `_OFFSET` macros (x + (-c) == x - c in IEEE).
    expr = "(double)raw" if factor == 1 else f"(double)raw * {macro}_FACTOR"
    pre = ""
    if offset:
        pre, expr = (expr, f"scaled + {macro}_OFFSET") if factor != 1 else ("", f"{expr} + {macro}_OFFSET")
    accept = f"!((value >= {C.double(sig.accept_min)}) && (value <= {C.double(sig.accept_max)}))"
    if not sig.signed and sig.raw_type_max > 2**63 - 1:
        # q's bounds: the raw type widened by one step, i.e. -1 and 2^64 (both doubles)
        return CDouble(
            decode_pre=pre,
            decode_expr=expr,
            exact=exact,
            phys="",
            phys_name="",
            phys_local=False,
            phys_defines=False,
            window_test="",
            special_test="",
            encode_test="",
            encode_tail="",
            ranges=_ranges(sig, False, [accept], _r_type_range(False)),
            wide_unsigned=True,
            refuse=f"!((q > -1.0) && (q < {C.double(sig.raw_type_max + 1)}))",
            rounded=f"{names.fn('round_abs')}((q < 0.0) ? -q : q)",
        )
    scaled = "false" if sig.is_identity else "true"
    init = f"{{{C.double(offset)}, {C.double(factor)}, {C.double(sig.accept_min)}, {C.double(sig.accept_max)}, {scaled}}}"
    return with_descriptor(names, sig, CDouble(
        decode_pre=pre, decode_expr=expr, exact=exact, phys=init, phys_name="", phys_local=True, phys_defines=False,
        window_test="", special_test="", encode_test="", encode_tail="", ranges=CRanges("", ""), wide_unsigned=False, refuse="", rounded="",
    ), f"{fn}_phys", local=True, defines=False)


def phys_store(sig: ir.Signal) -> str:
    """The runtime's shared encoder that writes the signal's field: `phys_encode_u8` for a uint8_t."""
    return f"phys_encode_{'i' if sig.signed else 'u'}{sig.storage_bits}"


def with_descriptor(names: CNames, sig: ir.Signal, d: CDouble, name: str, local: bool, defines: bool) -> CDouble:
    """The shared path's checks of `sig` with its descriptor named `name`: a special value is
    accepted wherever it lies, so r is rounded first where the signal has some; any other value
    is encoded as if it had none (rounded again: the code stays a call on every core)."""
    # phys_encode rounds without the domain check where the accepted range keeps q well inside it
    window = f"!{names.fn('phys_round')}(value, &{name}, &r)" if sig.max_quotient >= Q_SAFE else ""
    specials = any_of([f"r == {C.integer(sp.raw)}" for sp in sig.specials])
    special = f"{names.fn('phys_round')}(value, &{name}, &r) && ({specials})" if specials else ""
    # the accepted range first, in the call: r then lies between the roundings of its ends
    ranges = _ranges(sig, True, [], sig.accept_raw if d.exact else _r_type_range(True))
    test, tail = "", ""
    if ranges.outside:
        test = f"!{names.fn('phys_encode')}(value, &{name}, &r)"
    else:  # nothing left to compare: the runtime's encoder for the field's type writes it
        tail = f"{names.fn(phys_store(sig))}(value, &{name}, raw)"
    return replace(d, phys_name=name, phys_local=local, phys_defines=defines, window_test=window, special_test=special, encode_test=test, encode_tail=tail,
                   ranges=CRanges("", ranges.outside))


def fixed_scaling(sig: ir.Signal) -> tuple[int, int, int]:
    """(10^k, factor × 10^k, offset × 10^k) of the integer path (ir/encoding.decimal_scaling)."""
    return decimal_scaling(sig.factor, sig.offset, (sig.check_min, sig.check_max), half_steps=not sig.is_identity)


def fixed_scale(sig: ir.Signal) -> int:
    return fixed_scaling(sig)[0]


def fixed_path(names: CNames, sig: ir.Signal) -> CFixed | None:
    scale, ff, fo = fixed_scaling(sig)
    tmin, tmax = sig.raw_type_min, sig.raw_type_max
    core = [tmin, tmax, tmin * ff, tmax * ff, tmin * ff + fo, tmax * ff + fo, scale]
    # the open interval of inputs whose rounding stays within one step of the raw type
    below, above = sorted(((tmin - 1) * ff + fo, (tmax + 1) * ff + fo))
    fmin, fmax = int(sig.check_min * scale), int(sig.check_max * scale)
    for bits, ctype, lo, hi in INT_TYPES:
        fits = all(lo <= v <= hi for v in core)
        if bits == 32:  # int32_t only where every bound it is compared with is an int32_t too
            fits = fits and all(lo <= v <= hi for v in (below, above, fmin, fmax))
        if fits and _difference_fits(ff, fo, max(below + 1, lo), min(above - 1, hi)):
            return _signed_fixed(names, sig, scale, (ff, fo), ctype, (below, above), (lo, hi))
    if not sig.signed and ff > 0 and fo == 0 and tmax * ff <= U64_MAX:
        return _unsigned_fixed(names, sig, scale, ff, above)
    return None


def _difference_fits(ff: int, fo: int, vlo: int, vhi: int, bits: int = 64) -> bool:
    """Whether ±(value - fo), the numerator of the rounding, fits an int<bits>_t for every input."""
    ends = (vlo - fo, vhi - fo) if ff > 0 else (fo - vhi, fo - vlo)
    return all(-(2 ** (bits - 1)) <= v <= 2 ** (bits - 1) - 1 for v in ends)


def _signed_fixed(names: CNames, sig: ir.Signal, scale: int, scaling: tuple[int, int], ctype: str, bounds: tuple[int, int], trange: tuple[int, int]) -> CFixed:
    ff, fo = scaling
    lit = lambda v: C.integer(v, 32 if ctype == "int32_t" else 64)
    pre, arg = _field_value(sig, (ff, fo), trange)
    expr = f"({ctype}){arg}"
    if ff != 1:
        expr = f"{expr} * {lit(ff)}" if ctype == "int32_t" else f"{names.fn('mul64')}({expr}, {lit(ff)})"
    if fo:
        expr = (f"({expr})" if " * " in expr else expr) + (f" + {lit(fo)}" if fo > 0 else f" - {lit(-fo)}")
    outside, reach = _first_check(sig, scale, bounds, trange, lit)
    # ±(value - fo), so that the divisor |ff| is positive; in 32 bits where it fits, divided by a
    # multiply in either width (divide.py: no division, hence no libgcc helper, on any core)
    narrow = ctype == "int32_t" and _difference_fits(ff, fo, *reach, bits=32)
    value, offset = ("value" if narrow else "(int64_t)value", lit(abs(fo)))
    if ff > 0:
        num = value if not fo else f"{value} - {offset}" if fo > 0 else f"{value} + {offset}"
    else:
        num = f"-{value}" if not fo else f"{lit(fo)} - {value}"
    rounded, note = num, ""
    if abs(ff) != 1:
        rounded, note = _divided(names, num, abs(ff), max(abs(v - fo) for v in reach), "" if narrow else "64")
    return CFixed(
        scale=scale, scale_lit=C.integer(scale), type=ctype, decode_expr=expr, outside=any_of(outside),
        rounded=rounded, r_type="int64_t", ranges=_fixed_ranges(sig, True, scale, scaling, reach, lit), note=note, decode_pre=pre,
    )


def _field_value(sig: ir.Signal, scaling: tuple[int, int], trange: tuple[int, int]) -> tuple[tuple[str, ...], str]:
    """(statements, name) of decode_fixed's input. The result type holds every value of the field,
    not every value of the argument's type: where an argument beyond the field's bits (none that
    unpack gives) would overflow it, the argument is first read as the field's bits (the low bits,
    sign-extended), so the function has no undefined behaviour for any argument."""
    ff, fo = scaling
    b, n = sig.storage_bits, sig.length
    pmin, pmax = (-(2 ** (b - 1)), 2 ** (b - 1) - 1) if sig.signed else (0, 2**b - 1)
    if n == b or all(trange[0] <= v <= trange[1] for v in (pmin, pmax, pmin * ff + fo, pmax * ff + fo, pmin * ff, pmax * ff)):
        return (), "raw"
    w = 64 if b > 32 else 32  # locals (not composite expressions) are what is cast: MISRA 10.8
    if not sig.signed:
        return (f"const uint{w}_t field = (uint{w}_t)raw & {C.hex((1 << n) - 1, bits=w)};",), "field"
    sign = 1 << (n - 1)
    return (f"const uint{w}_t bits = ((uint{w}_t)raw & {C.hex((1 << n) - 1, bits=w)}) ^ {C.hex(sign, bits=w)};",
            f"const int{w}_t field = (int{w}_t)bits - {C.integer(sign, w)};"), "field"


def _unsigned_fixed(names: CNames, sig: ir.Signal, scale: int, ff: int, above: int) -> CFixed:
    """A wide unsigned field without offset: physical × scale = raw × ff, as a uint64_t."""
    lit = lambda v: C.unsigned(v, 64)
    expr = "(uint64_t)raw" if ff == 1 else f"{names.fn('mul64_u')}((uint64_t)raw, {lit(ff)})"
    outside, reach = _first_check(sig, scale, (-1, above), (0, U64_MAX), lit)
    rounded, note = _divided(names, "value", ff, reach[1], "_u64") if ff != 1 else ("value", "")
    return CFixed(
        scale=scale, scale_lit=C.integer(scale), type="uint64_t", decode_expr=expr, outside=any_of(outside),
        rounded=rounded, r_type="uint64_t", ranges=_fixed_ranges(sig, False, scale, (ff, 0), reach, lit), note=note,
    )


def _first_check(sig: ir.Signal, scale: int, bounds: tuple[int, int], trange: tuple[int, int], lit) -> tuple[list[str], tuple[int, int]]:  # type: ignore[no-untyped-def]
    """The check before the rounding, and the values that pass it: the open interval `bounds`,
    where the rounding stays within one step of the raw type, narrowed to the accepted range
    where the signal has no special values (with them, a value outside it may still encode one;
    without them, refusing it here leaves nothing to compare after the rounding)."""
    lo, hi = max(bounds[0] + 1, trange[0]), min(bounds[1] - 1, trange[1])
    low = f"value <= {lit(bounds[0])}" if bounds[0] >= trange[0] else ""
    high = f"value >= {lit(bounds[1])}" if bounds[1] <= trange[1] else ""
    if not sig.specials:
        fmin, fmax = int(sig.check_min * scale), int(sig.check_max * scale)
        if fmin > lo:
            lo, low = fmin, f"value < {lit(fmin)}"
        if fmax < hi:
            hi, high = fmax, f"value > {lit(fmax)}"
    return _either_side("value", lo, hi, low, high), (lo, hi)


def _divided(names: CNames, num: str, d: int, amax: int, width: str) -> tuple[str, str]:
    """The call that rounds num / d (d > 1, |num| <= amax) half away from zero by a multiply,
    and its comment: in 32-bit words (`width` ""), signed 64-bit ("64") or unsigned ("_u64")."""
    mg = divide.rounding(d, amax) if not width else divide.rounding64(d, amax)
    fn = {k: names.fn(f"div_round{width}_{k}") for k in ("mul", "mulhi", "mulrem")}
    return divide.call(fn, num, mg), divide.note(mg)
