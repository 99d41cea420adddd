"""What the generated crate's own tests (tests/vectors.rs, tests/properties.rs) need beyond the
crate's view: which helpers a spec's messages use, and the raw values whose physical round trip
(raw → physical → raw in doubles) the shared rule guarantees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import TIE_GUARANTEE, fits_runtime, to_raw_runtime
from canspec.render.literals import RUST
from canspec.targets.rust import ieee
from canspec.targets.rust.model import RustCrate, RustField, RustMessage


@dataclass(frozen=True)
class Pick:
    """The raw values the physical round trip of one field draws from: `lo..=hi`, or `values`."""

    lo: str = ""
    hi: str = ""
    values: tuple[str, ...] = ()


def _encodes_back(sig: ir.Signal, raw: int) -> bool:
    """The shared rule (every encode path computes it) takes the decoded value back to `raw`."""
    # the crate's getter: x × -1.0 where it writes -x, the same double
    x, f, o = sig.runtime_physical(raw), float(sig.factor), float(sig.offset)
    if not fits_runtime(sig.runtime_quotient(x), sig.raw_type_min, sig.raw_type_max) or to_raw_runtime(x, f, o) != raw:
        return False
    return any(s.raw == raw for s in sig.specials) or (float(sig.accept_min) <= x <= float(sig.accept_max) and sig.raw_min <= raw <= sig.raw_max)


def float_pick(sig: ir.Signal) -> Pick | None:
    """Where (|physical| + |offset|) / |factor| < TIE_GUARANTEE the decoded double is within
    2^-31 steps of the raw value and within the accepted range (ir/encoding.py), so every raw
    value there round-trips. Outside it doubles may not resolve one step: sample values checked
    here step for step instead. None: no raw value round-trips."""
    zero = sig.quotient(Fraction(0))  # the raw position of physical 0
    room = TIE_GUARANTEE - abs(zero)
    if room > 0:
        lo = max(sig.raw_min, math.floor(zero - room) + 1)
        hi = min(sig.raw_max, math.ceil(zero + room) - 1)
        if lo <= hi:
            return Pick(RUST.integer(lo), RUST.integer(hi))
    mid = (sig.raw_min + sig.raw_max) // 2
    samples = sorted(r for r in {sig.raw_min, sig.raw_min + 1, mid, mid + 1, sig.raw_max - 1, sig.raw_max} if sig.raw_min <= r <= sig.raw_max)
    good = tuple(RUST.integer(r) for r in samples if _encodes_back(sig, r))
    return Pick(values=good) if good else None


def ieee_pick(sig: ir.Signal) -> Pick:
    """Bit patterns whose float encodes back to them: the range's ends, zeros, ones and its middle
    inside the range; without a documented range also ±Inf and the quiet NaN of either sign."""
    lo, hi = float(ieee.literal_value(sig, up=True)), float(ieee.literal_value(sig, up=False))
    floats = [x for x in (lo, hi, 0.0, -0.0, 1.0, -1.0, lo / 2 + hi / 2) if lo <= x <= hi]
    patterns = {ieee.bits_of(x, sig.length) for x in floats}
    if sig.doc_min is None:
        patterns |= {ieee.bits_of(x, sig.length) for x in (math.inf, -math.inf)} | set(ieee.QUIET_NANS[sig.length])
    return Pick(values=tuple(RUST.integer(b) for b in sorted(patterns)))


def pick(field: RustField) -> Pick | None:
    if field.kind == "ieee":
        return ieee_pick(field.sig)
    if field.kind == "float":
        return float_pick(field.sig)
    return Pick(RUST.integer(field.sig.raw_min), RUST.integer(field.sig.raw_max))


@dataclass(frozen=True)
class MessageTests:
    msg: RustMessage
    picks: tuple[Pick, ...] | None  # per field; None: some field has no raw value that round-trips
    checksum_arg: str  # `frame`'s checksum argument: Some((byte, cover mask)) or None
    fd_checksum_arg: str  # `fd_frame`'s: Some(byte) or None
    sentinel: dict[str, str] = field(default_factory=dict)  # multiplexed: per field, what the values hold before `update`
    zero: dict[str, str] = field(default_factory=dict)  # and raw 0's physical value, the document's (raw × factor + offset)
    absent: dict[str, str] = field(default_factory=dict)  # and what `new` is given for a field the frame does not hold

    @property
    def fields_picks(self) -> tuple[tuple[RustField, Pick], ...]:
        return tuple(zip(self.msg.fields, self.picks or ()))

    @property
    def sampled(self) -> bool:
        return any(p.values for p in self.picks or ())

    @property
    def uses_physical(self) -> bool:
        """The vector check reads the case's physical values (enums compare raw values)."""
        return any(f.kind != "enum" for f in self.msg.fields)


def _mux_literals(f: RustField) -> tuple[str, str, str]:
    """Sentinel, raw 0's value and the value `new` must ignore, as literals of the field's physical type."""
    if f.enum is not None:
        return f"{f.enum.name}::from_raw({f.enum.repr}::MAX)", f"{f.enum.name}::from_raw(0)", f"{f.enum.name}::from_raw({f.enum.repr}::MAX)"
    if f.kind == "int":
        return f"{f.raw_type}::MAX", "0", f"{f.raw_type}::MAX"
    if f.kind == "scaled_int":
        return f"{f.phys_type}::MAX", RUST.integer(int(f.sig.offset)), f"{f.phys_type}::MAX"
    zero = "0.0" if f.kind == "ieee" else RUST.double(f.sig.runtime_physical(0))
    return "-1234.5", zero, f"{f.phys_type}::NAN"


@dataclass(frozen=True)
class CrateTests:
    messages: tuple[MessageTests, ...]
    kinds: frozenset[str]  # field kinds in any message
    has_fields: bool
    has_classic: bool  # some message is held as the u64 frame word
    has_ieee32: bool  # some field is a float32
    has_scaled: bool  # some field has a physical value other than its raw one (float or scaled_int)
    has_checksums: bool
    has_texts: bool
    picks_range: bool  # some physical round trip picks from a range
    picks_values: bool  # some from a list
    vector_imports: str  # the crate's items tests/vectors.rs names
    property_imports: str  # and tests/properties.rs
    strategy_shadowed: bool  # a message type is named like proptest's Strategy trait
    has_mux: bool  # some message is multiplexed


def build_tests(crate: RustCrate) -> CrateTests:
    tests = []
    for m in crate.messages:
        picks = tuple(pick(f) for f in m.fields)
        ck = f"Some(({m.msg.checksum.byte}, {m.cover_mask}))" if m.msg.checksum else "None"
        fd_ck = f"Some({m.msg.checksum.byte})" if m.msg.checksum else "None"
        lits = {f.name: _mux_literals(f) for f in m.fields} if m.is_multiplexed else {}
        tests.append(MessageTests(m, None if any(p is None for p in picks) else picks, ck, fd_ck,  # type: ignore[arg-type]
                                  *({name: lit[i] for name, lit in lits.items()} for i in range(3))))
    used = [p for t in tests if t.msg.fields for p in t.picks or ()]
    types = [m.name for m in crate.messages]
    texts = [m.text.assembler for m in crate.messages if m.text]
    enums = sorted({f.enum.name for m in crate.messages for f in m.fields if f.enum is not None})
    mux_values = [m.values for m in crate.messages if m.is_multiplexed]  # the vector test fills them with sentinels
    return CrateTests(
        messages=tuple(tests), kinds=crate.kinds, has_fields=any(m.fields for m in crate.messages),
        has_classic=any(not m.is_fd_frame for m in crate.messages),
        has_ieee32=any(f.phys_type == "f32" for m in crate.messages for f in m.fields),
        has_scaled=bool(crate.kinds & {"float", "scaled_int"}),
        has_checksums=any(m.msg.checksum for m in crate.messages), has_texts=bool(texts),
        picks_range=any(not p.values for p in used), picks_values=any(p.values for p in used),
        vector_imports=", ".join(["Messages", *(["EXTENDED_ID_FLAG"] if any(m.flagged for m in crate.messages) else []), *types, *mux_values, *enums, *texts]),
        property_imports=", ".join(["Error", "Messages", "EXTENDED_ID_FLAG", *types, *texts]),
        strategy_shadowed="Strategy" in types, has_mux=any(m.is_multiplexed for m in crate.messages),
    )
