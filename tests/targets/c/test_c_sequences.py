"""The shared sequence vectors through the generated C monitor and text reassembly (tests/targets/c/c_sequences.py):
the shipped spec with gcc and clang under ASan/UBSan, and every valid fixture's headers and sequences."""

from __future__ import annotations

import re

import c_sequences as seq
import pytest
from canspec.pipeline import compile_spec
from canspec.targets import registry
from repo_paths import GENERATED, ROOT

SUMMARY = re.compile(r"c sequences: (\d+) monitor sequences \((\d+) steps\), (\d+) text sequences \((\d+) steps\), (\d+) mismatches")
# the valid fixtures and the C target's corners
FIXTURES = [*sorted((ROOT / "tests" / "fixtures" / "valid").glob("*.yaml")),
            ROOT / "tests" / "targets" / "c" / "corners" / "c_corners.yaml"]


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_shipped_sequences(cc, tmp_path):
    code, out = seq.run_sequences(GENERATED / "vectors" / "sequences.json", ROOT / "spec", GENERATED / "c", tmp_path, cc)
    m = SUMMARY.search(out)
    assert code == 0 and m and m.group(5) == "0", out[-4000:]
    assert int(m.group(2)) > 300 and int(m.group(4)) > 40


@pytest.mark.parametrize("path", FIXTURES, ids=[p.stem for p in FIXTURES])
def test_fixture_sequences(path, tmp_path):
    compiled = compile_spec(path, seq.C_TARGETS)
    assert compiled.spec is not None, "\n".join(p.format() for p in compiled.problems)
    if compiled.spec.can is None:  # a JSON-only spec: no sequences to run
        assert registry()["vectors"].render(compiled.spec) == {}
        return
    files = {**registry()["c"].render(compiled.spec), **registry()["vectors"].render(compiled.spec)}
    for rel, data in files.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_bytes(data)
    code, out = seq.run_sequences(tmp_path / "vectors" / "sequences.json", path, tmp_path / "c", tmp_path / "build")
    assert code == 0 and ", 0 mismatches" in out, out[-4000:]
