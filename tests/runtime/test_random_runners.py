"""The C and Rust sequence runners against the independent model (model.py) on random traffic:
seeded random monitor and text sequences (random_traffic.py) for the shipped spec and two valid
fixtures of other features, written in the sequence-vector format with the model's expectations,
then replayed by tests/targets/c/c_sequences.py (gcc, ASan/UBSan) and by each crate's `tests/sequences.rs`
(one cargo workspace, one build, one run) — the same entry points as `make roundtrip-sequences-c`
and `-rust`. The Python package meets the model on random traffic in test_sequences.py.

Reproduce a failure with its seed: CANSPEC_SEQUENCE_SEED=<seed> python -m pytest tests/runtime -k random.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
from canspec.pipeline import compile_spec
from canspec.targets import registry
from repo_paths import ROOT, SPEC
from rust_workspace import add_member, write_workspace

from runtime import random_traffic

sys.path.insert(0, str(ROOT / "tests" / "targets" / "c"))
import c_sequences  # tests/targets/c is no package

SEED = int(os.environ.get("CANSPEC_SEQUENCE_SEED", "17"))
VALID = ROOT / "tests" / "fixtures" / "valid"
# spec → (monitor sequences, text sequences): the shipped spec (J1939, counters, checksums, fault
# codes, a VIN from several devices), 11-bit and 29-bit IDs with event-driven messages, and long
# multi-frame texts (12 frames, a signed index, a counter and checksum in the text message).
SPECS = {
    "shipped": (SPEC, 120, 60),
    "english_standard_bus": (VALID / "english_standard_bus.yaml", 120, 0),
    "long_multiframe_text": (VALID / "long_multiframe_text.yaml", 100, 80),
}
TARGET_DIR = Path(os.environ.get("CARGO_TARGET_DIR", str(ROOT / "build" / "rust" / "target")))
RUST_LINE = re.compile(r"rust sequences: (\d+) monitor sequences \(\d+ steps\), (\d+) text sequences \(\d+ steps\) from (\S+), (\d+) mismatches")
C_LINE = re.compile(r"c sequences: (\d+) monitor sequences \(\d+ steps\), (\d+) text sequences \(\d+ steps\), (\d+) mismatches")
FAILED_ID = re.compile(r"^  (?:sequence|monitor|text) (\d+)", re.MULTILINE)  # a runner's first mismatch


@pytest.fixture(scope="module")
def traffic(tmp_path_factory) -> Path:
    """Per spec under the root: its C headers, its crate and `vectors/sequences.json` of random
    sequences (the crate's sequence test reads `../vectors/sequences.json`)."""
    root = tmp_path_factory.mktemp("random_sequences")
    members = []
    for name, (path, monitor, texts) in SPECS.items():
        compiled = compile_spec(path)
        assert compiled.spec is not None and compiled.spec.can is not None, "\n".join(p.format() for p in compiled.problems)
        members.append(add_member({**registry()["rust"].render(compiled.spec), **registry()["c"].render(compiled.spec)}, root, name, "random"))
        doc = random_traffic.build(compiled.spec.can, SEED, monitor, texts)
        (root / name / "vectors").mkdir()
        (root / name / "vectors" / "sequences.json").write_text(json.dumps(doc, indent=1), encoding="utf-8")
    write_workspace(root, members)
    return root


def _failure(root: Path, name: str, output: str) -> str:
    """The seed, the runner's report and the first failing sequence, to reproduce it."""
    doc = json.loads((root / name / "vectors" / "sequences.json").read_text(encoding="utf-8"))
    m = FAILED_ID.search(output)
    seq = next((s for s in doc["monitor"] + doc["texts"] if m and s["id"] == int(m.group(1))), None)
    return f"seed {SEED}, spec {name}, file {root / name / 'vectors' / 'sequences.json'}\n{output[-5000:]}\nfirst failing sequence:\n{json.dumps(seq)[:6000]}"


@pytest.mark.parametrize("name", list(SPECS))
def test_c_runner_agrees_with_the_model_on_random_traffic(traffic, name):
    path, monitor, texts = SPECS[name]
    code, out = c_sequences.run_sequences(traffic / name / "vectors" / "sequences.json", path, traffic / name / "c", traffic / name / "build")
    m = C_LINE.search(out)
    assert code == 0 and m and m.group(3) == "0", _failure(traffic, name, out)
    assert (int(m.group(1)), int(m.group(2))) == (monitor, texts)


def test_rust_runners_agree_with_the_model_on_random_traffic(traffic):
    env = {**os.environ, "CARGO_TARGET_DIR": str(TARGET_DIR), "CARGO_TERM_COLOR": "never"}
    env.pop("RUSTFLAGS", None)
    env.pop("CANSPEC_SEQUENCES", None)
    proc = subprocess.run(["cargo", "test", "--offline", "--workspace", "--no-fail-fast", "--all-features", "--test", "sequences", "--", "--nocapture"],
                          cwd=traffic, env=env, capture_output=True, text=True, check=False)
    runs = {Path(os.path.normpath(m.group(3))).parent.parent.name: m for m in RUST_LINE.finditer(proc.stdout)}
    assert sorted(runs) == sorted(SPECS), f"seed {SEED}\n{proc.stdout[-4000:]}\n{proc.stderr[-6000:]}"
    for name, m in runs.items():
        report = proc.stdout[m.start() : m.start() + 6000]
        assert m.group(4) == "0", _failure(traffic, name, report)
        assert (int(m.group(1)), int(m.group(2))) == SPECS[name][1:]
    assert proc.returncode == 0, proc.stdout[-4000:] + proc.stderr[-4000:]


@pytest.mark.parametrize("name", list(SPECS))
def test_random_traffic_reaches_every_outcome(traffic, name):
    """The random files exercise what the runners are checked on: every fault, every state,
    recovery, counter steps within the tolerance, every text result, complete texts valid and not."""
    doc = json.loads((traffic / name / "vectors" / "sequences.json").read_text(encoding="utf-8"))
    frames = [st["expect"] for s in doc["monitor"] for st in s["steps"] if st["action"] == "frame"]
    checks = [st["expect"] for s in doc["monitor"] for st in s["steps"] if st["action"] == "check"]
    assert {f for e in frames for f in e["faults"]} == {"unknown_id", "length", "checksum", "counter_repeat", "counter_jump", "timeout"}
    assert {e["state"] for e in frames} == {None, "init", "valid", "invalid"}
    assert any(e["recovered"] for e in frames) and any(c["timeouts"] for c in checks)
    assert any((e["counter_delta"] or 0) > 1 and not e["faults"] for e in frames)
    steps = [st["expect"] for s in doc["texts"] for st in s["steps"]]
    if SPECS[name][2]:
        results = Counter(e["result"] for e in steps)
        assert set(results) >= {"ok", "inconsistent", "length", "index"}, results
        assert any(isinstance(e["text"], str) for e in steps) and any(e["text"] is False for e in steps)
