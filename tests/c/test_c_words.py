"""The C target's word plans (words.py, wordplans.py): executed in Python, every plan moves every field of
every message exactly between its frame bits and its struct slot. The oracle is plain bit
arithmetic on the frame word ((v >> start) & mask), not the plans themselves."""

from __future__ import annotations

import random

from canspec.targets.c import model as cmodel
from canspec.targets.c import wordplans
from canspec.targets.c import words as cwords


def _fields(cm):
    return [cwords.Field(s.field, s.start, s.length, s.sig.storage_bits, s.sig.signed, s.needs_check) for s in cm.signals]


def test_natural_layout():
    assert cwords.natural_offsets([8, 8, 8, 16, 8]) == [0, 1, 2, 4, 6]
    assert cwords.struct_size([8, 8, 8, 16, 8]) == 8
    assert cwords.natural_offsets([8, 8, 64]) == [0, 1, 8] and cwords.struct_size([8, 8, 64]) == 16
    assert cwords.struct_size([16] * 6 + [8]) == 14


def test_every_plan_moves_every_field_both_ways(spec):
    rng = random.Random(7)
    model = cmodel.build_model(spec)
    for cm in model.messages:
        fields = _fields(cm)
        offsets = cwords.natural_offsets([f.storage for f in fields])
        runs = wordplans.plan_runs(fields, offsets)
        assert [f.name for r in runs for f in r.fields] == [f.name for f in fields], cm.name
        for run in runs:  # a run stays inside one 8-byte block of the struct
            first = offsets[fields.index(run.fields[0])]
            assert all(offsets[fields.index(f)] // 8 == first // 8 for f in run.fields), cm.name
        for _ in range(300):
            v = rng.getrandbits(64)
            for run in runs:
                got = cwords.unpack_run(run, v)
                assert got == [(v >> f.start) & ((1 << f.length) - 1) for f in run.fields], (cm.name, hex(v))
                frame_bits = sum(((1 << f.length) - 1) << f.start for f in run.fields)
                assert cwords.pack_run(run, got) == v & frame_bits, (cm.name, hex(v))


def test_regular_fields_move_together(spec):
    """Four 2-bit fields per byte (control_command_1) move with a few SWAR steps, not one by one."""
    model = cmodel.build_model(spec)
    cm = next(m for m in model.messages if m.msg.name == "autocar_control_command_1")
    first = cm.unpack_runs[0]
    assert len(first.run.fields) == 8 and len(first.run.steps) == 3 and not first.run.groups
    assert first.run.cost < 8 * 6


def test_range_check_masks_cover_the_excess_bits(spec):
    model = cmodel.build_model(spec)
    cm = next(m for m in model.messages if m.msg.name == "front_sensor_distance_1")
    run = cm.pack_runs[0]  # sensors 1..4: 10 bits in uint16_t slots at bits 0, 16, 32, 48
    assert run.run.check == sum(0xFC00 << (16 * i) for i in range(4))


def test_flags_move_by_one_multiplication(spec):
    """vehicle_fault's flags (one bit each, spread over a byte each) move by a multiplication
    each way instead of three SWAR steps; its exactness does not depend on the data, so the
    words that make the most copies meet (all ones, alternating bits) are checked too."""
    model = cmodel.build_model(spec)
    cm = next(m for m in model.messages if m.msg.name == "vehicle_fault")
    muls = [r.run for r in cm.unpack_runs if r.run.mul is not None]
    assert len(muls) >= 2 and all(not r.steps for r in muls)
    fields = _fields(cm)
    runs = wordplans.plan_runs(fields, cwords.natural_offsets([f.storage for f in fields]))
    for v in ((1 << 64) - 1, 0x5555555555555555, 0xAAAAAAAAAAAAAAAA, 0x8000000000000001):
        for run in runs:
            got = cwords.unpack_run(run, v)
            assert got == [(v >> f.start) & ((1 << f.length) - 1) for f in run.fields], hex(v)
            assert cwords.pack_run(run, got) == v & sum(((1 << f.length) - 1) << f.start for f in run.fields), hex(v)


def test_a_multiplication_whose_copies_meet_is_refused():
    """Eight flags in bits 0..7 to bytes 0..7: flag 7 moved by flag 0's distance meets flag 0
    moved by flag 1's, so the sum would carry; seven flags are fine."""
    eight = tuple(cwords.Field(f"f{i}", i, 1, 8, False, True) for i in range(8))
    slots = tuple(8 * i for i in range(8))
    assert wordplans._mul_plan(eight, slots) is None
    seven = wordplans._mul_plan(eight[:7], slots[:7])
    assert seven is not None and seven.mul is not None
    for v in range(128):
        got = cwords.unpack_run(seven, v)
        assert got == [(v >> i) & 1 for i in range(7)]
        assert cwords.pack_run(seven, got) == v
