"""The bulk BLF reader reads exactly what python-can's BLFReader reads: every frame object
(classic, remote, error, CAN FD), its ID, length, data, channel and time stamp — also when
objects straddle log containers and bulk steps."""

from __future__ import annotations

import random

import can
import pytest
from canspec.logs import blf_bulk, logread
from canspec.logs import frames as fr


def messages(n, seed=5):
    rng = random.Random(seed)
    out = []
    for i in range(n):
        t = 1700000000 + i * 0.000137
        pick = rng.random()
        ext = rng.random() < 0.5
        fid = rng.getrandbits(29 if ext else 11)
        if pick < 0.05:
            out.append(can.Message(timestamp=t, arbitration_id=fid, is_extended_id=ext, is_remote_frame=True, dlc=rng.randrange(9), channel=rng.randrange(3)))
        elif pick < 0.08:
            out.append(can.Message(timestamp=t, is_error_frame=True, arbitration_id=fid, data=bytes(8), channel=0))
        elif pick < 0.15:
            size = rng.choice((12, 16, 24, 48, 64))
            out.append(can.Message(timestamp=t, arbitration_id=fid, is_extended_id=ext, is_fd=True, data=rng.randbytes(size), channel=1))
        else:
            out.append(can.Message(timestamp=t, arbitration_id=fid, is_extended_id=ext, data=rng.randbytes(rng.randrange(9)), channel=rng.randrange(2)))
    return out


@pytest.mark.parametrize("buffer_bytes", [blf_bulk.BUFFER_BYTES, 5000])
def test_bulk_blf_equals_python_can(tmp_path, monkeypatch, buffer_bytes):
    monkeypatch.setattr(blf_bulk, "BUFFER_BYTES", buffer_bytes)
    path = tmp_path / "mixed.blf"
    with can.BLFWriter(str(path)) as writer:
        for msg in messages(6000):
            writer.on_message_received(msg)
    mine = fr.concat([chunk.batch for chunk in logread.read_log(str(path))])
    theirs = list(can.BLFReader(str(path)))
    assert len(mine) == len(theirs) == 6000
    names = mine.channel_names()
    for i, m in enumerate(theirs):
        kind = 2 if m.is_error_frame else 1 if m.is_remote_frame else 0
        data = bytes(m.data) if kind == 0 else b""
        expected = (m.arbitration_id, m.is_extended_id, kind, len(data), int.from_bytes(data[:8], "little"), str(m.channel))
        assert (int(mine.frame_id[i]), bool(mine.extended[i]), int(mine.kind[i]), int(mine.dlc[i]), int(mine.word[i]), names[i]) == expected, i
        assert abs(mine.timestamp[i] - m.timestamp) < 1e-6
    assert mine.line.tolist() == list(range(1, 6001))
