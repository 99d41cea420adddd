"""The Rust view of the IR: what each message type, field and enum of the generated crate is
called and computes. Python owns all of it (names in naming.py, bit expressions in bits.py,
encode paths in encode.py, doc text in docs.py, enums in values.py); `templates/rust/` only
shapes the text.
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir import j1939
from canspec.ir.bits import describe
from canspec.ir.ids import MAX_STANDARD_ID
from canspec.ir.names import RUST_KEYWORDS, pascal, snake
from canspec.render.literals import RUST
from canspec.targets.rust import docs
from canspec.targets.rust.bits import (
    CLASSIC_BYTES,
    byte_masks,
    cast,
    frame_mask,
    misfit_expr,
    place,
    raw_type,
    refused_expr,
    store_stmt,
    type_bounds,
    unpack_expr,
)
from canspec.targets.rust.encode import Encoding, float_encoding, int_encoding, kind_of, scaled_int_type
from canspec.targets.rust.ieee import IeeeEncoding, ieee_encoding
from canspec.targets.rust.layout import holds_bytes
from canspec.targets.rust.mux import RustMuxField, mux_field
from canspec.targets.rust.naming import FieldNames, enum_type_names, field_names, special_const, stored_signals, type_name
from canspec.targets.rust.text import RustText, build_text
from canspec.targets.rust.values import RustEnum, build_enum, enum_users

# Getters named like a conversion (`to_x`, `from_x`) break clippy's naming conventions for methods
# taking `&self`; the names are the spec's.
CONVERSION_PREFIXES = ("to_", "from_", "into_", "as_", "is_")
MAX_ARGUMENTS = 7  # clippy's too_many_arguments threshold
TAKEN_CRATE_NAMES = frozenset({"std", "core", "alloc", "proc_macro", "test", "serde", "serde_json", "proptest"})


@dataclass(frozen=True)
class RustSpecial:
    const: str
    raw: str
    doc: str


@dataclass(frozen=True)
class RustField:
    sig: ir.Signal
    names: FieldNames
    qualified: str  # "message.signal", for error messages
    kind: str  # "enum" | "int" (identity) | "scaled_int" (integer factor/offset) | "float" (scaled, f64) | "ieee" (an IEEE 754 field)
    raw_type: str
    phys_type: str
    enum: RustEnum | None
    raw_expr: str  # the raw getter's body
    phys_expr: str  # the physical getter's body
    store: str  # the store method's body (from `value`)
    misfit: str | None  # `value` (raw type) does not fit the field; None: never
    encoding: Encoding | None  # scaled kinds: the codec call
    ieee: IeeeEncoding | None  # IEEE fields: their range and the `ieee` call
    set_arg: str  # what the setter passes to the codec (scaled kinds) or checks (`value`)
    set_check: str | None  # enum and int kinds: the refused-value condition on `set_arg`
    store_arg: str  # what the setter stores (from `raw` for scaled kinds, else `value`)
    min_lit: str  # scaled kinds: the documented range as the physical type's literals
    max_lit: str
    specials: tuple[RustSpecial, ...]
    doc: tuple[str, ...]
    short_doc: str  # the values struct's doc of the field (its line and a pointer to the getter)
    table_row: str
    bits_doc: str  # where the raw getter's field lies
    getter_allow: str  # a clippy lint the getter names break ("" for none)
    unit_note: str  # " (unit)" or ""
    tolerance: str  # vector test: |factor| as an f64 literal (a tie decodes within half a step)
    offset_abs: str  # and |offset| (the size of the decode's rounding)
    mux: RustMuxField | None = None  # in a multiplexed message: when it is present
    loaded_phys: str = ""  # multiplexed messages: the physical value of the frame's bits (`load`), present or not
    zero_phys: str = ""  # and of raw 0: what the values of a frame without the field hold

    @property
    def is_paged(self) -> bool:
        """Present only in some frames: its getters return an `Option`."""
        return self.mux is not None and bool(self.mux.frame_cond)

    @property
    def is_settable(self) -> bool:
        """Has public setters: not a multiplexer nor a multiplexed field (those change which bits mean what)."""
        return self.mux is None or not (self.is_paged or self.sig.is_multiplexer)

    @property
    def name(self) -> str:
        return self.names.base


@dataclass(frozen=True)
class RustMessage:
    msg: ir.Message
    name: str  # the type
    values: str  # its physical-values struct
    variant: str  # variant in `Messages`
    snake: str  # the message name as a snake_case item name in tests
    extended: str  # IS_EXTENDED's literal
    summary: tuple[str, ...]  # one doc line
    flagged: bool  # `Messages::decode` takes its identifier with EXTENDED_ID_FLAG
    decode_id: str  # that identifier
    example_imports: str  # what the crate doc's example imports
    fields: tuple[RustField, ...]  # data signals except the checksum
    counter: RustField | None
    text: RustText | None
    doc: tuple[str, ...]
    table: tuple[str, ...]  # the doc table of its signals (head, rule, rows)
    frame_id: str
    da: str  # J1939 destination address as an Option<u8>
    defined_mask: str  # frame bits the message defines (not reserved, not undefined): a u64, or per byte for FD frames
    fields_mask: str  # frame bits of the fields the type stores (no checksum, no reserved): a u64, or per byte for FD frames
    kept_bytes: tuple[tuple[int, str], ...]  # held as bytes: each byte a field lies in, and its value as decode keeps it (the fields' bits)
    holds_bytes: bool  # held as its bytes (`bytes: [u8; DLC]`), not as the u64 frame word (layout.py)
    frame_bytes: int  # what `encode` returns: 8 bytes (a classic frame, the u64 frame word), or an FD frame's dlc
    checksum_shift: int  # bit position of the checksum byte in the frame word
    cover_mask: str  # frame-word bits the checksum covers
    many_arguments: bool
    local: str  # the message under construction in `new` and `from_raw` (no parameter's name)

    @property
    def checksum(self) -> ir.Checksum | None:
        return self.msg.checksum

    @property
    def has_ieee(self) -> bool:
        return any(f.kind == "ieee" for f in self.fields)

    @property
    def is_fd_frame(self) -> bool:
        """Over 8 bytes: `encode` returns DLC bytes, and the tests build frames byte by byte."""
        return not self.msg.is_classic_length

    @property
    def is_multiplexed(self) -> bool:
        return self.msg.is_multiplexed

    @property
    def set_order(self) -> tuple[RustField, ...]:
        """The fields as `new` sets them: each multiplexer before the fields it selects."""
        return tuple(sorted(self.fields, key=lambda f: f.mux.depth if f.mux else 0))

    @property
    def length_only(self) -> bool:
        """`decode` tests the length and nothing else: no field, no checksum, some bytes."""
        return not self.fields and self.msg.checksum is None and self.msg.dlc > 0


@dataclass(frozen=True)
class RustCrate:
    package: str
    version: str
    title: tuple[str, ...]
    summary: tuple[str, ...]
    enums: tuple[RustEnum, ...]
    messages: tuple[RustMessage, ...]
    message_table: tuple[str, ...]
    is_j1939: bool
    pdu2_min_pf: int
    global_address: str
    id_flag_matters: bool  # an identifier without the extended flag may be a standard one of ours
    max_standard_id: str
    uses_codec: bool  # messages.rs calls into codec
    kinds: frozenset[str]  # the field kinds that occur
    frame_bytes: int  # the longest frame `encode` returns (8 without FD frames over 8 bytes)
    has_fd_frames: bool  # some message is held as its bytes (module `fd`)
    messages_use_fd: bool  # messages.rs calls into `fd`: a field over several bytes of an FD frame (its window reads), or an FD checksum


def _phys_expr(sig: ir.Signal, kind: str, raw: str, phys_type: str, enum: RustEnum | None) -> str:
    """The getter's body: the physical value from the raw getter's call `raw`."""
    if kind == "enum":
        assert enum is not None
        return f"{enum.name}::from_raw({cast(raw, raw_type(sig), enum.repr)})"
    if kind == "int":
        return raw
    if kind == "ieee":
        return f"{phys_type}::from_bits({raw})"
    if kind == "scaled_int":
        expr = cast(raw, raw_type(sig), phys_type)
        factor, offset = RUST.integer(int(sig.factor)), RUST.integer(int(abs(sig.offset)))
    else:
        expr = f"{raw} as f64"
        factor, offset = RUST.double(float(sig.factor)), RUST.double(float(abs(sig.offset)))
    if sig.factor == -1:
        expr = f"-({expr})"  # x × -1.0 is -x exactly
    elif sig.factor != 1:
        expr += f" * {factor}"
    if kind == "scaled_int" and sig.offset < -type_bounds(phys_type)[1]:
        expr += f" + {RUST.integer(int(sig.offset))}"  # the type's minimum: its magnitude has no literal
    elif sig.offset:
        expr += f" {'+' if sig.offset > 0 else '-'} {offset}"  # x - c == x + (-c) exactly in IEEE arithmetic
    return expr


def build_field(msg: ir.Message, type_name: str, sig: ir.Signal, enums: dict[str, RustEnum], bilingual: bool, held_as_bytes: bool) -> RustField:
    names = field_names(sig)
    kind = kind_of(sig)
    ty = raw_type(sig)
    enum = enums[sig.value_table.name] if kind == "enum" and sig.value_table is not None else None
    phys_type = {"enum": enum.name if enum else "", "int": ty, "scaled_int": scaled_int_type(sig) or "", "float": "f64", "ieee": f"f{sig.length}"}[kind]
    encoding = int_encoding(sig) if kind == "scaled_int" else float_encoding(sig) if kind == "float" else None
    ieee = ieee_encoding(sig) if kind == "ieee" else None
    at = place(sig, msg.dlc, held_as_bytes)
    set_arg, set_check, store_arg = "value", None, "value"
    if ieee is not None:
        store_arg = "raw"
    elif encoding is not None:
        set_arg = "i64::from(value)" if kind == "scaled_int" else "value"
        store_arg = cast("raw", encoding.returns, ty)
    elif enum is not None:
        set_check = refused_expr(sig, ty=enum.repr)
        store_arg = cast("value", enum.repr, ty)
    else:
        set_check = refused_expr(sig)
    min_lit = max_lit = ""
    if ieee is not None:
        min_lit, max_lit = ieee.min_lit, ieee.max_lit
    elif encoding is not None:
        min_lit, max_lit = (encoding.scale["check_min"], encoding.scale["check_max"]) if kind == "scaled_int" else \
            (RUST.double(float(sig.check_min)), RUST.double(float(sig.check_max)))
    return RustField(
        sig=sig,
        names=names,
        qualified=f"{msg.name}.{sig.name}",
        kind=kind,
        raw_type=ty,
        phys_type=phys_type,
        enum=enum,
        raw_expr=unpack_expr(sig, at=at),
        phys_expr=_phys_expr(sig, kind, f"self.{names.raw_getter}()", phys_type, enum),
        store=store_stmt(sig, at=at),
        misfit=misfit_expr(sig),
        encoding=encoding,
        ieee=ieee,
        set_arg=set_arg,
        set_check=set_check,
        store_arg=store_arg,
        min_lit=min_lit,
        max_lit=max_lit,
        specials=tuple(RustSpecial(special_const(names, s), RUST.integer(s.raw), docs.special_doc(sig, s, names.base)) for s in sig.specials),
        doc=docs.field_doc(sig),
        short_doc=docs.short_doc(sig, type_name, names.getter),
        table_row=docs.table_row(sig, names.base, bilingual),
        bits_doc=f"Motorola: {describe(sig.start, sig.length, sig.byte_order)}" if sig.is_big_endian else f"bits {sig.start}..={sig.last_bit}",
        getter_allow="clippy::wrong_self_convention" if names.base.startswith(CONVERSION_PREFIXES) else "",
        tolerance=RUST.double(float(abs(sig.factor))),
        offset_abs=RUST.double(float(abs(sig.offset))),
        unit_note=f" ({docs.doc_text(sig.unit)})" if sig.unit else "",
        mux=mux_field(msg, sig),
        loaded_phys=_phys_expr(sig, kind, f"self.{names.load}()", phys_type, enum) if msg.is_multiplexed else "",
        zero_phys=_phys_expr(sig, kind, f"Self::ZERO.{names.load}()", phys_type, enum) if msg.is_multiplexed else "",
    )


def kept_bytes(mask: int, dlc: int) -> tuple[tuple[int, str], ...]:
    """The bytes the decode of a message held as bytes copies, each with the expression it keeps (`bytes[i]`, masked
    where the fields hold part of it): the others stay 0, so decode does work for the bytes its
    fields lie in, not for the whole frame."""
    out = []
    for i in range(dlc):
        byte = (mask >> (8 * i)) & 0xFF
        if byte:
            out.append((i, f"bytes[{i}]" if byte == 0xFF else f"bytes[{i}] & {RUST.hex(byte, 2)}"))
    return tuple(out)


def build_message(msg: ir.Message, enums: dict[str, RustEnum], id_flag_matters: bool) -> RustMessage:
    name = type_name(msg.name)
    flagged = id_flag_matters and msg.is_extended
    table_bilingual = any(s.zh for s in stored_signals(msg))
    as_bytes = holds_bytes(msg)
    fields = tuple(build_field(msg, name, s, enums, table_bilingual, as_bytes) for s in stored_signals(msg))
    counter = next((f for f in fields if msg.counter and f.sig.name == msg.counter.signal), None)
    defined = stored = 0
    for s in msg.data_signals:
        defined |= frame_mask(s)
        stored |= frame_mask(s) if s.role != "checksum" else 0
    masks = (lambda mask: byte_masks(mask, msg.dlc)) if not msg.is_classic_length else RUST.integer
    j = msg.j1939
    return RustMessage(
        msg=msg, name=name, values=f"{pascal(msg.name)}Values", variant=name, snake=snake(msg.name), extended="true" if msg.is_extended else "false",
        summary=(docs.doc_text(msg.zh or msg.title),), flagged=flagged, decode_id=f"{name}::FRAME_ID | EXTENDED_ID_FLAG" if flagged else f"{name}::FRAME_ID",
        example_imports=f"Messages, {name}, EXTENDED_ID_FLAG" if flagged else f"Messages, {name}", fields=fields, counter=counter,
        text=build_text(msg, fields), doc=docs.message_doc(msg),
        table=(*docs.table_head(table_bilingual), *(f.table_row for f in fields)) if fields else (),
        frame_id=msg.id_text, da="None" if j is None or j.da is None else f"Some({RUST.hex(j.da, 2)})",
        defined_mask=masks(defined), fields_mask=masks(stored),
        holds_bytes=as_bytes, frame_bytes=CLASSIC_BYTES if msg.is_classic_length else msg.dlc,
        kept_bytes=kept_bytes(stored, msg.dlc) if as_bytes else (),
        checksum_shift=8 * msg.checksum.byte if msg.checksum else 0, cover_mask=RUST.integer(msg.checksum.cover_mask) if msg.checksum else "",
        many_arguments=len(fields) > MAX_ARGUMENTS, local="msg_" if any(f.names.field == "msg" for f in fields) else "msg",
    )


def build_crate(can: ir.CanProtocol) -> RustCrate:
    """The crate's view; assumes `canspec check` passed (targets/rust/check.py)."""
    users = {table: signals for table, signals in enum_users(can).items() if signals[0].value_table is not None}
    names = enum_type_names(can, users)
    enums = {table: build_enum(signals[0].value_table, signals, names[table]) for table, signals in users.items()}
    bilingual = any(m.zh for m in can.messages)
    id_flag_matters = any(not m.is_extended or m.frame_id <= MAX_STANDARD_ID for m in can.messages)
    messages = tuple(build_message(m, enums, id_flag_matters) for m in can.messages)
    kinds = frozenset(f.kind for m in messages for f in m.fields)
    return RustCrate(
        package=rust_crate_name(can.name), version=semver(can.version), title=docs.crate_title(can),
        summary=docs.crate_summary(can, bool(enums)), enums=tuple(enums.values()), messages=messages,
        message_table=(*docs.message_table_head(bilingual), *(docs.message_row(m.msg, m.name, bilingual) for m in messages)),
        is_j1939=can.bus.is_j1939, pdu2_min_pf=j1939.PDU2_MIN_PF, global_address=RUST.hex(j1939.GLOBAL_ADDRESS, 2),
        id_flag_matters=id_flag_matters, max_standard_id=RUST.integer(MAX_STANDARD_ID),
        uses_codec=bool(kinds & {"scaled_int", "float"}) or can.has_counters or any(m.checksum and not m.is_fd_frame for m in messages), kinds=kinds,
        frame_bytes=max((m.frame_bytes for m in messages), default=CLASSIC_BYTES), has_fd_frames=any(m.is_fd_frame for m in messages),
        messages_use_fd=any(m.is_fd_frame and m.checksum or any("fd::" in f.raw_expr for f in m.fields) for m in messages),
    )


def rust_crate_name(name: str) -> str:
    """The crate's name: the protocol's, unless that is a keyword or a crate the tests use."""
    name = snake(name)
    return f"{name}_protocol" if name in RUST_KEYWORDS or name in TAKEN_CRATE_NAMES else name


def semver(version: str) -> str:
    """The spec's `X.Y.Z` as Cargo reads it (no leading zeros)."""
    return ".".join(str(int(part)) for part in version.split("."))
