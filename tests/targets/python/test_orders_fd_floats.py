"""Motorola fields, CAN FD frames and IEEE floats in the generated package, against the reference
codec (generator/canspec/reference/codec.py, which agrees with cantools on this fixture): raw values
both ways, physical decode, the float encode rules (range, NaN/±Inf only without a documented range,
beyond the largest float32 refused), the python-can glue's FD frames and the monitor's Motorola counter."""

from __future__ import annotations

import math
import random
import struct

import can
import pytest
from canspec.pipeline import compile_spec
from canspec.reference import codec
from canspec.targets import python as target

from targets.python import pkgpath
from targets.python.vector_runner import attr_names, load_package

FIXTURE = pkgpath.ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml"
SPEC = compile_spec(FIXTURE, ["python"]).spec
CAN = SPEC.can
FLOAT32_MAX = struct.unpack("<f", b"\xff\xff\x7f\x7f")[0]


@pytest.fixture(scope="module")
def pkg(tmp_path_factory):
    root = tmp_path_factory.mktemp("orders-fd-floats")
    for rel, data in target.render_python(SPEC).items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_bytes(data)
    module = load_package(root / "python" / "chassis_fd")
    import chassis_fd.bus  # noqa: F401  (its python-can module)

    return module


def test_the_fixture_has_what_is_tested():
    sigs = [s for m in CAN.messages for s in m.data_signals]
    assert any(s.is_big_endian for s in sigs) and any(not s.is_big_endian for s in sigs)
    assert {s.length for s in sigs if s.is_float} == {32, 64} and any(m.dlc == 64 and m.is_fd for m in CAN.messages)
    assert any(m.counter is not None and m.counter.word_order == "big" for m in CAN.messages)


def _same(got, want) -> bool:
    if isinstance(want, float) and math.isnan(want):
        return math.isnan(got)
    return got == want and math.copysign(1, got) == math.copysign(1, want)


def test_random_frames_decode_and_encode_as_the_reference(pkg):
    rng = random.Random(24)
    for msg in CAN.messages:
        cls = pkg.BY_ID[msg.frame_id]
        names = attr_names(cls)
        for _ in range(300):
            raw = {s.name: rng.randint(s.raw_type_min, s.raw_type_max) for s in msg.data_signals if s.role != "checksum"}
            data = codec.pack(msg, raw)
            assert pkg.decode_raw(msg.frame_id, data) == codec.unpack(msg, data), msg.name
            assert pkg.encode_raw(msg.frame_id, raw) == data and cls.checksum_ok(data)
            decoded = pkg.decode(msg.frame_id, data)
            for s in msg.data_signals:
                want = float(codec.physical_number(s, codec.unpack(msg, data)[s.name]))
                assert _same(float(getattr(decoded, names[s.name])), want), (msg.name, s.name)
            if all(s.raw_allowed(codec.unpack(msg, data)[s.name]) for s in msg.data_signals if s.role == "data" and not s.is_float):
                try:
                    expected = codec.pack(msg, {s.name: codec.to_raw(s, getattr(decoded, names[s.name])) for s in msg.data_signals
                                                if s.role != "checksum"})
                except codec.CodecError:
                    with pytest.raises(pkg.RangeError):
                        decoded.encode()
                else:
                    assert decoded.encode() == expected, msg.name


FLOAT_INPUTS = [0.0, -0.0, 1.5, -1.5, 250.0, 250.00000000000003, -1e-300, 1e-45, FLOAT32_MAX, -FLOAT32_MAX, math.nextafter(FLOAT32_MAX, math.inf),
                3.5e38, -3.5e38, 1e308, math.inf, -math.inf, math.nan, 0.1, 1e6, 1000000.0000000001, 7, 10**400]


@pytest.mark.parametrize(("message", "signal"), [(m.name, s.name) for m in CAN.messages for s in m.data_signals if s.is_float])
def test_float_encode_rules_are_the_reference_rules(pkg, message, signal):
    msg = CAN.message(message)
    sig = next(s for s in msg.data_signals if s.name == signal)
    cls = pkg.BY_ID[msg.frame_id]
    attr = attr_names(cls)[signal]
    for x in FLOAT_INPUTS:
        try:
            bits = codec.float_raw(sig, x)
        except codec.CodecError:
            with pytest.raises(pkg.RangeError):
                cls(**{attr: x}).encode()
        else:
            assert pkg.decode_raw(msg.frame_id, cls(**{attr: x}).encode())[signal] == bits, (signal, x)
    with pytest.raises(TypeError):
        cls(**{attr: "1.0"}).encode()


def test_fd_messages_travel_as_fd_frames(pkg):
    ch = f"canspec-fd-{random.getrandbits(32):08x}"
    with can.Bus(interface="virtual", channel=ch, receive_own_messages=False) as tx, can.Bus(interface="virtual", channel=ch) as rx:
        for msg in CAN.messages:
            cls = pkg.BY_ID[msg.frame_id]
            frame = pkg.bus.to_can_message(cls())
            assert (frame.is_fd, frame.bitrate_switch, frame.dlc) == (msg.is_fd, msg.brs, msg.dlc), msg.name
            pkg.bus.send(tx, cls())
            assert isinstance(pkg.bus.receive(rx, timeout=1.0), cls)
    big = next(m for m in CAN.messages if m.dlc == 64)
    data = pkg.BY_ID[big.frame_id]().encode()
    classic = can.Message(arbitration_id=big.frame_id, is_extended_id=False, data=data[:8], is_fd=False)
    assert pkg.bus.decode_frame(classic).reason is pkg.bus.Skip.FD_FRAME
    small = next(m for m in CAN.messages if not m.is_fd)
    as_fd = can.Message(arbitration_id=small.frame_id, is_extended_id=False, data=pkg.BY_ID[small.frame_id]().encode(), is_fd=True)
    assert pkg.bus.decode_frame(as_fd).reason is pkg.bus.Skip.FD_FRAME


def test_monitor_reads_a_motorola_counter(pkg):
    msg = next(m for m in CAN.messages if m.counter is not None and m.counter.word_order == "big")
    mon = pkg.new_monitor()
    faults = []
    for t, counter in enumerate((1, 2, 2, 3, 9)):
        data = codec.pack(msg, {msg.counter.signal: counter})
        faults.append(mon.feed(t * 10, msg.frame_id, msg.is_extended, data).faults)
    assert [tuple(f.value for f in fs) for fs in faults] == [(), (), ("counter_repeat",), (), ("counter_jump",)]


def test_fd_frames_of_another_length_are_refused_and_any_buffer_is_read(pkg):
    """An FD message's bytes come out of one struct unpack: a frame one byte short or long is a
    FrameLengthError (not struct's error), and bytes, bytearray and memoryview decode alike."""
    rng = random.Random(7)
    fd = [m for m in CAN.messages if m.dlc > 8]
    assert fd
    for msg in fd:
        data = codec.pack(msg, {s.name: rng.randint(s.raw_type_min, s.raw_type_max) for s in msg.data_signals if s.role != "checksum"})
        for wrong in (data[:-1], data + b"\0", b""):
            for call in (pkg.decode, pkg.decode_raw):
                with pytest.raises(pkg.FrameLengthError):
                    call(msg.frame_id, wrong)
        want = pkg.decode_raw(msg.frame_id, data)
        assert want == codec.unpack(msg, data)
        assert pkg.decode_raw(msg.frame_id, bytearray(data)) == want == pkg.decode_raw(msg.frame_id, memoryview(data))
