"""The example ECU image (examples/ecu/) built with CMake for Cortex-M0+ and Cortex-M4 and run
under qemu-arm on the shared sequence vectors: what it printed for every frame and every
diagnostic request is held against the vectors' expected monitor results; the frames it sent are
decoded by the reference codec and held against the spec's cycle times and the commands the
vectors say it accepted. The sequences include checksum errors, counter jumps and timeouts."""

from __future__ import annotations

import itertools
import re
from fractions import Fraction

import ecu_image
import ecu_script
import pytest
from canspec.reference import codec

FAULT_TABLES = {"remote": "remote_entry_fault", "unmanned": "unmanned_entry_fault"}
LINE = re.compile(r"^(BOOT|RX|MON|TX|STACK) (.*)$")


@pytest.fixture(scope="module")
def spec():
    return ecu_script.node_spec(ecu_image.NODE)


@pytest.fixture(scope="module")
def chosen(spec):
    seqs = ecu_script.sequences(spec, ecu_image.NODE)
    categories = {s.vector["category"] for s in seqs}
    assert {"checksum", "counter_jump", "timeout", "in_order"} <= categories, categories
    return seqs


@pytest.fixture(scope="module")
def images(tmp_path_factory):
    assert not ecu_image.missing_tools(), f"missing {ecu_image.missing_tools()} (make setup)"
    tree = tmp_path_factory.mktemp("ecu")
    return tree, ecu_image.build(tree)


def header_macros(tree) -> dict[str, int]:
    """The monitor's event flags and states, as the generated header defines them."""
    text = (tree / "gateway" / "c" / "kaiwo_gateway_monitor.h").read_text(encoding="utf-8")
    return {m.group(1): int(m.group(2), 16 if m.group(2).startswith("0x") else 10)
            for m in re.finditer(r"#define KAIWO_GATEWAY_RX_(\w+)\s*(?:\\\s*)?(0x[0-9a-fA-F]+|\d+)u", text)}


def segments(output: str) -> list[list[tuple[str, dict[str, str], str]]]:
    """The printed lines per power-on: (kind, key=value fields, rest)."""
    out: list[list[tuple[str, dict[str, str], str]]] = []
    for line in output.splitlines():
        m = LINE.match(line)
        assert m, f"unexpected line {line!r}"
        fields = dict(re.findall(r"(\w+)=(\S+)", m.group(2)))
        if m.group(1) == "BOOT":
            out.append([])
        elif m.group(1) != "STACK":
            out[-1].append((m.group(1), fields, m.group(2)))
    return out


def codes(fields: dict[str, str]) -> dict[str, int]:
    return {table: int(fields[short]) for short, table in FAULT_TABLES.items()}


def check_frame(step, fields, flags, states, msgs):
    exp = step["expect"]
    events = int(fields["events"], 16)
    names = {name.lower() for name, bit in flags.items() if events & bit}
    rejected = names & {"unknown_id", "length", "checksum", "counter_repeat"}
    # a timeout the image's tick found before this frame arrived is no fault of the frame
    assert names - {"timeout", "recovered"} == set(exp["faults"]) - {"timeout"}, (step, fields)
    accepted = not rejected
    assert accepted == exp["accepted"] and ("recovered" in names) == exp["recovered"], (step, fields)
    if exp["message"] is not None:
        assert states[int(fields["state"])] == exp["state"], (step, fields)
    assert codes(fields) == exp["codes"], (step, fields)
    if exp["accepted"] and exp["message"] in ("autocar_eps_command", "autocar_speed_command"):
        msg = msgs[exp["message"]]
        raw = codec.unpack(msg, bytes.fromhex(step["data"]))
        name = "steering_angle_cmd" if exp["message"] == "autocar_eps_command" else "accel_cmd"
        printed = Fraction(int(fields[name].split("/")[0]), int(fields[name].split("/")[1]))
        assert printed == msg.signal(name).physical(raw[name]), (step, fields)


def check_report(step, fields, rest, states, ids):
    exp = step["expect"]
    printed = {int(k, 16): states[int(v)] for k, v in re.findall(r"\b([0-9A-F]{8})=(\d)", rest)}
    expected = {ids[name]: state for name, state in exp["states"].items() if state != "no_data"}
    assert printed == expected, (step, rest)
    assert codes(fields) == exp["codes"], (step, rest)


def check_transmissions(seq, lines, msgs, spec):
    """Each message the ECU sends, at its cycle from power-on, decodable, its counter stepping by
    one; eps_state and driving_state echo the last command the vectors say was accepted."""
    span = (seq.vector["steps"][-1]["t"] - seq.boot_t) % 2**32
    by_id = {m.frame_id: m for m in spec.can.messages}
    sent = [(int(f["t"]), by_id[int(f["id"], 16)], bytes.fromhex(f["data"])) for kind, f, _ in lines if kind == "TX"]
    tx = [m for m in spec.can.messages if m.sender == ecu_image.NODE]
    for m in tx:
        times = [(t - seq.boot_t) % 2**32 for t, msg, _ in sent if msg is m]
        assert times == list(range(0, span + 1, m.cycle_ms)), (m.name, times[:5])
        frames = [data for _, msg, data in sent if msg is m]
        assert all(len(d) == m.dlc and (m.checksum is None or codec.checksum_ok(m, d)) for d in frames), m.name
        if m.counter is not None:
            counters = [codec.unpack(m, d)[m.counter.signal] for d in frames]
            assert all((b - a) % m.counter.modulo == 1 for a, b in itertools.pairwise(counters)), (m.name, counters)
    for t, msg, data in sent:
        accepted = [s for s in seq.vector["steps"] if s["action"] == "frame" and s["expect"]["accepted"]
                    and (s["t"] - seq.boot_t) % 2**32 <= (t - seq.boot_t) % 2**32]
        if msg.name == "eps_state":
            last = [s for s in accepted if s["expect"]["message"] == "autocar_eps_command"][-1:]
            cmd = msgs["autocar_eps_command"]
            want = cmd.signal("steering_angle_cmd").physical(codec.unpack(cmd, bytes.fromhex(last[0]["data"]))["steering_angle_cmd"]) if last else 0
            assert msg.signal("steering_angle").physical(codec.unpack(msg, data)["steering_angle"]) == want, (t, data.hex())
        if msg.name == "driving_state":
            last = [s for s in accepted if s["expect"]["message"] == "autocar_speed_command"][-1:]
            want = codec.unpack(msgs["autocar_speed_command"], bytes.fromhex(last[0]["data"]))["gear_cmd"] if last else 0
            assert codec.unpack(msg, data)["gear_state"] == want, (t, data.hex())


@pytest.mark.parametrize("core", ecu_image.CORES)
def test_ecu_image_against_the_sequence_vectors(images, chosen, spec, core):
    tree, elves = images
    macros = header_macros(tree)
    flags = {
        name: bit for name, bit in macros.items() if name in {"UNKNOWN_ID", "LENGTH", "CHECKSUM", "COUNTER_JUMP", "COUNTER_REPEAT", "TIMEOUT", "RECOVERED"}
    }
    states = {macros[f"{s.upper()}"]: s for s in ("no_data", "init", "valid", "invalid")}
    assert len(flags) == 7 and len(states) == 4, macros
    msgs = {m.name: m for m in spec.can.messages}
    ids = {m.name: m.frame_id for m in spec.can.messages}
    output = ecu_image.run(elves[core], ecu_script.script(chosen))
    segs = segments(output)
    assert len(segs) == len(chosen)
    for seq, lines in zip(chosen, segs):
        steps = [s for s in seq.vector["steps"] if s["action"] != "start"]
        printed = [(kind, f, rest) for kind, f, rest in lines if kind in ("RX", "MON")]
        assert [k for k, _, _ in printed] == ["RX" if s["action"] == "frame" else "MON" for s in steps], seq.vector["id"]
        for step, (kind, fields, rest) in zip(steps, printed):
            assert int(fields["t"]) == step["t"]
            if kind == "RX":
                check_frame(step, fields, flags, states, msgs)
            else:
                check_report(step, fields, rest, states, ids)
        check_transmissions(seq, lines, msgs, spec)
    used, size = ecu_image.stack(output)
    assert 0 < used < size, (used, size)  # a stack that overflowed its paint would read as full


def test_ecu_image_sizes(images):
    _, elves = images
    for core, elf in elves.items():
        s = ecu_image.sizes(elf)
        assert 0 < s["text"] < 32 * 1024 and s["data"] < 1024, (core, s)
