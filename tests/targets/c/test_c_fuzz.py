"""Bounded libFuzzer runs (clang, ASan + UBSan) of the C unpack of every message, dispatch by
ID, VIN reassembly and the receive monitor: no crash, leak, undefined behaviour or broken
property. CANSPEC_FUZZ_SECONDS sets the time per target (default 20)."""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "fuzz"))
import run_fuzz

SECONDS = int(os.environ.get("CANSPEC_FUZZ_SECONDS", "20"))


@pytest.mark.parametrize("target", run_fuzz.TARGETS)
def test_fuzz_target(target, tmp_path):
    assert shutil.which("clang") is not None, "clang missing (run `make setup`)"
    r = run_fuzz.run(target, SECONDS, tmp_path)
    print(f"fuzz_{target}: {r['executions']} executions, cov {r['cov']}, ft {r['ft']}, corpus {r['corpus']}")
    assert r["clean"], r["log"]
    assert r["executions"] > 1000 and r["cov"] > 0
