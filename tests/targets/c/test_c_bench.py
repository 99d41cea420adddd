"""`make bench-c` (x86-64) still builds, times and counts: every mode prints its table and its
instruction counts, and the harness loop subtracted in call mode is the same code on both sides
(the premise of counting the codec alone). The figures themselves are the benchmark's, not a test's."""

from __future__ import annotations

import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench


def test_bench_c_counts_every_mode(tmp_path, capfd):
    rc = bench.main(["bench", str(tmp_path), "2000"])
    out = capfd.readouterr().out  # the timing tables come from the C executables
    assert rc == 0, out[-3000:]
    counts = re.findall(r"^\[([^\]]+)\] message .*callgrind; (inside the codec|loop included)", out, re.MULTILINE)
    assert [m for m, _ in counts] == ["call", "inline", f"call, {bench.XMODE}", f"inline, {bench.XMODE}"], out[-3000:]
    assert re.search(r"with the harness loop .*the same on both sides\)", out), out[-3000:]
    assert "DIFFER" not in out
    overall = re.findall(r"^overall \(sum\)\s+([\d.]+)\s+([\d.]+)", out, re.MULTILINE)
    assert len(overall) == 8 and all(float(a) > 0 and float(b) > 0 for a, b in overall), overall
