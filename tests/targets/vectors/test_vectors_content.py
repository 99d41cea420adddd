"""The shared vector file covers what the foundation promises, and its bytes are right by an
independent computation here (bit placement and XOR written out again, not via the codec)."""

from __future__ import annotations

from collections import Counter


def place(raw: int, start: int, length: int) -> int:
    return (raw & ((1 << length) - 1)) << start


def test_header(vectors, spec):
    assert vectors["spec"] == spec.name and vectors["version"] == "2.0.5" and vectors["sha256"] == spec.sha256


def test_coverage_per_message(vectors, can):
    kinds = Counter((c["message"], c["kind"]) for c in vectors["cases"])
    for msg in can.messages:
        sigs = [s for s in msg.data_signals if s.role != "checksum"]
        assert kinds[(msg.name, "zero")] == 1, msg.name
        if not sigs:
            continue
        assert kinds[(msg.name, "random")] >= 50
        assert kinds[(msg.name, "min")] == kinds[(msg.name, "max")] == len(sigs)
        enum_values = sum(len(s.value_table.entries) for s in sigs if s.value_table)
        assert kinds[(msg.name, "enum")] + kinds[(msg.name, "raw_only")] == enum_values
        if any(s.is_scaled and s.raw_max - s.raw_min >= 2 for s in sigs):
            assert kinds[(msg.name, "tie")] > 0, msg.name


def test_bytes_checksums_and_counters(vectors, can):
    for case in vectors["cases"]:
        msg = can.message(case["message"])
        value = 0
        for sig in msg.data_signals:
            value |= place(case["raw"][sig.name], sig.start, sig.length)
        data = bytearray(value.to_bytes(8, "little"))
        if msg.checksum:
            xor = 0
            for b in range(7):
                xor ^= data[b]
            assert case["raw"]["checksum"] == xor and data[7] == xor
        assert data.hex().upper() == case["data"], case
        if msg.counter:
            assert 0 <= case["raw"][msg.counter.signal] < msg.counter.modulo


def test_physical_values_are_raw_times_factor_plus_offset(vectors, can):
    for case in vectors["cases"]:
        msg = can.message(case["message"])
        for sig in msg.data_signals:
            expected = case["raw"][sig.name] * sig.factor + sig.offset
            got = case["physical"][sig.name]
            if case["kind"] == "tie" and case["note"].startswith(sig.name + " "):
                assert abs(got - float(expected)) <= float(sig.factor) / 2 * (1 + 1e-9)
            else:
                assert abs(got - float(expected)) <= 1e-9 * max(1, abs(float(expected))), (case, sig.name)


def test_vin_frames(vectors):
    (case, *_rest) = [v for v in vectors["multiframe"] if v["text"] == "LKLA6G1H8LA000205"]
    assert case["frame_id"] == 0x18FFAF00
    chunks = [bytes.fromhex(f) for f in case["frames"]]
    assert [c[0] >> 6 for c in chunks] == [0, 1, 2]  # ID 序号 in bits 6..7 of byte 1
    assert b"".join(c[1:] for c in chunks) == b"LKLA6G1H8LA000205" + b"\0" * 4
