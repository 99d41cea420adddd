"""`canspec decode -o`: a file is written beside the target and renamed over it only when the run
exits 0 or 1, so an unreadable input leaves the old file as it was (the tester found it emptied, or
a CSV cut to its header) and no temporary behind; a Parquet -o that names a file fails before any
decoding (it used to decode everything, then end in NotADirectoryError)."""

from __future__ import annotations

import os
import stat
import subprocess
import sys

import pytest
from repo_paths import CANSPEC_ENV

LINE = "(1700000000.000000) can0 1801B0A0#0000000000000000\n"


def decode(*args):
    return subprocess.run([sys.executable, "-m", "canspec", "decode", *args], capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=120)


@pytest.mark.parametrize("fmt", ["text", "json", "csv"])
def test_a_failed_run_leaves_the_output_file_as_it_was(tmp_path, fmt):
    good, garbage = tmp_path / "good.log", tmp_path / "garbage.asc"
    good.write_text(LINE)
    garbage.write_text("not an asc file\n")
    out = tmp_path / "out" / "keep.txt"
    out.parent.mkdir()
    out.write_text("the old output\n")
    for inputs in ([garbage], [good, garbage], [tmp_path / "missing.log"]):
        proc = decode("--format", fmt, "-o", str(out), *map(str, inputs))
        assert proc.returncode == 2, proc.stderr
        assert out.read_text() == "the old output\n"
        assert os.listdir(out.parent) == ["keep.txt"]  # no temporary left
    out.chmod(0o640)
    proc = decode("--format", fmt, "-o", str(out), str(good))
    assert proc.returncode == 0, proc.stderr
    assert "1801B0A0" in out.read_text() and os.listdir(out.parent) == ["keep.txt"]
    assert stat.S_IMODE(out.stat().st_mode) == 0o640  # the replaced file keeps its mode


def test_a_new_output_file_and_a_device(tmp_path):
    good = tmp_path / "good.log"
    good.write_text(LINE)
    new = tmp_path / "new.json"
    assert decode("--format", "json", "-o", str(new), str(good)).returncode == 0
    umask = os.umask(0)
    os.umask(umask)
    assert new.read_text().count("\n") == 1 and stat.S_IMODE(new.stat().st_mode) == 0o666 & ~umask
    assert decode("-o", os.devnull, str(good)).returncode == 0  # written in place, never renamed over
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)
    proc = decode("-o", str(tmp_path), str(good))
    assert proc.returncode == 2 and proc.stderr.strip() == f"canspec decode: cannot write {tmp_path}: Is a directory"


def test_parquet_output_that_is_a_file_fails_before_decoding(tmp_path):
    log = tmp_path / "base.log"
    log.write_text(LINE * 10)
    proc = decode("--format", "parquet", "-o", str(log), str(log))
    assert proc.returncode == 2
    # one line and no summary: nothing was decoded
    assert proc.stderr.strip() == f"canspec decode: cannot write {log}: it exists and is not a directory (--format parquet writes a directory of tables)"
    assert log.read_text() == LINE * 10
    proc = decode("--format", "parquet", "-o", str(log / "tables"), str(log))
    assert proc.returncode == 2 and proc.stderr.strip() == f"canspec decode: cannot write {log / 'tables'}: {log} is not a directory"
    out = tmp_path / "new" / "tables"
    assert decode("--format", "parquet", "-o", str(out), str(log)).returncode == 0
    assert (out / "autocar_eps_command" / "source=base" / "part-0.parquet").is_file()
