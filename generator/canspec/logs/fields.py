"""The fields of many frames of one message at once, as the reference codec reads them: a field is
bits [word_shift, word_shift + length) of the frame word — the message's dlc bytes read as one
integer, little-endian for an Intel field, big-endian for a Motorola one.

A classic frame (at most 8 bytes) is one uint64 column (frames.Batch.word, little-endian); its
big-endian word is that column byte-swapped and shifted down by the bytes the frame lacks, so a
Motorola field costs one more shift and mask. A longer (CAN FD) frame is a row of bytes; a field
is gathered from the up to 9 bytes it touches (in reversed byte order for a Motorola field: the
big-endian word of the bytes is the little-endian word of the reversed bytes)."""

from __future__ import annotations

import numpy as np

from canspec import ir

U64 = np.uint64


class MessageFrames:
    """Frames that all carry `msg` with its length."""

    def __init__(self, msg: ir.Message, word: np.ndarray, data: np.ndarray | None) -> None:
        self.msg, self.word = msg, word
        self.data = data if msg.dlc > 8 else None  # (frames, dlc) uint8
        self._big: np.ndarray | None = None

    @classmethod
    def of(cls, msg: ir.Message, batch, rows: np.ndarray | None = None) -> MessageFrames:  # type: ignore[no-untyped-def]
        """The frames of `batch` at `rows` (all of them when None)."""
        word = batch.word if rows is None else batch.word[rows]
        data = None
        if msg.dlc > 8:
            data = batch.data[:, : msg.dlc] if rows is None else batch.data[rows, : msg.dlc]
        return cls(msg, word, data)

    def __len__(self) -> int:
        return len(self.word)

    def _big_word(self) -> np.ndarray:
        if self._big is None:
            dlc = self.msg.dlc
            self._big = self.word.byteswap() >> U64(64 - 8 * dlc) if dlc else np.zeros_like(self.word)
        return self._big

    def bits(self, sig: ir.Signal) -> np.ndarray:
        """The field's bits as uint64 (no sign extension)."""
        if self.data is None:
            word = self._big_word() if sig.is_big_endian else self.word
            return (word & U64(sig.word_mask)) >> U64(sig.word_shift)
        return _gather_bits(self.data[:, ::-1] if sig.is_big_endian else self.data, sig.word_shift, sig.length)

    def raw(self, sig: ir.Signal) -> np.ndarray:
        """The raw values (uint64, or int64 when signed: two's complement wrap)."""
        bits = self.bits(sig)
        if not sig.sign_bit:
            return bits
        return ((bits ^ U64(sig.sign_bit)) - U64(sig.sign_bit)).view(np.int64)

    def present(self, sig: ir.Signal) -> np.ndarray | None:
        """Per frame, whether it holds the field: its whole chain of multiplexers holds selecting values
        (ir.Message.mux_chain); None for a field of every frame."""
        chain = self.msg.mux_chain(sig)
        if not chain:
            return None
        out = np.ones(len(self), bool)
        for cond in chain:
            raw = self.raw(self.msg.signal(cond.by))  # a multiplexer is unsigned
            out &= np.logical_or.reduce([(raw >= U64(lo)) & (raw <= U64(hi)) for lo, hi in cond.ranges])
        return out

    def checksum_ok(self) -> np.ndarray:
        """Whether the checksum byte equals the XOR of the bytes cover_mask selects."""
        check = self.msg.checksum
        assert check is not None
        if self.data is None:
            x = self.word & U64(check.cover_mask & (2**64 - 1))
            for shift in (32, 16, 8):
                x ^= x >> U64(shift)
            return (x & U64(0xFF)) == ((self.word >> U64(8 * check.byte)) & U64(0xFF))
        masks = np.frombuffer(check.cover_mask.to_bytes(self.msg.dlc, "little"), np.uint8)
        return np.bitwise_xor.reduce(self.data & masks, axis=1) == self.data[:, check.byte]

    def payloads(self) -> list[bytes]:
        """Every frame's data bytes."""
        if self.data is not None:
            return [bytes(row) for row in self.data]
        dlc = self.msg.dlc
        return [w.to_bytes(8, "little")[:dlc] for w in self.word.tolist()]


def _gather_bits(data: np.ndarray, shift: int, length: int) -> np.ndarray:
    """Bits [shift, shift + length) of each row of bytes read as one little-endian integer."""
    lo, r = divmod(shift, 8)
    take = min(8, data.shape[1] - lo)
    chunk = np.zeros((len(data), 8), np.uint8)
    chunk[:, :take] = data[:, lo: lo + take]
    bits = chunk.view("<u8").ravel() >> U64(r)
    if r + length > 64:  # the field reaches a ninth byte
        bits |= data[:, lo + 8].astype(np.uint64) << U64(64 - r)
    return bits & U64((1 << length) - 1)


def float_column(sig: ir.Signal, raw: np.ndarray) -> np.ndarray:
    """A float field's values (float64) from its bit patterns."""
    if sig.length == 32:
        with np.errstate(invalid="ignore"):  # a signalling-NaN pattern widens to a quiet NaN
            return raw.astype(np.uint32).view(np.float32).astype(np.float64)
    return np.ascontiguousarray(raw, dtype=np.uint64).view(np.float64)
