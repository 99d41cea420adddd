"""The reference reassembly of multi-frame text (a VIN), read from the IR: the rules the C
`_rx_feed`/`_rx_get`, the Python `…TextAssembler` and the Rust `…Text` follow, and which the
shared sequence vectors record. (Sample texts and a second key value: ir/textsamples.py.)

- A frame that does not decode (wrong length, wrong checksum) or whose index is outside
  0..frames-1 is refused and changes nothing.
- A frame contradicts the frames taken when one of the text's key signals (`MultiFrame.key_signals`,
  e.g. the device type) differs, or when its index was taken with a different chunk: the frames
  taken are dropped and reassembly restarts from this frame ("inconsistent"). Frames of two
  senders, or of a text and the next one at the same index, are never mixed. (The wire carries
  no text identifier: a frame of the previous text at an index the new one has not yet sent
  looks like the new text's own, until the new text's frame of that index arrives.)
- Once every index has been taken the text is the bytes before the first padding byte: every
  byte from there on, and every byte beyond the text length, must be padding, and the text
  printable ASCII (0x20..0x7E); otherwise it is invalid. Later frames that agree keep it complete.
"""

from __future__ import annotations

from canspec import ir
from canspec.reference import codec

OK, LENGTH, CHECKSUM, INDEX, INCONSISTENT = "ok", "length", "checksum", "index", "inconsistent"
PRINTABLE = range(0x20, 0x7F)


def text_of(mf: ir.MultiFrame, chunks: list[bytes]) -> str | None:
    """The text of a complete set of chunks, or None when its bytes break the rules."""
    data = b"".join(chunks)
    end = data.find(bytes([mf.padding]))
    end = len(data) if end < 0 else end
    if end > mf.text_length or any(b != mf.padding for b in data[end:]) or any(b not in PRINTABLE for b in data[:end]):
        return None
    return data[:end].decode("ascii")


class TextAssembler:
    """Reassembly state of one multi-frame message."""

    def __init__(self, msg: ir.Message) -> None:
        assert msg.multiframe is not None
        self.msg, self.mf = msg, msg.multiframe
        self.chunks: dict[int, bytes] = {}
        self.keys: tuple[int, ...] = ()

    def feed(self, data: bytes) -> str:
        """One frame: OK, LENGTH, CHECKSUM, INDEX or INCONSISTENT (the frame restarted reassembly)."""
        if len(data) != self.msg.dlc:
            return LENGTH
        if not codec.checksum_ok(self.msg, data):
            return CHECKSUM
        raw = codec.unpack(self.msg, data)
        mf = self.mf
        index = raw[mf.index_signal]
        if not 0 <= index < mf.frames:
            return INDEX
        chunk = (raw[mf.payload_signal] & ((1 << (8 * mf.bytes_per_frame)) - 1)).to_bytes(mf.bytes_per_frame, "little")
        keys = tuple(raw[k] for k in mf.key_signals)
        result = OK
        if self.chunks and (keys != self.keys or self.chunks.get(index, chunk) != chunk):
            self.chunks.clear()
            result = INCONSISTENT
        if not self.chunks:
            self.keys = keys
        self.chunks[index] = chunk
        return result

    @property
    def complete(self) -> bool:
        return len(self.chunks) == self.mf.frames

    def text(self) -> str | None:
        """The text once complete and valid; None while incomplete or when invalid (see `valid`)."""
        return text_of(self.mf, [self.chunks[i] for i in range(self.mf.frames)]) if self.complete else None
