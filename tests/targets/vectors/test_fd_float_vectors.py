"""The vectors of a Motorola / CAN FD / IEEE float spec (tests/fixtures/valid/motorola_fd_float.yaml),
checked by computations written out again here: the DBC bit numbering placed by hand (an Intel
field runs up from its LSB, a Motorola one down from its MSB to bit 0, then on from bit 7 of the
next byte), the floats unpacked with struct, the range rule of the spec document."""

from __future__ import annotations

import json
import math
import struct
from collections import Counter
from fractions import Fraction

import pytest
from canspec.pipeline import compile_spec
from canspec.targets import registry
from repo_paths import ROOT

FIXTURE = ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml"
FMT = {32: "<f", 64: "<d"}


@pytest.fixture(scope="module")
def fixture():
    spec = compile_spec(FIXTURE).spec
    assert spec is not None
    out = registry()["vectors"].render(spec)
    return spec.can, json.loads(out["vectors/can.json"]), json.loads(out["vectors/sequences.json"])


def frame_bits(start: int, length: int, order: str) -> list[int]:
    """The frame bits (8 × byte + bit) of value bits LSB first."""
    if order == "little_endian":
        return list(range(start, start + length))
    bits, b = [], start
    for _ in range(length):
        bits.append(b)
        b = b - 1 if b % 8 else b + 15
    return bits[::-1]


def place(data: bytearray, raw: int, start: int, length: int, order: str) -> None:
    for i, pos in enumerate(frame_bits(start, length, order)):
        if raw >> i & 1:
            data[pos // 8] |= 1 << (pos % 8)


def as_float(raw: int, length: int) -> float:
    return struct.unpack(FMT[length], raw.to_bytes(length // 8, "little"))[0]


def test_bytes_are_the_fields_placed_by_hand(fixture):
    can, vectors, _ = fixture
    for case in vectors["cases"]:
        msg = can.message(case["message"])
        data = bytearray(msg.dlc)
        for sig in msg.data_signals:
            place(data, case["raw"][sig.name] & sig.mask, sig.start, sig.length, sig.byte_order)
        if msg.checksum:
            assert case["raw"][msg.checksum.signal] == data[-1] == _xor(data[:-1]), case
        assert data.hex().upper() == case["data"], case


def _xor(data: bytes) -> int:
    out = 0
    for b in data:
        out ^= b
    return out


def test_float_physical_values_are_the_bits_as_floats(fixture):
    can, vectors, _ = fixture
    names = {"NaN", "Infinity", "-Infinity"}
    for case in vectors["cases"]:
        for sig in can.message(case["message"]).data_signals:
            if not sig.is_float:
                continue
            x, got = as_float(case["raw"][sig.name], sig.length), case["physical"][sig.name]
            if math.isnan(x):
                assert got == "NaN", case
            elif math.isinf(x):
                assert got == ("Infinity" if x > 0 else "-Infinity"), case
            else:
                assert got not in names and struct.pack("<d", got) == struct.pack("<d", x), case  # -0.0 keeps its sign


def test_float_kinds_follow_the_range_rule(fixture):
    """NaN/±Inf encode only without a documented range (else raw_only); a NaN other than the quiet
    one is nan_payload; every case called encodable holds a value inside the range."""
    can, vectors, _ = fixture
    quiet = {32: 0x7FC00000, 64: 0x7FF8000000000000}
    kinds = Counter()
    for case in vectors["cases"]:
        msg = can.message(case["message"])
        for sig in (s for s in msg.data_signals if s.is_float):
            raw = case["raw"][sig.name]
            x = as_float(raw, sig.length)
            ranged = sig.doc_min is not None
            if not math.isfinite(x) and ranged or math.isfinite(x) and ranged and not sig.doc_min <= Fraction(x) <= sig.doc_max:
                assert case["kind"] == "raw_only", case
            elif math.isnan(x) and raw != quiet[sig.length]:
                assert case["kind"] in ("nan_payload", "raw_only"), case
            elif sig.name in case.get("note", ""):
                kinds[(sig.name, case["kind"])] += 1
    assert kinds[("rel_speed", "float_special")] == 7 and kinds[("timestamp", "float_special")] == 7  # ±0, ±subnormal, NaN, ±Inf
    assert kinds[("distance", "float_special")] == 3  # +0, -0, the subnormal: NaN, ±Inf and the negative subnormal are raw_only
    assert all(kinds[(s, k)] == 1 for s in ("distance", "rel_speed", "timestamp", "mileage") for k in ("min", "max"))


def test_float_ends_and_random_values(fixture):
    _, vectors, _ = fixture
    by_note = {c["note"]: c for c in vectors["cases"] if "note" in c}
    f32_max = as_float(0x7F7FFFFF, 32)
    assert by_note["rel_speed lowest"]["physical"]["rel_speed"] == -f32_max
    assert by_note["timestamp highest"]["physical"]["timestamp"] == 1.7976931348623157e308
    assert by_note["distance highest"]["physical"]["distance"] == 250.0 and by_note["mileage lowest"]["physical"]["mileage"] == 0.0
    randoms = [c for c in vectors["cases"] if c["kind"] == "random" and c["message"] == "radar_objects"]
    values = [c["physical"]["rel_speed"] for c in randoms]
    assert all(struct.unpack("<f", struct.pack("<f", v))[0] == v for v in values)  # float32 values, exact in the file
    assert len(set(values)) > 40 and all(0 <= c["physical"]["distance"] <= 250 for c in randoms)


def test_fd_frames_have_their_length(fixture):
    can, vectors, sequences = fixture
    for case in vectors["cases"]:
        assert len(bytes.fromhex(case["data"])) == can.message(case["message"]).dlc
    short = {s["messages"][0]: s for s in sequences["monitor"] if s["category"] == "length"}
    lengths = [len(st["data"]) // 2 for st in short["radar_objects"]["steps"] if st["action"] == "frame"]
    assert lengths == [64, 48, 64, 64, 64]  # one FD length short: no 63-byte frame exists


def test_a_motorola_counter_counts_in_the_sequences(fixture):
    """The monitor reads the Motorola counter where it lies: frames with counter +1 are in order."""
    _, _, sequences = fixture
    seq = next(s for s in sequences["monitor"] if s["category"] == "in_order" and s["messages"] == ["wheel_speeds"])
    frames = [st["expect"] for st in seq["steps"] if st["action"] == "frame"]
    assert [f["faults"] for f in frames] == [[]] * 5 and [f["counter_delta"] for f in frames[1:]] == [1] * 4
    wrap = next(s for s in sequences["monitor"] if s["category"] == "counter_wrap")
    assert all(st["expect"]["faults"] == [] for st in wrap["steps"] if st["action"] == "frame")
