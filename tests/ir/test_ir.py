"""The IR computes meaning once: J1939 fields, segments, storage widths, variants, fingerprints.
Expected values are read off the document's tables."""

from __future__ import annotations

import random
import shutil
from fractions import Fraction

from canspec.ir import j1939
from canspec.ir.bits import segments
from canspec.ir.encoding import to_raw_runtime
from canspec.ir.ids import MAX_EXTENDED_ID, MAX_STANDARD_ID, id_text, max_id
from canspec.pipeline import compile_spec
from repo_paths import SPEC


def test_counts(spec, can):
    assert len(can.messages) == 25
    assert len(can.nodes) == 4 and {n.sa for n in can.nodes} == {0xB0, 0xA0, 0xC0, 0xD0}
    assert can.bus.bitrate == 250_000 and can.bus.id_format == "extended"
    assert len(spec.json) == 1 and len(spec.json[0].messages) == 10
    assert [v.version for v in spec.changelog.versions][0] == "1.0.0"
    assert spec.changelog.versions[-1].version == can.version == "2.0.5"


def test_j1939_fields_from_ids(can):
    eps = can.message("autocar_eps_command").j1939
    assert (eps.priority, eps.pf, eps.ps, eps.sa, eps.pgn, eps.da, eps.is_pdu2) == (6, 0x01, 0xB0, 0xA0, 0x0100, 0xB0, False)
    dev = can.message("device_id").j1939
    assert (dev.priority, dev.pf, dev.ps, dev.sa, dev.pgn, dev.da, dev.is_pdu2) == (6, 0xFF, 0xAF, 0x00, 0xFFAF, None, True)
    radar = can.message("rear_sensor_distance_2").j1939
    assert (radar.priority, radar.pgn) == (6, 0xFF04)  # E08, E27
    for msg in can.messages:
        assert j1939.compose(msg.j1939.priority, msg.j1939.pgn, msg.j1939.sa, msg.j1939.da) == msg.frame_id


def test_intel_segments():
    # 10-bit signal at bit 10: byte 1 bits 2..7 (6 bits), byte 2 bits 0..3 (4 bits)
    s = segments(10, 10)
    assert [(x.byte, x.byte_shift, x.width, x.value_shift, x.mask) for x in s] == [(1, 2, 6, 0, 0xFC), (2, 0, 4, 6, 0x0F)]
    vin = segments(8, 56)
    assert [x.byte for x in vin] == [1, 2, 3, 4, 5, 6, 7] and all(x.width == 8 for x in vin)


def test_variants_share_layout_with_real_differences(can):
    a, r, t = (can.message(f"{p}_speed_command") for p in ("autocar", "rgate", "tele"))
    assert [s.start for s in a.signals] == [s.start for s in r.signals] == [s.start for s in t.signals]
    assert a.signal("accel_cmd").factor == r.signal("accel_cmd").factor == Fraction("0.02")
    throttle = t.signal("throttle_brake_cmd")  # §3.22
    assert (throttle.factor, throttle.offset, throttle.unit, throttle.doc_min, throttle.doc_max) == (Fraction("0.2"), -100, "%", -100, 100)
    ra = can.message("rgate_control_command_1").signal("drive_mode_cmd")
    assert ra.value_table.by_raw(3).name == "remote" and (ra.raw_min, ra.raw_max) == (0, 3)  # §3.14
    ta = can.message("tele_control_command_1").signal("drive_mode_cmd")
    assert ta.value_table.by_raw(2).name == "tele" and (ta.raw_min, ta.raw_max) == (0, 2)  # §3.23
    c2 = can.message("rgate_control_command_2")
    assert [(s.start, s.length) for s in c2.reserved_signals] == [(16, 40)]  # §3.15
    assert "chassis_pitch" in {s.name for s in can.message("autocar_control_command_2").signals}


def test_storage_widths_and_roles(can):
    vin = can.message("device_id")
    assert vin.signal("id_chars").storage_bits == 64 and vin.signal("id_frame_index").storage_bits == 8
    assert vin.multiframe.frames == 3 and vin.multiframe.bytes_per_frame == 7 and vin.multiframe.payload_byte == 1
    checksummed = {m.name for m in can.messages if m.checksum}
    assert checksummed == {
        "autocar_eps_command",
        "rgate_eps_command",
        "tele_eps_command",
        "autocar_speed_command",
        "rgate_speed_command",
        "tele_speed_command",
        "driving_state",
    }
    assert can.message("autocar_control_command_1").counter.modulo == 16
    assert can.message("eps_state").counter.modulo == 256
    assert can.message("driving_state").counter is None


def test_fingerprint_tracks_wire_not_names(tmp_path, can):
    spec_copy = tmp_path / "spec"
    shutil.copytree(SPEC, spec_copy)
    gateway = spec_copy / "can" / "gateway.yaml"
    text = gateway.read_text(encoding="utf-8")
    gateway.write_text(text.replace("{name: steering_torque, zh: 方向盘力矩", "{name: driver_torque, zh: 司机力矩"), encoding="utf-8")
    renamed = compile_spec(spec_copy).spec.can
    assert renamed.message("eps_state").fingerprint == can.message("eps_state").fingerprint
    gateway.write_text(text.replace("factor: 0.3, offset: -38.4", "factor: 0.2, offset: -38.4"), encoding="utf-8")
    rescaled = compile_spec(spec_copy).spec.can
    assert rescaled.message("eps_state").fingerprint != can.message("eps_state").fingerprint
    assert len({m.fingerprint for m in can.messages}) == 25


def test_names_per_language(can):
    from canspec.ir.names import c_ident, pascal, rust_ident, upper_snake

    msg = can.message("rgate_speed_command")
    assert (pascal(msg.name), upper_snake(msg.name)) == ("RgateSpeedCommand", "RGATE_SPEED_COMMAND")
    off = can.message("vehicle_state_1").signal("door_state").value_table.by_raw(0)
    assert off.name == "off" and pascal(off.name) == "Off"  # `off` stays text, not YAML 1.1's False
    assert rust_ident("type") == "r#type" and c_ident("default") == "default_"


def test_accepted_range_facts_hold_for_every_value_in_it(can):
    """Signal.accept_raw bounds the runtime rule's raw value of every double in the accepted range
    (and is reached at its ends), and max_quotient bounds |q| there: sampled on every data signal,
    the rule computed by ir/encoding.to_raw_runtime and q exactly, not by the properties."""
    rng = random.Random(23)
    for msg in can.messages:
        for sig in msg.data_signals:
            lo, hi = float(sig.accept_min), float(sig.accept_max)
            xs = [lo, hi] + [rng.uniform(lo, hi) for _ in range(200)]
            raws = [to_raw_runtime(x, float(sig.factor), float(sig.offset)) for x in xs]
            assert min(raws) == sig.accept_raw[0] and max(raws) == sig.accept_raw[1], (msg.name, sig.name)
            assert all(abs((Fraction(x) - sig.offset) / sig.factor) <= sig.max_quotient for x in xs if sig.accept_min <= Fraction(x) <= sig.accept_max)
            assert sig.max_quotient in {abs((sig.accept_min - sig.offset) / sig.factor), abs((sig.accept_max - sig.offset) / sig.factor)}


def test_id_limits_and_text():
    assert (MAX_STANDARD_ID, MAX_EXTENDED_ID) == (2**11 - 1, 2**29 - 1)  # CAN 2.0A / 2.0B identifiers
    assert (max_id(False), max_id(True)) == (0x7FF, 0x1FFFFFFF)
    assert (id_text(0x123, False), id_text(0x1801B0A0, True), id_text(0x5, True)) == ("0x123", "0x1801B0A0", "0x00000005")
    assert (j1939.ID_MASK, j1939.PRIORITY_MASK) == (0x1FFFFFFF, 0x1C000000)  # J1939-21: priority is bits 26..28
