"""The intermediate representation: frozen, computed once by `build.py`, read by every target.

Everything more than one target needs is here already computed — raw ranges, storage widths,
per-byte segments, frame-word masks and sign bits, merged value labels, J1939 fields (only where
J1939 applies), what a checksum covers, send type and receive timeout, fingerprints — so targets
read it and templates only shape text.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from fractions import Fraction
from functools import cached_property

from canspec.ir.dbc_attributes import Attributes
from canspec.ir.labels import Label, SpecialValue, ValueTable
from canspec.ir.mux import MuxCondition, MuxGroup
from canspec.spec.problems import Loc

# Runtime rounding rule shared by every generated language (ir/encoding.py states what it guarantees):
#   q = (physical - offset) / factor            (IEEE-754 double, in this order)
#   a = |q|;  r = a >= EXACT_LIMIT ? a : floor((a + 0.5) + TIE_EPSILON);  raw = q < 0 ? -r : r
# TIE_EPSILON absorbs the representation error of decimal inputs such as -8.99 so that a
# decimal tie rounds away from zero exactly as the exact (Fraction) rule does; from EXACT_LIMIT
# (2^52) up every double is an integer already, and adding 0.5 would round to even.
TIE_EPSILON = 1e-9
TIE_EPSILON_TEXT = "1e-9"
EXACT_LIMIT = 2**52
EXACT_LIMIT_TEXT = "4503599627370496.0"


def to_physical(raw: int | Fraction, factor: Fraction, offset: Fraction) -> Fraction:
    """physical = raw × factor + offset, exactly: the one conversion every consumer uses (a raw
    value of half a step, as for a tie, gives the physical value between two raw values)."""
    return raw * factor + offset


def runtime_quotient(physical: float, factor: float, offset: float) -> float:
    """q = (physical - offset) / factor in IEEE doubles, in this order: the runtime rule's first step."""
    return (physical - offset) / factor


@dataclass(frozen=True)
class Segment:
    """One byte's share of a signal (either byte order): value bits [value_shift, value_shift+width)
    live in frame byte `byte` at bits [byte_shift, byte_shift+width)."""

    byte: int
    byte_shift: int
    width: int
    value_shift: int
    mask: int  # mask within the byte: ((1 << width) - 1) << byte_shift


@dataclass(frozen=True)
class Signal:
    name: str
    c_name: str  # the name in C identifiers: the spec's `c_name`, else `name`
    zh: str
    desc: str
    desc_zh: str
    start: int  # the LSB (little_endian) or the MSB (big_endian), numbered 8 × byte + bit as in a DBC (ir/bits.py)
    length: int
    signed: bool
    factor: Fraction
    offset: Fraction
    unit: str
    role: str  # "data" | "counter" | "checksum" | "reserved"
    doc_min: Fraction | None  # documented physical range, as printed (after errata)
    doc_max: Fraction | None
    raw_type_min: int  # what the bits can carry
    raw_type_max: int
    raw_min: int  # what a physical encode may produce: documented range ∩ type range
    raw_max: int
    phys_min: Fraction  # physical values of raw_min / raw_max
    phys_max: Fraction
    check_min: Fraction  # the physical range: documented range, else the encodable one
    check_max: Fraction
    # What the runtime range check compares against: check_min/max widened by |factor| × TIE_EPSILON
    # for non-integer scaling, so a value decoded in doubles (252 × 0.05 − 9 = 3.6000000000000014)
    # re-encodes, while 3.605 is still out of [-9, 3.6]; and further to the decoded doubles of
    # raw_min/raw_max where a double's step exceeds that (build._accepted).
    accept_min: Fraction
    accept_max: Fraction
    storage_bits: int  # 8 / 16 / 32 / 64: narrowest unsigned/signed container
    value_table: ValueTable | None
    specials: tuple[SpecialValue, ...]
    segments: tuple[Segment, ...]  # least significant first
    # The frame word: the message's dlc bytes read as one integer, little-endian for an Intel field and
    # big-endian for a Motorola one; the field is the contiguous bits [word_shift, word_shift + length).
    word_shift: int  # an Intel field's start
    word_mask: int  # mask << word_shift
    sign_bit: int  # 1 << (length - 1) for signed fields, else 0: raw = (bits ^ sign_bit) - sign_bit
    labels: tuple[Label, ...]  # value-table entries, then specials the table does not name, by raw
    decimals: int  # decimal places that print every physical value exactly (0: integer physical values)
    is_integer: bool  # factor and offset are integers: physical values are integers
    is_identity: bool  # factor 1, offset 0
    since: str | None
    errata: tuple[str, ...]
    loc: Loc | None = field(default=None, compare=False, hash=False)
    byte_order: str = "little_endian"  # or "big_endian" (Motorola)
    # An IEEE 754 binary32/binary64 field (length 32/64): its raw value is the bit pattern (unsigned),
    # its physical value the float those bits hold (factor 1, offset 0); the raw/phys ranges are the
    # float's finite range (or the documented one), and NaN/±Inf pass only without a documented range.
    is_float: bool = False
    # Multiplexing (ir/mux.py): present only while its multiplexer holds one of some values (None:
    # in every frame); a multiplexer is a field others name in their `mux`.
    mux: MuxCondition | None = None
    is_multiplexer: bool = False
    dbc_name: str = ""  # the name the DBC writes: the spec's `dbc_name` (a source's own spelling), else `name`
    receivers: tuple[str, ...] | None = None  # the nodes that read it where not all its message's receivers do (DBC only)
    dbc_attributes: Attributes = ()  # a source DBC's own attribute values (ir/dbc_attributes.py)

    @property
    def is_reserved(self) -> bool:
        return self.role == "reserved"

    @property
    def decodes_to_enum(self) -> bool:
        """Its physical value is a value-table entry: a table on an unscaled field (factor 1,
        offset 0). A scaled field's table names raw values (a DBC's VAL_ on a scaled signal):
        the field decodes to its scaled number like any other, in every language."""
        return self.value_table is not None and self.is_identity

    @property
    def is_big_endian(self) -> bool:
        return self.byte_order == "big_endian"

    @property
    def word_order(self) -> str:
        """The frame word's order for this field: "little" or "big" (int.from_bytes, to_bytes)."""
        return "big" if self.is_big_endian else "little"

    @property
    def is_scaled(self) -> bool:
        return not self.is_identity

    @property
    def mask(self) -> int:
        return (1 << self.length) - 1

    def label_of(self, raw: int) -> Label | None:
        return next((lb for lb in self.labels if lb.raw == raw), None)

    @property
    def last_bit(self) -> int:
        return self.start + self.length - 1

    @property
    def base_raw(self) -> int:
        """The raw value a field holds when nothing sets it (the other fields of a split text, of
        a vector, of a simulated message): 0 where the range allows it, else the nearest allowed
        (for a float field: the bits of the in-range float nearest 0.0)."""
        if self.is_float:
            from canspec.ir.encoding import float_inside  # here: encoding imports this module

            return float_inside(min(max(Fraction(0), self.check_min), self.check_max), self.length, up=self.check_min > 0)
        return min(max(0, self.raw_min), self.raw_max)

    # The runtime rule over the accepted range: the C and Python encoders decide their checks on
    # these. Properties, not fields, so that a signal derived by dataclasses.replace stays consistent.
    @cached_property
    def accept_raw(self) -> tuple[int, int]:
        """The raw values the runtime rule gives at the accepted range's two ends, lower first
        (the rule is monotonic in the value): every value in the range rounds between them."""
        from canspec.ir.encoding import to_raw_runtime  # here: encoding imports this module

        lo, hi = sorted(to_raw_runtime(float(v), float(self.factor), float(self.offset)) for v in (self.accept_min, self.accept_max))
        return lo, hi

    @cached_property
    def max_quotient(self) -> Fraction:
        """The largest |q| = |(value - offset) / factor| in the accepted range, exactly."""
        return max(abs(self.quotient(v)) for v in (self.accept_min, self.accept_max))

    def raw_allowed(self, raw: int) -> bool:
        """Whether a physical encode may produce this raw value (a float field: a value in the range,
        NaN or ±Inf only without one, and a NaN only as the format's quiet NaN)."""
        if self.is_float:
            from canspec.ir.encoding import bits_of_float, float_of_bits

            x = float_of_bits(raw, self.length)
            if math.isfinite(x):
                return self.accept_min <= Fraction(x) <= self.accept_max
            quiet = bits_of_float(math.nan, self.length)  # NaN's payload is lost: only the quiet NaN (either sign) comes back
            return self.doc_min is None and (math.isinf(x) or raw & ~(1 << (self.length - 1)) == quiet)
        return self.raw_min <= raw <= self.raw_max or any(s.raw == raw for s in self.specials)

    def physical(self, raw: int | Fraction) -> Fraction:
        return to_physical(raw, self.factor, self.offset)

    def quotient(self, physical: Fraction) -> Fraction:
        """(physical - offset) / factor, exactly: the raw value (a fraction between two) of a physical one."""
        return (physical - self.offset) / self.factor

    @cached_property
    def runtime_scale(self) -> tuple[float, float]:
        """factor and offset as the doubles the generated code holds (converted once: vectors ask per case)."""
        return float(self.factor), float(self.offset)

    def runtime_quotient(self, physical: float) -> float:
        """q as the generated code computes it, in doubles."""
        return runtime_quotient(physical, *self.runtime_scale)

    @property
    def reciprocal(self) -> float:
        """1 / factor in doubles: what a runtime may multiply by in place of dividing by the factor."""
        return 1.0 / float(self.factor)

    def runtime_physical(self, raw: int) -> float:
        """The generated decode in doubles: raw × factor, then + offset (two roundings, never fused;
        an identity factor or a zero offset is left out, as the generated code leaves it out)."""
        x = float(raw) * float(self.factor) if self.factor != 1 else float(raw)
        return x + float(self.offset) if self.offset else x


@dataclass(frozen=True)
class Checksum:
    """The XOR checksum: the frame's last byte is the XOR of every other byte of the frame, so
    a frame is intact exactly when the XOR of all its DLC bytes is 0."""

    algorithm: str  # "xor"
    signal: str
    byte: int  # the byte holding the checksum (the last byte)
    covers: tuple[int, ...]  # bytes XORed together: every other byte of the frame
    cover_mask: int  # those bytes in the frame read as one little-endian integer


@dataclass(frozen=True)
class Counter:
    signal: str
    length: int
    modulo: int  # 2^length: the counter wraps to 0 after modulo - 1
    start: int  # its LSB in the frame word (Signal.word_shift)
    word_mask: int
    word_order: str = "little"  # the frame word's order (Signal.word_order)


@dataclass(frozen=True)
class MultiFrame:
    """Text (a VIN) spread over several frames, chunk i in the frame whose index signal is i."""

    index_signal: str
    payload_signal: str
    encoding: str
    text_length: int
    frames: int
    bytes_per_frame: int
    payload_byte: int  # first frame byte of the chunk
    padding: int
    # The other data signals but counter and checksum: the same in every frame of one text (they
    # tell its sender apart, e.g. device_type); a frame that differs belongs to another text.
    key_signals: tuple[str, ...] = ()


@dataclass(frozen=True)
class J1939Id:
    priority: int
    edp: int
    dp: int
    pf: int
    ps: int
    sa: int
    pgn: int
    da: int | None  # destination address for PDU1 (pf < 240); None for broadcast PDU2
    is_pdu2: bool
    pgn_text: str  # "0x0F004"


@dataclass(frozen=True)
class Message:
    name: str
    c_name: str  # the name in C identifiers: the spec's `c_name`, else `name`
    title: str
    zh: str
    desc: str
    section: str
    frame_id: int
    is_extended: bool  # 29-bit identifier (else 11-bit)
    id_text: str  # "0x1801B0A0" (29-bit) / "0x123" (11-bit)
    dlc: int
    cycle_ms: int | None  # None: event-driven (sent on change or on request)
    timeout_ms: int | None  # receive monitors' default timeout: protocol_model.MONITOR_TIMEOUT_CYCLES cycles; None when event-driven
    sender: str  # a node name, or "ALL"
    receivers: tuple[str, ...]
    j1939: J1939Id | None  # the ID's J1939 fields when the bus uses J1939 addressing
    signals: tuple[Signal, ...]  # every field including reserved ones, by start bit
    layout: str | None
    layout_undefined: bool
    checksum: Checksum | None
    counter: Counter | None
    multiframe: MultiFrame | None
    fingerprint: int  # 32-bit hash of the wire layout
    errata: tuple[str, ...]
    loc: Loc | None = field(default=None, compare=False, hash=False)
    is_fd: bool = False  # a CAN FD frame (FDF): up to 64 data bytes
    brs: bool = False  # CAN FD bit-rate switching: the data phase at the bus's data_bitrate
    # The pages of each multiplexer, top-level multiplexer first (ir/mux.py): () without multiplexing.
    mux_groups: tuple[MuxGroup, ...] = ()

    @cached_property
    def is_multiplexed(self) -> bool:
        return bool(self.mux_groups)

    @cached_property
    def text_fields_in_pages(self) -> tuple[str, ...]:
        """The multi-frame text's index, payload and key fields that only some pages hold (a
        reassembler that reads them from every frame cannot take the text)."""
        m = self.multiframe
        return () if m is None else tuple(n for n in (m.index_signal, m.payload_signal, *m.key_signals) if self.signal(n).mux is not None)

    @cached_property
    def multiplexers(self) -> tuple[Signal, ...]:
        """The multiplexers, in frame order; one of them is in every frame (the top-level one)."""
        return tuple(s for s in self.signals if s.is_multiplexer)

    def mux_chain(self, sig: Signal) -> tuple[MuxCondition, ...]:
        """What a field's presence needs, top-level multiplexer first: () for a field in every frame."""
        chain: list[MuxCondition] = []
        while sig.mux is not None:
            chain.insert(0, sig.mux)
            sig = self.signal(sig.mux.by)
        return tuple(chain)

    def present(self, values: dict[str, int]) -> tuple[Signal, ...]:
        """The data fields a frame holds when its multiplexers hold `values` (raw; a multiplexer
        missing from it holds 0, as an encoder writes it), in frame order: the fields in every
        frame and those of the selected pages; the other pages' fields are absent."""
        return tuple(s for s in self.data_signals if all(c.holds(values.get(c.by, 0)) for c in self.mux_chain(s)))

    @cached_property
    def page_selections(self) -> tuple[dict[str, int], ...]:
        """Multiplexer values that select each page in turn (its lowest and its highest value; a
        multiplexer inside the page set to its first page's lowest): every field appears in one of
        them. () without multiplexing."""
        out: list[dict[str, int]] = []
        for group in self.mux_groups:
            chain = {c.by: c.first for c in self.mux_chain(self.signal(group.multiplexer))}
            for value in sorted({group.ranges[0][0], group.ranges[-1][1]}):
                values = chain | {group.multiplexer: value}
                while unset := [s.name for s in self.present(values) if s.is_multiplexer and s.name not in values]:
                    values[unset[0]] = next(g.ranges[0][0] for g in self.mux_groups if g.multiplexer == unset[0])
                if values not in out:
                    out.append(values)
        return tuple(out)

    @cached_property
    def page_layouts(self) -> tuple[dict[str, int], ...]:
        """One selection per distinct set of fields a frame can hold (what one bit diagram shows):
        page_selections, each layout once, in order. () without multiplexing."""
        seen: set[tuple[str, ...]] = set()
        out = []
        for values in self.page_selections:
            fields = tuple(s.name for s in self.present(values))
            if fields not in seen:
                seen.add(fields)
                out.append(values)
        return tuple(out)

    def page(self, values: dict[str, int]) -> Message:
        """The message as the frames that hold these multiplexer values see it: the fields of every
        frame and of the selected pages, each multiplexer fixed to its value (raw_min = raw_max),
        without multiplexing — a plain message whose frames are those of this page."""
        present = {s.name for s in self.present(values)}
        signals = tuple(
            replace(s, mux=None, is_multiplexer=False, raw_min=values.get(s.name, 0), raw_max=values.get(s.name, 0)) if s.is_multiplexer
            else replace(s, mux=None)
            for s in self.signals if s.is_reserved or s.name in present
        )
        return replace(self, signals=signals, mux_groups=())
    dbc_name: str = ""  # the name the DBC writes: the spec's `dbc_name`, else `name`
    dbc_senders: tuple[str, ...] = ()  # further senders the DBC lists (BO_TX_BU_); every other target knows `sender` only
    dbc_attributes: Attributes = ()  # a source DBC's own attribute values (ir/dbc_attributes.py)

    @property
    def is_classic_length(self) -> bool:
        """At most 8 data bytes: the whole frame fits one 64-bit word."""
        return self.dlc <= 8

    @cached_property
    def has_big_endian(self) -> bool:
        return any(s.is_big_endian for s in self.signals)

    @cached_property
    def has_float(self) -> bool:
        return any(s.is_float for s in self.signals)

    @property
    def last_byte(self) -> int:
        return self.dlc - 1

    @property
    def is_cyclic(self) -> bool:
        return self.cycle_ms is not None

    @cached_property
    def data_signals(self) -> tuple[Signal, ...]:
        """Signals that carry values (everything but reserved bits)."""
        return tuple(s for s in self.signals if not s.is_reserved)

    @cached_property
    def reserved_signals(self) -> tuple[Signal, ...]:
        return tuple(s for s in self.signals if s.is_reserved)

    def signal(self, name: str) -> Signal:
        return next(s for s in self.signals if s.name == name)
