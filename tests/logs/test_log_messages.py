"""Nothing in a log is dropped without a word, and what is said is true. Found by an independent
tester: python-can's readers printed raw text without file or line ("DLC vs Data Length mismatch
15[64] != 8", "TRCReader: Failed to parse message ...") and the records were dropped uncounted;
ASC lines with a time stamp python-can does not take (0.0x2000, -5.0, nan) vanished silently;
`--report` printed negative periods for a log whose time goes backwards; a negative candump time
stamp was "not a number"; UTF-16 or UTF-8-BOM logs were "binary data" or a malformed first line; an
unknown BLF compression method was "nothing decodable"; a 0-byte BLF object a raw ValueError; a TRC
3.0 file a misleading "invalid literal for int()"; `#R99999` and `#RZ` were remote frames."""

from __future__ import annotations

import json
import logging
import re
import struct
import subprocess
import sys

import can
import pytest
from canspec.logs import logread
from canspec.logs.candump import REMOTE, LineError, parse_line
from repo_paths import CANSPEC_ENV

ASC_HEAD = "date Sat Dec 05 23:46:14.732 2026\nbase hex  timestamps absolute\ninternal events logged\n" \
           "Begin Triggerblock Thu Jan 01 00:16:40.0 1970\n"  # 4 lines: the records start at line 5
DATA = "BE 48 E4 D8 0B BA 9A BA"
FRAME = "1801B0A0#BE48E4D80BBA9ABA"


def decode(*args):
    return subprocess.run([sys.executable, "-m", "canspec", "decode", *args], capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=120)


def summary(err: str) -> str:
    return next(line for line in err.splitlines() if " lines, " in line)


def test_python_can_warnings_are_malformed_lines_at_their_line(tmp_path):
    asc = tmp_path / "fd.asc"
    fd = " 0.010000 CANFD   1 Rx 1801B0A0x  1 0 {dlc} 8 " + DATA + "  0 0 3000 0 0 0 0 0\n"
    asc.write_text(ASC_HEAD + fd.format(dlc="8") + fd.format(dlc="f") + fd.format(dlc="8"))
    proc = decode(str(asc))
    assert proc.returncode == 0, proc.stderr
    assert "mismatch 15[64]" not in proc.stderr  # the library's own text is not printed raw
    assert f"{asc}:6: error: malformed line: DLC F means 64 data bytes, but the data length is 8: '0.010000 CANFD" in proc.stderr
    assert f"{asc}: 7 lines, 2 frames, 2 decoded" in summary(proc.stderr) and "1 malformed" in summary(proc.stderr)
    trc = tmp_path / "short.trc"
    record = "{n:>6})  {t:>13.1f}  Rx     1801B0A0  8  {data}\n"
    trc.write_text(";$FILEVERSION=1.1\n;$STARTTIME=44548.6\n" + "".join(
        record.format(n=i + 1, t=i * 10.0, data=DATA[:-3] if i == 1 else DATA) for i in range(3)))
    proc = decode(str(trc))
    assert proc.returncode == 0, proc.stderr
    assert "TRCReader" not in proc.stderr and "Failed to parse" not in proc.stderr
    assert f"{trc}:4: error: malformed line: a TRC record with too few columns (fewer data bytes than its length, or a column missing): '2)" \
        in proc.stderr
    assert f"{trc}: 5 lines, 2 frames, 2 decoded" in summary(proc.stderr) and "1 malformed" in summary(proc.stderr)
    assert decode("--strict", str(trc)).returncode == 1


def test_the_can_loggers_are_left_as_they_were(tmp_path):
    path = tmp_path / "fd.asc"
    path.write_text(ASC_HEAD + f" 0.010000 CANFD   1 Rx 1801B0A0x  1 0 f 8 {DATA}  0 0 3000 0 0 0 0 0\n")
    logger = logging.getLogger("can")
    before = (list(logger.handlers), logger.level, logger.propagate)
    problems = [p for chunk in logread.read_log(str(path)) for p in chunk.problems]
    assert [line for line, _ in problems] == [5]
    assert (list(logger.handlers), logger.level, logger.propagate) == before


def test_asc_frame_lines_python_can_would_skip_are_malformed(tmp_path):
    path = tmp_path / "times.asc"
    lines = ["0.000000", "0.0x2000", "-5.0", "nan", "1e400", "7", "0.050000"]
    path.write_text(ASC_HEAD + "".join(f" {t} 1  1801B0A0x       Rx   d 8 {DATA}\n" for t in lines)
                    + f" 1  1801B0A0x       Rx   d 8 {DATA}\n 0.060000 1 Statistic: D 1 R 0\nEnd TriggerBlock\n")
    proc = decode(str(path))
    assert proc.returncode == 0, proc.stderr
    for line, why in ((6, "time stamp '0.0x2000' is not a number"), (7, "time stamp -5.0 is negative (refused)"),
                      (8, "time stamp nan is not a finite number"), (9, "time stamp 1e400 is not a finite number"),
                      (10, "time stamp 7 is not in the ASC form SECONDS.FRACTION"), (12, "a frame record without a time stamp")):
        assert f"{path}:{line}: error: malformed line: {why}: " in proc.stderr
    assert f"{path}: 14 lines, 2 frames, 2 decoded" in summary(proc.stderr) and "6 malformed" in summary(proc.stderr)


def test_report_on_a_log_whose_time_goes_backwards(tmp_path):
    path = tmp_path / "back.log"
    path.write_text("".join(f"({t:.1f}) can0 {FRAME}\n" for t in (5.0, 1.0, 3.0, 3.5)))
    proc = decode("--report", str(path))
    assert proc.returncode == 0, proc.stderr
    assert f"{path}:2: warning: time goes backwards (1.000000 s after 5.000000 s); 1 step back in this log, left out of the measured periods" \
        in proc.stderr
    row = next(line for line in proc.stdout.splitlines() if line.startswith("autocar_eps_command"))
    assert not re.search(r"\s-\d", row) and " 1250.000 " in row and " 500.0..2000.0 " in row  # no negative period
    assert "time goes backwards: autocar_eps_command ×1 (first at line 2); periods are measured over the steps forward only" in proc.stdout
    (report,) = json.loads(decode("--report", "--format", "json", str(path)).stdout)["inputs"]
    eps = next(r for r in report["messages"] if r["message"] == "autocar_eps_command")
    assert (eps["period_ms"], eps["min_period_ms"], eps["max_period_ms"], eps["time_backwards"]) == (1250.0, 500.0, 2000.0, 1)
    assert report["time_backwards"] == {"count": 1, "first_line": 2, "first_time": 1.0, "time_before": 5.0}
    path.write_text("".join(f"({t:.1f}) can0 {FRAME}\n" for t in (1.0, 3.0, 5.0)))
    proc = decode("--report", str(path))
    assert "backwards" not in proc.stderr + proc.stdout and " 2000.000 " in proc.stdout


def test_candump_negative_time_and_remote_frame_forms():
    with pytest.raises(LineError, match=r"time stamp \(-5.0\) is negative \(refused\)"):
        parse_line(f"(-5.0) can0 {FRAME}")
    with pytest.raises(LineError, match=r"time stamp \(-x\) is not a number"):
        parse_line(f"(-x) can0 {FRAME}")
    for tail in ("R", "R0", "R8", "RF", "R8_F", "r"):  # can-utils: an optional DLC digit; candump -8 writes 8_9..8_F
        assert parse_line(f"(1.0) can0 1801B0A0#{tail}").kind == REMOTE, tail
    for tail in ("R99999", "RZ", "R8_", "R8_5", "R12"):
        with pytest.raises(LineError, match="expected nothing, one DLC digit"):
            parse_line(f"(1.0) can0 1801B0A0#{tail}")


def test_candump_remote_frames_on_the_command_line(tmp_path):
    path = tmp_path / "rtr.log"
    path.write_text(f"(1.0) can0 1801B0A0#R\n(1.1) can0 1801B0A0#R99999\n(1.2) can0 1801B0A0#RZ\n(1.3) can0 {FRAME}\n")
    proc = decode(str(path))
    assert f"{path}:2: error: malformed line: remote frame '1801B0A0#R99999'" in proc.stderr and f"{path}:3: error: malformed line" in proc.stderr
    assert f"{path}: 4 lines, 2 frames, 1 decoded, 1 remote" in summary(proc.stderr) and "2 malformed" in summary(proc.stderr)


def test_byte_order_marks(tmp_path):
    path = tmp_path / "bom.log"
    path.write_bytes(b"\xef\xbb\xbf" + f"(1.0) can0 {FRAME}\n".encode())
    proc = decode(str(path))
    assert proc.returncode == 0 and "malformed" not in summary(proc.stderr).replace("0 malformed", "")
    assert f"{path}: 1 lines, 1 frames, 1 decoded" in summary(proc.stderr)
    asc = tmp_path / "bom.asc"
    asc.write_bytes(b"\xef\xbb\xbf" + (ASC_HEAD + f" 0.000000 1  1801B0A0x       Rx   d 8 {DATA}\n").encode())
    assert f"{asc}: 5 lines, 1 frames, 1 decoded" in summary(decode(str(asc)).stderr)
    for encoding, mark, name in (("utf-16", "FF FE", "UTF-16"), ("utf-16-be", "FE FF", "UTF-16"), ("utf-32", "FF FE 00 00", "UTF-32")):
        path.write_bytes(("\ufeff" if encoding.endswith("be") else "").encode(encoding) + f"(1.0) can0 {FRAME}\n".encode(encoding))
        proc = decode(str(path))
        assert proc.returncode == 2
        assert proc.stderr.strip() == f"canspec decode: {path}: the file is {name} text (byte order mark {mark}); re-save it as UTF-8 or ASCII"


def write_blf(path, n: int) -> bytes:
    """An uncompressed BLF of n classic frames, 10 48-byte objects per log container (none is split)."""
    with can.BLFWriter(str(path), compression_level=0, max_container_size=480) as w:
        for i in range(n):
            w.on_message_received(can.Message(timestamp=1000 + i / 100, arbitration_id=0x1801B0A0, data=bytes.fromhex(DATA), channel=0))
    return path.read_bytes()


def test_blf_unknown_compression_and_an_object_of_0_bytes(tmp_path):
    path = tmp_path / "method.blf"
    data = bytearray(write_blf(path, 30))
    second = 144 + struct.unpack_from("<L", data, 144 + 8)[0]  # the second log container
    assert data[second:second + 4] == b"LOBJ"
    struct.pack_into("<H", data, second + 16, 7)
    path.write_bytes(data)
    proc = decode(str(path))
    assert proc.returncode == 0, proc.stderr
    assert f"{path}:11: error: the BLF log container at byte {second} has unknown compression method 7 (0 none, 2 zlib); its frames are not read" \
        in proc.stderr
    assert f"{path}: 20 lines, 20 frames, 20 decoded" in summary(proc.stderr) and "1 malformed" in summary(proc.stderr)
    struct.pack_into("<L", data, second + 8, 0)
    path.write_bytes(data)
    proc = decode(str(path))
    assert proc.returncode == 0, proc.stderr
    assert "ValueError" not in proc.stderr
    assert f"{path}:11: error: the BLF object at byte {second} claims 0 bytes, less than its 16-byte header; the rest of the file is not read" \
        in proc.stderr
    assert f"{path}: 10 lines, 10 frames, 10 decoded" in summary(proc.stderr)


def test_an_unsupported_trc_version_is_named(tmp_path):
    path = tmp_path / "v30.trc"
    path.write_text(";$FILEVERSION=3.0\n;$STARTTIME=44548.6\n;$COLUMNS=N,O,T,B,I,d,R,L,D\n"
                    f"      1         0.000 DT  1 1801B0A0 Rx -  8    {DATA}\n")
    proc = decode(str(path))
    assert proc.returncode == 2
    assert proc.stderr.strip() == f"canspec decode: {path}: unsupported TRC version 3.0 (supported: 1.0, 1.1, 1.3, 2.0, 2.1)"


def test_a_trc_record_without_a_finite_time_is_malformed(tmp_path):
    """python-can reads a TRC time offset `nan` as a time stamp nan: the frame had no time."""
    path = tmp_path / "nan.trc"
    path.write_text(";$FILEVERSION=2.1\n;$STARTTIME=44548.6\n;$COLUMNS=N,O,T,B,I,d,R,L,D\n"
                    + "".join(f"      {n}         {t} DT  1 1801B0A0 Rx -  8    {DATA}\n" for n, t in ((1, "0.000"), (2, "nan"), (3, "7.000"))))
    proc = decode(str(path))
    assert proc.returncode == 0, proc.stderr
    assert f"{path}:5: error: malformed line: time stamp nan is not a finite number: " in proc.stderr, proc.stderr
    assert f"{path}: 6 lines, 2 frames, 2 decoded" in summary(proc.stderr) and "1 malformed" in summary(proc.stderr)
