"""Multiplexed messages in the Rust view model (the crate's own tests on the vectors are in
test_rust_fixtures): when each field is present, worked out by hand from the mux fixture's
document; what a multiplexed message adds to the names `canspec check` keeps apart; the
multi-frame text the target refuses."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from canspec import ir
from canspec.pipeline import compile_spec
from canspec.targets import target_problems
from canspec.targets.rust import check
from canspec.targets.rust import model as rm
from repo_paths import ROOT

MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"
if not MUX.exists():  # the lead moves it into valid/ once every target carries multiplexing
    MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"


def _spec() -> ir.Spec:
    compiled = compile_spec(MUX, ["rust"])
    assert compiled.spec is not None and compiled.spec.can is not None, [p.format() for p in compiled.problems]
    return compiled.spec


def test_presence_conditions_follow_the_document():
    spec = _spec()
    assert target_problems(spec, ["rust"]) == []
    report = next(m for m in rm.build_crate(spec.can).messages if m.msg.name == "sensor_report")
    fields = {f.name: f for f in report.fields}
    # temperature: mode 0; pressure and level: mode 1 or 4..6; channel: mode 2; gain: channel 0, voltage: channels 1..3
    frame = {name: f.mux.frame_cond for name, f in fields.items()}
    assert frame == {
        "mode": "", "status": "", "counter": "", "channel": "self.load_mode() == 2", "temperature": "self.load_mode() == 0",
        "pressure": "matches!(self.load_mode(), 1 | 4..=6)", "level": "matches!(self.load_mode(), 1 | 4..=6)",
        "gain": "self.load_mode() == 2 && self.load_channel() == 0", "voltage": "self.load_mode() == 2 && matches!(self.load_channel(), 1..=3)",
    }
    # on the values struct: mode is the value table's enum, channel a plain integer
    assert fields["voltage"].mux.values_cond == "self.mode.wire() == 2 && matches!(self.channel, 1..=3)"
    assert [f.name for f in report.set_order][:4] == ["mode", "status", "counter", "channel"]  # multiplexers before their pages
    assert [f.name for f in report.fields if f.is_paged] == ["channel", "temperature", "pressure", "gain", "voltage", "level"]
    assert [f.name for f in report.fields if f.is_settable] == ["status", "counter"]  # a multiplexer's setter would re-page the frame
    assert fields["temperature"].zero_phys == "Self::ZERO.load_temperature() as f64 * 0.1"


def test_multiplexed_messages_keep_their_method_names_apart():
    spec = _spec()
    can = spec.can
    report = can.message("sensor_report")
    # a field named like another's presence method (`has_level`) or frame reader (`load_status`)
    for name in ("has_level", "load_status"):
        extra = dataclasses.replace(report.signal("status"), name=name, start=48, length=4, mux=None, is_multiplexer=False)
        clashing = dataclasses.replace(can, messages=tuple(dataclasses.replace(m, signals=(*m.signals, extra)) if m is report else m for m in can.messages))
        found = [(p.rule, p.message) for p in check.problems(dataclasses.replace(spec, can=clashing))]
        assert [r for r, _ in found] == ["rust-name-clash"] and f"`{name}`" in found[0][1], found
    # a message without multiplexing has neither (existing specs keep their names)
    argument = dataclasses.replace(can.message("host_command").signal("argument"), mux=None)
    assert rm.field_names(argument).members(argument, False) == ("argument", "argument_raw", "set_argument", "set_argument_raw", "store_argument")


def test_text_reading_a_multiplexed_field_is_refused(tmp_path: Path):
    spec = tmp_path / "text.yaml"
    spec.write_text(
        "schema_version: 1\nkind: can_protocol\nprotocol: {name: vin_bus, version: 1.0.0}\n"
        "bus: {bitrate: 500000, id_format: standard, addressing: none, byte_order: little_endian}\nnodes:\n  - {name: A}\n  - {name: B}\n"
        "messages:\n  - name: vin\n    id: 0x102\n    sender: A\n    receivers: [B]\n    dlc: 8\n"
        "    multiframe: {index: frame, payload: chars, encoding: ascii, text_length: 17, frames: 3, padding: 0x20}\n    signals:\n"
        "      - {name: frame, start: 0, len: 2}\n      - {name: kind, start: 2, len: 2}\n"
        "      - {name: extra, start: 4, len: 4, mux: {by: kind, values: [1]}}\n      - {name: chars, start: 8, len: 56}\n",
        encoding="utf-8",
    )
    compiled = compile_spec(spec, ["rust"])
    assert compiled.spec is None
    assert [(p.rule, p.loc.line if p.loc else None) for p in compiled.problems] == [("rust-text-mux", 18)], [p.format() for p in compiled.problems]
