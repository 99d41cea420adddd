"""Damaged records in ASC, TRC and BLF logs are malformed input like a bad candump line: reported at
FILE:LINE (or record), counted in the summary, exit 0 (1 with --strict), and the rest of the file is
still read where it can be. Found by an independent tester: an ID over 29 bits crashed ("internal
error: OverflowError"), one bad record silently dropped the rest of an ASC/TRC file with exit 0 and
"0 lines", and a truncated BLF gave part of its frames with no word."""

from __future__ import annotations

import random
import struct
import subprocess
import sys

import can
import pytest
from canspec.logs import blf_bulk, logread
from repo_paths import CANSPEC_ENV

ASC_HEAD = "date Sat Dec 05 23:46:14.732 2026\nbase hex  timestamps absolute\ninternal events logged\n" \
           "Begin Triggerblock Thu Jan 01 00:16:40.0 1970\n 0.000000 Start of measurement\n"
TRC_HEAD = ";$FILEVERSION=2.1\n;$STARTTIME=44548.6\n;$COLUMNS=N,O,T,B,I,d,R,L,D\n"
DATA = "BE 48 E4 D8 0B BA 9A BA"


def decode(*args):
    return subprocess.run([sys.executable, "-m", "canspec", "decode", *args], capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=120)


def asc_line(i: int, frame_id: str, data: str = DATA) -> str:
    return f" {i / 100:.6f} 1  {frame_id}x       Rx   d 8 {data}\n"


def trc_line(i: int, frame_id: str, data: str = DATA) -> str:
    return f"{i:>7}      {i * 10:>8.3f} DT  1 {frame_id} Rx -  8    {data}\n"


def summary(err: str) -> str:
    return err.strip().splitlines()[-1]


def test_an_id_over_29_bits_in_asc_or_trc_is_a_malformed_line(tmp_path):
    for name, head, line in (("big.asc", ASC_HEAD, asc_line), ("big.trc", TRC_HEAD, trc_line)):
        path = tmp_path / name
        first = head.count("\n") + 1
        path.write_text(head + line(0, "1801B0A0") + line(1, "FFFFFFFFFF") + line(2, "1801B0A0"))
        proc = decode(str(path))
        assert proc.returncode == 0, proc.stderr
        assert "internal error" not in proc.stderr and "Traceback" not in proc.stderr
        assert f"{path}:{first + 1}: error: malformed line: frame ID FFFFFFFFFF does not fit 29 bits" in proc.stderr
        assert f"{path}: {first + 2} lines, 2 frames, 2 decoded" in summary(proc.stderr) and "1 malformed" in summary(proc.stderr)
        assert decode("--strict", str(path)).returncode == 1


def test_one_bad_asc_or_trc_record_is_counted_and_the_rest_is_read(tmp_path):
    for name, head, line in (("mid.asc", ASC_HEAD, asc_line), ("mid.trc", TRC_HEAD, trc_line)):
        path = tmp_path / name
        records = [line(i, "1801B0A0", DATA[:-2] + "ZZ" if i == 3 else DATA) for i in range(200)]
        path.write_text(head + "".join(records))
        first = head.count("\n") + 1
        proc = decode(str(path))
        assert proc.returncode == 0, proc.stderr
        assert f"{path}:{first + 3}: error: malformed line: unreadable {name[-3:].upper()} record (ValueError: " in proc.stderr
        assert f"{path}: {first + 199} lines, 199 frames, 199 decoded" in summary(proc.stderr) and "1 malformed" in summary(proc.stderr)
        assert len(proc.stdout.splitlines()) == 199
        assert decode("--strict", str(path)).returncode == 1


@pytest.mark.parametrize("after_header", ["", "internal events logged\n", "Begin Triggerblock Thu Jan 01 00:16:40.0 1970\n"])
def test_the_first_asc_record_right_after_the_header_is_read(tmp_path, after_header):
    """python-can's ASC header parse consumes the line after `date`/`base` (`Begin Triggerblock`
    where a file has one): a file without it lost its first frame, with no word."""
    path = tmp_path / "short.asc"
    head = "date Sat Dec 05 23:46:14.732 2026\nbase hex  timestamps absolute\n" + after_header
    path.write_text(head + "".join(asc_line(i, "1801B0A0") for i in range(3)))
    proc = decode(str(path))
    first = head.count("\n") + 1
    assert proc.returncode == 0 and len(proc.stdout.splitlines()) == 3, proc.stderr
    assert f"{path}: {first + 2} lines, 3 frames, 3 decoded" in summary(proc.stderr)


def test_an_unparsable_trc_header_makes_the_file_unreadable(tmp_path):
    path = tmp_path / "start.trc"
    path.write_text(TRC_HEAD.replace("44548.6", "abc") + trc_line(0, "1801B0A0"))
    proc = decode(str(path))
    assert proc.returncode == 2
    assert proc.stderr.strip() == f"canspec decode: {path}: not a readable TRC file (ValueError: could not convert string to float: 'abc')"


def write_blf(path, n: int, compression_level: int = -1) -> bytes:
    rng = random.Random(n)  # data that does not compress away: the file has something to cut
    with can.BLFWriter(str(path), compression_level=compression_level) as w:
        for i in range(n):
            w.on_message_received(can.Message(timestamp=1000 + i / 100, arbitration_id=0x1801B0A0, data=rng.randbytes(8), channel=0))
    return path.read_bytes()


def test_a_truncated_blf_is_reported_with_what_is_missing(tmp_path):
    path = tmp_path / "cut.blf"
    whole = write_blf(path, 300)
    cut = len(whole) * 2 // 3
    path.write_bytes(whole[:cut])
    proc = decode(str(path))
    assert proc.returncode == 0, proc.stderr
    frames = int(summary(proc.stderr).split(" lines, ")[1].split(" frames")[0])
    assert 0 < frames < 300 and "1 malformed" in summary(proc.stderr)
    size = struct.unpack_from("<L", whole, 144 + 8)[0]  # the log container after the 144-byte file header
    assert f"{path}:{frames + 1}: error: truncated BLF file: it ends inside the object at byte 144 ({144 + size - cut} of its {size} bytes missing)" \
        in proc.stderr
    assert decode("--strict", str(path)).returncode == 1
    path.write_bytes(whole)  # the whole file: no problem
    assert "malformed" not in decode(str(path)).stderr.replace("0 malformed", "")


def claim_huge(data: bytes, inner: int) -> bytes:
    """An uncompressed BLF whose `inner`-th object (0: the log container) claims 0xFFFFFFF0 bytes."""
    at = -1
    for _ in range(inner + 1):
        at = data.index(b"LOBJ", at + 1)
    return data[: at + 8] + struct.pack("<L", 0xFFFFFFF0) + data[at + 12:]


def test_a_blf_object_claiming_more_bytes_than_follow_is_reported(tmp_path):
    path = tmp_path / "huge.blf"
    path.write_bytes(claim_huge(write_blf(path, 10, compression_level=0), 2))
    proc = decode(str(path))
    assert proc.returncode == 0, proc.stderr
    assert f"{path}:2: error: a BLF object claims 4294967280 bytes but " in proc.stderr and "; the rest of the file (" in proc.stderr
    assert f"{path}: 1 lines, 1 frames, 1 decoded" in summary(proc.stderr)


def test_a_huge_blf_object_mid_file_stops_the_reading_not_the_memory(tmp_path, monkeypatch):
    """Read in bulk steps, the bytes after an object claiming 4 GiB would pile up waiting for it;
    once they exceed a bulk step the object is reported and reading stops."""
    monkeypatch.setattr(blf_bulk, "BUFFER_BYTES", 5000)
    path = tmp_path / "mid.blf"
    path.write_bytes(claim_huge(write_blf(path, 20000, compression_level=0), 5))
    chunks = list(logread.read_log(str(path)))
    problems = [p for c in chunks for p in c.problems]
    assert sum(len(c.batch) for c in chunks) == 4
    assert len(problems) == 1 and problems[0][0] == 5 and problems[0][1].startswith("a BLF object claims 4294967280 bytes")
