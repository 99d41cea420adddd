"""A batch of CAN frames as columns (NumPy), the one shape every log reader produces and the
bulk decoder consumes: no Python object per frame. Its Arrow form (`to_arrow`/`from_arrow`) is
what a distributed engine (Dask, Spark's mapInArrow) passes between log readers and decoders.

Columns: timestamp (float64 s, NaN when the log has none), channel (int32 codes into
`channels`), frame_id (uint32, without flags), extended (bool), kind (uint8: data/remote/error,
candump.DATA..ERROR), dlc (uint8: data bytes), word (uint64: the first 8 data bytes read
little-endian — the frame word of reference/codec.py), line (int64: the line or record number,
for problems)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from canspec.logs.candump import Frame

COLUMNS = ("timestamp", "channel", "frame_id", "extended", "kind", "dlc", "word", "line")
DTYPES = (np.float64, np.int32, np.uint32, np.bool_, np.uint8, np.uint8, np.uint64, np.int64)


@dataclass
class Batch:
    timestamp: np.ndarray
    channel: np.ndarray
    frame_id: np.ndarray
    extended: np.ndarray
    kind: np.ndarray
    dlc: np.ndarray
    word: np.ndarray
    line: np.ndarray
    channels: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.frame_id)

    @classmethod
    def empty(cls) -> Batch:
        return cls(*(np.zeros(0, dtype=t) for t in DTYPES))

    def take(self, index: np.ndarray) -> Batch:
        """The frames at `index` (an index or boolean mask), in that order."""
        return Batch(*(getattr(self, c)[index] for c in COLUMNS), channels=self.channels)

    def channel_names(self) -> np.ndarray:
        names = np.array([*self.channels, ""], dtype=object)
        return names[np.where(self.channel < 0, len(self.channels), self.channel)]

    def to_arrow(self):  # type: ignore[no-untyped-def]
        import pyarrow as pa

        arrays = [pa.array(getattr(self, c)) for c in COLUMNS]
        codes = pa.array(self.channel, mask=self.channel < 0)
        arrays[1] = pa.DictionaryArray.from_arrays(codes, pa.array(self.channels, pa.string()))
        return pa.RecordBatch.from_arrays(arrays, names=list(COLUMNS))

    @classmethod
    def from_arrow(cls, batch) -> Batch:  # type: ignore[no-untyped-def]
        """A Batch from an Arrow record batch or table with the columns of `to_arrow`."""
        import pyarrow as pa
        import pyarrow.compute as pc

        cols = {}
        for name, dtype in zip(COLUMNS, DTYPES):
            col = batch.column(name)
            if isinstance(col, pa.ChunkedArray):
                col = col.combine_chunks()
            if name == "channel":
                col = col if pa.types.is_dictionary(col.type) else pc.dictionary_encode(col)
                channels = tuple(col.dictionary.to_pylist())
                col = col.indices.fill_null(-1)
            cols[name] = np.asarray(col.to_numpy(zero_copy_only=False), dtype=dtype)
        return cls(**cols, channels=channels)


def concat(batches: Sequence[Batch]) -> Batch:
    """One batch from several; channel codes are remapped onto one list of names."""
    batches = [b for b in batches if len(b)]
    if not batches:
        return Batch.empty()
    names: dict[str, int] = {}
    parts = []
    for b in batches:
        remap = np.array([names.setdefault(n, len(names)) for n in b.channels] + [-1], dtype=np.int32)
        parts.append(remap[np.where(b.channel < 0, len(b.channels), b.channel)])
    out = Batch(*(np.concatenate([getattr(b, c) for b in batches]) for c in COLUMNS), channels=tuple(names))
    out.channel = np.concatenate(parts)
    return out


def from_frames(frames: Sequence[Frame], lines: Sequence[int]) -> Batch:
    """Columns from frames read one at a time (the exact line reader, python-can's readers)."""
    names: dict[str, int] = {}
    n = len(frames)
    ts = np.fromiter((np.nan if f.timestamp is None else f.timestamp for f in frames), np.float64, n)
    chan = np.fromiter((-1 if f.channel is None else names.setdefault(f.channel, len(names)) for f in frames), np.int32, n)
    word = np.fromiter((int.from_bytes(f.data[:8], "little") for f in frames), np.uint64, n)
    return Batch(
        ts, chan,
        np.fromiter((f.frame_id for f in frames), np.uint32, n),
        np.fromiter((f.extended for f in frames), np.bool_, n),
        np.fromiter((f.kind for f in frames), np.uint8, n),
        np.fromiter((min(len(f.data), 255) for f in frames), np.uint8, n),
        word, np.asarray(lines, dtype=np.int64), channels=tuple(names),
    )
