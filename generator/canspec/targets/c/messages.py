"""The C view of one message: its facts as C literals, its struct and its pack/unpack (codec.py).

The struct holds every data signal, the counter and the checksum as raw values, in frame order,
each in the narrowest integer type that holds its bits (an IEEE float field: a float or double,
see floats.py); reserved bits have no field (pack sends them as 0).
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir import j1939
from canspec.ir.names import snake
from canspec.render.literals import C
from canspec.targets.c.codec import CCodec, build_codec, word_zeros, zero_first
from canspec.targets.c.codec64 import build_codec64
from canspec.targets.c.mux import CPresence, build_mux_codecs, mux_words, presence
from canspec.targets.c.names import CNames
from canspec.targets.c.signals import CSignal, build_signal


@dataclass(frozen=True)
class CJ1939:
    """A message's J1939 identifier fields as C literals."""

    priority: str
    pgn: str
    sa: str
    da: str | None  # PDU1 only
    info_da: str  # the destination address, the global address for PDU2 broadcasts


@dataclass(frozen=True)
class CMessage:
    msg: ir.Message
    name: str  # snake name
    macro: str
    fn: str
    type: str
    index_const: str  # enumerator in the message index enum
    member: str  # its member in the any-message union
    frame_id: str  # literals
    fingerprint: str
    dlc: str
    cycle_ms: str | None  # None: event-driven
    info_cycle: str  # msg_info_t.cycle_ms: its macro, or 0 when event-driven
    counter_modulo: str  # msg_info_t.counter_modulo: 0 without a counter
    counter_start: str  # msg_info_t.counter_start: its first bit in the frame
    j1939: CJ1939 | None
    signals: tuple[CSignal, ...]  # data signals incl. counter/checksum, not reserved
    codec: CCodec  # the byte form: every core
    pack64: CCodec | None  # the form of <PREFIX>_STRATEGY 3 (64-bit registers), where its pack differs
    pack_words: CCodec | None  # <PREFIX>_STRATEGY 2 (unaligned word stores), where its pack differs (codec.word_zeros)
    zero_fill: str  # the shared function that zeroes the frame first in pack_words ("" where none: model.zero_fills)
    pack_small: CCodec | None  # below <PREFIX>_STRATEGY 2, built for size: where its pack differs (codec.zero_first)
    unpack64: CCodec | None  # the same, where its unpack differs (each function is written once where not)
    presence: tuple[CPresence, ...]  # a multiplexed message's `<field>_is_present` tests (mux.py)
    counter: CSignal | None
    counter_mask: str
    comment: str


def _j1939(msg: ir.Message) -> CJ1939 | None:
    j = msg.j1939
    if j is None:
        return None
    da = C.hex(j.da) if j.da is not None else None
    return CJ1939(C.unsigned(j.priority), f"{j.pgn_text}u", C.hex(j.sa, 2), da, da or C.hex(j1939.GLOBAL_ADDRESS, 2))


def _word64(codec: CCodec, codec64: CCodec | None) -> tuple[CCodec | None, CCodec | None]:
    """The form of <PREFIX>_STRATEGY 3 for pack, for unpack: where it differs from the byte form (a
    function the same in both is written once, without the #if)."""
    if codec64 is None:
        return None, None
    pack = (codec64.pack_locals, codec64.pack) != (codec.pack_locals, codec.pack)
    unpack = (codec64.unpack_locals, codec64.unpack) != (codec.unpack_locals, codec.unpack)
    return (codec64 if pack else None), (codec64 if unpack else None)


def build_message(names: CNames, msg: ir.Message, enum_types: dict[str, str]) -> CMessage:
    sigs = tuple(build_signal(names, msg, s, enum_types) for s in msg.data_signals)
    counter = next((s for s in sigs if msg.counter and s.sig.name == msg.counter.signal), None)
    base = names.message(msg.name)
    err = names.const("err_range")
    if msg.is_multiplexed:
        codec, codec64 = build_mux_codecs(msg, sigs, err, names.const("ok"))
    else:
        codec = build_codec(msg, sigs, err)
        codec64 = build_codec64(msg, sigs, err, codec)
    pack64, unpack64 = _word64(codec, codec64)
    fill = names.fn("zero", str(msg.dlc))
    filled = zero_first(msg, sigs, err, codec, f"{fill}(dst);")
    return CMessage(
        msg=msg,
        name=snake(msg.name),
        macro=names.const(base),
        fn=names.fn(base),
        type=names.fn(base, "t"),
        index_const=names.const("msg", base),
        member=CNames.member(msg.c_name),
        frame_id=f"{msg.id_text}u",
        fingerprint=C.hex(msg.fingerprint, 8),
        dlc=C.unsigned(msg.dlc),
        cycle_ms=C.unsigned(msg.cycle_ms) if msg.cycle_ms is not None else None,
        j1939=_j1939(msg),
        info_cycle=names.const(base, "cycle_ms") if msg.cycle_ms is not None else C.unsigned(0),
        counter_modulo=C.unsigned(msg.counter.modulo if msg.counter else 0),
        counter_start=C.unsigned(msg.counter.start if msg.counter else 0),
        signals=sigs,
        codec=codec,
        pack64=pack64,
        pack_words=filled or (mux_words(msg, sigs, err, codec, names.const("ok")) if msg.is_multiplexed else word_zeros(msg, sigs, err, codec)),
        zero_fill=fill if filled else "",
        pack_small=zero_first(msg, sigs, err, codec, f"(void)memset(dst, 0, {msg.dlc}u);"),
        unpack64=unpack64,
        presence=presence(msg, sigs),
        counter=counter,
        counter_mask=C.hex(msg.counter.modulo - 1) if msg.counter else "",
        comment=f"{msg.title} / {msg.zh}" if msg.title and msg.zh else msg.title or msg.zh,
    )
