"""Issue 9, scale: a synthetic spec of 2,000 messages and 30,000 signals checks and generates
(DBC and vectors), and the generated DBC holds all of it when cantools reads it. Timings are
the benchmark's job (`make bench-scale`), not this test's."""

from __future__ import annotations

import re
import sys
from collections import Counter
from pathlib import Path

import cantools
import pytest
from canspec_cli import ROOT, assert_no_traceback, run_canspec

sys.path.insert(0, str(ROOT / "tools"))
import synth_spec


@pytest.fixture(scope="module")
def big_spec(tmp_path_factory: pytest.TempPathFactory) -> Path:
    spec = tmp_path_factory.mktemp("scale") / "synthetic"
    synth_spec.synthesize(spec, 2000, 30000, seed=1)
    return spec


def test_check_2000_messages_30000_signals(big_spec: Path) -> None:
    proc = run_canspec("check", big_spec, timeout=900)
    assert_no_traceback(proc)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert "synthetic 1.0.0: ok (2000 messages, 30000 signals, 2 value tables)" in proc.stderr


def test_gen_dbc_and_vectors_at_scale(big_spec: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = run_canspec("gen", big_spec, "-o", out, "-t", "dbc", "-t", "vectors", timeout=1800)
    assert_no_traceback(proc)
    assert proc.returncode == 0, proc.stderr[-2000:]
    db = cantools.database.load_file(str(out / "dbc" / "synthetic.dbc"), encoding="utf-8", strict=True)
    assert len(db.messages) == 2000
    assert sum(len(m.signals) for m in db.messages) == 30000
    assert len({m.frame_id for m in db.messages}) == 2000
    # The vectors file is ~140 MB: count its cases per message without building it in memory.
    text = (out / "vectors" / "can.json").read_bytes()
    per_message = Counter(re.findall(rb'"message": "(msg_\d{5})"', text))
    assert len(per_message) == 2000 and min(per_message.values()) >= 50
    # Regenerating changes nothing (deterministic at scale too).
    again = run_canspec("gen", big_spec, "-o", out, "-t", "dbc", "-t", "vectors", "--check", timeout=1800)
    assert again.returncode == 0, again.stdout[-2000:] + again.stderr[-2000:]


@pytest.mark.parametrize("copies", [1, 3])
def test_replicated_shipped_spec(copies: int, tmp_path: Path) -> None:
    spec = tmp_path / f"x{copies}"
    messages, _ = synth_spec.replicate(spec, copies)
    assert messages == 25 * copies
    proc = run_canspec("check", spec)
    assert proc.returncode == 0, proc.stderr
    assert f"kaiwo_gateway 2.0.5: ok ({25 * copies} messages, {264 * copies} signals" in proc.stderr
    if copies == 1:  # 1x is the shipped spec itself, without its reconstructed revisions
        for f in (ROOT / "spec").rglob("*.yaml"):
            rel = f.relative_to(ROOT / "spec")
            if rel.parts[0] == "history":
                continue
            assert (spec / rel).read_bytes() == f.read_bytes()
