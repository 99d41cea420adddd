"""Text sequences of `vectors/sequences.json`: the frames of multi-frame texts (VINs) fed one by
one, with what reassembly must give after each (reference/textframes.py): the feed's result
(ok, length, checksum, index, inconsistent) and the text — a string once complete and valid,
`null` while incomplete, `false` when complete but invalid.

Covers, per multi-frame message: in order, out of order, repeated frames, interleaved senders
(a key signal such as the device type differing), a stale frame of the previous text after a
newer one began, recovery with the next complete set, an index beyond the text's frames, short
frames, a wrong checksum and invalid text bytes — each where the message can carry it.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from canspec import ir
from canspec.ir import textsamples
from canspec.reference import codec
from canspec.reference import textframes as tf

SAMPLE = "LSKG5GC13KA123456"
OTHER = "ZZZZZZZ13KA654321"


def frames_of(msg: ir.Message, text: bytes, **keys: int) -> list[bytes]:
    """The frames carrying `text` (already at most frames × bytes long), other fields at their base."""
    mf = msg.multiframe
    assert mf is not None
    data = text.ljust(mf.frames * mf.bytes_per_frame, bytes([mf.padding]))
    out = []
    for i in range(mf.frames):
        raw = {s.name: s.base_raw for s in msg.present({m.name: m.base_raw for m in msg.multiplexers}) if s.role != "checksum"}
        raw.update(keys)
        raw[mf.index_signal] = i
        payload = int.from_bytes(data[i * mf.bytes_per_frame : (i + 1) * mf.bytes_per_frame], "little")
        payload_sig = msg.signal(mf.payload_signal)
        raw[mf.payload_signal] = (payload ^ payload_sig.sign_bit) - payload_sig.sign_bit
        out.append(codec.pack(msg, raw))
    return out


class TextSequence:
    def __init__(self, msg: ir.Message, category: str, note: str) -> None:
        self.asm = tf.TextAssembler(msg)
        self.record: dict[str, Any] = {"category": category, "note": note, "message": msg.name, "frame_id": msg.frame_id, "steps": []}

    def feed(self, *frames: bytes) -> TextSequence:
        for data in frames:
            result = self.asm.feed(data)
            text: str | bool | None = self.asm.text()
            if text is None and self.asm.complete:
                text = False
            self.record["steps"].append({"data": data.hex().upper(), "expect": {"result": result, "text": text}})
        return self

    def done(self) -> dict[str, Any]:
        return self.record


def text_sequences(msg: ir.Message) -> Iterator[dict[str, Any]]:
    mf = msg.multiframe
    assert mf is not None
    a, b = textsamples.sample_text(mf, SAMPLE).encode(), textsamples.sample_text(mf, OTHER).encode()
    fa, fb = frames_of(msg, a), frames_of(msg, b)
    n = msg.name
    yield TextSequence(msg, "in_order", f"{n}: frames 0..{mf.frames - 1}").feed(*fa).done()
    yield TextSequence(msg, "out_of_order", f"{n}: frames in reverse order").feed(*reversed(fa)).done()
    yield TextSequence(msg, "repeated", f"{n}: every frame twice, then the text again").feed(*(f for x in fa for f in (x, x)), fa[0]).done()
    if a != b:
        yield TextSequence(msg, "stale", f"{n}: a complete text, then a frame of the next text, then the rest of it").feed(*fa, *fb).done()
        note = f"{n}: the next text begins, a stale frame of the previous one arrives, then a complete set (recovery)"
        yield TextSequence(msg, "stale", note).feed(*fa, fb[0], fa[0], *fb).done()
    other = textsamples.other_key(msg)
    if other is not None and mf.frames > 1:
        fc = frames_of(msg, b, **{other[0]: other[1]})
        mixed = [f for pair in zip(fa, fc) for f in pair]
        yield TextSequence(msg, "interleaved", f"{n}: two senders ({other[0]}) interleaved, then one complete set (recovery)").feed(*mixed, *fa).done()
    index = msg.signal(mf.index_signal)
    if index.raw_type_max >= mf.frames:
        bad = codec.pack(msg, {**codec.unpack(msg, fa[0]), mf.index_signal: mf.frames})
        yield TextSequence(msg, "index", f"{n}: an index beyond the text's frames is refused").feed(fa[0], bad, *fa[1:]).done()
    short = fa[0][:-1] if msg.dlc > 0 else b"\x00"
    yield TextSequence(msg, "length", f"{n}: a frame one byte short is refused").feed(short, *fa).done()
    if msg.checksum is not None:
        broken = bytearray(fa[0])
        broken[msg.checksum.byte] ^= 1
        yield TextSequence(msg, "checksum", f"{n}: a frame with a wrong checksum is refused").feed(bytes(broken), *fa).done()
    bad_char = 0x01 if mf.padding != 0x01 else 0x02
    yield TextSequence(msg, "invalid_text", f"{n}: a control character in the text").feed(*frames_of(msg, bytes([bad_char]) + a[1:])).done()


def all_text_sequences(can: ir.CanProtocol) -> list[dict[str, Any]]:
    out = [s for m in can.messages if m.multiframe is not None for s in text_sequences(m)]
    for i, s in enumerate(out):
        s["id"] = i
    return out
