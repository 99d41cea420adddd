"""The Python view of one signal: its attribute, type, default, docstring line, and the
expressions and decisions its decode and encode need (`code.py` turns them into statements).

Decode reads a field of up to three bytes from those bytes (`d3 | d4 << 8`, small ints), or from a 16-bit word
`hN` when it spans exactly two bytes that no other field shares (word_pairs); a wider one from the whole frame as
one integer, little-endian `v` for Intel fields and big-endian `b` for Motorola ones (ir.Signal.word_order). Each is
a shift, a mask and a sign extension. A field of at most 12 bits that is scaled or signed decodes by indexing a precomputed
tuple with its bits (PyScale), within a budget of entries per package. Encode follows the shared rounding rule (ir/encoding.py) in doubles; float
literals are the shortest repr of the nearest double of the exact decimal. An IEEE float field's
raw value is its bit pattern, turned into the float and back by `struct` (`_unpack_f32`, ...).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import FLOAT_MAX, decimal_text
from canspec.ir.mux import ranges_text
from canspec.render.literals import PYTHON
from canspec.targets.python.naming import CLASS_SCOPE_BUILTINS, Namespace
from canspec.targets.python.reads import frame_bytes, own_bytes, pair_of

# Method names of every message class: an attribute never takes one of these.
# The widest field decoded through a PyScale table (4,096 entries), and the most entries of all a
# package's tables together (about 2 MB of floats): fields beyond either decode by arithmetic.
MAX_SCALE_BITS = 12
MAX_SCALE_ENTRIES = 1 << 16
METHODS = frozenset({"encode", "decode", "update", "checksum_ok", "pack_raw", "unpack_raw", "to_raw", "from_raw", "next_counter", "advance_counter",
                     "present_signals", "is_present"})
ATTRIBUTE_RESERVED = METHODS | CLASS_SCOPE_BUILTINS


@dataclass(frozen=True)
class PySpecial:
    const: str  # class constant name, e.g. SENSOR_1_DISTANCE_NO_OBSTACLE
    raw_hex: str
    physical: str  # literal in the attribute's type
    comment: str


@dataclass(frozen=True)
class PyLookup:
    """Raw → enum member (or the plain int where the table has no entry), for decode."""

    var: str
    enum: str
    bits: int
    is_tuple: bool  # a tuple indexed by raw (every raw of the field); else a dict of the members


@dataclass(frozen=True)
class PyScale:
    """Raw bits → physical value of a narrow field, for decode: one tuple index replaces the sign extension
    and the scaling (CPython does not specialize int × float; an index of a tuple by an int it does). Each
    entry is computed by the same expression decode would evaluate, so the values are the same doubles."""

    var: str
    bits: int
    value: str  # the physical value of the raw bits `r`, as decode writes it


@dataclass(frozen=True)
class PySignal:
    sig: ir.Signal
    name: str  # the spec's signal name (keys of raw dicts, vectors)
    attr: str  # attribute name
    doc: str  # one docstring line: Chinese name, unit, range, encoding
    py_type: str  # "float", "int", "Gear | int"
    const_type: str  # type of its special-value constants: "float" | "int"
    default: str  # literal of the default attribute value
    raw_expr: str  # raw value from its frame byte `dN` or frame word `v` / `b` (sign-extended)
    frame_bytes: tuple[tuple[int, int], ...] | None  # the frame bytes it is read from, with their shifts (fields.frame_bytes)
    own_bytes: bool  # a field of a CAN FD frame: read from its own bytes (fields.own_bytes)
    phys_expr: str  # physical value from the frame integer `v`
    specials: tuple[PySpecial, ...]
    allowed: str  # string literal: the allowed range as errors show it
    descriptor: str  # module-level name of the slow-path descriptor
    descriptor_args: str  # its _SignalSpec(...) arguments after message and signal name
    descriptor_tail: str  # its arguments after the allowed text: ", 32, True" (float bits, NaN/±Inf allowed) for a float field
    var: str  # encode: local holding the attribute
    raw_var: str  # encode: local holding the raw value
    # encode decisions
    direct: bool  # factor 1 and an integer offset: raw = x - offset, exact on ints
    q_expr: str  # (x - offset) / factor as the runtime computes it (on `m.attr` when direct, else on `var`)
    lo_lit: str  # the physical range check, as literals comparable with the attribute
    hi_lit: str
    q_nonneg: bool  # q >= 0 for every value passing the range check: no sign branch
    exact_branch: bool  # |q| may reach EXACT_LIMIT inside the range: the rule's 2^52 branch is needed
    raw_check: bool  # a value passing the range check may still round outside raw_min..raw_max
    # multiplexing: what the field's presence needs, top-level multiplexer first (ir.Message.mux_chain; () in every frame)
    chain: tuple[ir.MuxCondition, ...] = ()
    pair: int | None = None  # read from the 16-bit word `hN` of frame bytes N, N + 1 (word_pairs), not from `frame_bytes`
    key_var: str = ""  # a multiplexer: the decode local holding its raw value
    phys_from_key: str = ""  # and its physical value from that local

    @property
    def is_checksum(self) -> bool:
        return self.sig.role == "checksum"

    @property
    def word(self) -> str:
        return word_var(self.sig)

    @property
    def read(self) -> str | None:
        """What unpack reads first: the frame's bytes (`d`, see `frame_bytes`), a frame word (`v`, `b`), or
        nothing (None: a field of a CAN FD frame, read from its own bytes, see `own_bytes`)."""
        if self.frame_bytes is not None:  # or its 16-bit word `pair`
            return "d"
        return None if self.own_bytes else self.word

    @property
    def decode_word(self) -> str | None:
        """What decode reads the field from; None for a float read by struct from its bytes."""
        return None if float_offset(self.sig, 0) is not None else self.read


def _paren(expr: str) -> str:
    atomic = expr.isidentifier() or (expr.startswith("_from_bytes(") and expr.count("(") == 1 and expr.endswith(")"))  # a name, or one call
    return expr if atomic else f"({expr})"


def word_var(sig: ir.Signal) -> str:
    """The local holding the frame word the field lies in: `v` (little-endian) or `b` (big-endian)."""
    return "b" if sig.is_big_endian else "v"


def raw_expr(sig: ir.Signal, frame_bits: int, pair: tuple[int, int] | None = None) -> str:
    """The raw value from its frame bytes, 16-bit word (`pair`: its first byte and the field's shift, see pair_of) or
    frame word: shift, mask, sign-extend (no outer parentheses)."""
    expr, var = _bits_expr(sig, frame_bits, pair)
    if sig.signed:
        # Bytes joined by `|` bind looser than `^`: parenthesized, so the sign flip applies to the whole value.
        value = f"({expr})" if expr == var and " | " in var else expr
        expr = f"({value} ^ {PYTHON.hex(sig.sign_bit)}) - {PYTHON.hex(sig.sign_bit)}"
    return expr


def bits_expr(sig: ir.Signal, frame_bits: int, pair: tuple[int, int] | None = None) -> str:
    """The field's bits as an unsigned int (raw_expr without the sign extension)."""
    return _bits_expr(sig, frame_bits, pair)[0]


def _bits_expr(sig: ir.Signal, frame_bits: int, pair: tuple[int, int] | None) -> tuple[str, str]:
    """The field's bits (shifted and masked) and what they are read from."""
    parts = frame_bytes(sig, frame_bits)
    if pair is not None:
        var, shift, bits = f"h{pair[0]}", pair[1], 16
    elif parts is not None:
        var = " | ".join(f"d{i}" if up == 0 else f"d{i} << {up}" for i, up in parts)
        shift, bits = sig.word_shift % 8, 8 * len(parts)
    elif frame_bits > 64:
        var, shift, bits = own_bytes(sig, frame_bits)
    else:
        var, shift, bits = word_var(sig), sig.word_shift, frame_bits
    expr = var if shift == 0 else f"{_paren(var)} >> {shift}"
    if shift + sig.length < bits:
        expr = f"{_paren(expr)} & {PYTHON.hex(sig.mask)}"
    return expr, var


def scale_value(sig: ir.Signal, enum: str | None) -> str | None:
    """What a PyScale table holds for raw bits `r` of this field, or None where decode computes the value
    itself: a float, enum or multiplexer field, a wide one, or one whose raw value is its physical value."""
    if sig.is_float or enum is not None or sig.is_multiplexer or sig.length > MAX_SCALE_BITS:
        return None
    raw = f"(r ^ {PYTHON.hex(sig.sign_bit)}) - {PYTHON.hex(sig.sign_bit)}" if sig.signed else "r"
    value = phys_expr(sig, raw, _kind(sig, enum))
    return None if value == "r" else value


def float_offset(sig: ir.Signal, dlc: int) -> int | None:
    """The first frame byte of a float field that fills whole bytes (read by struct from the data
    itself, in its byte order), else None. Only whether it is one when `dlc` is 0."""
    if not sig.is_float or sig.word_shift % 8:
        return None
    return sig.word_shift // 8 if not sig.is_big_endian else dlc - (sig.word_shift + sig.length) // 8


def phys_expr(sig: ir.Signal, raw: str, kind: str, dlc: int = 0) -> str:
    """physical = raw × factor + offset: integers for integer scaling, else doubles; a float field's
    bits unpacked (straight from the frame's bytes where it fills whole bytes)."""
    if sig.is_float:
        offset = float_offset(sig, dlc)
        if offset is not None:
            return f"_unpack_f{sig.length}_{'be' if sig.is_big_endian else 'le'}(data, {offset})[0]"
        return f'_unpack_f{sig.length}(({raw}).to_bytes({sig.length // 8}, "little"))[0]'
    as_int = kind == "int"
    expr = raw
    if sig.factor != 1:
        expr = f"{_paren(expr)} * {PYTHON.number(sig.factor, as_int)}"
    if sig.offset != 0:
        expr = _paren(expr) if sig.factor == 1 else expr
        expr = f"{expr} + {PYTHON.number(sig.offset, as_int)}" if sig.offset > 0 else f"{expr} - {PYTHON.number(abs(sig.offset), as_int)}"
    return expr


def q_expr(sig: ir.Signal, direct: bool, x: str) -> str:
    """`(x - offset) / factor` in the rule's order; `x - off` stays exact on ints when direct.
    Subtracting a negative offset is written as adding its magnitude (the same IEEE result)."""
    off = sig.offset
    if off == 0:
        expr = x
    elif off > 0:
        expr = f"{x} - {PYTHON.number(off, direct)}"
    else:
        expr = f"{x} + {PYTHON.number(abs(off), direct)}"
    if not direct and sig.factor != 1:
        expr = f"({expr}) / {PYTHON.double(sig.factor)}" if off != 0 else f"{expr} / {PYTHON.double(sig.factor)}"
    return expr


def raw_check(sig: ir.Signal, direct: bool) -> bool:
    """Whether a value inside the (double) range check can round to a raw outside raw_min..raw_max.
    Rounding is monotonic, so the two ends of the range decide."""
    if direct:
        return True
    lo, hi = sig.accept_raw
    return not sig.raw_min <= lo <= hi <= sig.raw_max


def exact_branch(sig: ir.Signal) -> bool:
    """Whether a value inside the range check may give |q| >= EXACT_LIMIT (with a margin for the
    double arithmetic): only then does the generated fast path need the rule's 2^52 branch."""
    return sig.max_quotient >= ir.EXACT_LIMIT * Fraction(999, 1000)


def range_text(sig: ir.Signal) -> str:
    """The allowed range as errors show it, e.g. "[-1080, 1080] deg or 0 (no_limit)"."""
    if sig.is_float and sig.doc_min is None:
        return f"any float{sig.length}: finite within ±{float(FLOAT_MAX[sig.length])!r}, NaN or ±Inf"
    text = f"[{decimal_text(sig.check_min)}, {decimal_text(sig.check_max)}]"
    if sig.unit:
        text += f" {sig.unit}"
    if sig.specials:
        text += " or " + ", ".join(f"{decimal_text(s.physical)} ({s.name})" for s in sig.specials)
    return text


def labelled(name: str, label_zh: str) -> str:
    """`name (中文)`, or the name alone in an English-only spec."""
    return f"{name} ({label_zh})" if label_zh else name


def label_comment(label: str, label_zh: str) -> str:
    """A value's comment: `中文 (English)`, or the English label alone."""
    return PYTHON.comment(f"{label_zh} ({label})" if label_zh else label)


def doc_line(sig: ir.Signal, enum: str | None, chain: tuple[ir.MuxCondition, ...] = ()) -> str:
    parts = [sig.zh] if sig.zh else []
    if chain:  # None in a decoded message whose multiplexers select another page
        parts.append("present when " + " and ".join(f"{c.by} = {ranges_text(c.ranges)}" for c in chain) + ", else None")
    if sig.unit:
        parts.append(f"unit {sig.unit}")
    if sig.is_float:
        parts.append(f"IEEE float{sig.length}, " + ("any value (NaN and ±Inf too)" if sig.doc_min is None else f"range {range_text(sig)}"))
    else:
        parts.append(f"range [{decimal_text(sig.check_min)}, {decimal_text(sig.check_max)}]")
    if sig.is_scaled:
        formula = "raw" if sig.factor == 1 else f"raw × {decimal_text(sig.factor)}"
        if sig.offset:
            formula += f" {'-' if sig.offset < 0 else '+'} {decimal_text(abs(sig.offset))}"
        parts.append(f"physical = {formula}")
    if enum is not None:
        parts.append(f"values {enum}")
    parts += [f"{decimal_text(s.physical)} = {labelled(s.name, s.label_zh)}" for s in sig.specials]
    if sig.role in ("counter", "checksum"):
        parts.append({"counter": "rolling counter", "checksum": "XOR checksum, filled by encode"}[sig.role])
    if sig.desc:
        parts.append(sig.desc)
    return PYTHON.doc("; ".join(parts))


def default_raw(sig: ir.Signal) -> int:
    """The raw value of a new message's attribute: physical 0 when allowed, else raw 0, else the nearest allowed raw."""
    zero = sig.quotient(Fraction(0))
    if sig.check_min <= 0 <= sig.check_max and zero.denominator == 1 and sig.raw_min <= zero <= sig.raw_max:
        return int(zero)
    return sig.base_raw


def _kind(sig: ir.Signal, enum: str | None) -> str:
    if enum is not None:
        return "enum"
    return "int" if sig.is_integer else "float"


def double_within(bound: Fraction, up: bool) -> float:
    """The double nearest `bound` on its inner side (at or above it where `up`, else at or below): a
    double compared with it gives the exact comparison with `bound` (as the reference codec compares)."""
    x = float(bound)
    if up and Fraction(x) < bound:
        x = math.nextafter(x, math.inf)
    elif not up and Fraction(x) > bound:
        x = math.nextafter(x, -math.inf)
    return x


def _default(sig: ir.Signal, kind: str, enum: str | None, members: dict[int, str]) -> str:
    if sig.is_float:  # 0.0 where the range allows it, else the range's lower end
        return PYTHON.double(0.0 if sig.check_min <= 0 <= sig.check_max else double_within(sig.accept_min, up=True))
    raw = default_raw(sig)
    if enum is not None:
        return f"{enum}.{members[raw]}" if raw in members else str(raw)
    return PYTHON.number(sig.physical(raw), kind != "float")


def _descriptor_args(sig: ir.Signal, direct: bool, lo_lit: str, hi_lit: str) -> str:
    """What the slow path of encode needs (see _runtime.SignalSpec), after message and signal name."""
    raws = [str(s.raw) for s in sig.specials]
    specials = ", ".join(raws) + ("," if len(raws) == 1 else "")
    offset_int = str(sig.offset.numerator) if direct else "0"
    return ", ".join(
        (str(direct), PYTHON.double(sig.factor), PYTHON.double(sig.offset), offset_int, lo_lit, hi_lit, str(sig.raw_min), str(sig.raw_max),
         str(sig.raw_type_min), str(sig.raw_type_max), f"frozenset(({specials}))")
    )


@dataclass(frozen=True)
class SignalContext:
    """What a signal's view needs from its message and package."""

    message: str  # the message's name
    index: int  # position among the message's data signals (names encode locals)
    frame_bits: int
    attrs: Namespace  # the message class's attribute names
    consts: Namespace  # the message class's constant names
    module: Namespace  # module-level names of messages.py
    enum: str | None  # the enum class of its value table, when it decodes to one
    members: dict[int, str]  # raw → member name of that enum
    lookup: PyLookup | None
    scale: PyScale | None = None
    chain: tuple[ir.MuxCondition, ...] = ()  # ir.Message.mux_chain of the signal
    pairs: tuple[str, frozenset[int]] = ("<", frozenset())  # word_pairs of the message


def _specials(sig: ir.Signal, consts: Namespace, as_int: bool) -> tuple[PySpecial, ...]:
    return tuple(
        PySpecial(consts.take(f"{sig.name}_{s.name}".upper()), PYTHON.hex(s.raw), PYTHON.number(s.physical, as_int),
                  label_comment(s.label, s.label_zh))
        for s in sig.specials
    )


def _phys(sig: ir.Signal, raw: str, kind: str, ctx: SignalContext, pair: tuple[int, int] | None = None) -> str:
    """The physical value from the raw expression `raw`: scaled (from its scale table, indexed by its bits), or the enum member."""
    if ctx.lookup is not None:
        return f"{ctx.lookup.var}[{raw}]" if ctx.lookup.is_tuple else f"_member({ctx.lookup.var}, {raw})"
    if ctx.scale is not None:
        return f"{ctx.scale.var}[{bits_expr(sig, ctx.frame_bits, pair)}]"
    return phys_expr(sig, raw, kind, ctx.frame_bits // 8)


def build_signal(sig: ir.Signal, ctx: SignalContext) -> PySignal:
    kind = _kind(sig, ctx.enum)
    as_int = kind != "float"
    pair = pair_of(sig, ctx.frame_bits, ctx.pairs)
    raw = raw_expr(sig, ctx.frame_bits, pair)
    phys = _phys(sig, raw, kind, ctx, pair)
    key_var = f"k{ctx.index}" if sig.is_multiplexer else ""
    direct = sig.factor == 1 and sig.offset.denominator == 1 and sig.check_min <= sig.phys_min and sig.phys_max <= sig.check_max and not sig.is_float
    lo, hi = sig.accept_min, sig.accept_max  # the runtime comparison (display uses check_min/max)
    lo_lit = PYTHON.number(lo, as_int and lo.denominator == 1)
    hi_lit = PYTHON.number(hi, as_int and hi.denominator == 1)
    tail = ""
    if sig.is_float:  # compared as doubles, with the exact answer: the bounds' doubles on their inner side
        lo_lit, hi_lit = PYTHON.double(double_within(lo, up=True)), PYTHON.double(double_within(hi, up=False))
        tail = f", {sig.length}, {sig.doc_min is None}"
    attr, var = ctx.attrs.take(sig.name), f"x{ctx.index}"
    in_page = bool(ctx.chain)
    return PySignal(
        sig=sig, name=sig.name, attr=attr, doc=doc_line(sig, ctx.enum, ctx.chain),
        py_type={"enum": f"{ctx.enum} | int", "int": "int", "float": "float"}[kind] + (" | None" if in_page else ""),
        const_type="float" if kind == "float" else "int", default=_default(sig, kind, ctx.enum, ctx.members), raw_expr=raw,
        frame_bytes=frame_bytes(sig, ctx.frame_bits), own_bytes=ctx.frame_bits > 64, pair=None if pair is None else pair[0],
        phys_expr=phys,
        specials=_specials(sig, ctx.consts, as_int), allowed=PYTHON.string(range_text(sig)), descriptor=ctx.module.take(f"_{ctx.message}__{sig.name}".upper()),
        descriptor_args=_descriptor_args(sig, direct, lo_lit, hi_lit), descriptor_tail=tail, var=var, raw_var=f"r{ctx.index}", direct=direct,
        q_expr=q_expr(sig, direct, f"m.{attr}" if direct and not in_page else var), lo_lit=lo_lit, hi_lit=hi_lit,
        q_nonneg=sig.factor > 0 and float(lo) >= float(sig.offset), exact_branch=exact_branch(sig), raw_check=raw_check(sig, direct),
        chain=ctx.chain, key_var=key_var, phys_from_key=_phys(sig, key_var, kind, ctx) if key_var else "",
    )
