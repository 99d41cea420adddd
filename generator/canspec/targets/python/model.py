"""The Python target's view of the IR: every name, literal, shift, mask and bound the
generated package needs, computed here so the templates only place text.

Decode reads the whole frame as one little-endian integer `v` (Intel signals are then a
shift and a mask); encode ORs the raw values back into one integer. Python owns the
literal syntax: floats as their shortest repr (the nearest double of the exact decimal).
"""

from __future__ import annotations

import keyword
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import decimal_text, to_raw_runtime
from canspec.ir.names import pascal, py_ident, snake, upper_snake
from canspec.render.literals import double_repr

# How many raws a decode lookup tuple may cover; wider enum fields use a dict lookup.
MAX_TUPLE_LOOKUP_BITS = 8
# Method names of every message class: a signal of that name gets a trailing underscore.
RESERVED_ATTRS = frozenset({"encode", "decode", "checksum_ok", "pack_raw", "unpack_raw", "to_raw", "from_raw", "next_counter", "advance_counter"})


@dataclass(frozen=True)
class PyEnumMember:
    name: str  # UPPER_SNAKE
    raw: int
    label_zh: str
    label: str


@dataclass(frozen=True)
class PyEnum:
    class_name: str
    table: str
    members: tuple[PyEnumMember, ...]


@dataclass(frozen=True)
class PyLookup:
    """Raw → enum member (or the plain int where the table has no entry), for decode."""

    var: str
    enum: str
    bits: int
    is_tuple: bool  # a tuple indexed by raw (every raw of the field); else a dict of the members


@dataclass(frozen=True)
class PySpecial:
    const: str  # class constant name, e.g. SENSOR_1_DISTANCE_NO_OBSTACLE
    raw: int
    physical: str  # literal in the attribute's type
    label_zh: str
    label: str


@dataclass(frozen=True)
class PySignal:
    name: str  # the spec's signal name (keys of raw dicts, vectors)
    attr: str  # attribute name
    zh: str
    doc: str  # one docstring line: Chinese name, unit, range, encoding
    role: str
    py_type: str  # "float", "int", "Gear | int"
    kind: str  # "enum" | "int" | "float"
    enum: str | None
    lookup: str | None
    default: str  # literal of the default attribute value
    raw_expr: str  # raw value from the frame integer `v` (sign-extended)
    phys_expr: str  # physical value from the frame integer `v`
    shift: int
    length: int
    mask: str  # hex literal of (1 << length) - 1
    signed: bool
    # encode
    direct: bool  # factor 1 and an integer offset: raw = x - offset, exact on ints
    offset_lit: str
    offset_float: str  # the offset as a float literal (slow path)
    offset_int: str  # the integer offset of a direct signal, else 0
    factor_lit: str
    q_expr: str  # (x - offset) / factor as the runtime computes it, on `var`
    var: str  # encode: local holding the attribute
    raw_var: str  # encode: local holding the raw value
    lo_lit: str  # the physical range check, as literals comparable with the attribute
    hi_lit: str
    q_nonneg: bool  # q >= 0 for every value passing the range check: no sign branch
    raw_check: bool  # a value passing the range check may still round outside raw_min..raw_max
    raw_min: int
    raw_max: int
    raw_type_min: int
    raw_type_max: int
    specials: tuple[PySpecial, ...]
    range_text: str  # the allowed range as shown in errors, e.g. "[-1080, 1080] deg"
    descriptor: str  # module-level name of the slow-path descriptor


@dataclass(frozen=True)
class PyChecksum:
    attr: str
    shift: int  # bit position of the checksum byte in the frame integer
    cover_mask: str  # hex literal: bytes the XOR covers
    folds: tuple[int, ...]  # shifts that fold the covered bytes into one (XOR)
    whole_frame: bool  # covers + checksum byte = every byte: a frame is right when all its bytes XOR to 0


@dataclass(frozen=True)
class PyMultiFrame:
    index_attr: str
    payload_attr: str
    frames: int
    bytes_per_frame: int
    text_length: int
    padding: int
    encoding: str
    func_split: str
    func_join: str
    assembler: str
    total_bytes: int  # frames × bytes per frame
    last_index: int
    padding_lit: str  # the padding byte as a bytes literal


@dataclass(frozen=True)
class PyMessage:
    name: str
    class_name: str
    raw_class: str  # TypedDict of raw values
    title: str
    zh: str
    desc: str
    section: str
    frame_id: int
    dlc: int
    cycle_ms: int
    sender: str
    receivers: tuple[str, ...]
    j1939: ir.J1939Id
    fingerprint: int
    signals: tuple[PySignal, ...]  # data signals (reserved bits are not in the API)
    checksum: PyChecksum | None
    counter: PySignal | None
    counter_modulo: int
    multiframe: PyMultiFrame | None
    decode_func: str
    encode_func: str
    pack_func: str
    unpack_func: str
    names_var: str  # frozenset of the raw keys
    raw_functional: bool  # raw keys that are not identifiers: functional TypedDict syntax
    frame_bits: int


@dataclass(frozen=True)
class PyPackage:
    package: str  # import name
    dist_name: str
    version: str
    title: str
    title_zh: str
    document: str
    bitrate: int
    enums: tuple[PyEnum, ...]
    lookups: tuple[PyLookup, ...]
    messages: tuple[PyMessage, ...]
    example: PyMessage


def num_lit(value: Fraction, as_int: bool) -> str:
    if as_int:
        if value.denominator != 1:
            raise ValueError(f"{value} is not an integer")
        return str(value.numerator)
    return double_repr(value)


def _check_intel(msg: ir.Message, sig: ir.Signal) -> None:
    for seg in sig.segments:
        if seg.byte * 8 + seg.byte_shift != sig.start + seg.value_shift:
            raise ValueError(f"{msg.name}.{sig.name}: only Intel (little-endian) signals are supported by the python target")


def _raw_expr(sig: ir.Signal, frame_bits: int) -> str:
    """The raw value from the frame integer `v`: shift, mask, sign-extend (no outer parentheses)."""
    expr = "v" if sig.start == 0 else f"v >> {sig.start}"
    if sig.start + sig.length < frame_bits:
        expr = f"{_paren(expr)} & 0x{sig.mask:X}"
    if sig.signed:
        sign = 1 << (sig.length - 1)
        expr = f"({expr} ^ 0x{sign:X}) - 0x{sign:X}"
    return expr


def _paren(expr: str) -> str:
    return expr if expr.isidentifier() else f"({expr})"


def _phys_expr(sig: ir.Signal, raw: str, kind: str, lookup: str | None) -> str:
    if kind == "enum":
        return f"{lookup}[{raw}]"
    as_int = kind == "int"
    expr = raw
    if sig.factor != 1:
        expr = f"{_paren(expr)} * {num_lit(sig.factor, as_int)}"
    if sig.offset != 0:
        expr = _paren(expr) if sig.factor == 1 else expr
        expr = f"{expr} + {num_lit(sig.offset, as_int)}" if sig.offset > 0 else f"{expr} - {num_lit(-sig.offset, as_int)}"
    return expr


def _q_expr(sig: ir.Signal, direct: bool, x: str) -> str:
    """`(x - offset) / factor` in the rule's order; `x - off` stays exact on ints when direct.
    Subtracting a negative offset is written as adding its magnitude (the same IEEE result)."""
    off = sig.offset
    as_int = direct
    if off == 0:
        expr = x
    elif off > 0:
        expr = f"{x} - {num_lit(off, as_int)}"
    else:
        expr = f"{x} + {num_lit(-off, as_int)}"
    if not direct and sig.factor != 1:
        expr = f"({expr}) / {double_repr(sig.factor)}" if off != 0 else f"{expr} / {double_repr(sig.factor)}"
    return expr


def _raw_check(sig: ir.Signal, direct: bool) -> bool:
    """Whether a value inside the (double) range check can round to a raw outside raw_min..raw_max.
    Rounding is monotonic, so the two ends of the range decide."""
    if direct:
        return True
    ends = (to_raw_runtime(float(sig.accept_min), float(sig.factor), float(sig.offset)), to_raw_runtime(float(sig.accept_max), float(sig.factor), float(sig.offset)))
    return not all(sig.raw_min <= raw <= sig.raw_max for raw in ends)


def _range_text(sig: ir.Signal) -> str:
    text = f"[{decimal_text(sig.check_min)}, {decimal_text(sig.check_max)}]"
    if sig.unit:
        text += f" {sig.unit}"
    if sig.specials:
        text += " or " + ", ".join(f"{decimal_text(s.physical)} ({s.name})" for s in sig.specials)
    return text


def _doc(sig: ir.Signal, kind: str, enum: str | None) -> str:
    parts = [sig.zh] if sig.zh else []
    if sig.unit:
        parts.append(f"unit {sig.unit}")
    parts.append(f"range [{decimal_text(sig.check_min)}, {decimal_text(sig.check_max)}]")
    if sig.is_scaled:
        sign = "-" if sig.offset < 0 else "+"
        parts.append(f"physical = raw × {decimal_text(sig.factor)} {sign} {decimal_text(abs(sig.offset))}")
    if enum is not None:
        parts.append(f"values {enum}")
    for s in sig.specials:
        parts.append(f"{decimal_text(s.physical)} = {s.name} ({s.label_zh})")
    if sig.role in ("counter", "checksum"):
        parts.append({"counter": "rolling counter", "checksum": "XOR checksum, filled by encode"}[sig.role])
    if sig.desc:
        parts.append(sig.desc)
    return "; ".join(parts)


def _signal(msg: ir.Message, sig: ir.Signal, index: int, frame_bits: int, enum_names: dict[str, str], lookups: dict[tuple[str, int], PyLookup]) -> PySignal:
    _check_intel(msg, sig)
    attr = py_ident(snake(sig.name))
    if attr in RESERVED_ATTRS:
        attr = f"{attr}_"
    enum = enum_names[sig.value_table.name] if sig.value_table is not None and sig.is_identity else None
    if enum is not None:
        kind = "enum"
    elif sig.is_integer:
        kind = "int"
    else:
        kind = "float"
    as_int = kind != "float"
    lookup = None
    if enum is not None:
        assert sig.value_table is not None
        key = (sig.value_table.name, sig.length)
        if key not in lookups:
            is_tuple = not sig.signed and sig.length <= MAX_TUPLE_LOOKUP_BITS
            lookups[key] = PyLookup(f"_{upper_snake(sig.value_table.name)}_{sig.length}", enum, sig.length, is_tuple)
        lookup = lookups[key].var
    raw = _raw_expr(sig, frame_bits)
    phys = _phys_expr(sig, raw, kind, lookup)
    if enum is not None and sig.value_table is not None and not lookups[(sig.value_table.name, sig.length)].is_tuple:
        phys = f"_member({lookup}, {raw})"
    direct = sig.factor == 1 and sig.offset.denominator == 1 and sig.check_min <= sig.phys_min and sig.phys_max <= sig.check_max
    default_raw = _default_raw(sig)
    default_phys = sig.physical(default_raw)
    if enum is not None:
        assert sig.value_table is not None
        entry = sig.value_table.by_raw(default_raw)
        default = f"{enum}.{upper_snake(entry.name)}" if entry is not None else str(default_raw)
    else:
        default = num_lit(default_phys, as_int)
    lo, hi = sig.accept_min, sig.accept_max  # the runtime comparison (display uses check_min/max)
    lo_lit = num_lit(lo, True) if lo.denominator == 1 and as_int else double_repr(lo)
    hi_lit = num_lit(hi, True) if hi.denominator == 1 and as_int else double_repr(hi)
    q_nonneg = sig.factor > 0 and float(lo) - float(sig.offset) >= 0
    specials = tuple(
        PySpecial(f"{upper_snake(sig.name)}_{upper_snake(s.name)}", s.raw, num_lit(s.physical, as_int), s.label_zh, s.label) for s in sig.specials
    )
    py_type = {"enum": f"{enum} | int", "int": "int", "float": "float"}[kind]
    return PySignal(
        name=sig.name, attr=attr, zh=sig.zh, doc=_doc(sig, kind, enum), role=sig.role, py_type=py_type, kind=kind, enum=enum,
        lookup=lookup, default=default, raw_expr=raw, phys_expr=phys, shift=sig.start, length=sig.length, mask=f"0x{sig.mask:X}",
        signed=sig.signed, direct=direct, offset_lit=num_lit(sig.offset, sig.offset.denominator == 1) if direct else double_repr(sig.offset),
        offset_float=double_repr(sig.offset), offset_int=str(sig.offset.numerator) if direct else "0", factor_lit=double_repr(sig.factor), lo_lit=lo_lit, hi_lit=hi_lit, q_nonneg=q_nonneg, raw_min=sig.raw_min, raw_max=sig.raw_max,
        raw_type_min=sig.raw_type_min, raw_type_max=sig.raw_type_max, specials=specials, range_text=_range_text(sig),
        q_expr=_q_expr(sig, direct, f"m.{attr}" if direct else f"x{index}"), var=f"x{index}", raw_check=_raw_check(sig, direct), raw_var=f"r{index}", descriptor=f"_{upper_snake(msg.name)}__{upper_snake(sig.name)}",
    )


def _default_raw(sig: ir.Signal) -> int:
    """The raw value of a new message's attribute: physical 0 when allowed, else raw 0, else the nearest allowed raw."""
    if sig.check_min <= 0 <= sig.check_max and (-sig.offset / sig.factor).denominator == 1:
        raw = int(-sig.offset / sig.factor)
        if sig.raw_min <= raw <= sig.raw_max:
            return raw
    return min(max(0, sig.raw_min), sig.raw_max)


def _folds(nbytes: int) -> tuple[int, ...]:
    """Shifts that XOR-fold `nbytes` bytes of an integer into its lowest byte."""
    out = []
    span = 1
    while span < nbytes:
        span *= 2
    while span > 1:
        span //= 2
        out.append(span * 8)
    return tuple(out)


def _message(msg: ir.Message, enum_names: dict[str, str], lookups: dict[tuple[str, int], PyLookup]) -> PyMessage:
    frame_bits = msg.dlc * 8
    signals = tuple(_signal(msg, s, i, frame_bits, enum_names, lookups) for i, s in enumerate(msg.data_signals))
    by_name = {s.name: s for s in signals}
    checksum = None
    if msg.checksum is not None:
        if msg.checksum.algorithm != "xor":
            raise ValueError(f"{msg.name}: checksum algorithm {msg.checksum.algorithm!r} is not supported by the python target")
        cover = sum(0xFF << (8 * b) for b in msg.checksum.covers)
        whole = sorted((*msg.checksum.covers, msg.checksum.byte)) == list(range(msg.dlc))
        checksum = PyChecksum(by_name[msg.checksum.signal].attr, msg.checksum.byte * 8, f"0x{cover:X}", _folds(msg.dlc), whole)
    counter = by_name[msg.counter.signal] if msg.counter is not None else None
    mf = None
    if msg.multiframe is not None:
        m = msg.multiframe
        base = snake(msg.name)
        mf = PyMultiFrame(
            by_name[m.index_signal].attr, by_name[m.payload_signal].attr, m.frames, m.bytes_per_frame, m.text_length, m.padding, m.encoding,
            f"split_{base}_text", f"join_{base}_text", f"{pascal(msg.name)}TextAssembler", m.frames * m.bytes_per_frame, m.frames - 1,
            repr(bytes([m.padding])),
        )
    base = snake(msg.name)
    return PyMessage(
        name=msg.name, class_name=pascal(msg.name), raw_class=f"{pascal(msg.name)}Raw", title=msg.title, zh=msg.zh, desc=msg.desc,
        section=msg.section, frame_id=msg.frame_id, dlc=msg.dlc, cycle_ms=msg.cycle_ms, sender=msg.sender, receivers=msg.receivers,
        j1939=msg.j1939, fingerprint=msg.fingerprint, signals=signals, checksum=checksum, counter=counter,
        counter_modulo=msg.counter.modulo if msg.counter is not None else 0, multiframe=mf,
        decode_func=f"_decode_{base}", encode_func=f"_encode_{base}", pack_func=f"_pack_{base}", unpack_func=f"_unpack_{base}",
        names_var=f"_{upper_snake(msg.name)}_SIGNALS", raw_functional=any(not s.name.isidentifier() or keyword.iskeyword(s.name) for s in signals),
        frame_bits=frame_bits,
    )


def build_package(spec: ir.Spec) -> PyPackage:
    can = spec.can
    assert can is not None
    enum_names = {t.name: pascal(t.name) for t in can.value_tables}
    enums = tuple(
        PyEnum(enum_names[t.name], t.name, tuple(PyEnumMember(upper_snake(e.name), e.raw, e.label_zh, e.label) for e in t.entries))
        for t in can.value_tables
    )
    lookups: dict[tuple[str, int], PyLookup] = {}
    messages = tuple(_message(m, enum_names, lookups) for m in can.messages)
    example = next((m for m in messages if m.checksum is not None and m.counter is not None), messages[0])
    return PyPackage(
        package=py_ident(snake(can.name)), dist_name=snake(can.name).replace("_", "-"), version=can.version, title=can.title,
        title_zh=can.title_zh, document=can.document, bitrate=can.bus.bitrate, enums=enums,
        lookups=tuple(sorted(lookups.values(), key=lambda lk: lk.var)), messages=messages, example=example,
    )
