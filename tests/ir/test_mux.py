"""Multiplexing in the IR: the pages of tests/fixtures/valid/multiplexed.yaml as its signal table
states them (expected values written from the document, not from the build), which fields a
frame holds for given multiplexer values, and fingerprints that see a page change."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec import ir
from canspec.ir.mux import exclusive, groups, ranges_of
from canspec.pipeline import compile_spec
from repo_paths import ROOT

MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"


@pytest.fixture(scope="module")
def can() -> ir.CanProtocol:
    compiled = compile_spec(MUX, targets=["dbc"])
    assert compiled.spec is not None and compiled.spec.can is not None, [p.format() for p in compiled.problems]
    return compiled.spec.can


def test_signals_carry_their_condition(can: ir.CanProtocol) -> None:
    msg = can.message("sensor_report")
    assert [s.name for s in msg.multiplexers] == ["mode", "channel"]
    assert msg.signal("mode").mux is None and msg.signal("mode").is_multiplexer
    assert msg.signal("pressure").mux == ir.MuxCondition("mode", ((1, 1), (4, 6)))
    assert msg.signal("voltage").mux == ir.MuxCondition("channel", ((1, 3),))
    assert msg.signal("channel").is_multiplexer and msg.signal("channel").mux == ir.MuxCondition("mode", ((2, 2),))
    assert msg.signal("status").mux is None and not msg.signal("status").is_multiplexer
    assert msg.mux_chain(msg.signal("voltage")) == (ir.MuxCondition("mode", ((2, 2),)), ir.MuxCondition("channel", ((1, 3),)))
    assert msg.mux_chain(msg.signal("status")) == ()


def test_pages(can: ir.CanProtocol) -> None:
    msg = can.message("sensor_report")
    assert msg.is_multiplexed and can.has_multiplexing
    assert msg.mux_groups == (
        ir.MuxGroup("mode", ((0, 0),), ("temperature",)),
        ir.MuxGroup("mode", ((1, 1), (4, 6)), ("pressure", "level")),
        ir.MuxGroup("mode", ((2, 2),), ("channel",)),
        ir.MuxGroup("channel", ((0, 0),), ("gain",)),
        ir.MuxGroup("channel", ((1, 3),), ("voltage",)),
    )
    assert can.message("host_command").mux_groups == (ir.MuxGroup("command", ((0, 9), (20, 20)), ("argument",)),)


@pytest.mark.parametrize(("values", "present"), [
    ({"mode": 0}, ["mode", "status", "temperature", "counter"]),
    ({"mode": 5}, ["mode", "status", "pressure", "level", "counter"]),
    ({"mode": 2, "channel": 0}, ["mode", "status", "channel", "gain", "counter"]),
    ({"mode": 2, "channel": 3}, ["mode", "status", "channel", "voltage", "counter"]),
    ({"mode": 2, "channel": 7}, ["mode", "status", "channel", "counter"]),
    ({"mode": 3, "channel": 1}, ["mode", "status", "counter"]),  # channel absent: its pages too
    ({}, ["mode", "status", "temperature", "counter"]),  # a multiplexer not given holds 0
])
def test_present(can: ir.CanProtocol, values: dict[str, int], present: list[str]) -> None:
    assert sorted(s.name for s in can.message("sensor_report").present(values)) == sorted(present)


def test_value_arithmetic() -> None:
    assert ranges_of([5, [1, 3], 4, [9, 9]]) == ((1, 5), (9, 9))
    assert exclusive({"m": ((0, 0),)}, {"m": ((1, 2),)})
    assert not exclusive({"m": ((0, 3),)}, {"m": ((3, 4),)})
    assert not exclusive({"m": ((0, 0),)}, {"k": ((1, 1),)})
    assert groups("m", [("a", ((0, 4),)), ("b", ((3, 6),))]) == (
        ir.MuxGroup("m", ((0, 2),), ("a",)), ir.MuxGroup("m", ((3, 4),), ("a", "b")), ir.MuxGroup("m", ((5, 6),), ("b",)))


def test_fingerprint_sees_a_page_change(can: ir.CanProtocol, tmp_path: Path) -> None:
    moved = tmp_path / "moved.yaml"
    moved.write_text(MUX.read_text(encoding="utf-8").replace("values: [[0, 9], 20]", "values: [[0, 9], 21]"), encoding="utf-8")
    other = compile_spec(moved, targets=["dbc"]).spec
    assert other is not None and other.can is not None
    assert other.can.message("host_command").fingerprint != can.message("host_command").fingerprint
    assert other.can.message("sensor_report").fingerprint == can.message("sensor_report").fingerprint


def test_page_selections_and_views(can: ir.CanProtocol) -> None:
    msg = can.message("sensor_report")
    assert msg.page_selections == ({"mode": 0}, {"mode": 1}, {"mode": 6}, {"mode": 2, "channel": 0}, {"mode": 2, "channel": 1}, {"mode": 2, "channel": 3})
    page = msg.page({"mode": 2, "channel": 3})
    assert not page.is_multiplexed and [s.name for s in page.data_signals] == ["mode", "status", "channel", "voltage", "counter"]
    assert (page.signal("mode").raw_min, page.signal("mode").raw_max, page.signal("channel").raw_max) == (2, 2, 3)
    assert page.signal("voltage").mux is None and page.signal("voltage").word_mask == msg.signal("voltage").word_mask
    assert can.message("host_command").page_selections == ({"command": 0}, {"command": 20})
