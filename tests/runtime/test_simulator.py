"""The rest-bus simulator end to end on python-can's virtual bus, in one process: the simulator
sends on one bus instance, the generated package's receive monitor watches a second one on the
same channel. Five seconds of AUTOCAR's traffic are all valid with periods within ±10 % of the
cycles; every injected fault is detected with 0x1813A0B0's code; values change while it runs; the
command line runs; a spec with 11-bit IDs, event-driven messages and no fault table works too.
The measured periods are written to build/simulate/periods.json."""

from __future__ import annotations

import json
import subprocess
import sys
import threading
import time
import uuid

import can
import pytest
from canspec import cli
from canspec.commands.simulate import command
from canspec.runtime import supervision
from canspec.runtime.simulate import RestBus, SimFault, SimulationError
from repo_paths import CANSPEC_ENV, ROOT

from targets.python import pkgpath  # noqa: F401  (puts the generated package on sys.path)
from runtime.test_sequences import spec_ir

NODE = "AUTOCAR"
TOLERANCE = 0.10


def channel() -> str:
    return f"canspec-sim-{uuid.uuid4().hex[:8]}"


def watch(rx: can.BusABC, mon, seconds: float, on_event=None) -> list:
    """Feed every frame for `seconds` to the monitor (checking timeouts as time goes); the faults seen."""
    from kaiwo_gateway import bus as kb

    faults = []
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        frame = rx.recv(0.005)
        if frame is not None:
            ev = kb.feed(mon, frame)
            if ev is not None and ev.faults:
                faults.append(ev)
            if on_event is not None and ev is not None:
                on_event(ev, frame)
        faults += mon.check(round(time.time() * 1000))
    return faults


def test_five_seconds_all_valid_with_periods_within_ten_percent(spec):
    import kaiwo_gateway as kg

    ch = channel()
    with can.Bus(interface="virtual", channel=ch) as tx, can.Bus(interface="virtual", channel=ch) as rx:
        mon = kg.new_monitor()
        sim = RestBus(spec.can, NODE, tx)
        sent = {m: spec.can.message(m) for m in sim.messages}
        assert sorted(sent) == sorted(m.name for m in spec.can.messages if m.sender == NODE)
        with sim:
            faults = watch(rx, mon, 5.0)
    assert faults == []
    periods = {}
    for name, msg in sent.items():
        s = mon.stats(name)
        assert mon.state(name) is kg.monitor.State.VALID, name
        assert s.frames == s.accepted and s.frames >= 0.9 * 5000 / msg.cycle_ms, (name, s)
        assert abs(s.mean_gap_ms - msg.cycle_ms) <= TOLERANCE * msg.cycle_ms, (name, s)
        periods[name] = {"cycle_ms": msg.cycle_ms, "frames": s.frames, "mean_ms": round(s.mean_gap_ms, 3), "min_ms": s.min_gap_ms, "max_ms": s.max_gap_ms}
    out = ROOT / "build" / "simulate"
    out.mkdir(parents=True, exist_ok=True)
    (out / "periods.json").write_text(json.dumps(periods, indent=1) + "\n", encoding="utf-8")
    print(json.dumps(periods))


@pytest.mark.parametrize(("message", "fault", "detected", "code"), [
    ("autocar_eps_command", SimFault.DROP, "timeout", 7),
    ("autocar_eps_command", SimFault.CORRUPT_CHECKSUM, "checksum", 5),
    ("autocar_speed_command", SimFault.CORRUPT_CHECKSUM, "checksum", 6),
    ("autocar_speed_command", SimFault.FREEZE_COUNTER, "counter_repeat", 7),  # no new data: it times out
    ("autocar_control_command_1", SimFault.FREEZE_COUNTER, "counter_repeat", 7),
])
def test_injected_faults_are_detected_with_the_protocols_codes(spec, message, fault, detected, code):
    import kaiwo_gateway as kg

    ch = channel()
    with can.Bus(interface="virtual", channel=ch) as tx, can.Bus(interface="virtual", channel=ch) as rx, RestBus(spec.can, NODE, tx) as sim:
        mon = kg.new_monitor()
        assert watch(rx, mon, 0.4) == []
        assert mon.state(message) is kg.monitor.State.VALID
        sim.inject(message, fault)
        timeout = spec.can.message(message).timeout_ms
        faults = watch(rx, mon, 2 * timeout / 1000 + 0.1)
        kinds = {f.value for ev in faults if isinstance(ev, kg.monitor.FrameEvent) for f in ev.faults}
        timeouts = {ev.message for ev in faults if isinstance(ev, kg.monitor.TimeoutEvent)}
        assert detected in kinds or (detected == "timeout" and message in timeouts), faults[:3]
        assert {ev.message for ev in faults} == {message}, "only the faulty message"
        assert mon.state(message) is kg.monitor.State.INVALID
        assert mon.fault_codes() == {"remote_entry_fault": code, "unmanned_entry_fault": code}
        sim.clear(message)
        watch(rx, mon, 0.3)
        assert mon.state(message) is kg.monitor.State.VALID and mon.fault_codes() == {"remote_entry_fault": 0, "unmanned_entry_fault": 0}


def test_values_are_settable_while_it_runs(spec):
    import kaiwo_gateway as kg

    ch = channel()
    seen = []
    with can.Bus(interface="virtual", channel=ch) as tx, can.Bus(interface="virtual", channel=ch) as rx, RestBus(spec.can, NODE, tx) as sim:
        sim.set("autocar_speed_command", accel_cmd=-1.5, gear_cmd=1)
        with pytest.raises(SimulationError, match="accel_cmd"):
            sim.set("autocar_speed_command", accel_cmd=99)
        with pytest.raises(SimulationError, match="checksum"):
            sim.set("autocar_speed_command", checksum=1)
        with pytest.raises(SimulationError, match="does not send"):
            sim.set("vehicle_state_1", speed=1)
        sim.set("autocar_eps_command", eps_ctrl_mode="auto_angle")  # a value name: raw 0x20
        assert command(sim, "set autocar_eps_command eps_ctrl_mode=manual_assist") == "set autocar_eps_command {'eps_ctrl_mode': 'manual_assist'}"
        with pytest.raises(SimulationError) as err:
            sim.set("autocar_eps_command", eps_ctrl_mode="stop")
        assert str(err.value) == ("autocar_eps_command.eps_ctrl_mode: 'stop' is neither a number nor a value name "
                                  "(its value names: auto_angle, manual_assist, stop_control)")
        for line, usage in (("set", "set MESSAGE SIGNAL=VALUE..."), ("set autocar_eps_command eps_ctrl_mode", "set MESSAGE SIGNAL=VALUE..."),
                            ("fault autocar_eps_command", "fault MESSAGE KIND")):
            with pytest.raises(SimulationError) as err:
                command(sim, line)
            assert str(err.value) == f"{line!r}: expected `{usage}`"
        mon = kg.new_monitor()
        watch(rx, mon, 0.2, lambda ev, frame: seen.append(kg.bus.decode_frame(frame)))
    speeds = [m for m in seen if isinstance(m, kg.AutocarSpeedCommand)]
    assert speeds and speeds[-1].accel_cmd == pytest.approx(-1.5) and speeds[-1].gear_cmd == kg.Gear.DRIVE
    eps = [m for m in seen if isinstance(m, kg.AutocarEpsCommand)]
    assert eps and eps[-1].eps_ctrl_mode == kg.EpsModeCmd.MANUAL_ASSIST


def test_command_line(spec, capsys):
    import kaiwo_gateway as kg

    ch = channel()
    got: list = []
    with can.Bus(interface="virtual", channel=ch) as rx:
        args = ["simulate", "--node", NODE, "--channel", ch, "--duration", "0.5", "--set", "autocar_speed_command.accel_cmd=-2",
                "--fault", "autocar_eps_command=drop"]
        runner = threading.Thread(target=lambda: got.append(cli.main(args)))
        runner.start()
        frames = []
        while runner.is_alive():
            frame = rx.recv(0.01)
            if frame is not None:
                frames.append(kg.bus.decode_frame(frame))
        runner.join()
    assert got == [0]
    names = {type(m).__name__ for m in frames}
    assert names == {"AutocarSpeedCommand", "AutocarControlCommand1", "AutocarControlCommand2"}  # eps dropped
    assert all(m.accel_cmd == -2 for m in frames if isinstance(m, kg.AutocarSpeedCommand))
    err = capsys.readouterr().err
    assert "frames sent: autocar_eps_command 0, autocar_speed_command" in err
    assert cli.main(["simulate", "--node", "NOBODY", "--duration", "0"]) == 1
    assert "no node 'NOBODY'" in capsys.readouterr().err
    assert cli.main(["simulate", "--node", NODE, "--duration", "0", "--fault", "autocar_control_command_2=corrupt_checksum"]) == 1
    assert "has no checksum" in capsys.readouterr().err


def test_any_spec_standard_ids_event_driven_no_fault_table():
    spec = spec_ir(ROOT / "tests" / "fixtures" / "valid" / "english_only_standard_ids.yaml")
    ch = channel()
    with can.Bus(interface="virtual", channel=ch) as tx, can.Bus(interface="virtual", channel=ch) as rx:
        sim = RestBus(spec.can, "ECU", tx)
        assert sim.messages == ["type", "async_state", "extended_status"]
        mon = supervision.new_monitor(spec.can)
        events = []
        with sim:
            sim.set("type", self=2.5)  # event-driven: sent on the change
            end = time.monotonic() + 0.55
            while time.monotonic() < end:
                frame = rx.recv(0.01)
                if frame is not None:
                    events.append((frame, mon.feed(round(frame.timestamp * 1000), frame.arbitration_id, frame.is_extended_id, frame.data)))
    flags = {ev.message: frame.is_extended_id for frame, ev in events}
    assert flags == {"type": False, "async_state": False}  # extended_status is event-driven and unchanged: not sent
    assert all(not ev.faults for _, ev in events) and mon.fault_codes() == {}
    assert mon.stats("type").frames == 1 and 4 <= mon.stats("async_state").frames <= 7


def test_fd_frames_go_out_as_fd_and_a_motorola_counter_counts():
    """The FD fixture's node: the 64-byte message as an FD frame with bit-rate switching, the 12-byte one
    without; its Motorola counter advances frame by frame (no counter fault in canspec's monitor)."""
    spec = spec_ir(ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml")
    ch = channel()
    with can.Bus(interface="virtual", channel=ch) as tx, can.Bus(interface="virtual", channel=ch) as rx:
        sim = RestBus(spec.can, "ESC", tx, messages=["radar_objects"])
        mon = supervision.new_monitor(spec.can)
        frames = []
        for _ in range(3):
            for name in sim.messages:
                sim.send(name)
                frames.append(rx.recv(1.0))
    by_id = {m.frame_id: m for m in spec.can.messages}
    for frame in frames:
        msg = by_id[frame.arbitration_id]
        assert (frame.is_fd, frame.bitrate_switch, len(frame.data)) == (msg.is_fd, msg.brs, msg.dlc), msg.name
        assert not mon.feed(round(frame.timestamp * 1000), frame.arbitration_id, frame.is_extended_id, frame.data).faults
    assert {m.name for m in spec.can.messages if m.is_fd} <= {by_id[f.arbitration_id].name for f in frames}
    assert mon.stats("wheel_speeds").accepted == 3 and mon.stats("wheel_speeds").lost_frames == 0


def test_a_multiplexed_message_sends_the_page_its_multiplexers_select():
    """The mux fixture's SENSOR: values of every page are kept, each frame holds the pages the multiplexers
    select (cantools reading the generated DBC decodes exactly them), and the monitor sees no fault."""
    import cantools
    from canspec.generation import generate

    spec = spec_ir(ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml")
    db = cantools.database.load_string(generate(spec, ["dbc"])["dbc"]["dbc/mux_bus.dbc"].decode("utf-8"), database_format="dbc")
    ch = channel()
    with can.Bus(interface="virtual", channel=ch) as tx, can.Bus(interface="virtual", channel=ch) as rx:
        sim = RestBus(spec.can, "SENSOR", tx)
        mon = supervision.new_monitor(spec.can)
        sim.set("sensor_report", temperature=-12.5, pressure=1000.5, level=7, gain=3, voltage=12.34)
        seen = []
        for mode, channel_ in ((0, 0), (5, 0), (2, 0), (2, 3)):
            sim.set("sensor_report", mode=mode, channel=channel_)
            sim.send("sensor_report")
            frame = rx.recv(1.0)
            assert not mon.feed(round(frame.timestamp * 1000), frame.arbitration_id, frame.is_extended_id, frame.data).faults
            seen.append(db.decode_message(frame.arbitration_id, frame.data, decode_choices=False))
    assert [set(s) - {"mode", "status", "counter"} for s in seen] == [{"temperature"}, {"pressure", "level"}, {"channel", "gain"}, {"channel", "voltage"}]
    assert (seen[0]["temperature"], seen[1]["pressure"], seen[1]["level"], seen[2]["gain"]) == (-12.5, 1000.5, 7, 3)
    assert seen[3]["voltage"] == pytest.approx(12.34) and seen[3]["channel"] == 3


@pytest.mark.parametrize(("args", "says"), [
    (["--duration", "1e400"], "argument --duration: 1e400 is not a finite number"),  # was an internal OverflowError
    (["--duration", "nan"], "argument --duration: nan is not a finite number"),  # nan and -1 ran one frame, exit 0
    (["--duration", "-1"], "argument --duration: -1 is not in 0..31536000 (seconds;"),
    (["--bitrate", "-5"], "argument --bitrate: -5 is not in 1..20000000 (bit/s)"),
    (["--bitrate", "fast"], "argument --bitrate: 'fast' is not an integer"),
])
def test_arguments_no_run_can_have_are_usage_errors(args, says):
    proc = subprocess.run([sys.executable, "-m", "canspec", "simulate", "--node", NODE, "--channel", channel(), *args],
                          capture_output=True, text=True, env=CANSPEC_ENV, check=False, timeout=60)
    assert proc.returncode == 2 and proc.stderr.startswith("usage: canspec simulate") and f"canspec simulate: error: {says}" in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr and "frames sent" not in proc.stderr
