"""python-can integration: to/from can.Message, and the example on python-can's virtual bus."""

from __future__ import annotations

import subprocess
import sys

import pytest

from targets.python import pkgpath

can = pytest.importorskip("can")


def test_to_and_from_can_message(gw):
    from kaiwo_gateway import bus

    m = gw.AutocarSpeedCommand(accel_cmd=-1.5, gear_cmd=gw.Gear(1), counter=9)
    frame = bus.to_can_message(m, channel="vcan0")
    assert isinstance(frame, can.Message)
    assert frame.arbitration_id == 0x1803B0A0 and frame.is_extended_id and frame.dlc == 8 and bytes(frame.data) == m.encode()
    assert bus.from_can_message(frame) == gw.decode(0x1803B0A0, m.encode())
    bad = can.Message(arbitration_id=0x1803B0A0, is_extended_id=True, data=bytes(frame.data[:7]) + bytes([frame.data[7] ^ 1]))
    with pytest.raises(gw.ChecksumError):
        bus.from_can_message(bad)
    assert bus.from_can_message(bad, verify_checksum=False).counter == 9


def test_a_frame_matches_a_message_only_with_its_id_format(gw):
    from kaiwo_gateway import bus

    data = gw.AutocarSpeedCommand().encode()
    standard = can.Message(arbitration_id=0x1803B0A0 & 0x7FF, is_extended_id=False, data=data)
    wrong_format = can.Message(arbitration_id=0x1803B0A0, is_extended_id=False, data=data)
    for frame in (standard, wrong_format):
        with pytest.raises(gw.UnknownFrameError, match=r"unknown frame ID 0x[0-9A-F]+ \(11-bit\)") as exc:
            bus.from_can_message(frame)
        assert exc.value.is_extended is False
    with can.Bus(interface="virtual", channel="canspec-format") as tx, can.Bus(interface="virtual", channel="canspec-format") as rx:
        tx.send(wrong_format)
        assert bus.receive(rx, timeout=0.05) is None  # skipped: the protocol's 0x1803B0A0 is a 29-bit ID


def test_send_receive_skips_foreign_frames(gw):
    from kaiwo_gateway import bus

    with can.Bus(interface="virtual", channel="canspec-test") as tx, can.Bus(interface="virtual", channel="canspec-test") as rx:
        tx.send(can.Message(arbitration_id=0x123, is_extended_id=False, data=b"\x01"))
        bus.send(tx, gw.VehicleState2())
        got = bus.receive(rx, timeout=1.0)
        assert isinstance(got, gw.VehicleState2)
        assert bus.receive(rx, timeout=0.05) is None


def test_example_runs_on_the_virtual_bus():
    proc = subprocess.run([sys.executable, str(pkgpath.PACKAGE_DIR / "examples" / "virtual_bus.py")], capture_output=True, text=True,
                          env={"PYTHONPATH": str(pkgpath.PACKAGE_DIR), "PATH": "/usr/bin:/bin"}, timeout=60, check=False)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert len(lines) == 3 and all(line.startswith("AutocarEpsCommand(") for line in lines)
    assert [line.split("counter=")[1].split(",")[0] for line in lines] == ["1", "2", "3"]
