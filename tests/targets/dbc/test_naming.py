"""The DBC's signal names (targets/dbc/naming.py): per message by default; with
`dbc_signal_names: unique` a spec name with one definition is kept, and with several every
message's signal becomes `<name>_<frame ID>`, shortened to 32 characters and kept clear of every
other name; what counts as a definition."""

from __future__ import annotations

from pathlib import Path

from canspec.pipeline import compile_spec
from canspec.targets.dbc.naming import MAX_NAME, signal_names

LONG = "a_rather_long_signal_name_of_thirty"  # 35 characters

SPEC = """schema_version: 1
kind: can_protocol
protocol: {{name: naming, version: 1.0.0{option}}}
bus: {{bitrate: 500000, id_format: standard, addressing: none, byte_order: little_endian}}
nodes: [{{name: A}}, {{name: B}}]
messages:
  - {{name: one, id: 0x101, sender: A, receivers: [B], cycle_ms: 10, dlc: 8, signals: [{one}]}}
  - {{name: two, id: 0x102, sender: A, receivers: [B], cycle_ms: 10, dlc: 8, signals: [{two}]}}
  - {{name: three, id: 0x1FF, sender: B, receivers: [A], cycle_ms: 10, dlc: 8, signals: [{three}]}}
"""


def names(tmp_path: Path, one: str, two: str, three: str, unique: bool = True) -> dict[tuple[str, str], str]:
    path = tmp_path / "naming.yaml"
    option = ", dbc_signal_names: unique" if unique else ""
    path.write_text(SPEC.format(one=one, two=two, three=three, option=option), encoding="utf-8")
    result = compile_spec(path)
    assert result.spec is not None and result.spec.can is not None, [p.format() for p in result.problems]
    return signal_names(result.spec.can)


def test_by_default_every_message_keeps_its_own_names(tmp_path):
    got = names(tmp_path, "{name: level, start: 0, len: 8}", "{name: level, start: 0, len: 4}", "{name: level, start: 0, len: 8, unit: V}", unique=False)
    assert got == {("one", "level"): "level", ("two", "level"): "level", ("three", "level"): "level"}


def test_one_definition_keeps_the_spec_name(tmp_path):
    sig = "{name: level, start: 0, len: 8}"
    got = names(tmp_path, sig, sig, "{name: other, start: 0, len: 4}")
    assert got == {("one", "level"): "level", ("two", "level"): "level", ("three", "other"): "other"}


def test_any_difference_renames_every_occurrence(tmp_path):
    for other in ("{name: level, start: 0, len: 4}", "{name: level, start: 0, len: 8, unit: V}",
                  "{name: level, start: 0, len: 8, factor: 2}", "{name: level, start: 0, len: 8, desc: Other}",
                  "{name: level, start: 0, len: 8, special: {255: none}}"):
        got = names(tmp_path, "{name: level, start: 0, len: 8}", "{name: level, start: 8, len: 8}", other)
        assert got[("one", "level")] == "level_101" and got[("two", "level")] == "level_102", other
        assert got[("three", "level")] == "level_1FF", other


def test_receivers_are_part_of_the_definition_the_position_is_not(tmp_path):
    got = names(tmp_path, "{name: level, start: 0, len: 8}", "{name: level, start: 16, len: 8}", "{name: level, start: 0, len: 8}")
    assert got == {("one", "level"): "level_101", ("two", "level"): "level_102", ("three", "level"): "level_1FF"}  # three: B → A


def test_long_names_are_shortened_never_the_id(tmp_path):
    got = names(tmp_path, f"{{name: {LONG}, start: 0, len: 8}}", f"{{name: {LONG}, start: 0, len: 4}}", "{name: x, start: 0, len: 1}")
    assert got[("one", LONG)] == LONG[: MAX_NAME - 4] + "_101" and len(got[("one", LONG)]) == MAX_NAME
    assert got[("two", LONG)] == LONG[: MAX_NAME - 4] + "_102"
    assert got[("three", "x")] == "x"


def test_a_renamed_name_never_takes_a_kept_one(tmp_path):
    got = names(tmp_path, "{name: level, start: 0, len: 8}", "{name: level, start: 0, len: 4}", "{name: level_101, start: 0, len: 2}")
    assert got == {("one", "level"): "level_101_2", ("two", "level"): "level_102", ("three", "level_101"): "level_101"}


def test_unique_names_say_so_in_the_network_comment(tmp_path):
    from canspec.targets.dbc import render_dbc

    path = tmp_path / "naming.yaml"
    path.write_text(SPEC.format(one="{name: level, start: 0, len: 8}", two="{name: level, start: 0, len: 4}", three="{name: x, start: 0, len: 1}",
                                option=", dbc_signal_names: unique"), encoding="utf-8")
    result = compile_spec(path)
    assert result.spec is not None
    text = render_dbc(result.spec)["dbc/naming.dbc"].decode()
    assert "Signal names: a name the spec gives different definitions" in text and 'BA_ "SpecSignalName" SG_ 257 level_101 "level";' in text
