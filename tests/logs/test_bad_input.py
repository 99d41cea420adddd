"""Bad input never ends in a traceback or a silent exit 0: an unreadable file or a file in the
wrong format exits 2 with one line naming it; an input with nothing decodable exits 1 after its
summary; a closed stdout ends quietly; the progress bar shows only on a terminal."""

from __future__ import annotations

import fcntl
import os
import pty
import select
import struct
import subprocess
import sys
import termios

import pytest
from repo_paths import CANSPEC_ENV

LINE = "(1700000000.000000) can0 1801B0A0#0000000000000000\n"


def decode(*args, stdin=None):
    return subprocess.run([sys.executable, "-m", "canspec", "decode", *args], input=stdin, capture_output=True, env=CANSPEC_ENV, check=False, timeout=120)


@pytest.mark.parametrize(("name", "content", "says"), [
    ("x.blf", os.urandom(5000), "not a BLF file"),
    ("x.mf4", os.urandom(5000), "not a MF4 file"),
    ("x.asc", b"this is not\nan asc file\n", "not a Vector ASC log"),
    ("x.trc", b"0 1 2\n", "not a PEAK TRC log"),
    ("x.log", os.urandom(5000) + b"\0", "binary data, not a candump text log"),
    ("x.log", b"", "empty input"),
    ("x.log.gz", b"not gzip at all", "cannot read"),
    ("x.dat", b"123#00\n", "unknown log extension '.dat'"),
    ("x.blf", b"LOGG" + bytes(200), "not a readable BLF file (BlfError: BLF file header of 0 bytes"),
])
def test_unreadable_or_wrong_format_exits_2_with_one_line(tmp_path, name, content, says):
    path = tmp_path / name
    path.write_bytes(content)
    proc = decode(str(path))
    err = proc.stderr.decode()
    assert proc.returncode == 2, err
    assert err.strip().splitlines() == [line for line in err.strip().splitlines() if line.startswith(f"canspec decode: {path}: ")]
    assert says in err and "Traceback" not in err


def test_nothing_decodable_exits_1_after_the_summary(tmp_path):
    path = tmp_path / "garbage.log"
    path.write_text("hello\nworld\n18FEEE00#00\n")
    proc = decode(str(path))
    err = proc.stderr.decode()
    assert proc.returncode == 1
    assert f"{path}: 3 lines, 1 frames, 0 decoded" in err and f"{path}: nothing decodable in this input" in err
    # one good input and one unreadable: both reported, exit 2
    good = tmp_path / "good.log"
    good.write_text(LINE)
    proc = decode(str(good), str(tmp_path / "missing.asc"))
    assert proc.returncode == 2 and f"{good}: 1 lines, 1 frames, 1 decoded" in proc.stderr.decode()


def test_closed_stdout_ends_quietly(tmp_path):
    path = tmp_path / "big.log"
    path.write_text(LINE * 300000)
    proc = subprocess.Popen([sys.executable, "-m", "canspec", "decode", str(path)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=CANSPEC_ENV)
    assert proc.stdout.readline().startswith(b"(1700000000.000000) can0 1801B0A0")
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 0 and err == ""


def test_progress_bar_only_on_a_terminal(tmp_path):
    path = tmp_path / "bus.log"
    path.write_text(LINE * 1000)
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a terminal of 100 columns
    proc = subprocess.Popen([sys.executable, "-m", "canspec", "decode", str(path)], stdout=subprocess.DEVNULL, stderr=slave, env=CANSPEC_ENV)
    os.close(slave)
    seen = b""
    while select.select([master], [], [], 60)[0]:
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        seen += chunk
    assert proc.wait(timeout=60) == 0
    assert b"B/s" in seen or b"%|" in seen  # tqdm's bar
    assert b"B/s" not in decode(str(path)).stderr and b"%|" not in decode(str(path)).stderr


def test_options_are_documented_in_help_and_readme():
    help_text = subprocess.run([sys.executable, "-m", "canspec", "decode", "--help"], capture_output=True, text=True, env=CANSPEC_ENV, check=True).stdout
    readme = (__import__("repo_paths").ROOT / "README.md").read_text(encoding="utf-8")
    for option in ("--input-format", "--format", "--output", "--raw", "--report", "--strict", "--max-problems", "--spec"):
        assert option in help_text and option in readme, option


DAMAGED_CASES = 24


@pytest.fixture(scope="module")
def clean_logs(tmp_path_factory):
    """A short log in the binary formats and gzip (logsynth writes them as the tools do)."""
    from logs import logsynth

    out = tmp_path_factory.mktemp("clean-logs")
    frames = logsynth.frames_from_cases([(0x1801B0A0, True, bytes(range(8))), (0x123, False, b"\x01\x02")], 400)
    return [logsynth.write(fmt, out / logsynth.FORMATS[fmt], frames) for fmt in ("mf4", "blf", "candump_gz")]


@pytest.mark.parametrize("case", range(DAMAGED_CASES))
def test_a_damaged_binary_log_is_one_line_or_its_readable_part(tmp_path, clean_logs, case):
    """Bytes flipped, cut or inserted in an MF4, BLF or gzip log: asammdf, the BLF reader and zlib each fail
    their own way (MdfException, zlib.error, struct.error; fuzzing found each as an 'internal error', and asammdf's
    half-opened file printing a traceback from its __del__). canspec says 'not a readable … file' with exit 2,
    or decodes what it could read and names where the rest was lost."""
    import random

    rng = random.Random(case)
    source = clean_logs[case % len(clean_logs)]
    data = bytearray(source.read_bytes())
    for _ in range(rng.randint(1, 4)):
        i = rng.randrange(64, len(data))
        if rng.random() < 0.3:
            data = data[:i]
        else:
            data[i : i + rng.randint(1, 16)] = bytes(rng.randrange(256) for _ in range(rng.randint(0, 16)))
    path = tmp_path / source.name
    path.write_bytes(bytes(data))
    proc = decode(str(path), "--format", "json")
    err = proc.stderr.decode()
    assert proc.returncode in (0, 1, 2), err
    assert "Traceback" not in err and "Exception ignored" not in err and "internal error" not in err, err
    if proc.returncode == 2:
        assert err.strip().splitlines() == [f"canspec decode: {path}: {err.strip().split(': ', 2)[2]}"], err
