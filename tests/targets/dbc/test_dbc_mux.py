"""Multiplexing in the DBC, checked by cantools reading it: the markers and SG_MUL_VAL_ lines give
cantools the spec's pages (its signal tree), and for random raw values on every page the
reference codec's frame decodes in cantools to the same values (cantools, like the codec, returns
only the selected pages' fields) and cantools encodes those values to the same bytes."""

from __future__ import annotations

import random
from pathlib import Path

import cantools
import pytest
from canspec import ir
from canspec.ir import mux
from canspec.pipeline import compile_spec
from canspec.reference import codec
from canspec_cli import assert_no_traceback, run_canspec
from dbc_support import load_cantools, vectors, write_dbc
from repo_paths import ROOT

MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"
ROUNDS = 60


@pytest.fixture(scope="module")
def spec() -> ir.Spec:
    compiled = compile_spec(MUX, targets=["dbc", "vectors"])
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    return compiled.spec


@pytest.fixture(scope="module")
def db(spec: ir.Spec, tmp_path_factory: pytest.TempPathFactory):
    return load_cantools(write_dbc(spec, tmp_path_factory.mktemp("dbc")))


def test_cantools_reads_the_pages(db) -> None:
    # the fixture's table, as cantools' signal tree writes it (values of a range one by one)
    report = db.get_message_by_name("sensor_report")
    channel = {"channel": {0: ["gain"], 1: ["voltage"], 2: ["voltage"], 3: ["voltage"]}}
    pages = {0: ["temperature"], 1: ["pressure", "level"], 2: [channel], 4: ["pressure", "level"], 5: ["pressure", "level"], 6: ["pressure", "level"]}
    assert report.signal_tree == [{"mode": pages}, "status", "counter"]
    command = db.get_message_by_name("host_command")
    assert command.signal_tree == [{"command": {v: ["argument"] for v in [*range(10), 20]}}]


def _selections(msg: ir.Message, rng: random.Random) -> list[dict[str, int]]:
    """Multiplexer values that select each page in turn (and one value no page holds)."""
    out = []
    for group in msg.mux_groups:
        values = {c.by: c.first for c in msg.mux_chain(msg.signal(group.multiplexer))}
        lo, hi = rng.choice(group.ranges)
        values[group.multiplexer] = rng.randint(lo, hi)
        out.append(values)
    top = msg.multiplexers[0]
    taken = {v for g in msg.mux_groups if g.multiplexer == top.name for lo, hi in g.ranges for v in range(lo, hi + 1)}
    out.append({top.name: next(v for v in range(top.raw_type_max + 1) if v not in taken)})
    return out


def _frames(msg: ir.Message, rng: random.Random) -> list[tuple[dict[str, int], bytes]]:
    frames = []
    for _ in range(ROUNDS):
        for values in _selections(msg, rng):
            # a multiplexer the selection leaves open selects one of its pages, drawn first
            while open_ := [s.name for s in msg.present(values) if s.is_multiplexer and s.name not in values]:
                lo, hi = rng.choice([r for g in msg.mux_groups if g.multiplexer == open_[0] for r in g.ranges])
                values[open_[0]] = rng.randint(lo, hi)
            raw = {s.name: values.get(s.name, rng.randint(s.raw_type_min, s.raw_type_max)) for s in msg.present(values)}
            frames.append((raw, codec.pack(msg, raw)))
    return frames


@pytest.mark.parametrize("name", ["sensor_report", "host_command"])
def test_cantools_agrees_on_every_page(spec: ir.Spec, db, name: str) -> None:
    msg, rng = spec.can.message(name), random.Random(name)
    dbc_msg = db.get_message_by_name(name)
    checked = 0
    for raw, data in _frames(msg, rng):
        assert codec.unpack(msg, data) == raw
        if any(not any(g.multiplexer == m.name and mux.holds(g.ranges, raw[m.name]) for g in msg.mux_groups) for m in msg.multiplexers if m.name in raw):
            # a value no page holds: the codec gives the fields of every frame, cantools refuses the frame
            with pytest.raises(cantools.database.DecodeError):
                dbc_msg.decode(data, decode_choices=False, scaling=False)
            continue
        assert dbc_msg.decode(data, decode_choices=False, scaling=False) == raw, (raw, data.hex())
        assert dbc_msg.encode(raw, scaling=False, strict=False) == data, raw
        physical = dbc_msg.decode(data, decode_choices=False)
        assert physical.keys() == raw.keys()
        for key, value in physical.items():
            assert value == pytest.approx(float(codec.physical_value(msg.signal(key), raw[key])), rel=1e-12, abs=1e-12)
        checked += 1
    assert checked >= ROUNDS * len(msg.mux_groups)


def test_codec_keeps_pages_apart(spec: ir.Spec) -> None:
    msg = spec.can.message("sensor_report")
    data = codec.pack(msg, {"mode": 1, "pressure": 0x1234, "level": 7})
    assert data == bytes([0x01, 0x34, 0x12, 0x07, 0, 0, 0, 0])  # the bits of the other pages stay 0
    assert codec.unpack(msg, data) == {"mode": 1, "status": 0, "pressure": 0x1234, "level": 7, "counter": 0}
    with pytest.raises(codec.CodecError, match="temperature"):
        codec.pack(msg, {"mode": 1, "temperature": 5})
    with pytest.raises(codec.CodecError, match="gain"):
        codec.pack(msg, {"mode": 2, "channel": 1, "gain": 5})


def test_every_target_carries_pages(tmp_path: Path) -> None:
    proc = run_canspec("check", MUX)
    assert_no_traceback(proc)
    assert proc.returncode == 0, proc.stderr
    ok = run_canspec("gen", "-o", tmp_path, MUX)
    assert_no_traceback(ok)
    assert ok.returncode == 0 and (tmp_path / "dbc" / "mux_bus.dbc").is_file() and (tmp_path / "python" / "mux_bus" / "messages.py").is_file(), ok.stderr


def test_vectors_hold_every_page_and_cantools_agrees(spec: ir.Spec, db) -> None:
    """The vectors' cases, page by page: each holds its multiplexers' values and only the fields of
    the pages they select (cantools decodes to exactly those), and every page appears."""
    cases = vectors(spec)["cases"]
    seen: set[tuple[str, tuple[str, ...]]] = set()
    for case in cases:
        msg, dbc_msg, data = spec.can.message(case["message"]), db.get_message_by_name(case["message"]), bytes.fromhex(case["data"])
        assert dbc_msg.decode(data, decode_choices=False, scaling=False) == case["raw"], case
        assert dbc_msg.encode(case["raw"], scaling=False, strict=False) == data, case
        physical = dbc_msg.decode(data, decode_choices=False)
        assert physical.keys() == case["physical"].keys(), case
        for key, value in physical.items():
            tolerance = abs(msg.signal(key).factor) / 2 * (1 + 1e-9) if case["kind"] == "tie" else 1e-9 * max(1.0, abs(value))
            assert abs(float(case["physical"][key]) - value) <= tolerance, (case, key)
        seen.add((case["message"], tuple(sorted(case["raw"]))))
    # the fixture's pages (its table): mode 0, mode 1/4..6, mode 2 with channel 0 and 1..3; command 0..9/20
    assert seen == {
        ("sensor_report", ("counter", "mode", "status", "temperature")),
        ("sensor_report", ("counter", "level", "mode", "pressure", "status")),
        ("sensor_report", ("channel", "counter", "gain", "mode", "status")),
        ("sensor_report", ("channel", "counter", "mode", "status", "voltage")),
        ("host_command", ("argument", "command")),
    }
    modes = {c["raw"]["mode"] for c in cases if c["message"] == "sensor_report"}
    assert modes == {0, 1, 2, 6}  # each page at its lowest and highest value
