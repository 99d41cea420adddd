"""The C target's view of the IR: C names, types, literals and pack plans.

Python owns the meaning here — bit positions, masks, range-check expressions, fixed-point
scales, literal syntax — so the `templates/c/` family only loops and places text.

Pack plan: every frame is at most 8 bytes and every signal is Intel (little-endian), so a
signal is a contiguous bit field [start, start+length) of the frame read as one
little-endian 64-bit word `v`. Unpack assembles `v` from the bytes once (one load on a
little-endian host), moves the fields of each run of adjacent struct fields into their
slots together and stores them (merged into word stores); pack does the reverse, checks a
run's field widths with one mask and writes the frame word with one store. The run plans
(which fields, which shifts and masks) are in cwords.py.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import decimal_text
from canspec.ir.names import c_ident, snake, upper_snake
from canspec.render.literals import c_hex, c_int, c_uint, float_lit
from canspec.targets.c import words as cwords

MAX_DLC = 8
DOUBLE_EXACT = 2**53  # integers up to this are exact in an IEEE double
# A value-table entry named `<layout>_xor_error` is the fault code for a checksum failure of
# a message with that layout; `message_timeout` is the code for a receive timeout.
XOR_ERROR_SUFFIX = "_xor_error"
TIMEOUT_ENTRY = "message_timeout"


class CModelError(ValueError):
    pass


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
    accept_min: str  # what encode compares against: the range widened by |factor| × 1e-9 (ir.Signal)
    accept_max: str
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
class CRun:
    """C text of one run (see cwords.Run): the local `var` holds its slot word."""

    run: cwords.Run
    var: str
    unpack_init: str  # value of `var` from the frame word `v`
    unpack_steps: tuple[str, ...]  # statements moving the fields into their slots
    stores: tuple[tuple[str, str], ...]  # (field, value from `var`)
    pack_init: str  # value of `var` from the struct fields (one merged load)
    pack_steps: tuple[str, ...]  # statements moving the fields back to their frame bits
    placed: str  # `var` shifted to its frame bits
    offset: int  # little-endian word path: the run's bytes in the struct
    nbytes: int  # (up to the next run: includes padding, never another run's field)
    pad_mask: str  # pack: mask clearing padding bytes read with the fields ("" if none)
    extra: str  # pack: a second local for the fields moved by groups beside SWAR steps ("" if none)
    le_value: str  # unpack, word path: the slot word as stored (a signed field sign-extended)


@dataclass(frozen=True)
class CByteField:
    """A whole-byte field at the struct's end copied as a byte (a load and a store) instead of
    being moved within a word (a shift or two, a mask and an OR each way)."""

    field: str
    byte: int  # frame byte
    value: str  # unpack: the byte from the frame word `v`


@dataclass(frozen=True)
class CMessage:
    msg: ir.Message
    name: str  # snake name
    macro: str
    fn: str
    type: str
    index_const: str  # enumerator in the message index enum
    signals: tuple[CSignal, ...]  # data signals incl. counter/checksum, not reserved
    unpack_runs: tuple[CRun, ...]  # every struct field, in struct order
    layout_check: str  # condition true when the struct layout is the one the word path assumes
    pack_runs: tuple[CRun, ...]  # the fields pack reads (not the checksum)
    frame_load: str  # the frame word `v` from src[0..dlc-1] (unpack)
    frame_word: str  # the frame word `w` from the packed runs (pack, without checksum)
    frame_stores: tuple[str, ...]  # dst[i] from `w`, per frame byte
    range_terms: tuple[str, ...]  # uint64_t terms, OR != 0: a field does not fit its bits
    byte_fields: tuple[CByteField, ...]  # whole-byte fields unpack copies byte by byte (not in the runs)
    pack_byte_stores: tuple[CByteField, ...]  # those pack stores byte by byte after the frame word
    checksum_byte: int
    checksum_pack: str  # uint64_t term OR'ed into `w`: the checksum byte in place
    checksum_ok: str  # condition on `v`: the checksum byte is right
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
    if sig.signed:
        lit = lambda v: c_int(v, bits)
        range_check = "" if fits_type else f"(src->{field} < {lit(sig.raw_type_min)}) | (src->{field} > {lit(sig.raw_type_max)})"
    else:
        lit = lambda v: c_uint(v, bits)
        range_check = ""
    # physical (double)
    factor, offset = sig.factor, sig.offset
    # Two statements: C compilers may contract `raw * f + o` within one expression into an FMA
    # (clang does when constant folding), which would round differently from the shared rule.
    expr = "(double)raw"
    if factor != 1:
        expr += f" * {float_lit(factor)}"
    if offset:
        sign = "+" if offset > 0 else "-"
        expr = f"scaled {sign} {float_lit(abs(offset))}" if factor != 1 else f"{expr} {sign} {float_lit(abs(offset))}"
    decode_pre = f"(double)raw * {float_lit(factor)}" if factor != 1 and offset else ""
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
        fexpr += f" * {c_int(ff, fbits)}"
    if fo:
        fexpr += f" + {c_int(fo, fbits)}" if fo > 0 else f" - {c_int(-fo, fbits)}"
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
        range_check=range_check, needs_check=not fits_type and not sig.signed,
        raw_type_min=lit(sig.raw_type_min), raw_type_max=lit(sig.raw_type_max),
        raw_min=c_int(sig.raw_min, 64), raw_max=c_int(sig.raw_max, 64),
        q_low=float_lit(sig.raw_type_min - 1), q_high=float_lit(sig.raw_type_max + 1),
        factor=float_lit(factor), offset=float_lit(offset),
        check_min=float_lit(sig.check_min), check_max=float_lit(sig.check_max), accept_min=float_lit(sig.accept_min), accept_max=float_lit(sig.accept_max), decode_expr=expr, decode_pre=decode_pre,
        specials=specials, enum=enums.get(sig.value_table.name) if sig.value_table else None,
        scale=c_int(scale), scale_int=scale, fixed_type=ft, fixed_factor=c_int(ff, fbits), fixed_offset=c_int(fo, fbits),
        fixed_min=c_int(fmin, fbits), fixed_max=c_int(fmax, fbits), fixed_decode_expr=fexpr,
        fixed_q_low=c_int(fql, fbits), fixed_q_high=c_int(fqh, fbits),
        is_data=sig.role == "data", has_double=max(-sig.raw_type_min, sig.raw_type_max) <= DOUBLE_EXACT, unit=sig.unit, comment=comment,
    )


def _enum(prefix: str, pmacro: str, table: ir.ValueTable) -> CEnum:
    tname = snake(table.name)
    entries = tuple(CEnumEntry(f"{pmacro}_{upper_snake(table.name)}_{upper_snake(e.name)}", e.name, e.raw, e.label, e.label_zh) for e in table.entries)
    return CEnum(table.name, f"{prefix}_{tname}_t", f"{prefix}_{tname}_name", entries)


def _byte_of(word: str, b: int) -> str:
    return f"(uint8_t){word}" if b == 0 else f"(uint8_t)({word} >> {8 * b})"


def _shifted(expr: str, shift: int) -> str:
    """expr << shift (negative: >>), as C text."""
    if shift == 0:
        return expr
    return f"({expr} << {shift})" if shift > 0 else f"({expr} >> {-shift})"


IMM32 = 0x7FFFFFFF  # x86-64 and/or/test take sign-extended 32-bit immediates: wider masks cost a load


def _move(word: str, mask: int, shift: int) -> str:
    """C text of (word & mask) moved by `shift` bits (negative: right). A contiguous mask that
    starts or ends at a word edge, before or after the move, and is too wide for an immediate
    either side, is cut out by two shifts instead (no mask constant)."""
    top = (1 << 64) - 1
    moved = ((mask << shift) if shift >= 0 else (mask >> -shift)) & top
    lo = (mask & -mask).bit_length() - 1
    n = mask.bit_length() - lo
    dest = lo + shift
    if mask == ((1 << n) - 1) << lo and mask > IMM32 and moved > IMM32:
        if lo + n == 64 or dest + n == 64:  # nothing above it before, or nothing left above after
            return _shifted(f"({word} >> {lo})" if lo else word, dest)
        if lo == 0 or dest == 0:  # nothing below it before, or nothing left below after
            return _shifted(f"({word} << {64 - n - lo})" if 64 - n - lo else word, dest - (64 - n))
    return _shifted(f"({word} & {c_hex(mask, 64)})", shift)


def _runs(sigs: list[CSignal] | tuple[CSignal, ...], offsets: dict[str, int], size: int, letter: str, drop: int) -> tuple[CRun, ...]:
    fields = [cwords.Field(s.field, s.start, s.length, s.sig.storage_bits, s.sig.signed, s.needs_check) for s in sigs]
    by_field = {s.field: s for s in sigs}
    runs = cwords.plan_runs(fields, [offsets[f.name] for f in fields])
    starts = [offsets[r.fields[0].name] for r in runs] + [size]
    return tuple(_crun(run, f"{letter}{i}", by_field, starts[i], min(8, starts[i + 1] - starts[i]), drop) for i, run in enumerate(runs))


def _crun(run: cwords.Run, var: str, by_field: dict[str, CSignal], offset: int, nbytes: int, drop: int) -> CRun:
    """`drop`: frame bits pack leaves out (the checksum byte, filled afterwards)."""
    storage = sum(((1 << f.storage) - 1) << s for f, s in zip(run.fields, run.slots))
    # group moves mask their fields; SWAR steps need zeros around them
    pad = "" if run.groups or storage == (1 << (8 * nbytes)) - 1 else f"{var} &= {c_hex(storage, 64)};"
    le_value = var
    signed = next((f for f in run.fields if f.signed), None)
    if signed is not None:  # alone in its run: the struct holds it sign-extended to its type
        sign = c_hex(1 << (signed.length - 1), 64)
        pad = f"{var} &= {c_hex((1 << signed.length) - 1, 64)};"
        le_value = f"(uint64_t)((int64_t)({var} ^ {sign}) - (int64_t){sign})"
    m = lambda mask: c_hex(mask, 64)
    stores, loads = [], []
    for f, slot in zip(run.fields, run.slots):
        s = by_field[f.name]
        if f.signed:  # alone in its run, at slot 0: sign-extend its bits
            sign = c_hex(1 << (f.length - 1), 64)
            stores.append((f.name, f"({s.type})((int64_t)({var} ^ {sign}) - (int64_t){sign})"))
            loads.append(f"((uint64_t)(int64_t)src->{f.name} & {m((1 << f.length) - 1)})")
        else:
            stores.append((f.name, f"({s.type}){var}" if slot == 0 else f"({s.type})({var} >> {slot})"))
            loads.append(_shifted(f"(uint64_t)src->{f.name}", slot))
    top = (1 << cwords.WORD) - 1
    moves = [_move("v", g.frame, g.shift) for g in run.groups]
    kept = [g for g in (cwords.Group(g.shift, g.frame & ~drop) for g in run.groups) if g.frame]
    backs = [_move(var, ((g.frame << g.shift) if g.shift >= 0 else (g.frame >> -g.shift)) & top, -g.shift) for g in kept]
    if run.swar == 0:
        return CRun(
            run=run, var=var, unpack_init=" | ".join(moves), unpack_steps=(), stores=tuple(stores),
            pack_init=" | ".join(loads), pack_steps=(), placed=" | ".join(backs) or "0u", extra="", le_value=le_value,
            offset=offset, nbytes=nbytes, pad_mask=pad,
        )
    # SWAR part: from the frame word to the slots and back
    init = _shifted("v", run.base)
    remaining = cwords.WORD - max(0, -run.base)
    needed = run.first != (((1 << remaining) - 1) << max(0, run.base)) & top
    init = f"{init} & {m(run.first)}" if needed else init
    ups, downs = [], []
    if run.mul is not None:
        ups.append(f"{var} = ({var} * {m(run.mul.up)}) & {m(run.swar_mask)};")
    for st in run.steps:
        if st.simple:
            ups.append(f"{var} = ({var} | ({var} << {st.shift})) & {m(st.after)};")
        else:
            ups.append(f"{var} = ({var} & {m(st.stay)}) | (({var} << {st.shift}) & {m(st.after & ~st.stay)});")
    extra = ""
    placed = _shifted(var, -run.base)
    if run.groups:  # the other fields move by groups, from the frame word / before the steps
        ups.append(f"{var} |= {' | '.join(moves)};")
        if backs:
            extra = f"{var}g"
            downs.append(f"{extra} = {' | '.join(backs)};")
            placed = f"{placed} | {extra}"
        downs.append(f"{var} &= {m(run.swar_mask)};")
    elif pad:
        downs.append(pad)
    # Like the steps, the multiplication needs only the fields' bits in the word: the padding
    # mask clears the bytes between fields and the range check the bits above each one.
    if run.mul is not None:
        back = f" & {m(run.mul.back)}" if run.mul.back else ""
        downs.append(f"{var} = (({var} * {m(run.mul.down)}) >> {run.mul.shift}){back};")
    for st in reversed(run.steps):
        if st.simple_back:
            downs.append(f"{var} = ({var} | ({var} >> {st.shift})) & {m(st.before)};")
        else:
            downs.append(f"{var} = ({var} & {m(st.stay)}) | (({var} >> {st.shift}) & {m(st.before & ~st.stay)});")
    return CRun(
        run=run, var=var, unpack_init=init, unpack_steps=tuple(ups), stores=tuple(stores),
        pack_init=" | ".join(loads), pack_steps=tuple(downs), placed=placed, extra=extra, le_value=le_value,
        offset=offset, nbytes=nbytes, pad_mask="",  # the padding mask is in the steps
    )

def _peeled(sigs: tuple[CSignal, ...], offsets: dict[str, int], size: int, checksum: str | None) -> tuple[CSignal, ...]:
    """The struct's trailing whole-byte fields (8 unsigned bits on a byte boundary in a uint8_t)
    whose frame byte is not their struct offset: copying such a byte costs less than moving it
    within the word. With a checksum only the checksum byte itself (pack needs the whole word
    for the XOR). At least one field stays in the word runs."""
    out: list[CSignal] = []
    kept = list(sigs)
    for s in reversed(sigs[1:]):
        whole = s.length == 8 and s.start % 8 == 0 and s.sig.storage_bits == 8 and not s.sig.signed
        if not whole or s.start // 8 == offsets[s.field] or (checksum is not None and s.sig.name != checksum):
            break
        if _words_cost(kept[:-1], offsets) + BYTE_COPY_COST >= _words_cost(kept, offsets):
            break  # it moves (almost) for free with the others
        out.append(kept.pop())
    # The runs' word access must not cover a peeled byte: pack's load would then span unpack's
    # word store and its byte store, which a CPU cannot forward (a stall of ~10 cycles).
    while out and _run_end(sigs[: len(sigs) - len(out)], offsets, size) > offsets[out[-1].field]:
        out.pop()
    return tuple(reversed(out))


BYTE_COPY_COST = 4  # a byte load and store, both ways


def _words_cost(sigs: list[CSignal], offsets: dict[str, int]) -> int:
    """The word planner's cost estimate of these struct fields' runs."""
    fields = [cwords.Field(s.field, s.start, s.length, s.sig.storage_bits, s.sig.signed, s.needs_check) for s in sigs]
    return sum(r.cost for r in cwords.plan_runs(fields, [offsets[f.name] for f in fields]))


def _run_end(sigs: tuple[CSignal, ...], offsets: dict[str, int], size: int) -> int:
    """Where the word runs of these (leading) struct fields end: their last byte, rounded up to
    a whole 2-, 4- or 8-byte access when that stays inside the struct (the bytes past the fields
    are padding or peeled fields, written afterwards)."""
    last = sigs[-1]
    start = offsets[last.field] // 8 * 8  # the runs stay inside 8-byte blocks
    ext = offsets[last.field] + last.sig.storage_bits // 8 - start
    n = 1
    while n < ext:
        n *= 2
    return start + n if start + n <= size else start + ext


def _message(prefix: str, pmacro: str, msg: ir.Message, enums: dict[str, CEnum], faults: list[tuple[ir.ValueTable, CEnum]]) -> CMessage:
    if msg.dlc > MAX_DLC:
        raise CModelError(f"{msg.name}: DLC {msg.dlc} > 8 (CAN FD) is not supported by the C target")
    mname = snake(msg.name)
    sigs = tuple(_signal(prefix, pmacro, msg, s, enums) for s in msg.data_signals)
    counter = next((c for c in sigs if msg.counter and c.sig.name == msg.counter.signal), None)
    ck_byte, ck_pack, ck_ok, ck_fold = -1, "", "", False
    xor_codes: list[tuple[str, str]] = []
    data = [s for s in sigs if not (msg.checksum and s.sig.name == msg.checksum.signal)]
    offsets = dict(zip((s.field for s in sigs), cwords.natural_offsets([s.sig.storage_bits for s in sigs])))
    if msg.checksum is not None:
        ck = msg.checksum
        csig = msg.signal(ck.signal)
        if ck.algorithm != "xor" or csig.start != 8 * ck.byte or csig.length != 8:
            raise CModelError(f"{msg.name}: only an XOR checksum filling a whole byte is supported")
        ck_byte = ck.byte
        ck_field = c_ident(snake(ck.signal))
        ck_fold = msg.dlc == 8 and set(ck.covers) == set(range(8)) - {ck.byte}
        if ck_fold:  # the checksum byte is 0 in `w`: the XOR of all of its bytes is the checksum
            used = {b for s in data for seg in s.sig.segments for b in (seg.byte,)}
            fold = f"{prefix}_xor_fold32((uint32_t)w)" if max(used, default=0) < 4 else f"{prefix}_xor_fold(w)"
            ck_pack = f"((uint64_t){fold} << {8 * ck.byte})"
            ck_ok = f"{prefix}_xor_is_zero(v)"
        else:
            covered = " ^ ".join(_byte_of("w", b) for b in ck.covers) or "0u"
            ck_pack = f"((uint64_t)(uint8_t)({covered}) << {8 * ck.byte})"
            ck_ok = f"(uint8_t)({' ^ '.join(_byte_of('v', b) for b in ck.covers) or '0u'}) == {_byte_of('v', ck.byte)}"
        for table, cenum in faults:
            entry = next((e for e in table.entries if msg.layout and e.name == f"{msg.layout}{XOR_ERROR_SUFFIX}"), None)
            if entry:
                xor_codes.append((cenum.table, next(c.const for c in cenum.entries if c.value == entry.raw)))
    size = cwords.struct_size([s.sig.storage_bits for s in sigs])
    ck_bits = 0xFF << (8 * ck_byte) if msg.checksum is not None else 0
    peeled = _peeled(sigs, offsets, size, msg.checksum.signal if msg.checksum is not None else None)
    worded = sigs[: len(sigs) - len(peeled)]
    end = _run_end(worded, offsets, size) if peeled else size
    unpack_runs = _runs(worded, offsets, end, "r", 0)
    # pack reads the same words unpack writes (the checksum slot too, then drops its bits)
    pack_runs = _runs(worded, offsets, end, "p", ck_bits)
    byte_fields = tuple(CByteField(s.field, s.start // 8, _byte_of("v", s.start // 8)) for s in peeled)
    typ = f"{prefix}_{mname}_t"
    layout = " && ".join([f"offsetof({typ}, {s.field}) == {offsets[s.field]}u" for s in sigs] + [f"sizeof({typ}) == {size}u"])
    range_terms = [f"({r.var} & {c_hex(r.run.check, 64)})" for r in pack_runs if r.run.check]
    range_terms += [f"(uint64_t)({s.range_check})" for s in data if s.range_check]
    frame_load = " | ".join(f"(uint64_t)src[{b}]" if b == 0 else f"((uint64_t)src[{b}] << {8 * b})" for b in range(msg.dlc))
    frame_word = " | ".join(r.placed for r in pack_runs) or "0u"
    if msg.checksum is not None and any(f.name == ck_field and r.run.swar != 0 for r in pack_runs for f in r.run.fields):
        frame_word = f"({frame_word}) & {c_hex(((1 << 64) - 1) & ~(0xFF << (8 * ck_byte)), 64)}"
    by_byte = {b.byte: b for b in byte_fields}
    frame_stores = tuple(
        f"src->{by_byte[b].field}" if b in by_byte and msg.checksum is None else "(uint8_t)w" if b == 0 else f"(uint8_t)(w >> {8 * b})"
        for b in range(msg.dlc))
    j = msg.j1939
    return CMessage(
        msg=msg, name=mname, macro=f"{pmacro}_{upper_snake(msg.name)}", fn=f"{prefix}_{mname}", type=f"{prefix}_{mname}_t",
        index_const=f"{pmacro}_MSG_{upper_snake(msg.name)}", signals=sigs,
        unpack_runs=unpack_runs, pack_runs=pack_runs, layout_check=layout, frame_load=frame_load, frame_word=frame_word,
        frame_stores=frame_stores, range_terms=tuple(range_terms), byte_fields=byte_fields,
        pack_byte_stores=() if msg.checksum is not None else byte_fields,
        checksum_byte=ck_byte, checksum_pack=ck_pack, checksum_ok=ck_ok, checksum_fold=ck_fold,
        counter=counter, counter_mask=c_hex(msg.counter.modulo - 1) if msg.counter else "",
        da=c_hex(j.da) if j.da is not None else None, fault_xor_codes=tuple(xor_codes),
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
            payload_byte=mf.payload_byte, text_length=mf.text_length, padding=c_hex(mf.padding),
            fn=f"{cm.fn}_text", type=f"{cm.fn}_text_rx_t", macro=f"{cm.macro}_TEXT",
            others=tuple(s for s in cm.signals if s.sig.name not in (mf.index_signal, mf.payload_signal)),
        ))
    return CModel(
        prefix=prefix, macro=pmacro, guard=f"{pmacro}_H", can=can, messages=messages,
        enums=tuple(enums[t.name] for t in can.value_tables), fault_tables=tuple(fault_tables), vins=tuple(vins),
        msg_type=f"{prefix}_msg_t", msg_none=f"{pmacro}_MSG_NONE", status=f"{prefix}_status_t",
    )
