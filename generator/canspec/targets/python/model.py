"""The Python target's view of the IR: every name, literal, text and statement the generated
package needs, so the templates only place text. Signals are in `fields.py`, the statements
of encode/decode in `code.py`, identifiers in `naming.py`."""

from __future__ import annotations

import textwrap
from dataclasses import dataclass, replace
from typing import Any

from canspec import ir
from canspec.ir.names import pascal, snake
from canspec.render.literals import PYTHON
from canspec.targets.python import code, pages
from canspec.targets.python.fields import (
    ATTRIBUTE_RESERVED,
    MAX_SCALE_ENTRIES,
    PyLookup,
    PyScale,
    PySignal,
    SignalContext,
    build_signal,
    float_offset,
    label_comment,
    scale_value,
)
from canspec.targets.python.naming import BUILTINS, HARD_KEYWORDS, Namespace, package_name
from canspec.targets.python.reads import word_pairs

# How many raws a decode lookup tuple may cover; wider enum fields use a dict lookup.
MAX_TUPLE_LOOKUP_BITS = 8
# Names the package defines itself (its modules, __init__ constants, errors, messages.py's API and
# imports): message and enum classes never take one.
PACKAGE_NAMES = frozenset({
    "annotations", "enums", "errors", "j1939", "messages", "multiframe", "bus", "monitor", "supervision", "PROTOCOL", "VERSION", "DOCUMENT", "BITRATE",
    "SPEC_SHA256", "Error", "DecodeError", "EncodeError", "ChecksumError", "FrameLengthError", "RangeError", "RawRangeError", "UnknownFrameError",
    "UnknownSignalError", "TextError", "TextIndexError", "InconsistentTextError", "InvalidTextError", "new_monitor", "TEXT_ASSEMBLERS", "FaultTable",
    "MessageRule", "CounterRule", "ChecksumRule", "Monitor", "BY_ID", "MESSAGES", "Buffer", "Message", "checksum_ok", "decode", "decode_raw", "encode",
    "encode_raw", "Callable", "Mapping", "ClassVar", "Protocol", "TypeAlias", "TypedDict", "cast", "dataclass", "dataclasses", "Iterable", "IntEnum",
    "_new", "_from_bytes", "_update", "_SignalSpec", "_check_raw", "_member", "_lookup", "_to_raw", "_DECODERS", "_UNPACKERS", "_PACKERS",
    "_unpack_f32", "_unpack_f64", "_pack_f32", "_pack_f64", "_unpack_f32_le", "_unpack_f32_be", "_unpack_f64_le", "_unpack_f64_be",
    "_FD_BUS"})
# The package's modules, as its docstring introduces them.
MODULE_DOCS = {
    "messages": "dataclasses, encode/decode",
    "enums": "value tables",
    "errors": "what decode and encode raise",
    "j1939": "29-bit ID helpers",
    "multiframe": "texts spread over several frames, e.g. the VIN",
    "monitor": "the receive monitor: timeouts, counters, checksums, states, fault codes",
    "supervision": "the monitor configured for this protocol (`new_monitor`)",
    "bus": "python-can integration; needs python-can",
}
# Constants of every message class: special-value constants never take one.
CLASS_CONSTANTS = frozenset(
    {
        "NAME", "FRAME_ID", "IS_EXTENDED", "DLC", "CYCLE_MS", "PRIORITY", "PGN", "PDU_FORMAT", "PDU_SPECIFIC", "SOURCE_ADDRESS",
        "DESTINATION_ADDRESS", "FINGERPRINT", "SIGNALS", "COUNTER_MODULO", "COUNTER_START", "COUNTER_LENGTH", "COUNTER_WORD_ORDER",
        "IS_FD", "BRS", "CHECKSUM_BYTE", "CHECKSUM_COVER",
    }
)


@dataclass(frozen=True)
class PyEnumMember:
    name: str  # UPPER_SNAKE
    raw: int
    comment: str


@dataclass(frozen=True)
class PyEnum:
    class_name: str
    table: str
    members: tuple[PyEnumMember, ...]


@dataclass(frozen=True)
class PyMultiFrame:
    index_attr: str
    payload_attr: str
    frames: int
    bytes_per_frame: int
    text_length: int
    padding_hex: str
    encoding: str
    func_split: str
    func_join: str
    assembler: str
    total_bytes: int  # frames × bytes per frame
    last_index: int
    padding_lit: str  # the padding byte as a bytes literal
    chunk_mask: str  # hex literal: the payload's text bits
    text_func: str  # the module's helper: chunks → text
    key_attrs: tuple[str, ...]  # attributes every frame of one text shares (MultiFrame.key_signals)
    base: str  # dict literal: the raw values of the other fields without a template (Signal.base_raw, where not 0)


@dataclass(frozen=True)
class PyMessage:
    name: str
    class_name: str
    raw_class: str  # TypedDict of raw values
    heading: str  # first docstring line
    frame_line: str  # second docstring line: ID, DLC, timing, sender → receivers
    desc: str
    id_lit: str  # the frame ID as the protocol writes it: 0x1801B0A0, 0x123
    is_extended: bool
    dlc: int
    cycle_ms: int | None  # None: event-driven
    j1939: ir.J1939Id | None
    fingerprint: str
    signals: tuple[PySignal, ...]  # data signals (reserved bits are not in the API)
    checksum: code.PyChecksum | None
    counter: PySignal | None
    counter_modulo: int
    counter_start: int
    counter_big: bool  # a Motorola counter: COUNTER_START counts in the frame read as a big-endian integer
    is_fd: bool
    brs: bool
    counter_length: int
    checksum_byte: int
    checksum_cover: str  # hex literal of ir.Checksum.cover_mask ("" without a checksum)
    rule_args: tuple[str, ...]  # supervision.py: the monitor's MessageRule(...) arguments, from the class
    multiframe: PyMultiFrame | None
    decode_func: str
    encode_func: str
    pack_func: str
    unpack_func: str
    names_var: str  # frozenset of the raw keys
    raw_functional: bool  # a raw key is a keyword: the TypedDict needs the functional syntax
    decode_checks: tuple[str, ...]  # statements (see code.py): the start of decode
    unpack_checks: tuple[str, ...]  # and of unpack
    encode_lines: tuple[str, ...]
    pack_lines: tuple[str, ...]
    checksum_ok_lines: tuple[str, ...]
    # multiplexing (pages.py): decode's assignments, unpack's body, and `_present_<message>`'s body, or () without it
    decode_lines: tuple[str, ...]
    unpack_lines: tuple[str, ...]
    present_func: str
    present_lines: tuple[str, ...]
    byte_struct: tuple[str, str] | None  # the struct.Struct (name, format) decode reads bytes and 16-bit words by, see code.struct_items


@dataclass(frozen=True)
class PyPackage:
    package: str  # import name
    protocol: str
    dist_name: str
    version: str
    title: str  # "Title (中文标题)", docstring-safe
    description: str  # the distribution's one-line description
    document: str
    bitrate: int
    is_j1939: bool
    enums: tuple[PyEnum, ...]
    used_enums: tuple[str, ...]  # enum classes messages.py names (fields that decode to them)
    lookups: tuple[PyLookup, ...]
    scales: tuple[PyScale, ...]  # in order of first use
    messages: tuple[PyMessage, ...]
    example: PyMessage | None
    modules: tuple[str, ...]  # submodules __init__ imports (all but `bus`, which needs python-can)
    modules_doc: tuple[str, ...]  # the package docstring's lines about its modules
    has_signals: bool  # some message has a data signal (slow-path descriptors)
    has_values: bool  # some message has a signal encode takes from the caller (not only a checksum)
    has_checksums: bool
    has_counters: bool
    has_multiframe: bool
    tuple_lookups: bool  # some enum field decodes through a tuple (`_lookup`)
    dict_lookups: bool  # some through a dict (`_member`)
    float_helpers: tuple[str, ...]  # the struct helpers of _runtime its IEEE float fields use (imported with a leading `_`)
    byte_structs: bool  # a message reads its frame through a struct.Struct (PyMessage.byte_struct)
    fault_tables: tuple[ir.FaultTable, ...]


def titled(title: str, zh: str) -> str:
    return f"{title} ({zh})" if zh else title


def _frame_line(msg: ir.Message) -> str:
    timing = f"every {msg.cycle_ms} ms" if msg.cycle_ms is not None else "event-driven"
    route = f"{msg.sender} → {', '.join(msg.receivers)}" if msg.receivers else f"sent by {msg.sender}"
    fd = (", CAN FD" + (" with bit-rate switching" if msg.brs else "")) if msg.is_fd else ""
    return PYTHON.doc(f"Frame {msg.id_text} ({'29' if msg.is_extended else '11'}-bit{fd}), DLC {msg.dlc}, {timing}, {route}.")


def _heading(msg: ir.Message) -> str:
    text = f"{msg.title} — {msg.zh}" if msg.zh else msg.title
    return PYTHON.doc(f"{text} (§{msg.section})." if msg.section else f"{text}.")


class _Builder:
    """Builds the messages in document order, handing out names from the package's scopes."""

    def __init__(self, can: ir.CanProtocol) -> None:
        self.module = Namespace(PACKAGE_NAMES | BUILTINS)
        self.classes = {m.name: self.module.take(pascal(m.name)) for m in can.messages}
        self.enum_names = {t.name: self.module.take(pascal(t.name)) for t in can.value_tables}
        self.enums = tuple(
            PyEnum(self.enum_names[t.name], t.name, tuple(PyEnumMember(e.name.upper(), e.raw, label_comment(e.label, e.label_zh)) for e in t.entries))
            for t in can.value_tables
        )
        self.members = {e.table: {m.raw: m.name for m in e.members} for e in self.enums}
        self.lookups: dict[tuple[str, int, bool], PyLookup] = {}
        self.scales: dict[tuple[int, str], PyScale] = {}
        self.scale_entries = 0  # of all tables so far (MAX_SCALE_ENTRIES)

    def lookup(self, sig: ir.Signal) -> PyLookup | None:
        if not sig.decodes_to_enum:
            return None
        key = (sig.value_table.name, sig.length, sig.signed)  # a signed field's raw may be negative: never a tuple index
        if key not in self.lookups:
            is_tuple = not sig.signed and sig.length <= MAX_TUPLE_LOOKUP_BITS
            var = self.module.take(f"_{sig.value_table.name}_{'s' if sig.signed else ''}{sig.length}".upper())
            self.lookups[key] = PyLookup(var, self.enum_names[sig.value_table.name], sig.length, is_tuple)
        return self.lookups[key]

    def scale(self, sig: ir.Signal, enum: str | None) -> PyScale | None:
        value = scale_value(sig, enum)
        if value is None:
            return None
        key = (sig.length, value)
        if key not in self.scales:
            if self.scale_entries + (1 << sig.length) > MAX_SCALE_ENTRIES:
                return None
            self.scale_entries += 1 << sig.length
            self.scales[key] = PyScale(self.module.take(f"_SCALE_{len(self.scales) + 1}"), sig.length, value)
        return self.scales[key]

    def signals(self, msg: ir.Message, pairs: tuple[str, frozenset[int]]) -> tuple[PySignal, ...]:
        attrs, consts = Namespace(ATTRIBUTE_RESERVED), Namespace(CLASS_CONSTANTS)
        out = []
        for i, sig in enumerate(msg.data_signals):
            lookup = self.lookup(sig)
            enum = lookup.enum if lookup is not None else None
            members = self.members[sig.value_table.name] if lookup is not None and sig.value_table is not None else {}
            ctx = SignalContext(msg.name, i, msg.dlc * 8, attrs, consts, self.module, enum, members, lookup, self.scale(sig, enum), msg.mux_chain(sig), pairs)
            out.append(build_signal(sig, ctx))
        return tuple(out)

    def multiframe(self, msg: ir.Message, by_name: dict[str, PySignal]) -> PyMultiFrame | None:
        m = msg.multiframe
        if m is None:
            return None
        split, join = self.module.take(f"split_{msg.name}_text"), self.module.take(f"join_{msg.name}_text")
        return PyMultiFrame(
            by_name[m.index_signal].attr, by_name[m.payload_signal].attr, m.frames, m.bytes_per_frame, m.text_length, PYTHON.hex(m.padding, 2), m.encoding,
            split, join, self.module.take(f"{self.classes[msg.name]}TextAssembler"), m.frames * m.bytes_per_frame, m.frames - 1, repr(bytes([m.padding])),
            PYTHON.hex((1 << (8 * m.bytes_per_frame)) - 1), self.module.take(f"_{msg.name}_text"), tuple(by_name[k].attr for k in m.key_signals),
            "{" + ", ".join(f"{PYTHON.string(s.name)}: {s.base_raw}" for s in msg.data_signals if s.role != "checksum" and s.base_raw) + "}",
        )

    def message(self, msg: ir.Message) -> PyMessage:
        pairs = word_pairs(msg)
        signals = self.signals(msg, pairs)
        by_name = {s.name: s for s in signals}
        checksum = code.make_checksum(msg, tuple(s for s in signals if not s.is_checksum))
        frame = code.Frame(msg.name, msg.id_text, msg.dlc, signals, checksum, pair_order=pairs[0])
        if code.struct_items(frame):
            frame = replace(frame, byte_struct=self.module.take(f"_{msg.name.upper()}_BYTES"))
        cls = self.classes[msg.name]
        names_var, pack_func = self.module.take(f"_{msg.name.upper()}_SIGNALS"), self.module.take(f"_pack_{msg.name}")
        funcs = {kind: self.module.take(f"_{kind}_{msg.name}") for kind in ("decode", "encode", "unpack")}
        raw_class = self.module.take(f"{cls}Raw")
        return PyMessage(
            name=msg.name, class_name=cls, raw_class=raw_class, heading=_heading(msg), frame_line=_frame_line(msg),
            desc=PYTHON.doc(msg.desc), id_lit=msg.id_text, is_extended=msg.is_extended, dlc=msg.dlc, cycle_ms=msg.cycle_ms, j1939=msg.j1939,
            fingerprint=PYTHON.hex(msg.fingerprint, 8), signals=signals, checksum=checksum,
            counter=by_name[msg.counter.signal] if msg.counter is not None else None, counter_modulo=msg.counter.modulo if msg.counter is not None else 0,
            counter_start=msg.counter.start if msg.counter is not None else 0, counter_big=msg.counter is not None and msg.counter.word_order == "big",
            is_fd=msg.is_fd, brs=msg.brs, counter_length=msg.counter.length if msg.counter is not None else 0,
            checksum_byte=msg.checksum.byte if msg.checksum is not None else 0,
            checksum_cover=PYTHON.hex(msg.checksum.cover_mask) if msg.checksum is not None else "", rule_args=_rule_args(cls, msg),
            multiframe=self.multiframe(msg, by_name), decode_func=funcs["decode"], encode_func=funcs["encode"], pack_func=pack_func,
            unpack_func=funcs["unpack"], names_var=names_var, raw_functional=any(s.name in HARD_KEYWORDS for s in signals),
            decode_checks=code.frame_checks(frame, True), unpack_checks=code.frame_checks(frame, False),
            encode_lines=code.encode(frame, pack_func), pack_lines=code.pack(frame, names_var),
            checksum_ok_lines=code.checksum_ok(frame), byte_struct=(frame.byte_struct, code.struct_format(frame)) if frame.byte_struct else None,
            **self.pages(msg, signals, raw_class),
        )

    def pages(self, msg: ir.Message, signals: tuple[PySignal, ...], raw_class: str) -> dict[str, Any]:
        if not msg.is_multiplexed:
            return {"decode_lines": (), "unpack_lines": (), "present_func": "", "present_lines": ()}
        return {"decode_lines": pages.decode(signals), "unpack_lines": pages.unpack(signals, raw_class),
                "present_func": self.module.take(f"_present_{msg.name}"), "present_lines": pages.present(signals)}


def _float_helpers(can: ir.CanProtocol) -> tuple[str, ...]:
    """What encode (pack_f32, ...) and decode (unpack_f32 from the word, unpack_f32_be from the bytes, ...) of float fields use."""
    out = set()
    for s in (s for m in can.messages for s in m.data_signals if s.is_float):
        order = "_be" if s.is_big_endian else "_le"
        out |= {f"pack_f{s.length}", f"unpack_f{s.length}" + (order if float_offset(s, 0) is not None else "")}
    return tuple(sorted(out))


def _rule_args(cls: str, msg: ir.Message) -> tuple[str, ...]:
    return (
        f"{cls}.NAME", f"{cls}.FRAME_ID", f"{cls}.IS_EXTENDED", f"{cls}.DLC",
        f"{cls}.CYCLE_MS * timeout_cycles" if msg.cycle_ms is not None else "None",
        (f"CounterRule({cls}.COUNTER_START, {cls}.COUNTER_LENGTH" + (f", {cls}.COUNTER_WORD_ORDER)" if msg.counter.word_order == "big" else ")"))
        if msg.counter is not None else "None",
        f"ChecksumRule({cls}.CHECKSUM_BYTE, {cls}.CHECKSUM_COVER)" if msg.checksum is not None else "None",
    )


def _modules_doc(present: dict[str, bool]) -> tuple[str, ...]:
    return tuple(textwrap.wrap("Modules: " + ", ".join(f"`{m}` ({doc})" for m, doc in MODULE_DOCS.items() if present[m]) + ".", 100))


def build_package(spec: ir.Spec) -> PyPackage:
    can = spec.can
    assert can is not None
    b = _Builder(can)
    messages = tuple(b.message(m) for m in can.messages)
    example = next((m for m in messages if m.checksum is not None and m.counter is not None), messages[0] if messages else None)
    lookups = tuple(sorted(b.lookups.values(), key=lambda lk: lk.var))
    present = dict.fromkeys(MODULE_DOCS, True) | {"enums": bool(can.value_tables), "j1939": can.bus.is_j1939, "multiframe": can.has_multiframe}
    title = titled(can.title, can.title_zh)
    return PyPackage(
        package=package_name(can.name), protocol=can.name, dist_name=snake(can.name).replace("_", "-"), version=can.version, title=PYTHON.doc(title),
        description=f"{title} V{can.version}: generated CAN bindings", document=can.document, bitrate=can.bus.bitrate, is_j1939=can.bus.is_j1939,
        enums=b.enums, used_enums=tuple(sorted({lk.enum for lk in lookups})), lookups=lookups, scales=tuple(b.scales.values()),
        messages=messages, example=example,
        modules=tuple(sorted(m for m in MODULE_DOCS if m != "bus" and present[m])), modules_doc=_modules_doc(present),
        has_signals=any(m.signals for m in messages), has_values=any(not s.is_checksum for m in messages for s in m.signals),
        has_checksums=can.has_checksums, has_counters=can.has_counters, has_multiframe=can.has_multiframe,
        tuple_lookups=any(lk.is_tuple for lk in lookups), dict_lookups=any(not lk.is_tuple for lk in lookups), fault_tables=can.fault_tables,
        float_helpers=_float_helpers(can), byte_structs=any(m.byte_struct for m in messages),
    )
