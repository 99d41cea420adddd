"""The Rust view of a multi-frame text (a VIN over several frames): how the generated reassembler
splits a text into frames and puts it back together."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from canspec import ir
from canspec.ir.names import pascal
from canspec.ir.textsamples import other_key, sample_text
from canspec.render.literals import RUST
from canspec.targets.rust.bits import cast

if TYPE_CHECKING:
    from canspec.targets.rust.model import RustField


@dataclass(frozen=True)
class RustText:
    """Multi-frame text: how its frames are split and reassembled."""

    index: RustField
    payload: RustField
    text_length: int
    frames: int
    bytes_per_frame: int
    total: int  # frames × bytes_per_frame
    padding: str
    assembler: str
    seen_type: str  # the bit set of frames seen
    all_seen: str  # that bit set when every frame has been seen
    index_store: str  # `index` (usize) as the index field's raw type
    index_of: str  # the frame index (usize) of `frame`
    error_index: str  # `index` as the error's u8
    chunk_to_raw: str  # `word` ([u8; 8]) as the payload's raw value
    raw_to_chunk: str  # `frame`'s payload as bytes
    text_pattern: str  # proptest: a Rust string literal of the regex of a text that round-trips
    keys: tuple[RustField, ...]  # fields every frame of one text shares (MultiFrame.key_signals)
    other_key: RustField | None  # tests: a key field with another valid raw value, other_raw
    other_raw: str
    sample_a: str  # tests: two texts that round-trip
    sample_b: str



SEEN_TYPES = ((32, "u32"), (64, "u64"), (128, "u128"))
MAX_TEXT_FRAMES = SEEN_TYPES[-1][0]
SAMPLE_TEXTS = ("LSKG5GC13KA123456", "COCKPIT0000000042")


def build_text(msg: ir.Message, fields: tuple[RustField, ...]) -> RustText | None:
    m = msg.multiframe
    if m is None:
        return None
    index = next(f for f in fields if f.sig.name == m.index_signal)
    payload = next(f for f in fields if f.sig.name == m.payload_signal)
    if index.sig.signed:  # the frame number is the field's bit pattern
        index_of = f"(frame.{index.names.raw_getter}() as u64 & {RUST.integer(index.sig.mask)}) as usize"
    else:
        index_of = f"usize::from(frame.{index.names.raw_getter}())" if index.raw_type in ("u8", "u16") else f"frame.{index.names.raw_getter}() as usize"
    word = "u64::from_le_bytes(word)"
    if payload.raw_type == "u64":
        to_chunk = f"frame.{payload.names.raw_getter}().to_le_bytes()"
    elif payload.sig.signed:
        to_chunk = f"(frame.{payload.names.raw_getter}() as u64).to_le_bytes()"
    else:
        to_chunk = f"u64::from(frame.{payload.names.raw_getter}()).to_le_bytes()"
    pad = m.padding
    ranges = [(lo, hi) for lo, hi in ((0x20, pad - 1), (pad + 1, 0x7E)) if lo <= hi] if 0x20 <= pad <= 0x7E else [(0x20, 0x7E)]
    pattern = "[" + "".join(f"\\x{{{lo:02X}}}-\\x{{{hi:02X}}}" for lo, hi in ranges) + f"]{{0,{m.text_length}}}"
    found = other_key(msg)
    other = (next(f for f in fields if f.sig.name == found[0]), RUST.integer(found[1])) if found is not None else (None, "")
    return RustText(
        index=index,
        payload=payload,
        text_length=m.text_length,
        frames=m.frames,
        bytes_per_frame=m.bytes_per_frame,
        total=m.frames * m.bytes_per_frame,
        padding=RUST.hex(pad, 2),
        assembler=f"{pascal(msg.name)}Text",
        seen_type=next(t for n, t in SEEN_TYPES if m.frames <= n),
        all_seen=RUST.integer((1 << m.frames) - 1),
        index_store=cast("index", "usize", index.raw_type),
        index_of=index_of,
        error_index=f"frame.{index.names.raw_getter}()" if index.raw_type == "u8" else "u8::try_from(index).unwrap_or(u8::MAX)",
        chunk_to_raw=cast(word, "u64", payload.raw_type),
        raw_to_chunk=to_chunk,
        text_pattern=RUST.string(pattern),
        keys=tuple(f for f in fields if f.sig.name in m.key_signals),
        other_key=other[0],
        other_raw=other[1],
        sample_a=sample_text(m, SAMPLE_TEXTS[0]),
        sample_b=sample_text(m, SAMPLE_TEXTS[1]),
    )
