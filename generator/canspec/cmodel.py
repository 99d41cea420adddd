"""The C target's view of the IR: C names, types, literals and pack plans.

Python owns the meaning here — bit positions, masks, range-check expressions, fixed-point
scales, literal syntax — so the `templates/c/` family only loops and places text.

Pack plan: every frame is at most 8 bytes and every signal is Intel (little-endian), so a
signal is a contiguous bit field [start, start+length) of the frame read as one
little-endian 64-bit word. Pack ORs shifted fields into that word and stores it; unpack
loads it once and shifts/masks each field out. Compilers turn the byte-wise load/store
into single word accesses.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.encoding import decimal_text
from canspec.format import c_double
from canspec.naming import c_ident, snake, upper_snake

MAX_DLC = 8
DOUBLE_EXACT = 2**53  # integers up to this are exact in an IEEE double
# A value-table entry named `<layout>_xor_error` is the fault code for a checksum failure of
# a message with that layout; `message_timeout` is the code for a receive timeout.
XOR_ERROR_SUFFIX = "_xor_error"
TIMEOUT_ENTRY = "message_timeout"


class CModelError(ValueError):
    pass


def uint_lit(value: int, bits: int = 32) -> str:
    if value < 0:
        raise CModelError(f"negative unsigned literal {value}")
    if bits > 32 or value > 0xFFFFFFFF:
        return f"UINT64_C({value})"
    return f"{value}u"


def int_lit(value: int, bits: int = 32) -> str:
    if bits > 32 or not -(2**31) < value < 2**31:
        return f"INT64_C({value})" if value > -(2**63) else "INT64_MIN"
    return f"{value}" if value >= 0 else f"({value})"


def hex_lit(value: int, bits: int = 32) -> str:
    if bits > 32 or value > 0xFFFFFFFF:
        return f"UINT64_C(0x{value:X})"
    return f"0x{value:X}u"


def ctype(bits: int, signed: bool) -> str:
    return f"{'int' if signed else 'uint'}{bits}_t"


def decimals(value: Fraction) -> int:
    text = decimal_text(value)
    return len(text.split(".")[1]) if "." in text else 0


def fixed_bits(lo: int, hi: int) -> int:
    return 32 if -(2**31) <= lo and hi < 2**31 else 64


@dataclass(frozen=True)
class CSpecial:
    macro: str
    value: str  # literal in the field's type
    raw: int
    label: str


@dataclass(frozen=True)
class CEnumEntry:
    const: str
    name: str
    value: int
    label: str
    label_zh: str


@dataclass(frozen=True)
class CEnum:
    table: str
    type: str
    name_fn: str
    entries: tuple[CEnumEntry, ...]


@dataclass(frozen=True)
class CSignal:
    sig: ir.Signal
    field: str
    macro: str  # KAIWO_GATEWAY_MSG_SIG
    fn: str  # kaiwo_gateway_msg_sig
    type: str
    length: int
    start: int
    range_check: str  # C condition true when a signed src->field does not fit its bits
    needs_check: bool  # unsigned field whose type is wider than its bits
    pack_terms: tuple[tuple[int, str], ...]  # (byte, term OR'ed into that byte)
    unpack_expr: str  # value from the frame bytes src[]
    raw_type_min: str
    raw_type_max: str
    raw_min: str  # int64 literals for the physical encode's raw range
    raw_max: str
    q_low: str  # double: q must lie strictly between these before rounding
    q_high: str
    factor: str  # double literal
    offset: str
    check_min: str  # double literals of the documented / encodable range
    check_max: str
    decode_expr: str  # double from `raw` (and `scaled` when decode_pre is set)
    decode_pre: str  # `const double scaled = <this>;` before decode_expr, or ""
    specials: tuple[CSpecial, ...]
    enum: CEnum | None
    # integer-only (fixed-point) path: physical * scale is an integer of fixed_type
    scale: str
    scale_int: int
    fixed_type: str
    fixed_factor: str
    fixed_offset: str
    fixed_min: str
    fixed_max: str
    fixed_decode_expr: str
    fixed_q_low: str  # fixed input must lie strictly between these before rounding
    fixed_q_high: str
    is_data: bool  # has physical encode/decode (not counter/checksum)
    has_double: bool  # every raw value is exact in a double (|raw| <= 2^53): double encode/decode exist
    unit: str
    comment: str


@dataclass(frozen=True)
class CMessage:
    msg: ir.Message
    name: str  # snake name
    macro: str
    fn: str
    type: str
    index_const: str  # enumerator in the message index enum
    signals: tuple[CSignal, ...]  # data signals incl. counter/checksum, not reserved
    range_checks: tuple[str, ...]  # any true: a field does not fit its bits
    pack_bytes: tuple[str, ...]  # per frame byte: its value from src (checksum byte: "")
    checksum_byte: int
    checksum_xor: str  # XOR of the covered bytes b<i> (pack)
    checksum_check: str  # XOR of the covered bytes src[i] (unpack)
    checksum_fold: bool  # covers all other 7 bytes: valid iff the XOR of all 8 bytes is 0
    counter: CSignal | None
    counter_mask: str
    da: str | None
    fault_xor_codes: tuple[tuple[str, str], ...]  # (fault enum const) per fault table
    comment: str


@dataclass(frozen=True)
class CFaultTable:
    """A value table of receive-fault codes (e.g. unmanned_entry_fault) the monitor maps onto."""

    enum: CEnum
    fn: str
    timeout_const: str
    none_const: str


@dataclass(frozen=True)
class CVin:
    cm: CMessage
    index: CSignal
    payload: CSignal
    frames: int
    bytes_per_frame: int
    payload_byte: int
    text_length: int
    padding: str
    fn: str
    type: str
    macro: str
    others: tuple[CSignal, ...]  # other signals carried in every frame (e.g. device_type)


@dataclass(frozen=True)
class CModel:
    prefix: str
    macro: str
    guard: str
    can: ir.CanProtocol
    messages: tuple[CMessage, ...]
    enums: tuple[CEnum, ...]
    fault_tables: tuple[CFaultTable, ...]
    vins: tuple[CVin, ...]
    msg_type: str
    msg_none: str
    status: str


def _signal(prefix: str, pmacro: str, msg: ir.Message, sig: ir.Signal, enums: dict[str, CEnum]) -> CSignal:
    mname = snake(msg.name)
    sname = snake(sig.name)
    bits = sig.storage_bits
    t = ctype(bits, sig.signed)
    field = c_ident(sname)
    if sig.length > 63 and not sig.signed:
        raise CModelError(f"{msg.name}.{sig.name}: {sig.length}-bit unsigned fields are not supported by the C target")
    fits_type = sig.length == bits
    wide = 64 if sig.length > 32 else 32
    acc = f"uint{wide}_t"
    if sig.signed:
        lit = lambda v: int_lit(v, bits)  # noqa: E731
        range_check = "" if fits_type else f"(src->{field} < {lit(sig.raw_type_min)}) | (src->{field} > {lit(sig.raw_type_max)})"
        bits_of = f"((uint64_t)(int64_t)src->{field} & {hex_lit(sig.mask, 64)})"
    else:
        lit = lambda v: uint_lit(v, bits)  # noqa: E731
        range_check = ""
        bits_of = f"src->{field}"
    pack_terms = []
    for seg in sig.segments:
        value = f"({acc}){bits_of}" if not sig.signed and bits <= 32 else f"(uint32_t)(uint8_t)({bits_of} >> {seg.value_shift})"
        if not sig.signed and bits <= 32 and seg.value_shift:
            value = f"({value} >> {seg.value_shift})"
        pack_terms.append((seg.byte, f"({value} << {seg.byte_shift})" if seg.byte_shift else value))
    unpack_terms = []
    for seg in sig.segments:
        term = f"src[{seg.byte}]"
        if seg.byte_shift:
            term = f"({term} >> {seg.byte_shift})"
        if seg.byte_shift + seg.width < 8:
            term = f"({term} & {hex_lit((1 << seg.width) - 1)})"
        if seg.value_shift:
            term = f"(({acc}){term} << {seg.value_shift})"
        unpack_terms.append(term)
    combined = " | ".join(unpack_terms)
    if sig.signed:
        sign = 1 << (sig.length - 1)
        unpack = f"({t})((int64_t)((uint64_t)({combined}) ^ {hex_lit(sign, 64)}) - (int64_t){hex_lit(sign, 64)})"
    else:
        unpack = f"({t})({combined})"
    # physical (double)
    factor, offset = sig.factor, sig.offset
    # Two statements: C compilers may contract `raw * f + o` within one expression into an FMA
    # (clang does when constant folding), which would round differently from the shared rule.
    expr = "(double)raw"
    if factor != 1:
        expr += f" * {c_double(factor)}"
    if offset:
        sign = "+" if offset > 0 else "-"
        expr = f"scaled {sign} {c_double(abs(offset))}" if factor != 1 else f"{expr} {sign} {c_double(abs(offset))}"
    decode_pre = f"(double)raw * {c_double(factor)}" if factor != 1 and offset else ""
    # fixed point: physical * 10^k is an integer for every raw value, both range bounds and
    # (for scaled signals) every half step, so the integer path can express each rounding tie
    # and rounds it exactly as the double path does.
    k = max(decimals(factor), decimals(offset), decimals(sig.check_min), decimals(sig.check_max),
            0 if sig.is_identity else decimals(factor / 2))
    scale = 10**k
    ff, fo = int(factor * scale), int(offset * scale)
    fmin, fmax = int(sig.check_min * scale), int(sig.check_max * scale)
    fql, fqh = (sig.raw_type_min - 1) * ff + fo, (sig.raw_type_max + 1) * ff + fo
    ends = [fql, fqh, fmin, fmax]
    fbits = fixed_bits(min(ends), max(ends))
    ft = ctype(fbits, True)
    fexpr = f"({ft})raw"
    if ff != 1:
        fexpr += f" * {int_lit(ff, fbits)}"
    if fo:
        fexpr += f" + {int_lit(fo, fbits)}" if fo > 0 else f" - {int_lit(-fo, fbits)}"
    specials = tuple(
        CSpecial(f"{pmacro}_{upper_snake(msg.name)}_{upper_snake(sig.name)}_{upper_snake(sp.name)}", lit(sp.raw), sp.raw, sp.label)
        for sp in sig.specials
    )
    comment = sig.zh
    if sig.unit:
        comment += f" [{sig.unit}]"
    return CSignal(
        sig=sig, field=field, macro=f"{pmacro}_{upper_snake(msg.name)}_{upper_snake(sig.name)}",
        fn=f"{prefix}_{mname}_{sname}", type=t, length=sig.length, start=sig.start,
        range_check=range_check, needs_check=not fits_type and not sig.signed, pack_terms=tuple(pack_terms), unpack_expr=unpack,
        raw_type_min=lit(sig.raw_type_min), raw_type_max=lit(sig.raw_type_max),
        raw_min=int_lit(sig.raw_min, 64), raw_max=int_lit(sig.raw_max, 64),
        q_low=c_double(sig.raw_type_min - 1), q_high=c_double(sig.raw_type_max + 1),
        factor=c_double(factor), offset=c_double(offset),
        check_min=c_double(sig.check_min), check_max=c_double(sig.check_max), decode_expr=expr, decode_pre=decode_pre,
        specials=specials, enum=enums.get(sig.value_table.name) if sig.value_table else None,
        scale=int_lit(scale), scale_int=scale, fixed_type=ft, fixed_factor=int_lit(ff, fbits), fixed_offset=int_lit(fo, fbits),
        fixed_min=int_lit(fmin, fbits), fixed_max=int_lit(fmax, fbits), fixed_decode_expr=fexpr,
        fixed_q_low=int_lit(fql, fbits), fixed_q_high=int_lit(fqh, fbits),
        is_data=sig.role == "data", has_double=max(-sig.raw_type_min, sig.raw_type_max) <= DOUBLE_EXACT, unit=sig.unit, comment=comment,
    )


def _enum(prefix: str, pmacro: str, table: ir.ValueTable) -> CEnum:
    tname = snake(table.name)
    entries = tuple(CEnumEntry(f"{pmacro}_{upper_snake(table.name)}_{upper_snake(e.name)}", e.name, e.raw, e.label, e.label_zh) for e in table.entries)
    return CEnum(table.name, f"{prefix}_{tname}_t", f"{prefix}_{tname}_name", entries)


def _message(prefix: str, pmacro: str, msg: ir.Message, enums: dict[str, CEnum], faults: list[tuple[ir.ValueTable, CEnum]]) -> CMessage:
    if msg.dlc > MAX_DLC:
        raise CModelError(f"{msg.name}: DLC {msg.dlc} > 8 (CAN FD) is not supported by the C target")
    mname = snake(msg.name)
    sigs = tuple(_signal(prefix, pmacro, msg, s, enums) for s in msg.data_signals)
    counter = next((c for c in sigs if msg.counter and c.sig.name == msg.counter.signal), None)
    ck_byte, ck_xor, ck_check, ck_fold = -1, "", "", False
    xor_codes: list[tuple[str, str]] = []
    data = [s for s in sigs if not (msg.checksum and s.sig.name == msg.checksum.signal)]
    byte_terms: dict[int, list[str]] = {}
    for s in data:
        for b, term in s.pack_terms:
            byte_terms.setdefault(b, []).append(term)
    if msg.checksum is not None:
        ck = msg.checksum
        csig = msg.signal(ck.signal)
        if ck.algorithm != "xor" or csig.start != 8 * ck.byte or csig.length != 8:
            raise CModelError(f"{msg.name}: only an XOR checksum filling a whole byte is supported")
        ck_byte = ck.byte
        ck_xor = " ^ ".join(f"b{b}" for b in ck.covers if b in byte_terms) or "0u"
        ck_check = " ^ ".join(f"src[{b}]" for b in ck.covers)
        ck_fold = msg.dlc == 8 and set(ck.covers) == set(range(8)) - {ck.byte}
        for table, cenum in faults:
            entry = next((e for e in table.entries if msg.layout and e.name == f"{msg.layout}{XOR_ERROR_SUFFIX}"), None)
            if entry:
                xor_codes.append((cenum.table, next(c.const for c in cenum.entries if c.value == entry.raw)))
    pack_bytes = tuple("" if b == ck_byte else (f"(uint8_t)({' | '.join(byte_terms[b])})" if b in byte_terms else "0u") for b in range(msg.dlc))
    # Range checks: unsigned fields of one width share one compare (a | b | c > 2^n - 1).
    groups: dict[tuple[int, int], list[str]] = {}
    for s in data:
        if s.needs_check:
            groups.setdefault((s.length, 64 if s.sig.storage_bits == 64 else 32), []).append(f"src->{s.field}")
    checks = [f"((uint{w}_t)({' | '.join(fields)}) > {uint_lit((1 << n) - 1, w)})" for (n, w), fields in groups.items()]
    checks += [s.range_check for s in data if s.range_check]
    j = msg.j1939
    return CMessage(
        msg=msg, name=mname, macro=f"{pmacro}_{upper_snake(msg.name)}", fn=f"{prefix}_{mname}", type=f"{prefix}_{mname}_t",
        index_const=f"{pmacro}_MSG_{upper_snake(msg.name)}", signals=sigs,
        range_checks=tuple(checks), pack_bytes=pack_bytes,
        checksum_byte=ck_byte, checksum_xor=ck_xor, checksum_check=ck_check, checksum_fold=ck_fold,
        counter=counter, counter_mask=hex_lit(msg.counter.modulo - 1) if msg.counter else "",
        da=hex_lit(j.da) if j.da is not None else None, fault_xor_codes=tuple(xor_codes),
        comment=f"{msg.title} / {msg.zh}" if msg.title else msg.zh,
    )


def build_model(spec: ir.Spec) -> CModel:
    can = spec.can
    if can is None:
        raise CModelError("the spec has no CAN protocol")
    if can.bus.byte_order not in ("little_endian", "intel"):
        raise CModelError(f"byte order {can.bus.byte_order!r} is not supported by the C target")
    prefix = snake(can.name)
    pmacro = upper_snake(can.name)
    enums = {t.name: _enum(prefix, pmacro, t) for t in can.value_tables}
    fault_tables = []
    fault_pairs = []
    for t in can.value_tables:
        timeout = t.by_raw(next((e.raw for e in t.entries if e.name == TIMEOUT_ENTRY), -1))
        if timeout is None:
            continue
        ce = enums[t.name]
        none_entry = next((c for c in ce.entries if c.value == 0), None)
        if none_entry is None:
            continue
        fault_tables.append(CFaultTable(ce, f"{prefix}_monitor_{snake(t.name)}", next(c.const for c in ce.entries if c.value == timeout.raw), none_entry.const))
        fault_pairs.append((t, ce))
    messages = tuple(_message(prefix, pmacro, m, enums, fault_pairs) for m in can.messages)
    vins = []
    for cm in messages:
        mf = cm.msg.multiframe
        if mf is None:
            continue
        by = {s.sig.name: s for s in cm.signals}
        payload = by[mf.payload_signal]
        if payload.start != 8 * mf.payload_byte or payload.length < 8 * mf.bytes_per_frame:
            raise CModelError(f"{cm.msg.name}: multi-frame payload must start at byte {mf.payload_byte} and hold {mf.bytes_per_frame} bytes")
        vins.append(CVin(
            cm=cm, index=by[mf.index_signal], payload=payload, frames=mf.frames, bytes_per_frame=mf.bytes_per_frame,
            payload_byte=mf.payload_byte, text_length=mf.text_length, padding=hex_lit(mf.padding),
            fn=f"{cm.fn}_text", type=f"{cm.fn}_text_rx_t", macro=f"{cm.macro}_TEXT",
            others=tuple(s for s in cm.signals if s.sig.name not in (mf.index_signal, mf.payload_signal)),
        ))
    return CModel(
        prefix=prefix, macro=pmacro, guard=f"{pmacro}_H", can=can, messages=messages,
        enums=tuple(enums[t.name] for t in can.value_tables), fault_tables=tuple(fault_tables), vins=tuple(vins),
        msg_type=f"{prefix}_msg_t", msg_none=f"{pmacro}_MSG_NONE", status=f"{prefix}_status_t",
    )
