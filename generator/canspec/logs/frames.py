"""A batch of CAN frames as columns (NumPy), the one shape every log reader produces and the
bulk decoder consumes: no Python object per frame. Its Arrow form (`to_arrow`/`from_arrow`) is
what a distributed engine (Dask, Spark's mapInArrow) passes between log readers and decoders.

Columns: timestamp (float64 s, NaN when the log has none), channel (int32 codes into
`channels`), frame_id (uint32, without flags), extended (bool), kind (uint8: data/remote/error,
candump.DATA..ERROR), dlc (uint8: data bytes), word (uint64: the first 8 data bytes read
little-endian — the frame word of reference/codec.py), line (int64: the line or record number,
for problems), flags (uint8: FD, BRS, ESI bits of a CAN FD frame); and `data`, the bytes of
frames longer than 8 (CAN FD): a (frames, width) uint8 matrix, each row zero past its length,
of width 0 when no frame of the batch is longer than 8 bytes (the classic path carries nothing
more than the word)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from canspec.logs.candump import Frame

COLUMNS = ("timestamp", "channel", "frame_id", "extended", "kind", "dlc", "word", "line", "flags")
DTYPES = (np.float64, np.int32, np.uint32, np.bool_, np.uint8, np.uint8, np.uint64, np.int64, np.uint8)
FD, BRS, ESI = 1, 2, 4  # flags bits (the FD frame format, bit-rate switching, error state indicator)
NO_FLAGS, NO_DATA = np.zeros(0, np.uint8), np.zeros((0, 0), np.uint8)  # defaults: replaced by zeros of the batch's length


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
    flags: np.ndarray = field(default_factory=lambda: NO_FLAGS)  # left out: all zero (classic frames)
    channels: tuple[str, ...] = ()
    data: np.ndarray = field(default_factory=lambda: NO_DATA)  # left out (or None): no frame longer than 8 bytes

    def __post_init__(self) -> None:
        n = len(self.frame_id)
        if self.flags is None or len(self.flags) != n:
            self.flags = np.zeros(n, np.uint8)
        if self.data is None or (self.data.shape[1] == 0 and len(self.data) != n):
            self.data = np.zeros((n, 0), np.uint8)

    def __len__(self) -> int:
        return len(self.frame_id)

    @classmethod
    def empty(cls) -> Batch:
        return cls(*(np.zeros(0, dtype=t) for t in DTYPES))

    def take(self, index: np.ndarray) -> Batch:
        """The frames at `index` (an index or boolean mask), in that order."""
        data = self.data[index] if self.data.shape[1] else None  # classic frames: nothing to gather
        return Batch(*(getattr(self, c)[index] for c in COLUMNS), channels=self.channels, data=data)

    def frame_bytes(self, i: int) -> bytes:
        """The data bytes of frame `i`."""
        n = int(self.dlc[i])
        if n > 8:
            return self.data[i, :n].tobytes()
        return int(self.word[i]).to_bytes(8, "little")[:n]

    def channel_names(self) -> np.ndarray:
        names = np.array([*self.channels, ""], dtype=object)
        return names[np.where(self.channel < 0, len(self.channels), self.channel)]

    def to_arrow(self):  # type: ignore[no-untyped-def]
        import pyarrow as pa

        arrays = [pa.array(getattr(self, c)) for c in COLUMNS]
        codes = pa.array(self.channel, mask=self.channel < 0)
        arrays[1] = pa.DictionaryArray.from_arrays(codes, pa.array(self.channels, pa.string()))
        names = list(COLUMNS)
        if self.data.shape[1]:  # the bytes of FD frames, null for classic ones
            long = self.dlc > 8
            arrays.append(pa.array([self.frame_bytes(i) if long[i] else None for i in range(len(self))], pa.binary()))
            names.append("data")
        return pa.RecordBatch.from_arrays(arrays, names=names)

    @classmethod
    def from_arrow(cls, batch) -> Batch:  # type: ignore[no-untyped-def]
        """A Batch from an Arrow record batch or table with the columns of `to_arrow`."""
        import pyarrow as pa
        import pyarrow.compute as pc

        cols = {}
        names = batch.schema.names
        for name, dtype in zip(COLUMNS, DTYPES):
            if name not in names:  # an older producer's batch: classic frames
                continue
            col = batch.column(name)
            if isinstance(col, pa.ChunkedArray):
                col = col.combine_chunks()
            if name == "channel":
                col = col if pa.types.is_dictionary(col.type) else pc.dictionary_encode(col)
                channels = tuple(col.dictionary.to_pylist())
                col = col.indices.fill_null(-1)
            cols[name] = np.asarray(col.to_numpy(zero_copy_only=False), dtype=dtype)
        data = None
        if "data" in names:
            data = data_matrix([b or b"" for b in batch.column("data").to_pylist()])
        return cls(**cols, channels=channels, data=data)


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
    width = max(b.data.shape[1] for b in batches)
    data = np.concatenate([np.pad(b.data, ((0, 0), (0, width - b.data.shape[1]))) for b in batches]) if width else None
    out = Batch(*(np.concatenate([getattr(b, c) for b in batches]) for c in COLUMNS), channels=tuple(names), data=data)
    out.channel = np.concatenate(parts)
    return out


def data_matrix(payloads: Sequence[bytes]) -> np.ndarray | None:
    """The `data` matrix of frames with these payloads (None when none is longer than 8 bytes)."""
    width = max(map(len, payloads), default=0)
    if width <= 8:
        return None
    out = np.zeros((len(payloads), width), np.uint8)
    for i, p in enumerate(payloads):
        if len(p) > 8:
            out[i, : len(p)] = np.frombuffer(p, np.uint8)
    return out


def from_frames(frames: Sequence[Frame], lines: Sequence[int]) -> Batch:
    """Columns from frames read one at a time (the exact line reader, python-can's readers)."""
    names: dict[str, int] = {}
    n = len(frames)
    ts = np.fromiter((np.nan if f.timestamp is None else f.timestamp for f in frames), np.float64, n)
    chan = np.fromiter((-1 if f.channel is None else names.setdefault(f.channel, len(names)) for f in frames), np.int32, n)
    word = np.fromiter((int.from_bytes(f.data[:8], "little") for f in frames), np.uint64, n)
    flags = np.fromiter((f.flags for f in frames), np.uint8, n)
    return Batch(
        ts, chan,
        np.fromiter((f.frame_id for f in frames), np.uint32, n),
        np.fromiter((f.extended for f in frames), np.bool_, n),
        np.fromiter((f.kind for f in frames), np.uint8, n),
        np.fromiter((min(len(f.data), 255) for f in frames), np.uint8, n),
        word, np.asarray(lines, dtype=np.int64), flags, channels=tuple(names), data=data_matrix([f.data for f in frames]),
    )
