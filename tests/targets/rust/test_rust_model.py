"""The Rust view model: literals, identifiers, bit expressions and encode paths, checked against
values worked out by hand from the document's layouts and against the shared rule; what the
target refuses; the generator's failure modes."""

from __future__ import annotations

import dataclasses
import math
import random
from fractions import Fraction
from pathlib import Path

import pytest
from canspec import ir
from canspec.generation import GenerationError, generate
from canspec.ir.encoding import fits_runtime, to_raw_runtime
from canspec.pipeline import compile_spec
from canspec.render import formatters
from canspec.targets import rust as rust_target
from canspec.targets.rust import bits, check, docs, encode, layout, naming, tests_view, values
from canspec.targets.rust import model as rm
from repo_paths import GENERATED, ROOT

FIXTURES = sorted((ROOT / "tests" / "fixtures" / "valid").glob("*.yaml"))


def sig(can, message, name):
    return can.message(message).signal(name)


def fixture_can(name: str) -> ir.CanProtocol:
    compiled = compile_spec(ROOT / "tests" / "fixtures" / "valid" / f"{name}.yaml")
    assert compiled.spec is not None and compiled.spec.can is not None
    return compiled.spec.can


def test_doc_text():
    assert docs.doc_text("[0, 3] <x> `y`") == "\\[0, 3\\] &lt;x&gt; 'y'"
    # One line, no list item, no code fence, no bidirectional override (rustc rejects those).
    assert docs.doc_text("- a\n    b\t~~~") == "\\- a b \\~\\~\\~"
    assert docs.doc_text("x\u202ey") == "xU+202Ey"
    assert docs.doc_lines("one\n\n  1. two\n# three") == ["one", "", "1\\. two", "\\# three"]
    assert docs.both("", "Speed") == "Speed" and docs.both("车速", "Speed") == "车速 — Speed"


def test_unpack_expressions(can):
    # sensor 3 distance: bits 20..29 of the frame (§3.17), 10 bits in a u16.
    assert bits.unpack_expr(sig(can, "front_sensor_distance_1", "sensor_3_distance"), "bits") == "((bits >> 20) & 1023) as u16"
    # A byte-aligned byte needs no mask: the cast truncates.
    assert bits.unpack_expr(sig(can, "eps_state", "counter"), "bits") == "(bits >> 56) as u8"
    assert bits.unpack_expr(sig(can, "autocar_eps_command", "eps_ctrl_mode"), "bits") == "bits as u8"
    # The VIN characters fill bytes 1..7: the shift alone isolates them, and they are a u64 already.
    assert bits.unpack_expr(sig(can, "device_id", "id_chars"), "bits") == "bits >> 8"
    # A signed field is moved to the top and shifted back arithmetically.
    signed = dataclasses.replace(sig(can, "front_sensor_distance_1", "sensor_3_distance"), signed=True, raw_type_min=-512, raw_type_max=511)
    assert bits.unpack_expr(signed, "bits") == "(((bits << 34) as i64) >> 54) as i16"
    assert bits.pack_expr(signed, "x") == "(x as u64 & 1023) << 20"
    # The whole word: no shift, no mask, no cast to the same type.
    whole = dataclasses.replace(signed, start=0, word_shift=0, length=64, storage_bits=64, word_mask=(1 << 64) - 1)
    assert (bits.unpack_expr(whole), bits.pack_expr(whole, "v"), bits.store_stmt(whole, "v")) == ("self.bits as i64", "v as u64", "self.bits = v as u64;")
    unsigned = dataclasses.replace(whole, signed=False)
    assert (bits.unpack_expr(unsigned), bits.store_stmt(unsigned, "v")) == ("self.bits", "self.bits = v;")


def test_pack_expressions(can):
    assert bits.pack_expr(sig(can, "front_sensor_distance_1", "sensor_3_distance"), "d") == "u64::from(d) << 20"
    assert bits.pack_expr(sig(can, "autocar_eps_command", "eps_ctrl_mode"), "m") == "u64::from(m)"
    assert bits.pack_expr(sig(can, "device_id", "id_chars"), "c") == "c << 8"


def test_range_conditions(can):
    distance = sig(can, "front_sensor_distance_1", "sensor_3_distance")
    assert bits.misfit_expr(distance) == "value > 1023"
    # 0..500 cm, or 0x3FF "no obstacle".
    assert bits.refused_expr(distance) == "value != 1023 && value > 500"
    # A full byte: every u8 fits and is allowed — no check at all (clippy rejects `x <= 255`).
    counter = sig(can, "eps_state", "counter")
    assert bits.misfit_expr(counter) is None and bits.refused_expr(counter) is None
    # Gear command: 4 bits, documented 0..2 (E11); checked as the enum's type.
    gear = sig(can, "autocar_speed_command", "gear_cmd")
    assert bits.misfit_expr(gear) == "value > 15"
    assert bits.refused_expr(gear) == "value > 2"
    assert bits.refused_expr(gear, ty="i16") == "!(0..=2).contains(&value)"


def test_crate_model(can):
    crate = rm.build_crate(can)
    assert crate.package == "kaiwo_gateway" and crate.version == "2.0.5" and crate.is_j1939 and not crate.id_flag_matters
    eps = next(m for m in crate.messages if m.msg.name == "autocar_eps_command")
    assert eps.name == "AutocarEpsCommand" and eps.values == "AutocarEpsCommandValues" and eps.decode_id == "AutocarEpsCommand::FRAME_ID"
    # The checksum is byte 7 and covers bytes 0..6.
    assert eps.checksum_shift == 56 and eps.cover_mask == "0xFF_FFFF_FFFF_FFFF"
    assert [f.name for f in eps.fields] == ["eps_ctrl_mode", "counter", "max_angular_speed", "steering_angle_cmd"]
    # max_angular_speed: factor 2, whole deg/s 0..510 in a u16; steering angle: factor 0.1.
    assert [f.kind for f in eps.fields] == ["enum", "int", "scaled_int", "float"]
    assert [f.phys_type for f in eps.fields] == ["EpsModeCmd", "u8", "u16", "f64"]
    assert eps.fields[2].phys_expr == "self.max_angular_speed_raw() as u16 * 2"
    assert eps.fields[3].phys_expr == "self.steering_angle_cmd_raw() as f64 * 0.1 - 1080.0"
    temp = next(f for m in crate.messages if m.msg.name == "vehicle_state_3" for f in m.fields if f.name == "battery_max_temp")
    assert (temp.kind, temp.phys_type, temp.phys_expr) == ("scaled_int", "i16", "self.battery_max_temp_raw() as i16 - 40")
    assert eps.da == "Some(0xB0)"
    # Bits 40..55 are reserved: the defined bits are everything else.
    assert eps.defined_mask == "0xFF00_00FF_FFFF_FFFF"
    # The type stores the fields' bits only: no reserved bits, no checksum byte (byte 7).
    assert eps.fields_mask == "0xFF_FFFF_FFFF"
    gear = next(e for e in crate.enums if e.table == "gear")
    assert [(v.name, v.raw) for v in gear.variants] == [("Neutral", "0"), ("Drive", "1"), ("Reverse", "2"), ("Reserved", "3")]
    assert (gear.repr, gear.other, gear.other_tag) == ("u8", "_Other", "4")


def test_names_escape_keywords_and_the_crates_own_names():
    assert [naming.type_name(n) for n in ("self", "option", "error", "text", "gear", "x_1")] == ["Self_", "Option_", "Error_", "Text_", "Gear", "X1"]
    assert naming.variant_name("self") == "Self_" and naming.variant_name("type") == "Type"
    names = naming.field_names(dataclasses.replace(rm_template(), name="type"))
    assert (names.field, names.getter, names.raw_getter, names.setter, names.store) == ("r#type", "r#type", "type_raw", "set_type", "store_type")
    names = naming.field_names(dataclasses.replace(rm_template(), name="self"))
    assert (names.field, names.getter) == ("self_", "self_")
    # A signal named like a method every message type has: its getter gets the `_`.
    names = naming.field_names(dataclasses.replace(rm_template(), name="values"))
    assert (names.field, names.getter, names.raw_getter) == ("values", "values_", "values_raw")
    assert rm.rust_crate_name("type") == "type_protocol" and rm.rust_crate_name("serde") == "serde_protocol" and rm.semver("2.01.0") == "2.1.0"


def rm_template() -> ir.Signal:
    from test_rust_bits import TEMPLATE

    return TEMPLATE


def _problems(can: ir.CanProtocol) -> list[tuple[str, str]]:
    spec = ir.Spec("x", "1", "0" * 64, can, (), None, "0")
    return [(p.rule, p.message) for p in check.problems(spec)]


def test_clashing_names_are_refused(can):
    # a message named like a value table is common: the table's enum gets `Value` after its name
    alike = dataclasses.replace(can, messages=(*can.messages, dataclasses.replace(can.messages[0], name="gear", frame_id=0x1234)))
    assert _problems(alike) == []
    assert naming.enum_type_names(alike, ["gear", "epb"]) == {"gear": "GearValue", "epb": "Epb"}
    assert next(e for e in rm.build_crate(alike).enums if e.table == "gear").name == "GearValue"
    speed = can.message("autocar_speed_command")
    raw = dataclasses.replace(speed.signal("accel_cmd"), name="accel_cmd_raw", start=40)
    clashing = dataclasses.replace(can, messages=tuple(dataclasses.replace(m, signals=(*m.signals, raw)) if m is speed else m for m in can.messages))
    found = _problems(clashing)
    assert found and {r for r, _ in found} == {"rust-name-clash"} and "`accel_cmd_raw`" in found[0][1]
    assert _problems(can) == []


def test_value_tables_get_the_narrowest_type_holding_every_user(can):
    gear = sig(can, "autocar_speed_command", "gear_cmd")
    wide = dataclasses.replace(gear, length=12, storage_bits=16, raw_type_max=4095)
    signed = dataclasses.replace(gear, signed=True, raw_type_min=-8, raw_type_max=7)
    assert values.repr_type([gear, wide]) == "u16" and values.repr_type([gear, signed]) == "i8"
    u64 = dataclasses.replace(gear, length=64, storage_bits=64, raw_type_max=(1 << 64) - 1)
    assert values.repr_type([u64, signed]) is None
    assert [p.rule for p in values.problems({"gear": [u64, signed]})] == ["rust-value-table-width"]
    # A table defining every value of its type has no catch-all.
    full = ir.ValueTable("all", tuple(ir.ValueEntry(r, f"v{r}", "", f"V{r}") for r in range(256)))
    byte = dataclasses.replace(gear, length=8, raw_type_max=255, value_table=full)
    enum = values.build_enum(full, [byte], "Full")
    assert (enum.repr, enum.other, len(enum.variants)) == ("u8", None, 256)
    # Negative raw values: the first free value at 0 or above tags the catch-all.
    neg = ir.ValueTable("n", (ir.ValueEntry(-1, "minus", "", "Minus"), ir.ValueEntry(0, "zero", "", "Zero")))
    assert values.build_enum(neg, [signed], "Neg").other_tag == "1"


def test_raw_is_two_halves_when_the_bits_carry_two_or_more_values_the_table_leaves_out(can):
    gear = sig(can, "autocar_speed_command", "gear_cmd")

    def table(*raws: int) -> ir.ValueTable:
        return ir.ValueTable("t", tuple(ir.ValueEntry(r, f"v{r}", "", f"V{r}") for r in raws))

    def field(bits: int) -> ir.Signal:
        return dataclasses.replace(gear, length=bits, raw_type_min=0, raw_type_max=(1 << bits) - 1)

    # Counted by hand: the values 0 .. 2^bits - 1 the table does not name.
    assert not values.raw_halves(table(0, 1), [field(1)])  # none left out
    assert not values.raw_halves(table(0, 1, 3), [field(2)])  # only 2
    assert values.raw_halves(table(0, 1), [field(2)])  # 2 and 3
    assert values.raw_halves(table(1, 2, 3), [field(8)])  # 0 and 4 .. 255
    assert values.raw_halves(table(0, 1), [field(1), field(8)])  # the widest user counts
    # A signed 2-bit field carries -2 .. 1.
    signed = dataclasses.replace(gear, length=2, signed=True, raw_type_min=-2, raw_type_max=1)
    assert not values.raw_halves(table(-2, -1, 0), [signed]) and values.raw_halves(table(0, 1), [signed])
    # The enum carries it; a table naming every value of its type has no catch-all and one match.
    assert values.build_enum(table(1, 2, 3), [field(8)], "T").halves
    assert not values.build_enum(table(0, 1, 3), [field(2)], "T").halves
    full = table(*range(256))
    assert not values.build_enum(full, [field(8)], "Full").halves


def test_encode_paths(can):
    steering = sig(can, "autocar_eps_command", "steering_angle_cmd")  # 0.1, -1080..1080 deg: quotients 0..21600
    assert encode.float_encoding(steering).function == "to_raw_documented_unsigned_recip"
    big = dataclasses.replace(steering, length=60, storage_bits=64, raw_type_max=(1 << 60) - 1, raw_max=(1 << 60) - 1, factor=Fraction(2), offset=Fraction(0),
                              check_min=Fraction(0), check_max=Fraction(1 << 61), accept_min=Fraction(0), accept_max=Fraction(1 << 61))
    # Quotients reach 2^52: the rounding's 2^52 branch is needed, which only round_half_away has.
    assert encode.float_encoding(big).function == "to_raw_documented"
    wide = dataclasses.replace(big, length=64, raw_type_max=(1 << 64) - 1, raw_max=(1 << 64) - 1)
    assert (encode.float_encoding(wide).function, encode.float_encoding(wide).returns) == ("to_raw_u64", "u64")
    # An integer factor on a float field: the shortcut's range is the documented one, not its whole numbers.
    odd = dataclasses.replace(big, length=40, raw_type_max=(1 << 40) - 1, raw_min=1, raw_max=5, check_min=Fraction(1, 2), check_max=Fraction(21, 2),
                              accept_min=Fraction(1, 2), accept_max=Fraction(21, 2), is_integer=True)
    short = encode.documented_range_suffices(odd, integer_path=False)
    # 0.5 is documented but rounds to raw 0, below raw_min 1: the first double the full rule
    # accepts is the one that rounds to 1 (tie epsilon included).
    assert _full_rule(odd, 0.5) is None and _full_rule(odd, 1.0) == 1 and short.pass_max == 10.5
    assert short.suffices and _full_rule(odd, short.pass_min) == 1 and _full_rule(odd, math.nextafter(short.pass_min, 0)) is None


def _full_rule(sig: ir.Signal, x: float) -> int | None:
    """The shared runtime rule, step for step: the field check, the rounding, the ranges."""
    f, o = float(sig.factor), float(sig.offset)
    if math.isnan(x) or not fits_runtime((x - o) / f, sig.raw_type_min, sig.raw_type_max):
        return None
    raw = to_raw_runtime(x, f, o)
    if any(s.raw == raw for s in sig.specials):
        return raw
    if float(sig.accept_min) <= x <= float(sig.accept_max) and sig.raw_min <= raw <= sig.raw_max:
        return raw
    return None


def _inputs(f: rm.RustField, lo: float, hi: float, rng: random.Random) -> list[float]:
    sig, fa, o = f.sig, float(f.sig.factor), float(f.sig.offset)
    xs = [lo, hi, math.nextafter(lo, -math.inf), math.nextafter(hi, math.inf), math.nextafter(lo, math.inf), math.nextafter(hi, -math.inf)]
    for end in (float(sig.accept_min), float(sig.accept_max), float(sig.check_min), float(sig.check_max)):
        xs += [end, math.nextafter(end, -math.inf), math.nextafter(end, math.inf)]
    raws = range(sig.raw_type_min, sig.raw_type_max + 1) if sig.raw_type_max - sig.raw_type_min < 5000 else \
        [sig.raw_min, sig.raw_max, *(rng.randint(sig.raw_min, sig.raw_max) for _ in range(2000))]
    xs += [r * fa + o for r in raws] + [(r + 0.5) * fa + o for r in raws]
    xs += [rng.uniform(lo - fa, hi + fa) for _ in range(500)]
    return [float(round(x)) for x in xs] if f.kind == "scaled_int" else xs


SHORTCUTS = ("to_raw_documented", "to_raw_documented_unsigned", "to_raw_documented_unsigned_recip", "to_raw_int_documented",
             "to_raw_documented_or_special", "to_raw_int_documented_or_special")


@pytest.mark.parametrize("name", ["shipped", "wide_and_signed_fields", "english_only_standard_ids", "reserved_names_j1939"])
def test_documented_range_shortcut_agrees_with_the_full_rule(can, name):
    """Where the generator drops checks it proved redundant, the shortcut gives the full rule's
    answer on every raw step (or a sample of a wide field's), every tie, both range ends and
    their neighbouring doubles."""
    rng = random.Random(5)
    checked = 0
    for msg in rm.build_crate(can if name == "shipped" else fixture_can(name)).messages:
        for f in msg.fields:
            if f.encoding is None or f.encoding.function not in SHORTCUTS:
                continue
            sig, fa, o = f.sig, float(f.sig.factor), float(f.sig.offset)
            # The literals the shortcut compares against (integers for the integer path).
            lo, hi = (float(int(f.encoding.scale[k], 0)) if f.kind == "scaled_int" else float(f.encoding.scale[k]) for k in ("check_min", "check_max"))
            for x in _inputs(f, lo, hi, rng):
                if lo <= x <= hi:
                    shortcut = to_raw_runtime(x, fa, o)
                elif f.encoding.function.endswith("_or_special"):
                    continue  # outside the documented range this path is the full rule itself
                else:
                    shortcut = None
                assert shortcut == _full_rule(sig, x), (msg.msg.name, sig.name, x)
                checked += 1
    assert checked > 1000


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_physical_round_trip_picks_round_trip(path: Path):
    """The raw values the crate's physical round-trip test draws from come back under the full rule."""
    compiled = compile_spec(path)
    assert compiled.spec is not None
    if compiled.spec.can is None:
        return
    rng = random.Random(7)
    for msg in rm.build_crate(compiled.spec.can).messages:
        for f in msg.fields:
            pick = tests_view.pick(f)
            if f.kind != "float" or pick is None:
                continue
            raws = [int(v, 0) for v in pick.values] or [rng.randint(int(pick.lo, 0), int(pick.hi, 0)) for _ in range(300)] + [int(pick.lo, 0), int(pick.hi, 0)]
            for raw in raws:
                assert _full_rule(f.sig, f.sig.runtime_physical(raw)) == raw, (msg.msg.name, f.sig.name, raw)


def test_missing_rustfmt_is_a_clear_error(spec, monkeypatch):
    monkeypatch.setattr(formatters.shutil, "which", lambda name: None)
    with pytest.raises(GenerationError, match="rustfmt not found"):
        generate(spec, ["rust"])


def test_committed_crate_is_what_the_generator_writes(spec):
    produced = rust_target.render_rust(spec)
    for rel, data in produced.items():
        assert (GENERATED / rel).read_bytes() == data, f"{rel} is stale: run make gen"


def test_static_modules_are_copied_with_the_header(spec):
    produced = rust_target.render_rust(spec)
    static = ROOT / "templates" / "rust" / "static"
    for rel in ("src/codec.rs", "src/j1939.rs"):
        text = produced[f"rust/{rel}"].decode("utf-8")
        header, _, body = text.partition("\n\n")
        assert header.startswith("// Generated by canspec") and f"sha256 {spec.sha256}" in header
        assert body == (static / rel).read_text(encoding="utf-8"), f"{rel}: the static file must be rustfmt-clean as it stands"
    # Without J1939 addressing there is no j1939 module; without value tables no values module.
    compiled = compile_spec(ROOT / "tests" / "fixtures" / "valid" / "english_only_standard_ids.yaml")
    assert compiled.spec is not None
    files = rust_target.render_rust(compiled.spec)
    assert "rust/src/j1939.rs" not in files and "rust/src/values.rs" not in files and "rust/src/codec.rs" in files
    lib = files["rust/src/lib.rs"].decode("utf-8")
    assert "pub mod j1939" not in lib and "values::*" not in lib and "PDU2_MIN_PF" not in files["rust/src/constants.rs"].decode("utf-8")


def test_many_flags_count_one_instruction_each_held_as_bytes(can):
    # Counted by hand from the spec's tables (layout.py's costs):
    # vehicle_fault: 21 flags, a 2-bit field at bit 0 (word 2, bytes 2), 2-bit fields at 24 and 26
    # (word 3 + 3, bytes 2 + 3), 4-bit fields at 28, 32, 36, 40, 44 (word 3 each, bytes 1, 2, 1, 2, 1)
    # in bytes 0..5: word 21 + 2 + 6 + 15 = 44; bytes 6 loads + 21 + 2 + 5 + 7 = 41 (21 flags >= FLAG_RUN).
    fault = can.message("vehicle_fault")
    assert layout.holds_bytes(fault)
    # rgate_control_command_2: 2 flags (bits 0 and 7), 2-bit at 1 and 4-bit at 3 (3 and 3 either way),
    # whole bytes 1 and 7 (word 3 and 2): word 1 + 1 + 3 + 3 + 3 + 2 = 13; bytes 3 loads + 2 + 2 + 3 + 3 = 13: a tie keeps the word.
    assert not layout.holds_bytes(can.message("rgate_control_command_2"))
    flag = next(s for s in fault.signals if s.name == "dc_fault")
    assert (layout._byte_cost(flag, layout.FLAG_RUN - 1), layout._byte_cost(flag, layout.FLAG_RUN), layout._word_cost(flag)) == (2, 1, 1)
    assert next(m for m in rm.build_crate(can).messages if m.msg.name == "vehicle_fault").holds_bytes
