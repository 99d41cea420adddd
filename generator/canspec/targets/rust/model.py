"""The Rust view of the IR: type names, identifiers, literals and the bit expressions of the
generated crate. Python owns all of it; `templates/rust/` only shapes the text.

Frames are handled as one little-endian `u64` (`bits`): every signal is Intel order, so a
signal is `(bits >> start) & mask` — one shift and one mask, whatever bytes it spans.
"""

from __future__ import annotations

import math
import re
import struct
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.names import pascal, rust_ident, snake, upper_snake
from canspec.render.literals import float_lit, grouped_int, num

OTHER_VARIANT = "_Other"  # catch-all of every value-table enum (as dbc-codegen names it)
RESERVED_TYPE_NAMES = frozenset({"Error", "Messages", "Frame", "Vin", "Scale", "Result", "Option", "Self"})
SEMVER = re.compile(r"^\d+\.\d+\.\d+(-[0-9A-Za-z.-]+)?$")


# --- literals ------------------------------------------------------------------------------


def int_type(bits: int, signed: bool) -> str:
    return f"{'i' if signed else 'u'}{bits}"




def doc_text(text: str) -> str:
    """Text safe inside a `///` comment: no accidental links, HTML tags or code fences."""
    return text.replace("\\", "\\\\").replace("[", "\\[").replace("]", "\\]").replace("<", "&lt;").replace(">", "&gt;").replace("`", "'")



# --- bit expressions ---------------------------------------------------------------------


def unpack_expr(sig: ir.Signal) -> str:
    """The raw value of `sig` from the frame word `bits`, as its storage type."""
    ty = int_type(sig.storage_bits, sig.signed)
    if sig.signed:
        # Move the field to the top, then an arithmetic shift back sign-extends it.
        left = 64 - sig.start - sig.length
        moved = f"(bits << {left})" if left else "bits"
        return f"(({moved} as i64) >> {64 - sig.length}) as {ty}"
    shifted = f"bits >> {sig.start}" if sig.start else "bits"
    if sig.start + sig.length < 64 and sig.length != sig.storage_bits:
        return f"(({shifted}) & {grouped_int(sig.mask)}) as {ty}" if sig.start else f"({shifted} & {grouped_int(sig.mask)}) as {ty}"
    if ty == "u64":
        return shifted
    return f"({shifted}) as {ty}" if sig.start else f"{shifted} as {ty}"


def pack_expr(sig: ir.Signal, field: str) -> str:
    """The field's bits in place in the frame word, from the variable `field` (a raw value
    that fits the field)."""
    if sig.signed:
        value = f"({field} as u64 & {grouped_int(sig.mask)})"
    elif sig.storage_bits == 64:
        value = field
    else:
        value = f"u64::from({field})"
    return f"{value} << {sig.start}" if sig.start else value


def outside_expr(var: str, lo: int | None, hi: int | None) -> str | None:
    """`var` outside [lo, hi]; a None bound is implied by the type. None when never."""
    if lo is None and hi is None:
        return None
    if lo is None:
        return f"{var} > {grouped_int(hi)}"  # type: ignore[arg-type]
    if hi is None:
        return f"{var} < {grouped_int(lo)}"
    if lo == hi:
        return f"{var} != {grouped_int(lo)}"
    return f"!({grouped_int(lo)}..={grouped_int(hi)}).contains(&{var})"


def _bounds(lo: int, hi: int, sig: ir.Signal) -> tuple[int | None, int | None]:
    """Drop bounds the storage type already implies (clippy rejects `x >= 0` on unsigned)."""
    store_lo = -(1 << (sig.storage_bits - 1)) if sig.signed else 0
    store_hi = (1 << (sig.storage_bits - (1 if sig.signed else 0))) - 1
    return (None if lo <= store_lo else lo), (None if hi >= store_hi else hi)


def misfit_expr(sig: ir.Signal, var: str = "value") -> str | None:
    """`var` (storage type) does not fit the field's bits; None when every value of the type fits."""
    return outside_expr(var, *_bounds(sig.raw_type_min, sig.raw_type_max, sig))


def refused_expr(sig: ir.Signal, var: str = "value") -> str | None:
    """A raw `var` a physical encode may not produce: neither a special value nor within the
    documented range (for integer signals, whose physical value is the raw value). None: never."""
    lo = max(sig.raw_min, math.ceil((sig.check_min - sig.offset) / sig.factor))
    hi = min(sig.raw_max, math.floor((sig.check_max - sig.offset) / sig.factor))
    outside = outside_expr(var, *_bounds(lo, hi, sig))
    if outside is None:
        return None
    return " && ".join([*(f"{var} != {grouped_int(s.raw)}" for s in sig.specials if not lo <= s.raw <= hi), outside])


# --- view model --------------------------------------------------------------------------


@dataclass(frozen=True)
class RustVariant:
    name: str
    raw: int
    doc: str


@dataclass(frozen=True)
class RustEnum:
    name: str
    table: str
    repr: str
    variants: tuple[RustVariant, ...]
    other: str
    other_tag: int  # discriminant of the catch-all: the first raw value the table leaves free


@dataclass(frozen=True)
class RustSpecial:
    const: str
    raw: str
    doc: str


@dataclass(frozen=True)
class RustField:
    sig: ir.Signal
    name: str  # the signal name (snake)
    qualified: str  # "message.signal", for error messages
    field: str  # struct field holding the raw value
    getter: str
    raw_getter: str
    setter: str
    raw_setter: str
    raw_type: str
    kind: str  # "enum" | "int" (identity) | "scaled_int" (integer factor/offset) | "float"
    phys_type: str
    enum: str | None
    unpack: str
    pack: str  # the raw value `value` in place in the frame word
    clear: str  # frame-word mask without the field's bits
    misfit: str | None  # `value` (raw type) does not fit the field; None: never
    refused: str | None  # `value` (raw type) may not come from a physical encode; None: never
    scale: dict[str, str]  # float signals: literals of the codec::Scale
    const_prefix: str  # FIELD_NAME for associated constants
    factor_lit: str  # the factor as an f64 literal
    to_raw: str  # the codec function for physical → raw (scaled kinds)
    specials_slice: str  # float signals: `&[..]` of special raws (i64)
    phys_expr: str  # physical value from `self.<field>`
    specials: tuple[RustSpecial, ...]
    doc: tuple[str, ...]
    short_doc: str  # one line: name, range and unit
    table_row: str
    is_counter: bool
    strategy_lo: str  # test strategy: physical-encodable raw range (for the round-trip tests)
    strategy_hi: str
    type_lo: str
    type_hi: str
    reciprocal: str = ""  # the double nearest 1/factor, for `to_raw_documented_unsigned_recip`


@dataclass(frozen=True)
class RustMessage:
    msg: ir.Message
    name: str  # the type
    values: str  # its physical-values struct
    variant: str  # variant in `Messages`
    fields: tuple[RustField, ...]  # data signals except the checksum
    checksum: ir.Checksum | None
    checksum_expr: str  # over `bytes`
    checksum_fold: bool  # the checksum covers every other byte of an 8-byte frame: fold the word
    checksum_shift: int  # bit position of the checksum byte in the frame word
    checksum_clear: str  # frame-word mask without the checksum byte
    counter: RustField | None
    multiframe: dict[str, object] | None
    da: str
    doc: tuple[str, ...]
    defined_mask: str  # frame-word bits the message defines (not reserved, not undefined)
    fields_mask: str  # frame-word bits of the fields the type stores (no checksum, no reserved)


def _phys_expr(sig: ir.Signal, field: str) -> str:
    expr = f"self.{field} as f64"
    if sig.factor != 1:
        expr += f" * {float_lit(sig.factor)}"
    if sig.offset > 0:
        expr += f" + {float_lit(sig.offset)}"
    elif sig.offset < 0:
        expr += f" - {float_lit(-sig.offset)}"  # x - c == x + (-c) exactly in IEEE arithmetic
    return expr


# Integer factors below this give the same raw value in exact integer arithmetic as the
# double rule (a non-tie quotient is at least 1/(2·factor) > TIE_EPSILON away from a tie).
MAX_INT_FACTOR = 500_000_000


def scaled_int_type(sig: ir.Signal) -> str | None:
    """The integer type of a scaled signal whose physical values are all integers (integer
    factor and offset), holding every physical value and `raw × factor`; None if there is none."""
    if not sig.is_integer or sig.is_identity or not 0 < sig.factor < MAX_INT_FACTOR or sig.storage_bits > 32:
        return None
    ends = [sig.raw_type_min * sig.factor + sig.offset, sig.raw_type_max * sig.factor + sig.offset, sig.raw_type_min * sig.factor, sig.raw_type_max * sig.factor]
    lo, hi = min(ends), max(ends)
    for bits in (8, 16, 32):
        if lo >= 0 and hi < 1 << bits:
            return f"u{bits}"
        if -(1 << (bits - 1)) <= lo and hi < 1 << (bits - 1):
            return f"i{bits}"
    return None


def _power_of_two(value: Fraction) -> bool:
    n, d = value.numerator, value.denominator
    return n > 0 and n & (n - 1) == 0 and d & (d - 1) == 0


def _double_key(x: float) -> int:
    """Doubles in order as integers (-0.0 and 0.0 share a key)."""
    bits = struct.unpack("<q", struct.pack("<d", x))[0]
    return bits if bits >= 0 else -(bits & 0x7FFF_FFFF_FFFF_FFFF)


def _double_of_key(key: int) -> float:
    bits = key if key >= 0 else (-key) | -0x8000_0000_0000_0000
    return struct.unpack("<d", struct.pack("<q", bits))[0]


def _first_true(pred, lo: float, hi: float) -> float | None:  # type: ignore[no-untyped-def]
    """The smallest double in [lo, hi] where the monotone (false…true) `pred` holds."""
    if pred(lo):
        return lo
    if not pred(hi):
        return None
    a, b = _double_key(lo), _double_key(hi)  # pred(a) false, pred(b) true
    while b - a > 1:
        mid = (a + b) // 2
        if pred(_double_of_key(mid)):
            b = mid
        else:
            a = mid
    return _double_of_key(b)


def documented_range_suffices(sig: ir.Signal) -> tuple[bool, bool, float | None, float | None]:
    """Whether, for this signal, one range check [lo, hi] on the physical value can replace
    the other checks of the shared rule (q inside the field's raw range, raw inside [raw_min,
    raw_max]); whether q is then never negative; and for non-integer signals that range: the
    doubles of [accept_min, accept_max] every check passes. Proof by monotonicity: q =
    (x - offset) / factor and the rounding are non-decreasing in x in IEEE arithmetic, and
    Python floats are the same doubles the generated code uses, so the doubles that pass form
    an interval, found exactly by bisection over the doubles. (Special values are checked by
    the full rule, which callers fall back to outside that range.)"""
    if sig.factor <= 0:
        return False, False, None, None
    from canspec.ir.encoding import to_raw_runtime

    f, o = float(sig.factor), float(sig.offset)
    lo, hi = float(sig.accept_min), float(sig.accept_max)
    if sig.is_integer:  # the integer path compares whole values: its ends are the whole ones inside
        lo, hi = float(math.ceil(sig.check_min)), float(math.floor(sig.check_max))
        q_lo, q_hi = (lo - o) / f, (hi - o) / f
        if not (sig.raw_type_min <= q_lo and q_hi <= sig.raw_type_max):
            return False, False, None, None
        if not (sig.raw_min <= to_raw_runtime(lo, f, o) and to_raw_runtime(hi, f, o) <= sig.raw_max):
            return False, False, None, None
        return True, q_lo >= 0, None, None

    def high_enough(x: float) -> bool:
        return (x - o) / f >= sig.raw_type_min and to_raw_runtime(x, f, o) >= sig.raw_min

    def low_enough(x: float) -> bool:
        return (x - o) / f <= sig.raw_type_max and to_raw_runtime(x, f, o) <= sig.raw_max

    first = _first_true(high_enough, lo, hi)
    last = _first_true(lambda x: not low_enough(x), lo, hi)
    if last is not None:
        last = _double_of_key(_double_key(last) - 1) if last > lo else None
    else:
        last = hi
    if first is None or last is None or first > last:
        return False, False, None, None
    return True, (first - o) / f >= 0, first, last


def _int_phys_expr(sig: ir.Signal, field: str, ty: str) -> str:
    expr = f"self.{field}" if ty == int_type(sig.storage_bits, sig.signed) else f"self.{field} as {ty}"
    if sig.factor != 1:
        expr += f" * {grouped_int(int(sig.factor))}"
    if sig.offset > 0:
        expr += f" + {grouped_int(int(sig.offset))}"
    elif sig.offset < 0:
        expr += f" - {grouped_int(int(-sig.offset))}"
    return expr


def _range_text(lo: Fraction | None, hi: Fraction | None) -> str:
    return "—" if lo is None else f"{num(lo)} … {num(hi)}"


def _field_doc(sig: ir.Signal) -> tuple[str, ...]:
    lines = [doc_text(f"{sig.zh} — {sig.desc}" if sig.desc else sig.zh)]
    if sig.desc_zh:
        lines += ["", doc_text(sig.desc_zh)]
    lines += [
        "",
        "| start bit | length | factor | offset | unit | range | raw |",
        "|---|---|---|---|---|---|---|",
        f"| {sig.start} | {sig.length} | {num(sig.factor)} | {num(sig.offset)} | {doc_text(sig.unit) or '—'} "
        f"| {_range_text(sig.check_min, sig.check_max)} | {grouped_int(sig.raw_min)} … {grouped_int(sig.raw_max)} |",
    ]
    for s in sig.specials:
        lines += ["", doc_text(f"Special raw value {grouped_int(s.raw)}: {s.label_zh} ({s.label})")]
    if sig.errata:
        lines += ["", doc_text(f"Errata: {', '.join(sig.errata)} (see spec/ERRATA.md)")]
    return tuple(lines)


def build_field(msg: ir.Message, sig: ir.Signal, enums: dict[str, RustEnum]) -> RustField:
    name = snake(sig.name)
    raw_type = int_type(sig.storage_bits, sig.signed)
    int_phys = scaled_int_type(sig)
    if sig.value_table is not None:
        kind, phys_type, enum = "enum", enums[sig.value_table.name].name, enums[sig.value_table.name].name
    elif sig.is_identity:
        kind, phys_type, enum = "int", raw_type, None
    elif int_phys is not None:
        kind, phys_type, enum = "scaled_int", int_phys, None
    else:
        kind, phys_type, enum = "float", "f64", None
    if kind == "scaled_int":
        lo, hi = math.ceil(sig.check_min), math.floor(sig.check_max)
        bounds = {"check_min": grouped_int(lo), "check_max": grouped_int(hi), "factor": grouped_int(int(sig.factor)), "offset": grouped_int(int(sig.offset))}
    else:
        bounds = {"check_min": float_lit(sig.check_min), "check_max": float_lit(sig.check_max), "accept_min": float_lit(sig.accept_min), "accept_max": float_lit(sig.accept_max),
                  "factor": float_lit(sig.factor), "offset": float_lit(sig.offset)}
    scale = {
        **bounds,
        "raw_min": grouped_int(sig.raw_min), "raw_max": grouped_int(sig.raw_max),
        "type_min": grouped_int(sig.raw_type_min), "type_max": grouped_int(sig.raw_type_max),
    }
    suffices, nonnegative, pass_min, pass_max = documented_range_suffices(sig)
    if pass_min is not None and pass_max is not None:
        # The doubles the full rule accepts (without specials): the shortcut's one range check,
        # and for the full rule the same answers (outside it another check fails anyway).
        if pass_min != float(sig.accept_min):
            scale["accept_min"] = float_lit(Fraction(repr(pass_min)))  # shortest decimal of that double
        if pass_max != float(sig.accept_max):
            scale["accept_max"] = float_lit(Fraction(repr(pass_max)))
    if kind == "scaled_int":
        to_raw = ("to_raw_int_documented_or_special" if sig.specials else "to_raw_int_documented") if suffices else "to_raw_int"
    elif suffices and sig.specials:
        to_raw = "to_raw_documented_or_special"
    else:
        to_raw = ("to_raw_documented_unsigned" if nonnegative else "to_raw_documented") if suffices else "to_raw"
        # Quotients below 2^17 and a factor that is not a power of two (whose division the
        # compiler makes a multiplication already): the reciprocal path gives the same result (codec.rs).
        if to_raw == "to_raw_documented_unsigned" and pass_max is not None and (pass_max - float(sig.offset)) / float(sig.factor) < 2.0**17 \
                and not _power_of_two(Fraction(sig.factor)):
            to_raw = "to_raw_documented_unsigned_recip"
    specials = tuple(
        RustSpecial(upper_snake(f"{name}_{s.name}"), f"{grouped_int(s.raw)}", doc_text(f"{sig.zh}: {s.label_zh} ({s.label})") + f", raw value of `{name}`")
        for s in sig.specials
    )
    return RustField(
        sig=sig, name=name, qualified=f"{msg.name}.{sig.name}", field=rust_ident(name),
        getter=rust_ident(name), raw_getter=rust_ident(f"{name}_raw"), setter=f"set_{name}", raw_setter=f"set_{name}_raw",
        raw_type=raw_type, kind=kind, phys_type=phys_type, enum=enum,
        unpack=unpack_expr(sig), pack=pack_expr(sig, "value"), clear=grouped_int(((1 << 64) - 1) ^ (sig.mask << sig.start)),
        misfit=misfit_expr(sig), refused=refused_expr(sig), scale=scale, const_prefix=upper_snake(name), factor_lit=float_lit(sig.factor), to_raw=to_raw,
        specials_slice="&[" + ", ".join(grouped_int(s.raw) for s in sig.specials) + "]",
        phys_expr=_int_phys_expr(sig, f"{rust_ident(name + '_raw')}()", phys_type) if kind == "scaled_int" else _phys_expr(sig, f"{rust_ident(name + '_raw')}()"),
        specials=specials, doc=_field_doc(sig),
        reciprocal=float_lit(Fraction(repr(1.0 / float(sig.factor)))) if to_raw == "to_raw_documented_unsigned_recip" else "",
        short_doc=doc_text(f"{sig.zh}: {_range_text(sig.check_min, sig.check_max)} {sig.unit}".rstrip()),
        table_row=f"| `{name}` | {doc_text(sig.zh)} | {sig.start} | {sig.length} | {num(sig.factor)} | {num(sig.offset)} | {doc_text(sig.unit) or '—'} |",
        is_counter=sig.role == "counter",
        strategy_lo=grouped_int(sig.raw_min), strategy_hi=grouped_int(sig.raw_max),
        type_lo=grouped_int(sig.raw_type_min), type_hi=grouped_int(sig.raw_type_max),
    )


def build_enum(table: ir.ValueTable, signals: list[ir.Signal]) -> RustEnum:
    widths = {s.storage_bits for s in signals}
    if len(widths) != 1:
        raise ValueError(f"value table {table.name}: used by signals of {sorted(widths)}-bit storage; the Rust target needs one width per table")
    bits = widths.pop()
    variants = []
    seen: set[str] = set()
    for e in table.entries:
        vname = pascal(e.name)
        if vname in seen or vname == OTHER_VARIANT:
            raise ValueError(f"value table {table.name}: entries give the Rust variant {vname} twice; rename one")
        seen.add(vname)
        variants.append(RustVariant(vname, e.raw, doc_text(f"{e.raw}: {e.label_zh} — {e.label}")))
    used = {e.raw for e in table.entries}
    free = next((v for v in range(1 << bits) if v not in used), None)
    if free is None:
        raise ValueError(f"value table {table.name}: defines every {bits}-bit value; the Rust target needs one free for its catch-all")
    return RustEnum(pascal(table.name), table.name, int_type(bits, False), tuple(variants), OTHER_VARIANT, free)


def _message_doc(msg: ir.Message) -> tuple[str, ...]:
    lines = [doc_text(f"{msg.zh} — {msg.title}"), ""]
    if msg.desc:
        lines += [doc_text(msg.desc), ""]
    j = msg.j1939
    lines += [
        f"ID `0x{msg.frame_id:08X}` (29-bit), DLC {msg.dlc}, every {msg.cycle_ms} ms, section {doc_text(msg.section)} of the document.",
        f"J1939: priority {j.priority}, PGN 0x{j.pgn:05X}, source address 0x{j.sa:02X}"
        + (f", destination 0x{j.da:02X}." if j.da is not None else " (broadcast)."),
        doc_text(f"Sender {msg.sender}; receivers {', '.join(msg.receivers)}."),
    ]
    if msg.layout_undefined:
        lines += ["", "The document lists this message but defines no layout: it carries no signals."]
    if msg.checksum:
        lines += ["", f"Byte {msg.checksum.byte} is the XOR of bytes {', '.join(map(str, msg.checksum.covers))}: `encode` fills it, decoding checks it."]
    if msg.counter:
        lines += ["", f"`{msg.counter.signal}` is a rolling counter modulo {msg.counter.modulo}."]
    if msg.errata:
        lines += ["", doc_text(f"Errata: {', '.join(msg.errata)} (see spec/ERRATA.md)")]
    return tuple(lines)


def build_message(msg: ir.Message, enums: dict[str, RustEnum]) -> RustMessage:
    name = pascal(msg.name)
    fields = tuple(build_field(msg, s, enums) for s in msg.data_signals if s.role != "checksum")
    counter = next((f for f in fields if msg.counter and f.name == snake(msg.counter.signal)), None)
    checksum_expr, fold, shift, clear = "", False, 0, ""
    if msg.checksum:
        checksum_expr = " ^ ".join(f"bytes[{b}]" for b in msg.checksum.covers)
        fold = msg.dlc == 8 and set(msg.checksum.covers) == set(range(8)) - {msg.checksum.byte}
        shift = 8 * msg.checksum.byte
        clear = grouped_int(((1 << 64) - 1) ^ (0xFF << shift))
    mf = None
    if msg.multiframe:
        m = msg.multiframe
        mf = {
            "index": next(f for f in fields if f.name == snake(m.index_signal)),
            "payload": next(f for f in fields if f.name == snake(m.payload_signal)),
            "text_length": m.text_length, "frames": m.frames, "bytes_per_frame": m.bytes_per_frame,
            "padding": grouped_int(m.padding), "assembler": f"{name}Text", "payload_bytes": m.bytes_per_frame,
            "total": m.frames * m.bytes_per_frame,
        }
        payload = mf["payload"]
        assert isinstance(payload, RustField)
        if payload.raw_type == "u64":
            mf["chunk_to_raw"], mf["raw_to_chunk"] = "u64::from_le_bytes(word)", f"frame.{payload.raw_getter}().to_le_bytes()"
        else:
            mf["chunk_to_raw"] = f"u64::from_le_bytes(word) as {payload.raw_type}"
            mf["raw_to_chunk"] = f"u64::from(frame.{payload.raw_getter}()).to_le_bytes()"
    defined = 0
    for s in msg.data_signals:
        defined |= s.mask << s.start
    stored = 0
    for f in fields:
        stored |= f.sig.mask << f.sig.start
    da = "None" if msg.j1939.da is None else f"Some(0x{msg.j1939.da:02X})"
    return RustMessage(msg, name, f"{name}Values", name, fields, msg.checksum, checksum_expr, fold, shift, clear, counter, mf, da,
                       _message_doc(msg), grouped_int(defined), grouped_int(stored))


@dataclass(frozen=True)
class RustCrate:
    package: str
    version: str
    enums: tuple[RustEnum, ...]
    messages: tuple[RustMessage, ...]


def build_crate(can: ir.CanProtocol) -> RustCrate:
    users: dict[str, list[ir.Signal]] = {}
    tables = {t.name: t for t in can.value_tables}
    for msg in can.messages:
        for s in msg.data_signals:
            if s.value_table is not None:
                users.setdefault(s.value_table.name, []).append(s)
                tables.setdefault(s.value_table.name, s.value_table)
    enums = {name: build_enum(tables[name], sigs) for name, sigs in sorted(users.items())}
    messages = tuple(build_message(m, enums) for m in can.messages)
    names: dict[str, str] = {}
    for kind, n in [*(("value table", e.name) for e in enums.values()), *(("message", m.name) for m in messages),
                    *(("message values", m.values) for m in messages),
                    *(("message text", str(m.multiframe["assembler"])) for m in messages if m.multiframe)]:
        if n in RESERVED_TYPE_NAMES or n in names:
            raise ValueError(f"Rust type name {n} of {kind} clashes with {names.get(n, 'a name of the crate')}; rename one in the spec")
        names[n] = kind
    version = can.version if SEMVER.match(can.version) else "0.0.0"
    return RustCrate(rust_crate_name(can.name), version, tuple(enums.values()), messages)


def rust_crate_name(name: str) -> str:
    return snake(name) or "canspec_protocol"


__all__ = [
    "RustCrate",
    "RustEnum",
    "RustField",
    "RustMessage",
    "build_crate",
    "doc_text",
    "misfit_expr",
    "pack_expr",
    "refused_expr",
    "unpack_expr",
]
