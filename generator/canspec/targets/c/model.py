"""The C target's view of the IR: names, types, literals and pack plans of a whole protocol.

Python owns the meaning here (names.py, messages.py, signals.py, physical.py, divide.py, codec.py,
codec64.py) — bit positions, masks, range checks, fixed-point scales, literal syntax, what the
protocol uses at all — so the `templates/c/` family only loops, branches on booleans and places text.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, replace

from canspec import ir
from canspec.ir import j1939
from canspec.render.literals import C
from canspec.targets.c.codec import zero_fill
from canspec.targets.c.messages import CMessage, build_message
from canspec.targets.c.names import CNames
from canspec.targets.c.physical import phys_store, with_descriptor
from canspec.targets.c.signals import CSignal

INT_MIN, INT_MAX = -(2**31), 2**31 - 1  # C enumerators are ints (at least 32 bits on every target host)


@dataclass(frozen=True)
class CEnumEntry:
    const: str
    name: str
    raw: int
    value: str  # literal (an enumerator's int, or a macro's typed constant)
    case: str  # literal in the name function's switch
    label: str
    label_zh: str


@dataclass(frozen=True)
class CEnum:
    table: str
    type: str
    name_fn: str
    is_enum: bool  # an enum; else (a value beyond int) a typedef with one macro per value
    base: str  # the typedef's and the name function's parameter type
    entries: tuple[CEnumEntry, ...]

    def const_of(self, raw: int) -> str | None:
        return next((e.const for e in self.entries if e.raw == raw), None)


@dataclass(frozen=True)
class CFaultStep:
    """One active code the monitor can report: a checksum failure of any of `messages` (their
    index consts), or with no messages a timeout of any message."""

    code: str
    messages: tuple[str, ...]


@dataclass(frozen=True)
class CFaultTable:
    """A value table of receive-fault codes (e.g. unmanned_entry_fault) the monitor maps onto."""

    enum: CEnum
    fn: str
    none_const: str
    steps: tuple[CFaultStep, ...]  # lowest code first: the first active one is reported


@dataclass(frozen=True)
class CVin:
    cm: CMessage
    index: CSignal
    payload: CSignal
    frames: int
    last_index: int
    bytes_per_frame: int
    payload_byte: int
    payload_last: int  # last frame byte of the text
    text_length: int
    length_lit: str  # text_length, frames, bytes_per_frame as C literals
    frames_lit: str
    bytes_lit: str
    capacity: int  # characters rx_get's output needs, with the terminating NUL
    received_bytes: int  # bytes of the received-frames bit set
    padding: str
    index_ok: str  # condition on `f`: its index names a frame of the text ("" if every index does)
    fn: str
    type: str
    macro: str
    others: tuple[CSignal, ...]  # other fields every frame of one text carries alike (e.g. device_type)
    has_float_others: bool  # some of them are floats: compared by bit pattern (NaN equals itself; -0 is not 0)


@dataclass(frozen=True)
class CModel:
    prefix: str
    macro: str
    guard: str
    can: ir.CanProtocol
    names: CNames
    messages: tuple[CMessage, ...]
    extended: tuple[CMessage, ...]  # the 29-bit / 11-bit ones, for the ID switches
    standard: tuple[CMessage, ...]
    enums: tuple[CEnum, ...]
    fault_tables: tuple[CFaultTable, ...]
    vins: tuple[CVin, ...]
    msg_type: str
    msg_none: str
    status: str
    is_j1939: bool
    j1939: tuple[tuple[str, str], ...]  # (macro suffix, C literal): the J1939 constants of ir/j1939.py
    has_bits_differ: bool  # a multi-frame text compares float fields (`<prefix>_bits_differ`)
    has_phys: bool  # some signal encodes through the runtime's `<prefix>_phys_*` functions
    has_phys_round: bool  # ... one with special values or with a q beyond phys_encode's domain (through `<prefix>_phys_round`)
    phys_stores: tuple[tuple[str, str], ...]  # (function, field type): the `<prefix>_phys_encode_<type>` encoders used
    zero_fills: tuple[tuple[str, int, tuple[str, ...]], ...]  # (function, frame bytes, body): codec.zero_fill, for the packs that call it
    phys_q_min: str  # the rounding's domain [min, max) as double literals
    phys_q_max: str
    format_arg: bool  # the protocol has 11-bit IDs: lookups by ID take the frame's format too
    bitrate: str
    data_bitrate: str  # the CAN FD data phase's ("" where the bus gives none)
    cycle_type: str  # of msg_info_t.cycle_ms
    counter_start_type: str  # of msg_info_t.counter_start (a counter past bit 255 of an FD frame needs 16 bits)
    big_endian_counters: bool  # some counter is Motorola: msg_info_t says which are (counter_big_endian)
    state_slots: str  # length of per-message arrays (1 without messages: C has no empty arrays)
    timeout_cycles: str
    counter_tolerance: str
    valid_after: str


def _enum(names: CNames, table: ir.ValueTable) -> CEnum:
    raws = [e.raw for e in table.entries]
    is_enum = INT_MIN <= min(raws) and max(raws) <= INT_MAX
    if min(raws) < 0:
        base, case = "int64_t", (lambda v: C.integer(v, 64))
    elif max(raws) > 0xFFFFFFFF:
        base, case = "uint64_t", (lambda v: C.unsigned(v, 64))
    else:
        base, case = "uint32_t", C.unsigned
    words = names.table(table.name)
    entries = tuple(
        CEnumEntry(names.const(words, e.name), e.name, e.raw, str(e.raw) if is_enum else case(e.raw), case(e.raw), e.label, e.label_zh) for e in table.entries
    )
    return CEnum(table.name, names.fn(words, "t"), names.fn(words, "name"), is_enum, base, entries)


def _fault_tables(names: CNames, can: ir.CanProtocol, enums: dict[str, CEnum], messages: tuple[CMessage, ...]) -> tuple[CFaultTable, ...]:
    """The protocol's fault-code tables (ir.FaultTable) that C holds in an enum."""
    index = {cm.msg.name: cm.index_const for cm in messages}
    out = []
    for t in can.fault_tables:
        ce = enums[t.table]
        if not ce.is_enum:
            continue
        by_code: dict[int, list[str]] = {}
        for name, code in t.checksum:
            by_code.setdefault(code, []).append(index[name])
        steps = [(code, tuple(msgs)) for code, msgs in by_code.items()] + [(t.timeout, ())]
        ordered = tuple(CFaultStep(ce.const_of(code) or "", msgs) for code, msgs in sorted(steps, key=lambda step: step[0]))
        out.append(CFaultTable(ce, names.fn("monitor", names.table(t.table)), ce.const_of(t.none) or "", ordered))
    return tuple(out)


def _vin(names: CNames, cm: CMessage, mf: ir.MultiFrame) -> CVin:
    by = {s.sig.name: s for s in cm.signals}
    index = by[mf.index_signal]
    base = names.message(cm.msg.name)
    frames = names.const(base, "text", "frames")
    cast = "(uint64_t)" if index.sig.signed else ""
    # frames of one text carry the same other fields; a counter or checksum changes per frame
    varying = {mf.index_signal, mf.payload_signal} | {x.signal for x in (cm.msg.counter, cm.msg.checksum) if x is not None}
    return CVin(
        cm=cm,
        index=index,
        payload=by[mf.payload_signal],
        frames=mf.frames,
        last_index=mf.frames - 1,
        bytes_per_frame=mf.bytes_per_frame,
        payload_byte=mf.payload_byte,
        payload_last=mf.payload_byte + mf.bytes_per_frame - 1,
        text_length=mf.text_length,
        length_lit=C.unsigned(mf.text_length),
        frames_lit=C.unsigned(mf.frames),
        bytes_lit=C.unsigned(mf.bytes_per_frame),
        capacity=mf.text_length + 1,
        received_bytes=(mf.frames + 7) // 8,
        padding=C.hex(mf.padding),
        index_ok=" && ".join(
            ([f"f.{index.field} >= 0"] if index.sig.signed else []) + ([f"{cast}f.{index.field} < {frames}"] if mf.frames <= index.sig.raw_type_max else [])
        ),
        fn=names.fn(base, "text"),
        type=names.fn(base, "text", "rx_t"),
        macro=names.const(base, "text"),
        others=tuple(s for s in cm.signals if s.sig.name not in varying),
        has_float_others=any(s.float is not None for s in cm.signals if s.sig.name not in varying),
    )


def _share_descriptors(names: CNames, messages: tuple[CMessage, ...]) -> tuple[CMessage, ...]:
    """Signals with the same offset, factor and accepted range share one `<prefix>_phys_t`, named
    after the first of them and defined at file scope before its encoder; a descriptor no other
    signal has stays in its encoder (MISRA C:2012 rule 8.9: an object one function uses is
    defined in it)."""
    users = Counter(s.double.phys for cm in messages for s in cm.signals if s.double is not None and s.double.phys)
    first: dict[str, str] = {}

    def shared(s: CSignal) -> CSignal:
        d = s.double
        if d is None or users[d.phys] < 2:
            return s
        defines = d.phys not in first
        name = first.setdefault(d.phys, d.phys_name)
        return replace(s, double=with_descriptor(names, s.sig, d, name, local=False, defines=defines))

    return tuple(replace(cm, signals=tuple(map(shared, cm.signals))) for cm in messages)



def _j1939_constants() -> tuple[tuple[str, str], ...]:
    return (("PDU2_MIN_PF", C.unsigned(j1939.PDU2_MIN_PF)), ("GLOBAL_ADDRESS", C.hex(j1939.GLOBAL_ADDRESS)), ("ID_MASK", C.hex(j1939.ID_MASK)),
            ("PRIORITY_MASK", C.hex(j1939.PRIORITY_MASK)))


def build_model(spec: ir.Spec) -> CModel:
    can = spec.can
    if can is None:
        raise ValueError("the spec has no CAN protocol")
    names = CNames.of(can)
    enums = {t.name: _enum(names, t) for t in can.value_tables}
    enum_types = {name: e.type for name, e in enums.items()}
    messages = _share_descriptors(names, tuple(build_message(names, m, enum_types) for m in can.messages))
    faults = _fault_tables(names, can, enums, messages)
    phys_users = [s for cm in messages for s in cm.signals if s.double is not None and s.double.phys]
    vins = tuple(_vin(names, cm, cm.msg.multiframe) for cm in messages if cm.msg.multiframe is not None)
    return CModel(
        prefix=names.prefix,
        macro=names.macro,
        guard=names.const("h"),
        can=can,
        names=names,
        messages=messages,
        extended=tuple(cm for cm in messages if cm.msg.is_extended),
        standard=tuple(cm for cm in messages if not cm.msg.is_extended),
        enums=tuple(enums.values()),
        fault_tables=faults,
        vins=vins,
        has_bits_differ=any(v.has_float_others for v in vins),
        msg_type=names.fn("msg_t"),
        msg_none=names.const("msg_none"),
        status=names.fn("status_t"),
        is_j1939=can.bus.is_j1939,
        j1939=_j1939_constants(),
        has_phys=bool(phys_users),
        has_phys_round=any(s.double is not None and (s.double.window_test or s.double.special_test) for s in phys_users),
        phys_stores=tuple(sorted({(names.fn(phys_store(s.sig)), s.type) for s in phys_users if s.double is not None and s.double.encode_tail})),
        zero_fills=tuple(sorted({(cm.zero_fill, cm.msg.dlc, zero_fill(cm.msg.dlc)) for cm in messages if cm.zero_fill})),
        phys_q_min=C.double(-(2**63)),
        phys_q_max=C.double(2**63),
        format_arg=can.has_standard,
        bitrate=C.unsigned(can.bus.bitrate),
        data_bitrate=C.unsigned(can.bus.data_bitrate) if can.bus.data_bitrate else "",
        cycle_type="uint16_t" if max((m.cycle_ms or 0 for m in can.messages), default=0) <= 0xFFFF else "uint32_t",
        counter_start_type="uint8_t" if max((m.counter.start for m in can.messages if m.counter), default=0) <= 0xFF else "uint16_t",
        big_endian_counters=any(m.counter.word_order == "big" for m in can.messages if m.counter),
        state_slots=names.const("msg_count") if messages else C.unsigned(1),
        timeout_cycles=C.unsigned(ir.MONITOR_TIMEOUT_CYCLES),
        counter_tolerance=C.unsigned(ir.MONITOR_COUNTER_TOLERANCE),
        valid_after=C.unsigned(ir.MONITOR_VALID_AFTER),
    )
