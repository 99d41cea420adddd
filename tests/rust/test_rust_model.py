"""The Rust view model: literals, identifiers and bit expressions, checked against values
worked out by hand from the document's layouts; the generator's failure modes."""

from __future__ import annotations

import dataclasses
import shutil

import pytest
from canspec.generate import GenerationError, generate
from canspec.render import formatters
from canspec.targets import rust as rust_target
from canspec.targets.rust import model as rm
from repo_paths import GENERATED


def sig(can, message, name):
    return can.message(message).signal(name)


def test_doc_text():
    assert rm.doc_text("[0, 3] <x> `y`") == "\\[0, 3\\] &lt;x&gt; 'y'"


def test_unpack_expressions(can):
    # sensor 3 distance: bits 20..29 of the frame (§3.17), 10 bits in a u16.
    assert rm.unpack_expr(sig(can, "front_sensor_distance_1", "sensor_3_distance")) == "((bits >> 20) & 1023) as u16"
    # A byte-aligned byte needs no mask: the cast truncates.
    assert rm.unpack_expr(sig(can, "eps_state", "counter")) == "(bits >> 56) as u8"
    assert rm.unpack_expr(sig(can, "autocar_eps_command", "eps_ctrl_mode")) == "bits as u8"
    # The VIN characters fill bytes 1..7: the shift alone isolates them.
    assert rm.unpack_expr(sig(can, "device_id", "id_chars")) == "bits >> 8"
    # A signed field is moved to the top and shifted back arithmetically.
    signed = dataclasses.replace(sig(can, "front_sensor_distance_1", "sensor_3_distance"), signed=True, raw_type_min=-512, raw_type_max=511)
    assert rm.unpack_expr(signed) == "(((bits << 34) as i64) >> 54) as i16"
    assert rm.pack_expr(signed, "x") == "(x as u64 & 1023) << 20"


def test_pack_expressions(can):
    assert rm.pack_expr(sig(can, "front_sensor_distance_1", "sensor_3_distance"), "d") == "u64::from(d) << 20"
    assert rm.pack_expr(sig(can, "autocar_eps_command", "eps_ctrl_mode"), "m") == "u64::from(m)"
    assert rm.pack_expr(sig(can, "device_id", "id_chars"), "c") == "c << 8"


def test_range_conditions(can):
    distance = sig(can, "front_sensor_distance_1", "sensor_3_distance")
    assert rm.misfit_expr(distance) == "value > 1023"
    # 0..500 cm, or 0x3FF "no obstacle".
    assert rm.refused_expr(distance) == "value != 1023 && value > 500"
    # A full byte: every u8 fits and is allowed — no check at all (clippy rejects `x <= 255`).
    counter = sig(can, "eps_state", "counter")
    assert rm.misfit_expr(counter) is None and rm.refused_expr(counter) is None
    # Gear command: 4 bits, documented 0..2 (E11).
    gear = sig(can, "autocar_speed_command", "gear_cmd")
    assert rm.misfit_expr(gear) == "value > 15"
    assert rm.refused_expr(gear) == "value > 2"
    # Motor speed ratio: raw 0..253 (1..254 rpm/(km/h)), 0xFF invalid.
    ratio = sig(can, "driving_state", "motor_speed_ratio")
    assert ratio.raw_min == 0 and ratio.raw_max == 253


def test_crate_model(can):
    crate = rm.build_crate(can)
    assert crate.package == "kaiwo_gateway" and crate.version == "2.0.5"
    eps = next(m for m in crate.messages if m.msg.name == "autocar_eps_command")
    assert eps.name == "AutocarEpsCommand" and eps.values == "AutocarEpsCommandValues"
    assert eps.checksum_fold and eps.checksum_shift == 56 and eps.checksum_clear == "0xFF_FFFF_FFFF_FFFF"
    assert [f.name for f in eps.fields] == ["eps_ctrl_mode", "counter", "max_angular_speed", "steering_angle_cmd"]
    # max_angular_speed: factor 2, whole deg/s 0..510 in a u16; steering angle: factor 0.1.
    assert [f.kind for f in eps.fields] == ["enum", "int", "scaled_int", "float"]
    assert [f.phys_type for f in eps.fields] == ["EpsModeCmd", "u8", "u16", "f64"]
    assert eps.fields[2].phys_expr == "self.max_angular_speed_raw() as u16 * 2"
    temp = next(f for m in crate.messages if m.msg.name == "vehicle_state_3" for f in m.fields if f.name == "battery_max_temp")
    assert (temp.kind, temp.phys_type, temp.phys_expr) == ("scaled_int", "i16", "self.battery_max_temp_raw() as i16 - 40")
    assert eps.da == "Some(0xB0)"
    # Bits 40..55 are reserved: the defined bits are everything else.
    assert eps.defined_mask == "0xFF00_00FF_FFFF_FFFF"
    # The type stores the fields' bits only: no reserved bits, no checksum byte (byte 7).
    assert eps.fields_mask == "0xFF_FFFF_FFFF"
    gear = next(e for e in crate.enums if e.table == "gear")
    assert [(v.name, v.raw) for v in gear.variants] == [("Neutral", 0), ("Drive", 1), ("Reverse", 2), ("Reserved", 3)]


def test_type_name_clash_is_reported(can):
    clashing = dataclasses.replace(can, messages=(*can.messages, dataclasses.replace(can.messages[0], name="gear")))
    with pytest.raises(ValueError, match="Rust type name Gear"):
        rm.build_crate(clashing)


def test_missing_rustfmt_is_a_clear_error(spec, monkeypatch):
    monkeypatch.setattr(formatters.shutil, "which", lambda name: None)
    with pytest.raises(GenerationError, match="rustfmt not found"):
        generate(spec, ["rust"])


@pytest.mark.skipif(shutil.which("rustfmt") is None, reason="rustfmt is not installed")
def test_committed_crate_is_what_the_generator_writes(spec):
    produced = rust_target.render_rust(spec)
    for rel, data in produced.items():
        assert (GENERATED / rel).read_bytes() == data, f"{rel} is stale: run make gen"


def _full_rule(sig, x: float):
    """The shared runtime rule, step for step as the generated `codec::to_raw` computes it."""
    import math

    from canspec.ir.encoding import to_raw_runtime

    f, o = float(sig.factor), float(sig.offset)
    if math.isnan(x):
        return None
    q = (x - o) / f
    if not (sig.raw_type_min <= q <= sig.raw_type_max):
        return None
    raw = to_raw_runtime(x, f, o)
    if any(s.raw == raw for s in sig.specials):
        return raw
    if float(sig.accept_min) <= x <= float(sig.accept_max) and sig.raw_min <= raw <= sig.raw_max:
        return raw
    return None


def test_documented_range_shortcut_agrees_with_the_full_rule(can):
    """Where the generator drops checks it proved redundant, the shortcut gives the full rule's
    answer on every raw step, every tie, both range ends and their neighbouring doubles."""
    import math
    import random

    from canspec.ir.encoding import to_raw_runtime

    rng = random.Random(5)
    checked = 0
    for msg in rm.build_crate(can).messages:
        for f in msg.fields:
            if f.to_raw not in ("to_raw_documented", "to_raw_documented_unsigned", "to_raw_int_documented", "to_raw_documented_or_special",
                                "to_raw_int_documented_or_special"):
                continue
            sig = f.sig
            fa, o = float(sig.factor), float(sig.offset)
            # The range the generated shortcut checks: the literals it compares against.
            if f.kind == "scaled_int":
                lo, hi = float(math.ceil(sig.check_min)), float(math.floor(sig.check_max))
            else:
                lo, hi = float(f.scale["accept_min"]), float(f.scale["accept_max"])
            xs = [lo, hi, math.nextafter(lo, -math.inf), math.nextafter(hi, math.inf), math.nextafter(lo, math.inf), math.nextafter(hi, -math.inf)]
            for end in (float(sig.accept_min), float(sig.accept_max), float(sig.check_min), float(sig.check_max)):
                xs += [end, math.nextafter(end, -math.inf), math.nextafter(end, math.inf)]
            xs += [r * fa + o for r in range(sig.raw_type_min, sig.raw_type_max + 1)]
            xs += [(r + 0.5) * fa + o for r in range(sig.raw_type_min - 1, sig.raw_type_max + 1)]
            xs += [rng.uniform(lo - fa, hi + fa) for _ in range(500)]
            if f.kind == "scaled_int":
                xs = [float(round(x)) for x in xs]
            for x in xs:
                if lo <= x <= hi:
                    shortcut = to_raw_runtime(x, fa, o)
                elif f.to_raw.endswith("_or_special"):
                    continue  # outside the documented range this path is the full rule itself
                else:
                    shortcut = None
                assert shortcut == _full_rule(sig, x), (msg.msg.name, sig.name, x)
                checked += 1
    assert checked > 10_000
