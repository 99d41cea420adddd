"""The bulk BLF reader reads exactly what python-can's BLFReader reads: every frame object
(classic, remote, error, CAN FD), its ID, length, data, channel and time stamp — also when
objects straddle log containers and bulk steps."""

from __future__ import annotations

import random
import sys
from pathlib import Path

import can
import pytest
from canspec.logs import blf_bulk, logread
from canspec.logs import frames as fr

sys.path.insert(0, str(Path(__file__).resolve().parent))
import logsynth


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
            out.append(can.Message(timestamp=t, arbitration_id=fid, is_extended_id=ext, is_fd=True, data=rng.randbytes(size), channel=1,
                                   bitrate_switch=rng.random() < 0.5, error_state_indicator=rng.random() < 0.2))
        else:
            out.append(can.Message(timestamp=t, arbitration_id=fid, is_extended_id=ext, data=rng.randbytes(rng.randrange(9)), channel=rng.randrange(2)))
    return out


@pytest.mark.parametrize(("buffer_bytes", "fd64"), [(blf_bulk.BUFFER_BYTES, False), (5000, False), (5000, True)])
def test_bulk_blf_equals_python_can(tmp_path, monkeypatch, buffer_bytes, fd64):
    """fd64: FD frames as CAN_FD_MESSAGE_64 objects (logsynth's writer), else python-can's CAN_FD_MESSAGE."""
    monkeypatch.setattr(blf_bulk, "BUFFER_BYTES", buffer_bytes)
    path = tmp_path / "mixed.blf"
    with (logsynth._blf64_writer() if fd64 else can.BLFWriter)(str(path)) as writer:
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
        assert mine.frame_bytes(i) == data, i
        assert int(mine.flags[i]) == (fr.FD * m.is_fd | fr.BRS * m.bitrate_switch | fr.ESI * m.error_state_indicator if kind != 2 else 0), i
        assert abs(mine.timestamp[i] - m.timestamp) < 1e-6
    assert mine.line.tolist() == list(range(1, 6001))
