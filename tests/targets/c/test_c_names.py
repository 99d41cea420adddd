"""C names (targets/c/names.py, check.py): elements named like the runtime's own names are renamed
coherently, keyword names are escaped, and names that still meet are refused by `canspec check`
at the element that meets an earlier one, with the rule and a hint."""

from __future__ import annotations

from pathlib import Path

from canspec.pipeline import compile_spec
from canspec.targets.c.model import build_model
from canspec.targets.c.names import CNames

VALID = Path(__file__).resolve().parents[2] / "fixtures" / "valid"

SPEC = """\
schema_version: 1
kind: can_protocol
protocol: {{name: demo, version: 1.0.0}}
bus: {{bitrate: 250000, id_format: extended, addressing: none, byte_order: little_endian}}
nodes:
  - {{name: A}}
value_tables:
  gear:
    0: park
    1: drive
messages:
{messages}
"""
MESSAGE = """\
  - name: {name}
    id: {id}
    sender: A
    receivers: ALL
    cycle_ms: 10
    signals:
{signals}"""


def _spec(tmp_path: Path, *messages: tuple[str, list[str]]):
    text = SPEC.format(messages="\n".join(
        MESSAGE.format(name=name, id=0x100 + i, signals="\n".join(f"      - {s}" for s in sigs)) for i, (name, sigs) in enumerate(messages)))
    path = tmp_path / "spec.yaml"
    path.write_text(text, encoding="utf-8")
    return compile_spec(path)


def test_runtime_names_move_the_spec_element_aside():
    """A message `status` and `monitor`, tables `status` and `monitor` (fixture): the messages
    become `<name>_msg`, the tables `<name>_values`, every name of each element alike."""
    spec = compile_spec(VALID / "short_frames_and_names.yaml").spec
    names = CNames.of(spec.can)
    assert names.message("status") == "status_msg" and names.message("monitor") == "monitor_msg" and names.message("ping") == "ping"
    assert names.table("status") == "status_values" and names.table("monitor") == "monitor_values"
    model = build_model(spec)
    status = next(cm for cm in model.messages if cm.msg.name == "status")
    assert (status.type, status.fn, status.macro, status.index_const) == (
        "small_frames_status_msg_t", "small_frames_status_msg", "SMALL_FRAMES_STATUS_MSG", "SMALL_FRAMES_MSG_STATUS_MSG")
    assert status.member == "status" and model.status == "small_frames_status_t"  # the union member and the runtime keep theirs
    table = next(e for e in model.enums if e.table == "status")
    assert table.type == "small_frames_status_values_t" and table.entries[0].const == "SMALL_FRAMES_STATUS_VALUES_IDLE"
    assert [ft.fn for ft in model.fault_tables] == ["small_frames_monitor_monitor_values"]


def test_a_table_named_like_a_message_gives_way(tmp_path):
    compiled = _spec(tmp_path, ("gear", ["{name: position, start: 0, len: 2, values: gear}"]))
    names = CNames.of(compiled.spec.can)
    assert names.message("gear") == "gear" and names.table("gear") == "gear_values"


def test_keywords_are_escaped_in_fields_only(tmp_path):
    compiled = _spec(tmp_path, ("frame", ["{name: xor, start: 0, len: 8}", "{name: uint8_t, start: 8, len: 8}", "{name: class, start: 16, len: 8}"]))
    cm = build_model(compiled.spec).messages[0]
    assert [s.field for s in cm.signals] == ["xor_", "uint8_t_", "class_"]
    assert [s.fn for s in cm.signals] == ["demo_frame_xor", "demo_frame_uint8_t", "demo_frame_class"]


def test_names_that_meet_after_conversion_are_refused(tmp_path):
    """Message `a` with signal `b_c` and message `a_b` with signal `c` both give `demo_a_b_c_decode`."""
    compiled = _spec(tmp_path, ("a", ["{name: b_c, start: 0, len: 8}"]), ("a_b", ["{name: c, start: 0, len: 8}"]))
    assert compiled.spec is None
    (problem,) = [p for p in compiled.problems if p.rule == "c-name-clash"]
    assert problem.loc is not None and problem.loc.line == 25  # the second message's signal
    assert "`demo_a_b_c_decode`" in problem.message and "signal 'b_c' of message 'a'" in problem.message and problem.hint


def test_two_fields_of_one_message_that_meet_are_refused_once(tmp_path):
    """A counter and a checksum have no functions of their own: only their fields meet."""
    compiled = _spec(tmp_path, ("m", ["{name: mode, start: 0, len: 8, role: counter}", "{name: mode_, start: 56, len: 8, role: checksum}"]))
    assert compiled.spec is None
    assert [p.rule for p in compiled.errors] == ["c-name-clash"] and "field of `m`" in compiled.errors[0].message


def test_a_special_value_named_like_a_signal_macro_gets_a_suffix(tmp_path):
    compiled = _spec(tmp_path, ("m", ["{name: speed, start: 0, len: 8, special: {0xFF: max, 0xFE: stop}}"]))
    cm = build_model(compiled.spec).messages[0]
    assert [sp.macro for sp in cm.signals[0].specials] == ["DEMO_M_SPEED_STOP", "DEMO_M_SPEED_MAX_VALUE"]


LONG = "a_message_named_long_enough_to_reach_it"  # `demo_<LONG>_speed_value_decode`: 63 characters


def test_names_alike_in_63_characters_are_warned_at_the_signal(tmp_path):
    """`…_decode` and `…_decode_fixed` agree in their first 63 characters (all C99 guarantees a
    compiler reads): a warning at the signal, naming both names, the rule and a hint; and
    `check --strict` refuses the spec."""
    compiled = _spec(tmp_path, (LONG, ["{name: speed_value, start: 0, len: 8, factor: 0.5}"]))
    assert compiled.spec is not None and not compiled.errors
    alike = [p for p in compiled.problems if p.rule == "c-name-length"]
    assert alike and all(p.severity == "warning" and p.loc is not None and p.loc.line == 18 for p in alike)
    assert len(alike) == 1  # one per element, however many of its names agree
    assert f"`demo_{LONG}_speed_value_decode_fixed`" in alike[0].message and "first 63 characters" in alike[0].message
    assert "c_name" in alike[0].hint
    from canspec.cli import main

    assert main(["check", "--strict", "-q", str(tmp_path / "spec.yaml")]) == 1


def test_a_c_name_renames_every_c_name_of_its_element_and_settles_the_warning(tmp_path):
    compiled = _spec(tmp_path, (LONG, ["{name: speed_value, c_name: speed, start: 0, len: 8, factor: 0.5}"]))
    text = (tmp_path / "spec.yaml").read_text(encoding="utf-8").replace(f"  - name: {LONG}\n", f"  - name: {LONG}\n    c_name: long_msg\n")
    (tmp_path / "spec.yaml").write_text(text, encoding="utf-8")
    compiled = compile_spec(tmp_path / "spec.yaml")
    assert not [p for p in compiled.problems if p.rule == "c-name-length"]
    cm = build_model(compiled.spec).messages[0]
    assert (cm.type, cm.fn, cm.macro, cm.member) == ("demo_long_msg_t", "demo_long_msg", "DEMO_LONG_MSG", "long_msg")
    (sig,) = cm.signals
    assert (sig.field, sig.fn, sig.macro) == ("speed", "demo_long_msg_speed", "DEMO_LONG_MSG_SPEED")
    assert "spec name speed_value" in sig.comment  # the reviewer's key into the protocol table
    assert cm.msg.name == LONG and sig.sig.name == "speed_value"  # other targets keep the spec's names
