"""One fixture pair per change kind: the base spec and one edit of it, with the change and the
class the ladder of issue 7 gives it (wire > source > compatible > docs), written down here
from the ladder's definitions rather than taken from the tool."""

from __future__ import annotations

import dataclasses
import json

import pytest
from canspec.diff.classes import KINDS
from canspec.diff.compare import compare
from canspec.diff.inputs import load_model
from diff_helpers import BASE, ROOT, diff_paths, edited

CMD_RESERVED = "      - {role: reserved, start: 16, len: 48}\n"
NEW_MESSAGE = """  - name: extra
    title: Extra
    zh: 额外
    id: 0x1803A0B0
    j1939: {priority: 6, pf: 0x03, ps: 0xA0, sa: 0xB0}
    sender: ECU
    receivers: ALL
    cycle_ms: 100
    signals:
      - {name: level, zh: 液位, start: 0, len: 8, unit: "%", range: [0, 100]}
"""
DISTANCE = "      - {name: distance, zh: 距离, start: 16, len: 10, unit: cm, range: [0, 500], special: {0x3FF: [no_obstacle, 无障碍物]}}\n"
RESERVED_26 = "      - {role: reserved, start: 26, len: 22}\n"
SPEED = '      - {name: speed, zh: 车速, start: 8, len: 8, offset: -50, unit: km/h, range: [-50, 200], desc: "Vehicle speed."}\n'
TORQUE = "      - {name: torque, zh: 扭矩, start: 0, len: 16, factor: 0.1, offset: -1000, unit: Nm, range: [-1000, 1000]}\n"

# (case id, edits, expected {(kind, class, signal)})
CASES = [
    ("message_added", [("messages:\n", "messages:\n" + NEW_MESSAGE)], {("message_added", "compatible", None)}),
    ("message_removed", [("  - name: command\n", "  - name: command\n    section: gone\n")], None),  # replaced below
    ("message_id_changed", [("id: 0x1801B0A0\n    j1939: {priority: 6, pf: 0x01,", "id: 0x1809B0A0\n    j1939: {priority: 6, pf: 0x09,")],
     {("message_id_changed", "wire", None)}),
    ("message_renamed", [("  - name: command\n", "  - name: host_command\n")], {("message_renamed", "source", None)}),
    ("message_dlc_changed", [("    cycle_ms: 20\n", "    cycle_ms: 20\n    dlc: 6\n"), (CMD_RESERVED, "      - {role: reserved, start: 16, len: 32}\n")],
     {("message_dlc_changed", "wire", None)}),
    ("message_cycle_changed", [("    cycle_ms: 20\n", "    cycle_ms: 50\n")], {("message_cycle_changed", "compatible", None)}),
    ("message_receivers_changed", [("    sender: ECU\n    receivers: ALL\n", "    sender: ECU\n    receivers: [HOST]\n")],
     {("message_receivers_changed", "compatible", None)}),
    # status goes to HOST and VIEW (ALL but its sender); speed is now read by HOST alone
    ("signal_receivers_changed", [(SPEED, SPEED.replace('desc: "Vehicle speed."', 'desc: "Vehicle speed.", receivers: [HOST]'))],
     {("signal_receivers_changed", "compatible", "speed")}),
    ("message_title_changed", [("    title: Status\n    zh: 状态\n", "    title: Status frame\n    zh: 状态报文\n")],
     {("message_title_changed", "docs", None)}),
    ("message_description_changed", [("    title: Command\n    zh: 命令\n", "    title: Command\n    zh: 命令\n    desc: Sent every cycle.\n")],
     {("message_description_changed", "docs", None)}),
    ("message_checksum_changed", [("start: 56, len: 8, range: [0, 255], role: checksum}", "start: 56, len: 8, range: [0, 255]}")],
     {("message_checksum_changed", "wire", None), ("signal_role_changed", "wire", "checksum")}),
    ("signal_added_in_reserved_bits", [("      - {role: reserved, start: 2, len: 6}\n",
                                        "      - {name: flag, zh: 标志, start: 2, len: 1, range: [0, 1]}\n      - {role: reserved, start: 3, len: 5}\n")],
     {("signal_added", "compatible", "flag")}),
    ("signal_added_over_used_bits",
     [(DISTANCE, "      - {name: level, zh: 液位, start: 16, len: 8, unit: cm, range: [0, 200]}\n      - {role: reserved, start: 24, len: 2}\n")],
     {("signal_removed", "wire", "distance"), ("signal_added", "wire", "level")}),
    ("signal_removed", [(DISTANCE, "      - {role: reserved, start: 16, len: 10}\n")], {("signal_removed", "wire", "distance")}),
    ("signal_renamed_in_place", [(DISTANCE, DISTANCE.replace("name: distance, zh: 距离", "name: range_cm, zh: 量程"))],
     {("signal_renamed", "source", "range_cm"), ("signal_label_changed", "docs", "range_cm")}),
    ("signal_renamed", [(SPEED, SPEED.replace("name: speed", "name: vehicle_speed"))], {("signal_renamed", "source", "vehicle_speed")}),
    ("signal_moved", [(DISTANCE + RESERVED_26, "      - {role: reserved, start: 16, len: 10}\n" + DISTANCE.replace("start: 16", "start: 26")
                       + "      - {role: reserved, start: 36, len: 12}\n")], {("signal_moved", "wire", "distance")}),
    ("signal_renamed_and_moved", [(DISTANCE + RESERVED_26, "      - {role: reserved, start: 16, len: 10}\n"
                                   + DISTANCE.replace("start: 16", "start: 26").replace("name: distance", "name: range_cm")
                                   + "      - {role: reserved, start: 36, len: 12}\n")],
     {("signal_renamed", "source", "range_cm"), ("signal_moved", "wire", "range_cm")}),
    ("signal_resized", [(DISTANCE + RESERVED_26, DISTANCE.replace("len: 10", "len: 12") + "      - {role: reserved, start: 28, len: 20}\n")],
     {("signal_resized", "wire", "distance")}),
    ("signal_rescaled", [(TORQUE, TORQUE.replace("factor: 0.1", "factor: 0.2"))], {("signal_rescaled", "wire", "torque")}),
    ("signal_signedness_changed", [(TORQUE, TORQUE.replace("len: 16,", "len: 16, signed: true,"))], {("signal_signedness_changed", "wire", "torque")}),
    ("signal_unit_changed", [(SPEED, SPEED.replace("km/h", "mph"))], {("signal_unit_changed", "wire", "speed")}),
    ("signal_range_widened", [(SPEED, SPEED.replace("[-50, 200]", "[-50, 205]"))], {("signal_range_changed", "compatible", "speed")}),
    ("signal_range_narrowed", [(SPEED, SPEED.replace("[-50, 200]", "[-50, 150]"))], {("signal_range_changed", "wire", "speed")}),
    ("signal_role_changed", [("start: 48, len: 8, range: [0, 255], role: counter}", "start: 48, len: 8, range: [0, 255]}")],
     {("signal_role_changed", "wire", "counter")}),
    ("signal_values_table_renamed", [("value_tables:\n  mode:\n", "value_tables:\n  drive_mode:\n"), ("values: mode}", "values: drive_mode}")],
     {("signal_values_table_renamed", "source", "mode")}),
    ("signal_label_changed", [(SPEED, SPEED.replace("zh: 车速", "zh: 速度"))], {("signal_label_changed", "docs", "speed")}),
    ("signal_description_changed", [(SPEED, SPEED.replace("Vehicle speed.", "Vehicle speed over ground."))], {("signal_description_changed", "docs", "speed")}),
    ("value_added", [("    3: [reserved, 保留]\n", "    3: [manual, 手动]\n")], {("value_added", "compatible", "mode")}),
    ("value_removed", [("    2: [auto, 自动]\n", "")], {("value_removed", "wire", "mode")}),
    ("value_relabelled", [("    2: [auto, 自动]\n", "    2: [auto, 自动(节能)]\n")], {("value_relabelled", "wire", "mode")}),
    ("value_renamed", [("    2: [auto, 自动]\n", "    2: [automatic, 自动]\n")], {("value_renamed", "source", "mode")}),
    ("special_added", [(SPEED, SPEED.replace("range: [-50, 200],", "range: [-50, 200], special: {0xFF: [invalid, 无效]},"))],
     {("special_added", "compatible", "speed")}),
    ("special_removed", [(DISTANCE, DISTANCE.replace(", special: {0x3FF: [no_obstacle, 无障碍物]}", ""))], {("special_removed", "wire", "distance")}),
    ("special_relabelled", [(DISTANCE, DISTANCE.replace("无障碍物", "传感器故障"))], {("special_relabelled", "wire", "distance")}),
    ("special_renamed", [(DISTANCE, DISTANCE.replace("no_obstacle", "clear"))], {("special_renamed", "source", "distance")}),
]

# Issue 24: byte order, CAN FD and IEEE floats. Each pair differs only in that.
FD_BUS = ("bitrate: 250000,", "bitrate: 250000, data_bitrate: 1000000,")
CASES += [
    # torque's 16 bits as Motorola in bytes 0..1 (start = its MSB, bit 7): the same bits, other weights
    ("signal_byte_order_changed", [(TORQUE, TORQUE.replace("start: 0,", "start: 7, byte_order: big_endian,"))],
     {("signal_byte_order_changed", "wire", "torque")}),
    ("message_fd_changed", [("    cycle_ms: 20\n", "    cycle_ms: 20\n    fd: true\n")], {("message_fd_changed", "wire", None)}),
    # every node runs at the bus's rate: a wire break
    ("bus_bitrate_changed", [("bus: {bitrate: 250000,", "bus: {bitrate: 500000,")], {("bus_bitrate_changed", "wire", None)}),
    # a node changes no frame (but `receivers: ALL` now names it too); its description is docs
    ("node_added", [("  - {name: VIEW,", "  - {name: LOGGER, label: LOGGER, sa: 0xD0, zh: 记录仪}\n  - {name: VIEW,")],
     {("node_added", "compatible", None), ("message_receivers_changed", "compatible", None)}),
    ("node_description_changed", [("zh: 显示}", "zh: 显示屏}")], {("node_description_changed", "docs", None)}),
]

_COMMAND_BLOCK = BASE.read_text(encoding="utf-8").split("  - name: command\n")[1]
CASES[1] = ("message_removed", [("  - name: command\n" + _COMMAND_BLOCK, "")], {("message_removed", "wire", None)})


@pytest.mark.parametrize("case, edits, expected", CASES, ids=[c[0] for c in CASES])
def test_change_kind(tmp_path, case, edits, expected):
    new = edited(tmp_path, edits)
    got = {(c.kind, c.cls, c.signal) for c in diff_paths(BASE, new)}
    assert got == expected


def test_reverse_of_an_addition_is_a_removal(tmp_path):
    new = edited(tmp_path, [("messages:\n", "messages:\n" + NEW_MESSAGE)])
    assert {(c.kind, c.cls) for c in diff_paths(new, BASE)} == {("message_removed", "wire")}
    logger = edited(tmp_path, [("  - {name: VIEW,", "  - {name: LOGGER, label: LOGGER, sa: 0xD0, zh: 记录仪}\n  - {name: VIEW,")], "logger.yaml")
    nodes = {(c.kind, c.cls, c.subject, c.old) for c in diff_paths(logger, BASE) if c.kind.startswith("node")}
    assert nodes == {("node_removed", "compatible", "bus", "LOGGER")}


def test_a_range_moved_beyond_what_the_field_carries_is_docs(tmp_path):
    """speed (8 bits, offset -50) carries [-50, 205]: both ranges hold all of it, so the wire is the same."""
    old = edited(tmp_path, [(SPEED, SPEED.replace("[-50, 200]", "[-60, 210]"))], "old.yaml")
    new = edited(tmp_path, [(SPEED, SPEED.replace("[-50, 200]", "[-70, 220]"))])
    (change,) = diff_paths(old, new)
    assert (change.kind, change.cls, change.signal, change.old, change.new) == ("signal_range_changed", "docs", "speed", [-60, 210], [-70, 220])
    assert "the field carries [-50, 205]" in change.detail


def test_identical_specs_have_no_changes():
    assert diff_paths(BASE, BASE) == []


def test_sender_and_multiframe_changes_on_the_model():
    """Kinds a valid fixture edit cannot reach alone (a J1939 sender is tied to the ID's SA)."""
    old = load_model(str(BASE))
    msg = old.messages[0]
    moved = dataclasses.replace(msg, sender="HOST", multiframe=("index", "payload", "ascii", 17, 3, 0))
    new = dataclasses.replace(old, messages=(moved, *old.messages[1:]))
    assert {(c.kind, c.cls) for c in compare(old, new)} == {("message_sender_changed", "compatible"), ("message_multiframe_changed", "wire")}


LEVEL = "      - {name: level, start: 16, len: 32}\n      - {role: reserved, start: 48, len: 16}\n"
PAGED = ("      - {name: mode, start: 16, len: 8}\n      - {name: level, start: 24, len: 16, mux: {by: mode, values: [1]}}\n"
         "      - {role: reserved, start: 40, len: 24}\n")
# (case id, edits of the old revision, edits of the new one, expected): pairs whose old side is not the base
ATTRIBUTE_DEFS = ("value_tables:\n", "dbc_attributes:\n  ProbeMsg: {object: message, type: INT, min: 0, max: 100, default: 0}\n"
                  "  ProbeSig: {object: signal, type: INT, min: 0, max: 100, default: 0}\n"
                  "  ProbeNet: {object: network, type: STRING, default: \"\", value: a}\nvalue_tables:\n")
BOTH_EDITED = [
    ("signal_float_changed", [(CMD_RESERVED, LEVEL)], [(CMD_RESERVED, LEVEL.replace("len: 32}", "len: 32, float: true}"))],
     {("signal_float_changed", "wire", "level")}),
    ("message_brs_changed", [FD_BUS, ("    cycle_ms: 20\n", "    cycle_ms: 20\n    fd: true\n")],
     [FD_BUS, ("    cycle_ms: 20\n", "    cycle_ms: 20\n    fd: true\n    brs: false\n")], {("message_brs_changed", "compatible", None)}),
    ("signal_mux_changed", [(CMD_RESERVED, PAGED)], [(CMD_RESERVED, PAGED.replace("values: [1]", "values: [1, [4, 6]]"))],
     {("signal_mux_changed", "wire", "level")}),
    # a source DBC's own attributes, as a spec keeps them: a value of its own, or a changed default (every object without one)
    ("message_attribute_changed", [ATTRIBUTE_DEFS], [ATTRIBUTE_DEFS, ("    cycle_ms: 20\n", "    cycle_ms: 20\n    dbc_attributes: {ProbeMsg: 5}\n")],
     {("message_attribute_changed", "compatible", None)}),
    ("message_attribute_default_changed", [ATTRIBUTE_DEFS], [(ATTRIBUTE_DEFS[0], ATTRIBUTE_DEFS[1].replace("default: 0}", "default: 3}", 1))],
     {("message_attribute_changed", "compatible", None)}),
    ("signal_attribute_changed", [ATTRIBUTE_DEFS],
     [ATTRIBUTE_DEFS, (TORQUE, TORQUE.replace("range: [-1000, 1000]}", "range: [-1000, 1000], dbc_attributes: {ProbeSig: 7}}"))],
     {("signal_attribute_changed", "compatible", "torque")}),
    ("network_attribute_changed", [ATTRIBUTE_DEFS], [(ATTRIBUTE_DEFS[0], ATTRIBUTE_DEFS[1].replace("value: a}", "value: b}"))],
     {("network_attribute_changed", "compatible", None)}),
    # a byte-aligned byte is the same field in either order: start 56 Intel and start 63 Motorola are byte 7
    ("byte_order_of_a_whole_byte", [], [("start: 56, len: 8, range: [0, 255], role: checksum}",
                                         "start: 63, len: 8, byte_order: big_endian, range: [0, 255], role: checksum}")],
     set()),
]


@pytest.mark.parametrize("case, old_edits, new_edits, expected", BOTH_EDITED, ids=[c[0] for c in BOTH_EDITED])
def test_change_kind_between_edited_revisions(tmp_path, case, old_edits, new_edits, expected):
    old, new = edited(tmp_path, old_edits, "old.yaml"), edited(tmp_path, new_edits, "new.yaml")
    assert {(c.kind, c.cls, c.signal) for c in diff_paths(old, new)} == expected
    assert {(c.kind, c.cls, c.signal) for c in diff_paths(new, old)} == expected


def test_every_kind_has_a_fixture():
    covered = {kind for _, _, expected in CASES for kind, _, _ in expected} | {"message_sender_changed", "message_multiframe_changed"}
    covered |= {"node_removed"}  # test_reverse_of_an_addition_is_a_removal
    covered |= {kind for *_, expected in BOTH_EDITED for kind, _, _ in expected}
    assert covered == set(KINDS)


def test_the_change_record_schema_names_every_kind():
    """A changelog entry may name any kind diff reports (plus `unreconstructed`): the schema's list is written by hand."""
    schema = json.loads((ROOT / "spec" / "schema" / "canspec-spec.v1.schema.json").read_text(encoding="utf-8"))
    lists = [v for v in _walk(schema) if isinstance(v, dict) and "message_added" in (v.get("enum") or ())]
    assert len(lists) == 1 and set(lists[0]["enum"]) == set(KINDS) | {"unreconstructed"}


def _walk(node):  # type: ignore[no-untyped-def]
    yield node
    for child in node.values() if isinstance(node, dict) else node if isinstance(node, list) else ():
        yield from _walk(child)
