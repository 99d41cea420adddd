"""Every valid fixture (tests/fixtures/valid/) through the C target: each header compiles alone,
warning-free, with gcc and clang as C99 and as C++ (and optimised); the vector runner agrees
with the spec's own vectors on both pack/unpack paths and under ASan/UBSan; every name the
headers declare is one the C target's clash check knows (speccheck.py). Two specs at a time."""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import pytest
import speccheck

# the valid fixtures and the C target's own corners (Motorola-only frames, float keys of a text, pages with a checksum or in FD frames, ...)
HERE = Path(__file__).resolve().parent
FIXTURES = [*sorted((HERE.parents[1] / "fixtures" / "valid").glob("*.yaml")), HERE / "corners" / "c_corners.yaml", HERE / "corners" / "c_mux_corners.yaml"]
WORKERS = 2  # the machine is shared


@pytest.fixture(scope="module")
def failures(tmp_path_factory) -> dict[str, list[str]]:
    work = tmp_path_factory.mktemp("c-any-spec")
    with ProcessPoolExecutor(WORKERS, mp_context=multiprocessing.get_context("fork")) as pool:
        futures = {p.stem: pool.submit(speccheck.check_spec, p, work / p.stem) for p in FIXTURES}
        return {name: f.result() for name, f in futures.items()}


@pytest.mark.parametrize("name", [p.stem for p in FIXTURES])
def test_valid_fixture_passes_every_c_check(failures, name):
    assert failures[name] == [], "\n\n".join(failures[name])


def test_the_fixtures_reach_what_the_c_target_had_refused():
    """The fixtures hold what this suite exists for: 64-bit unsigned fields, 11-bit and mixed IDs,
    event-driven and DLC-0 messages, checksums in frames shorter than 8 bytes, J1939 without
    declared fields, multi-frame text of more than 8 frames, names the C runtime uses."""
    from canspec.pipeline import compile_spec

    cans = [c.spec.can for c in map(compile_spec, FIXTURES) if c.spec is not None and c.spec.can is not None]
    signals = [s for can in cans for m in can.messages for s in m.signals]
    messages = [m for can in cans for m in can.messages]
    assert any(s.length == 64 and not s.signed for s in signals) and any(s.length == 64 and s.signed for s in signals)
    assert any(can.has_standard and not any(m.is_extended for m in can.messages) for can in cans)
    assert any(can.has_standard and any(m.is_extended for m in can.messages) for can in cans)
    assert any(m.cycle_ms is None for m in messages) and any(m.dlc == 0 for m in messages)
    assert any(m.checksum is not None and m.dlc < 8 for m in messages)
    assert any(can.bus.is_j1939 for can in cans) and any(not can.bus.is_j1939 for can in cans)
    assert any(m.multiframe is not None and m.multiframe.frames > 8 for m in messages)
    assert any(m.name in ("status", "monitor") for m in messages)
