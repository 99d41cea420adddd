"""The sequence vectors (generated/vectors/sequences.json) against the independent model in
model.py — for the shipped spec and every valid fixture — and the generated Python package's
monitor and text assemblers against the same model on random interleavings, drops, repeats,
corruptions and timings (hypothesis)."""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

import pytest
from canspec.ir.build import build
from canspec.spec.loader import load
from canspec.spec.resolve import resolve
from canspec.spec.validate import validate
from canspec.targets.vectors import build_sequences
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from repo_paths import GENERATED, ROOT

from targets.python import sequence_runner
from runtime.model import ModelMonitor, ModelText

SEQUENCES = GENERATED / "vectors" / "sequences.json"
FIXTURES = sorted((ROOT / "tests" / "fixtures" / "valid").glob("*.yaml"))


def replay(can, data) -> list[str]:
    """Every mismatch between the file's expectations and the model."""
    errors = []
    for seq in data["monitor"]:
        model = ModelMonitor(can, **seq["params"])
        for i, step in enumerate(seq["steps"]):
            if step["action"] == "start":
                model.start(step["t"], step["messages"])
                continue
            if step["action"] == "frame":
                got = model.frame(step["t"], step["frame_id"], step["extended"], bytes.fromhex(step["data"]))
            else:
                got = {"timeouts": model.check(step["t"]), "states": {m: model.msgs[m].state for m in seq["messages"]}, "codes": model.codes()}
            if got != step["expect"]:
                errors.append(f"monitor {seq['id']} step {i}: model {got}, file {step['expect']}")
        end = {"stats": {m: model.msgs[m].stats for m in seq["messages"]}, "unknown_frames": model.unknown}
        if end != seq["end"]:
            errors.append(f"monitor {seq['id']} end: model {end}, file {seq['end']}")
    for seq in data["texts"]:
        model = ModelText(can.message(seq["message"]))
        for i, step in enumerate(seq["steps"]):
            got = {"result": model.feed(bytes.fromhex(step["data"])), "text": model.text()}
            if got != step["expect"]:
                errors.append(f"text {seq['id']} step {i}: model {got}, file {step['expect']}")
    return errors


def test_shipped_sequences_agree_with_the_model(can):
    data = json.loads(SEQUENCES.read_text(encoding="utf-8"))
    assert replay(can, data) == []


def test_shipped_sequences_cover_every_category():
    data = json.loads(SEQUENCES.read_text(encoding="utf-8"))
    monitor = Counter(s["category"] for s in data["monitor"])
    texts = Counter(s["category"] for s in data["texts"])
    for category in ("in_order", "counter_wrap", "repeated", "counter_jump", "stale", "checksum", "timeout", "length", "unknown_id", "interleaved"):
        assert monitor[category] > 0, category
    for category in ("in_order", "out_of_order", "repeated", "stale", "interleaved", "index", "length", "invalid_text"):
        assert texts[category] > 0, category
    frames = [st for s in data["monitor"] for st in s["steps"] if st["action"] == "frame"]
    faults = Counter(f for st in frames for f in st["expect"]["faults"])
    assert set(faults) == {"unknown_id", "length", "checksum", "counter_repeat", "counter_jump", "timeout"}
    assert any(st["expect"]["recovered"] for st in frames)
    within = [st for st in frames if (st["expect"]["counter_delta"] or 0) > 1 and not st["expect"]["faults"]]
    assert within, "a counter step within the tolerance"
    assert {c for st in frames for c in st["expect"]["codes"].values()} == {0, 5, 6, 7}  # 0x1813A0B0's codes
    # a check exactly at the limit reports nothing, 1 ms later the timeout
    limits = [s for s in data["monitor"] if s["category"] == "timeout" and "exactly" in s["note"]]
    assert limits


def test_python_runner_agrees():
    counts, errors = sequence_runner.run(SEQUENCES)
    assert errors == []
    assert counts["monitor steps"] > 300 and counts["text steps"] > 40


def spec_ir(path: Path):
    """The IR of a valid spec (the spec rules only: what a target refuses is not this test's concern)."""
    loaded = load(path)
    res = resolve(loaded)
    problems = [p for p in validate(res) if p.severity == "error"]
    assert not problems, "\n".join(p.format() for p in problems)
    return build(loaded, res)


@pytest.mark.parametrize("path", FIXTURES, ids=[p.stem for p in FIXTURES])
def test_fixture_sequences_agree_with_the_model(path: Path):
    spec = spec_ir(path)
    if spec.can is not None:
        assert replay(spec.can, json.loads(json.dumps(build_sequences(spec)))) == []


# --- random sequences: the generated package against the model ----------------------------------

SHAPES = ("autocar_eps_command", "vehicle_state_2", "driving_state")  # counter+checksum, no checksum, ...


def _frame(gw, msg, counter: int, mode: str) -> bytes:
    cls = gw.BY_ID[msg.frame_id]
    raw = {msg.counter.signal: counter % msg.counter.modulo} if msg.counter else {}
    data = bytearray(cls.pack_raw(raw))
    if mode == "corrupt" and msg.checksum:
        data[msg.checksum.byte] ^= 0x40
    if mode == "short":
        return bytes(data[:-1])
    return bytes(data)


EVENT = st.tuples(
    st.integers(0, len(SHAPES) - 1),  # which message
    st.sampled_from([1, 1, 1, 1, 2, 3, 0, 4, 200]),  # counter step (0: repeat; 200: far jump / stale)
    st.sampled_from(["ok"] * 8 + ["corrupt", "short", "drop"]),
    st.integers(0, 120),  # ms since the previous event
    st.booleans(),  # check timeouts after it
)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(events=st.lists(EVENT, min_size=3, max_size=80), tolerance=st.integers(0, 3), valid_after=st.integers(1, 4), start=st.booleans(),
       t0=st.sampled_from([0, 2**32 - 150]))
def test_package_monitor_agrees_with_the_model_on_random_traffic(can, gw, events, tolerance, valid_after, start, t0):
    mon = gw.new_monitor(counter_tolerance=tolerance, valid_after=valid_after)
    model = ModelMonitor(can, counter_tolerance=tolerance, valid_after=valid_after)
    msgs = [can.message(n) for n in SHAPES]
    counters = [0] * len(msgs)
    t = t0
    if start:
        mon.start(t % 2**32, SHAPES)
        model.start(t % 2**32, list(SHAPES))
    for which, step, mode, dt, check in events:
        t += dt
        now = t % 2**32
        msg = msgs[which]
        counters[which] += step
        if mode != "drop":
            data = _frame(gw, msg, counters[which], mode)
            got = sequence_runner.frame_result(mon.feed(now, msg.frame_id, msg.is_extended, data))
            assert got == model.frame(now, msg.frame_id, msg.is_extended, data)
        if check:
            assert [e.message for e in mon.check(now)] == model.check(now)
    for n in SHAPES:
        assert {k: getattr(mon.stats(n), k) for k in sequence_runner.STATS} == model.msgs[n].stats
        assert mon.state(n).value == model.msgs[n].state
    assert mon.fault_codes() == model.codes()


TEXT_EVENT = st.tuples(st.integers(0, 3), st.integers(0, 3), st.sampled_from(["ok"] * 6 + ["drop", "twice", "short", "bad_index"]))


@settings(max_examples=200, deadline=None)
@given(events=st.lists(TEXT_EVENT, max_size=40))
def test_package_text_assembler_agrees_with_the_model(can, gw, events):
    """Two senders (device types) × two texts, frames interleaved, dropped, repeated, short or with
    a bad index, in any order."""
    msg = can.message("device_id")
    texts = {
        (d, k): gw.split_device_id_text(text, gw.DeviceId(device_type=d)) for d in (0, 1) for k, text in enumerate(("LSKG5GC13KA123456", "LSKG5GC13KB999999"))
    }
    asm, model = gw.DeviceIdTextAssembler(), ModelText(msg)
    for which, index, mode in events:
        frames = texts[(which // 2, which % 2)]
        data = frames[index % 3].encode() if mode != "bad_index" else frames[0].pack_raw({**frames[0].to_raw(), "id_frame_index": 3})
        if mode == "short":
            data = data[:7]
        for _ in range({"drop": 0, "twice": 2}.get(mode, 1)):
            expected = model.feed(data)
            assert sequence_runner.text_step(gw, asm, gw.DeviceId, data) == {"result": expected, "text": model.text()}
