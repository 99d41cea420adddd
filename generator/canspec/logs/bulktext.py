"""The text output's `signal=value unit, ...` for all frames of one message at once: each signal's
texts are made as a column (a table lookup for narrow fields, one format mapped over the
physical values otherwise) and the columns joined. Gives exactly codec.text_decoder's text
(tested) with C-level loops instead of a Python call per frame."""

from __future__ import annotations

import numpy as np

from canspec import ir
from canspec.logs.bulk import physical_column
from canspec.logs.fields import MessageFrames
from canspec.reference import codec

SAFE_BITS = 52  # integer arithmetic in int64 is exact below this many bits of raw × factor + offset


def _table(sig: ir.Signal) -> np.ndarray:
    return np.array([codec.signal_text(sig, r) for r in range(sig.mask + 1)], dtype=object)


def signal_texts(sig: ir.Signal, frames: MessageFrames, tables: dict[str, np.ndarray]) -> list[str]:
    """`name=value[ unit]` of one signal for every frame."""
    raw = frames.raw(sig)
    if not sig.sign_bit and sig.length <= codec.TABLE_BITS:
        table = tables.get(sig.name)
        if table is None:
            table = tables[sig.name] = _table(sig)
        return table[raw].tolist()  # type: ignore[no-any-return]
    if sig.is_float:  # repr: the shortest text that reads back to the same float (nan, inf, -0.0)
        unit = f" {sig.unit}" if sig.unit else ""
        return [f"{sig.name}={x!r}{unit}" for x in physical_column(sig, raw).tolist()]
    if not sig.is_integer and not sig.decimals:
        return [codec.signal_text(sig, r) for r in raw.tolist()]
    texts = _numbers(sig, raw)
    if sig.labels:  # labelled raw values print their name instead (and no unit)
        hit = np.flatnonzero(np.isin(raw, np.array([lb.raw for lb in sig.labels], dtype=raw.dtype)))
        for i, r in zip(hit.tolist(), raw[hit].tolist()):
            texts[i] = codec.signal_text(sig, r)
    return texts


def _numbers(sig: ir.Signal, raw: np.ndarray) -> list[str]:
    """`name=value[ unit]` with the physical value printed in the signal's precision."""
    unit = f" {sig.unit}" if sig.unit else ""
    if sig.is_integer:
        factor, offset = int(sig.factor), int(sig.offset)
        fits = sig.length + max(abs(factor), abs(offset), 1).bit_length() + 1 < SAFE_BITS
        values = ir.to_physical(raw.astype(np.int64), factor, offset).tolist() if fits else [ir.to_physical(r, factor, offset) for r in raw.tolist()]
        return list(map(f"{sig.name}=%d{unit}".replace("%", "%%").replace("%%d", "%d", 1).__mod__, values))
    pattern = f"{sig.name}=%.{sig.decimals}f{unit}".replace("%", "%%").replace(f"%%.{sig.decimals}f", f"%.{sig.decimals}f", 1)
    return list(map(pattern.__mod__, physical_column(sig, raw).tolist()))


def message_texts(frames: MessageFrames, tables: dict[str, np.ndarray]) -> list[str]:
    """The fields text of every frame of one message (of a multiplexed one: the fields each frame holds)."""
    columns = [signal_texts(s, frames, tables) for s in frames.msg.data_signals]
    if frames.msg.is_multiplexed:
        return _page_texts(frames, columns)
    if not columns:
        return [""] * len(frames)
    if len(columns) == 1:
        return columns[0]
    return list(map(", ".join, zip(*columns)))


def _page_texts(frames: MessageFrames, columns: list[list[str]]) -> list[str]:
    """The texts joined per page layout: the frames that hold the same fields at once."""
    every = np.ones(len(frames), bool)
    held = np.stack([every if (p := frames.present(s)) is None else p for s in frames.msg.data_signals])
    layouts, which = np.unique(held.T, axis=0, return_inverse=True)
    out = np.empty(len(frames), dtype=object)
    for k, layout in enumerate(layouts):
        rows = np.flatnonzero(which.ravel() == k)
        picked = [np.asarray(columns[i], dtype=object)[rows].tolist() for i in np.flatnonzero(layout)]
        out[rows] = list(map(", ".join, zip(*picked)))
    return out.tolist()  # type: ignore[no-any-return]
