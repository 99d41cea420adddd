"""The C view of one message: its facts as C literals, its struct and its pack/unpack plan.

Every frame is at most 8 bytes and every signal is Intel (little-endian), so a signal is the bit
field [start, start+length) of the frame read as one little-endian 64-bit word `v`. Unpack
assembles `v` from the bytes once (one load on a little-endian host), moves the fields of each
run of adjacent struct fields into their slots together and stores them; pack does the
reverse, checks a run's field widths with one mask and writes the frame word with one store.
The XOR checksum covers every other byte of the frame (ir.Checksum.covers), and bytes past the
DLC are 0 in the frame word, so a frame is intact exactly when the XOR of all bytes of `v` is 0.
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir.names import snake
from canspec.render.literals import c_hex, c_uint, hex32, hex_byte
from canspec.targets.c import runs as cruns
from canspec.targets.c import words as cwords
from canspec.targets.c.names import CNames
from canspec.targets.c.runs import CRun, byte_of
from canspec.targets.c.signals import CSignal, build_signal

GLOBAL_ADDRESS = 0xFF  # J1939: the destination of a PDU2 broadcast


@dataclass(frozen=True)
class CByteField:
    """A whole-byte field at the struct's end copied as a byte (a load and a store) instead of
    being moved within a word (a shift or two, a mask and an OR each way)."""

    field: str
    byte: int  # frame byte
    value: str  # unpack: the byte from the frame word `v`


@dataclass(frozen=True)
class CJ1939:
    """A message's J1939 identifier fields as C literals."""

    priority: str
    pgn: str
    sa: str
    da: str | None  # PDU1 only
    info_da: str  # the destination address, the global address for PDU2 broadcasts


@dataclass(frozen=True)
class CChecksum:
    byte: int
    pack: str  # uint64_t term OR'ed into `w`: the checksum byte in place
    ok: str  # condition on `v`: the frame is intact


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
    unpack_runs: tuple[CRun, ...]  # every struct field, in struct order
    layout_check: str  # condition true when the struct layout is the one the word path assumes
    pack_runs: tuple[CRun, ...]  # the fields pack reads (not the checksum)
    frame_load: str  # the frame word `v` from src[0..dlc-1] (unpack)
    frame_word: str  # the frame word `w` from the packed runs (pack, without checksum)
    frame_stores: tuple[str, ...]  # dst[i] from `w`, per frame byte
    range_terms: tuple[str, ...]  # uint64_t terms, OR != 0: a field does not fit its bits
    byte_fields: tuple[CByteField, ...]  # whole-byte fields unpack copies byte by byte (not in the runs)
    pack_byte_stores: tuple[CByteField, ...]  # those pack stores byte by byte after the frame word
    checksum: CChecksum | None
    counter: CSignal | None
    counter_mask: str
    comment: str


def _j1939(msg: ir.Message) -> CJ1939 | None:
    j = msg.j1939
    if j is None:
        return None
    da = c_hex(j.da) if j.da is not None else None
    return CJ1939(c_uint(j.priority), f"{j.pgn_text}u", f"{hex_byte(j.sa)}u", da, da or f"{hex_byte(GLOBAL_ADDRESS)}u")


def _checksum(names: CNames, msg: ir.Message, data: list[CSignal]) -> CChecksum | None:
    ck = msg.checksum
    if ck is None:
        return None
    # The checksum byte is 0 in `w`: the XOR of all of its bytes is the checksum. When the data
    # lies in the low four bytes, so does every nonzero byte of `w`.
    used = {seg.byte for s in data for seg in s.sig.segments}
    fold = f"{names.fn('xor_fold32')}((uint32_t)w)" if max(used, default=0) < 4 else f"{names.fn('xor_fold')}(w)"
    return CChecksum(ck.byte, f"((uint64_t){fold} << {8 * ck.byte})", f"{names.fn('xor_is_zero')}(v)")


def build_message(names: CNames, msg: ir.Message, enum_types: dict[str, str]) -> CMessage:
    sigs = tuple(build_signal(names, msg, s, enum_types) for s in msg.data_signals)
    ck_name = msg.checksum.signal if msg.checksum is not None else None
    data = [s for s in sigs if s.sig.name != ck_name]
    counter = next((s for s in sigs if msg.counter and s.sig.name == msg.counter.signal), None)
    base = names.message(msg.name)
    plan = _plan(names.fn(base, "t"), msg, sigs, ck_name)
    return CMessage(
        msg=msg, name=snake(msg.name), macro=names.const(base), fn=names.fn(base),
        type=names.fn(base, "t"), index_const=names.const("msg", base), member=CNames.member(msg.name),
        frame_id=f"{msg.id_text}u", fingerprint=f"{hex32(msg.fingerprint)}u", dlc=c_uint(msg.dlc), cycle_ms=c_uint(msg.cycle_ms) if msg.cycle_ms is not None else None, j1939=_j1939(msg),
        info_cycle=names.const(base, "cycle_ms") if msg.cycle_ms is not None else c_uint(0),
        counter_modulo=c_uint(msg.counter.modulo if msg.counter else 0), counter_start=c_uint(msg.counter.start if msg.counter else 0),
        signals=sigs, **plan, range_terms=tuple(
            [f"({r.var} & {c_hex(r.run.check, 64)})" for r in plan["pack_runs"] if r.run.check]
            + [f"(uint64_t)({s.range_check})" for s in data if s.range_check]),
        checksum=_checksum(names, msg, data), counter=counter, counter_mask=c_hex(msg.counter.modulo - 1) if msg.counter else "",
        comment=f"{msg.title} / {msg.zh}" if msg.title and msg.zh else msg.title or msg.zh,
    )


def _plan(typ: str, msg: ir.Message, sigs: tuple[CSignal, ...], checksum: str | None) -> dict[str, object]:
    """The struct layout and the pack/unpack statements (CMessage fields)."""
    offsets = dict(zip((s.field for s in sigs), cwords.natural_offsets([s.sig.storage_bits for s in sigs])))
    size = cwords.struct_size([s.sig.storage_bits for s in sigs])
    ck_bits = 0xFF << (8 * msg.checksum.byte) if msg.checksum is not None else 0
    peeled = cruns.peeled(sigs, offsets, size, checksum) if sigs else ()
    worded = sigs[: len(sigs) - len(peeled)]
    end = cruns.run_end(worded, offsets, size) if peeled else size
    unpack_runs = cruns.plan(worded, offsets, end, "r", 0)
    # pack reads the same words unpack writes (the checksum slot too, then drops its bits)
    pack_runs = cruns.plan(worded, offsets, end, "p", ck_bits)
    byte_fields = tuple(CByteField(s.field, s.start // 8, byte_of("v", s.start // 8)) for s in peeled)
    layout = " && ".join([f"offsetof({typ}, {s.field}) == {offsets[s.field]}u" for s in sigs] + [f"sizeof({typ}) == {size}u"])
    frame_word = " | ".join(r.placed for r in pack_runs) or "0u"
    ck_field = CNames.member(checksum) if checksum is not None else None
    if any(f.name == ck_field and r.run.swar != 0 for r in pack_runs for f in r.run.fields):
        frame_word = f"({frame_word}) & {c_hex(((1 << 64) - 1) & ~ck_bits, 64)}"
    by_byte = {b.byte: b for b in byte_fields}
    return {
        "unpack_runs": unpack_runs, "pack_runs": pack_runs, "layout_check": layout, "byte_fields": byte_fields,
        "pack_byte_stores": () if checksum is not None else byte_fields, "frame_word": frame_word,
        "frame_load": " | ".join(f"(uint64_t)src[{b}]" if b == 0 else f"((uint64_t)src[{b}] << {8 * b})" for b in range(msg.dlc)),
        "frame_stores": tuple(f"src->{by_byte[b].field}" if b in by_byte and checksum is None else byte_of("w", b) for b in range(msg.dlc)),
    }
