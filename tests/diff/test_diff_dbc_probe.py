"""DBC edits an independent mutation probe over opendbc's files found diff missing or crashing on:
each pair differs in one thing the DBC says, and the expectation is what that line means."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec.diff.compare import compare
from canspec.diff.inputs import load_model
from diff_helpers import diff_paths, run_cli

_HEAD = 'VERSION ""\n\nNS_ :\n\nBS_:\n\nBU_: GW ECU1 ECU2\n\n'
_MUX_EXT = (
    "BO_ 257 MUX_EXT: 8 GW\n"
    ' SG_ SEL M : 0|4@1+ (1,0) [0|15] "" ECU1\n'
    ' SG_ SUBSEL m1M : 4|4@1+ (1,0) [0|15] "" ECU1\n'
    ' SG_ DEEP_A m2 : 8|16@1+ (1,0) [0|65535] "" ECU1\n'
    ' SG_ RANGED m4 : 24|8@1+ (1,0) [0|255] "" ECU1\n\n'
)
_MUL_VAL = "SG_MUL_VAL_ 257 SUBSEL SEL 1-1;\nSG_MUL_VAL_ 257 DEEP_A SUBSEL 2-2;\nSG_MUL_VAL_ 257 RANGED SEL 4-7;\n"


def _dbs(old: Path, new: Path):  # type: ignore[no-untyped-def]
    """Two databases compared as the CLI compares them: with their comments and attributes."""
    return compare(load_model(str(old), True), load_model(str(new), True))


def _dbc(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / f"{name}.dbc"
    path.write_text(_HEAD + text, encoding="utf-8")
    return path


def test_extended_multiplexing_naming_an_unmarked_signal_is_refused_not_a_crash(tmp_path):
    """RANGED loses its m4 but SG_MUL_VAL_ still gives it pages of SEL: cantools reads page values
    without a multiplexer. The import cannot say which frames carry RANGED: refused (exit 2), naming
    it — it was an internal error (None joined as a top-level multiplexer's name)."""
    old = _dbc(tmp_path, "old", _MUX_EXT + _MUL_VAL)
    new = _dbc(tmp_path, "new", _MUX_EXT.replace(" RANGED m4 :", " RANGED :") + _MUL_VAL)
    assert {(c.kind, c.signal) for c in diff_paths(old, old)} == set()
    code, _, err = run_cli("diff", old, new)
    assert code == 2 and "internal error" not in err
    assert "signal RANGED is multiplexed (mN) but has no multiplexer" in err


_CYCLE_DEF = 'BA_DEF_ BO_ "GenMsgCycleTime" INT 0 65535;\nBA_DEF_DEF_ "GenMsgCycleTime" 0;\n'
_PLAIN = 'BO_ 768 CLASSIC: 8 ECU2\n SG_ SPEED : 7|16@0+ (0.01,0) [0|655.35] "km/h" GW\n SG_ GEAR : 16|3@1+ (1,0) [0|7] "" GW,ECU1\n\n'


def test_a_cycle_time_given_where_there_was_none_is_a_cycle_change(tmp_path):
    """No GenMsgCycleTime (default 0: not cyclic) → 40 ms: the message becomes cyclic, compatible
    (cycle time is on the ladder's compatible rung). It printed 'no differences'."""
    old = _dbc(tmp_path, "old", _PLAIN + _CYCLE_DEF)
    new = _dbc(tmp_path, "new", _PLAIN + _CYCLE_DEF + 'BA_ "GenMsgCycleTime" BO_ 768 40;\n')
    assert {(c.kind, c.cls, c.old, c.new) for c in diff_paths(old, new)} == {("message_cycle_changed", "compatible", None, 40)}
    assert {(c.kind, c.cls, c.old, c.new) for c in diff_paths(new, old)} == {("message_cycle_changed", "compatible", 40, None)}


def test_a_signal_gaining_a_reader_its_message_already_had_is_a_receivers_change(tmp_path):
    """GEAR's SG_ line gains ECU2, which SPEED's already names: the message's readers (the union) stay
    GW, ECU1, ECU2 but GEAR's are now GW, ECU1, ECU2 — compatible, like a message's receivers. It
    printed 'no differences'."""
    plain = _PLAIN.replace('"km/h" GW', '"km/h" GW,ECU2')
    old = _dbc(tmp_path, "old", plain)
    new = _dbc(tmp_path, "new", plain.replace('"" GW,ECU1', '"" GW,ECU1,ECU2'))
    got = {(c.kind, c.cls, c.signal, tuple(c.old), tuple(c.new)) for c in diff_paths(old, new)}
    assert got == {("signal_receivers_changed", "compatible", "GEAR", ("ECU1", "GW"), ("ECU1", "ECU2", "GW"))}


_RATE_DEF = 'BA_DEF_ "Baudrate" INT 1000 1000000;\nBA_DEF_DEF_ "Baudrate" 500000;\n'


def test_the_bus_bit_rate_is_compared(tmp_path):
    """BA_ "Baudrate" 500000 → 250000: a node at the old rate cannot take part on the bus, a wire
    break. It printed 'no differences' (and did between two specs' `bus: {bitrate}` too)."""
    old = _dbc(tmp_path, "old", _PLAIN + _RATE_DEF + 'BA_ "Baudrate" 500000;\n')
    new = _dbc(tmp_path, "new", _PLAIN + _RATE_DEF + 'BA_ "Baudrate" 250000;\n')
    assert {(c.kind, c.cls, c.old, c.new) for c in diff_paths(old, new)} == {("bus_bitrate_changed", "wire", 500000, 250000)}
    code, out, _ = run_cli("diff", old, new, "--fail-on", "wire")
    assert code == 1 and "bus (bus)" in out and "bit rate 500 kbit/s → 250 kbit/s" in out


def test_a_bit_rate_the_file_does_not_state_is_not_compared(tmp_path):
    """Without a Baudrate the import assumes one (with a warning): that is no statement of the file's."""
    old = _dbc(tmp_path, "old", _PLAIN + _RATE_DEF + 'BA_ "Baudrate" 250000;\n')
    assert diff_paths(old, _dbc(tmp_path, "new", _PLAIN)) == []


def test_a_bus_type_the_frames_contradict_is_said_not_silently_dropped(tmp_path):
    """BusType "CAN" → "CAN FD" with classic frames only: the spec keeps the frames (its DBC writes
    BusType from them), so the two files mean the same frames; it printed "no differences" without a
    word. The import now warns on the side whose BusType its DBC will not say; both diff and import
    print it, and import --strict refuses the file."""
    defs = 'BA_DEF_ "BusType" STRING;\nBA_DEF_DEF_ "BusType" "CAN";\n'
    old = _dbc(tmp_path, "old", _PLAIN + defs + 'BA_ "BusType" "CAN";\n')
    new = _dbc(tmp_path, "new", _PLAIN + defs + 'BA_ "BusType" "CAN FD";\n')
    code, _, err = run_cli("diff", old, new)
    said = 'BusType is "CAN FD", but no message is a CAN FD frame: the spec keeps the frames, and its DBC says "CAN"'
    assert code == 0 and f"{new}: {said}" in err and f"{old}: BusType" not in err
    code, _, err = run_cli("import", "--strict", new, "-o", tmp_path / "spec")
    assert code == 1 and said in err and not (tmp_path / "spec").exists()


_ATTR_DEFS = ('BA_DEF_ BO_ "GenMsgSendType" ENUM "Cyclic","OnEvent";\nBA_DEF_ SG_ "GenSigStartValue" INT 0 100000;\n'
              'BA_DEF_ BU_ "NodeLayer" INT 0 10;\nBA_DEF_ "ProjectCode" STRING;\n'
              'BA_DEF_DEF_ "GenMsgSendType" "Cyclic";\nBA_DEF_DEF_ "GenSigStartValue" 0;\nBA_DEF_DEF_ "NodeLayer" 0;\nBA_DEF_DEF_ "ProjectCode" "";\n')


@pytest.mark.parametrize(("old_tail", "new_tail", "expected"), [
    # an ENUM BA_ holds the index: 1 is OnEvent
    ("", 'BA_ "GenMsgSendType" BO_ 768 1;\n', {("message_attribute_changed", None, "Cyclic", "OnEvent")}),
    ('BA_ "GenSigStartValue" SG_ 768 GEAR 2;\n', 'BA_ "GenSigStartValue" SG_ 768 GEAR 1;\n', {("signal_attribute_changed", "GEAR", 2, 1)}),
    ('BA_ "ProjectCode" "P1";\n', 'BA_ "ProjectCode" "P2";\n', {("network_attribute_changed", None, "P1", "P2")}),
    ('BA_ "NodeLayer" BU_ ECU2 3;\n', 'BA_ "NodeLayer" BU_ ECU2 2;\n', {("network_attribute_changed", None, 3, 2)}),
], ids=["message_enum_value", "signal_value", "network_value", "node_value"])
def test_two_dbcs_compare_their_own_attributes(tmp_path, old_tail, new_tail, expected):
    """A BA_ value of an attribute canspec carries but does not interpret: compatible (tools act on
    it; the bits decode as before). Each printed 'no differences'."""
    old = _dbc(tmp_path, "old", _PLAIN + _ATTR_DEFS + old_tail)
    new = _dbc(tmp_path, "new", _PLAIN + _ATTR_DEFS + new_tail)
    changes = _dbs(old, new)
    assert {(c.kind, c.signal, c.old, c.new) for c in changes} == expected and {c.cls for c in changes} == {"compatible"}


def test_a_changed_attribute_default_changes_every_object_without_a_value(tmp_path):
    """BA_DEF_DEF_ "GenSigStartValue" 0 → 5: SPEED and FLAG have no BA_ of it and start at 5 now; GEAR keeps its own 2."""
    plain = _PLAIN.replace(' SG_ GEAR', ' SG_ FLAG : 19|1@1+ (1,0) [0|1] "" GW\n SG_ GEAR')
    old = _dbc(tmp_path, "old", plain + _ATTR_DEFS + 'BA_ "GenSigStartValue" SG_ 768 GEAR 2;\n')
    new = _dbc(tmp_path, "new", plain + _ATTR_DEFS.replace('"GenSigStartValue" 0;', '"GenSigStartValue" 5;') + 'BA_ "GenSigStartValue" SG_ 768 GEAR 2;\n')
    assert {(c.kind, c.signal, c.old, c.new) for c in _dbs(old, new)} == {
        ("signal_attribute_changed", "SPEED", 0, 5), ("signal_attribute_changed", "FLAG", 0, 5)}


def test_the_cli_reports_an_attribute_change_between_two_dbcs(tmp_path):
    old = _dbc(tmp_path, "old", _PLAIN + _ATTR_DEFS)
    new = _dbc(tmp_path, "new", _PLAIN + _ATTR_DEFS + 'BA_ "GenMsgSendType" BO_ 768 1;\n')
    code, out, _ = run_cli("diff", old, new, "--fail-on", "compatible")
    assert code == 1 and "message_attribute_changed" in out and "attribute GenMsgSendType 'Cyclic' → 'OnEvent'" in out


_MUX = ('BO_ 256 MUXED: 8 GW\n SG_ MODE M : 0|8@1+ (1,0) [0|255] "" ECU1\n SG_ VOLTS m0 : 8|16@1+ (0.1,0) [0|6553.5] "V" ECU1\n'
        ' SG_ AMPS m1 : 8|16@1- (1,0) [-32768|32767] "A" ECU1\n\n')


def test_a_renamed_multiplexer_is_a_rename_not_new_pages(tmp_path):
    """MODE → PAGE_SEL, in its SG_ line only (nothing else names it): the same bits select the same
    pages, a source-breaking rename. VOLTS and AMPS were each reported signal_mux_changed, wire
    ('present while MODE = 0 → present while PAGE_SEL = 0')."""
    old = _dbc(tmp_path, "old", _MUX)
    new = _dbc(tmp_path, "new", _MUX.replace(" SG_ MODE M :", " SG_ PAGE_SEL M :"))
    assert {(c.kind, c.cls, c.signal) for c in _dbs(old, new)} == {("signal_renamed", "source", "PAGE_SEL")}


def test_renamed_fields_of_pages_sharing_bits_are_renames(tmp_path):
    """VOLTS (page 0) → VOLTAGE and AMPS (page 1) → CURRENT: both in bits 8..23, so bits alone match
    each to two fields; the page tells them apart. Each was reported removed and added, wire (so was
    every paged field of a spec against its source DBC, the spec's names being its own)."""
    old = _dbc(tmp_path, "old", _MUX)
    new = _dbc(tmp_path, "new", _MUX.replace(" VOLTS m0", " VOLTAGE m0").replace(" AMPS m1", " CURRENT m1"))
    assert {(c.kind, c.cls, c.old, c.new) for c in _dbs(old, new)} == {
        ("signal_renamed", "source", "VOLTS", "VOLTAGE"), ("signal_renamed", "source", "AMPS", "CURRENT")}


def test_a_reserved_label_is_a_placeholder_in_a_dbc_too(tmp_path):
    """VAL_ 2 "RESERVED" (opendbc's tesla_can.dbc writes it so) marks an unused raw value, as a spec's
    `reserved`: the DBC's import as a spec against the DBC itself reported value 2 added."""
    dbc = _dbc(tmp_path, "old", _PLAIN + 'VAL_ 768 GEAR 0 "P" 1 "R" 2 "RESERVED" ;\n')
    out = tmp_path / "imported"
    assert run_cli("import", dbc, "-o", out)[0] == 0
    assert [c for c in diff_paths(out, dbc) if c.cls != "source"] == []


def test_a_standard_id_made_extended_says_so(tmp_path):
    """BO_ 768 → BO_ 2147484416 (bit 31: the same number as a 29-bit ID): another frame on the bus.
    The change read 'frame ID 0x00000300 → 0x00000300'."""
    old = _dbc(tmp_path, "old", _PLAIN)
    new = _dbc(tmp_path, "new", _PLAIN.replace("BO_ 768 ", f"BO_ {0x80000000 | 768} "))
    assert [(c.kind, c.cls, c.detail) for c in diff_paths(old, new)] == [("message_id_changed", "wire", "frame ID 0x300 (11-bit) → 0x00000300 (29-bit)")]


def test_a_message_read_by_no_node_gaining_a_reader_is_a_receivers_change(tmp_path):
    """Every SG_ line's receiver Vector__XXX (none), then ECU1 for GEAR: the message is now read by
    ECU1, between two DBCs a receivers change (compatible). It printed 'no differences'."""
    plain = _PLAIN.replace('"km/h" GW', '"km/h" Vector__XXX').replace('"" GW,ECU1', '"" Vector__XXX')
    old = _dbc(tmp_path, "old", plain)
    new = _dbc(tmp_path, "new", plain.replace('[0|7] "" Vector__XXX', '[0|7] "" ECU1'))
    got = {(c.kind, c.cls, c.signal, tuple(c.old or ()), tuple(c.new or ())) for c in _dbs(old, new)}
    assert got == {("message_receivers_changed", "compatible", None, (), ("ECU1",))}


_UNFLAGGED = ('BO_ 2048 BIG_ID: 8 GW\n SG_ STATE : 0|8@1+ (1,0) [0|255] "" ECU1\n\n' + _CYCLE_DEF
              + 'CM_ BO_ 2048 "sent by the gateway";\nBA_ "GenMsgCycleTime" BO_ 2048 100;\nVAL_ 2048 STATE 0 "Off" 1 "On" ;\n')


@pytest.mark.parametrize(("old_text", "new_text", "expected"), [
    ('BA_ "GenMsgCycleTime" BO_ 2048 100;', 'BA_ "GenMsgCycleTime" BO_ 2048 200;', {("message_cycle_changed", None, 100, 200)}),
    ('1 "On" ;', '1 "On" 2 "Fault" ;', {("value_added", "STATE", None, "Fault")}),
    ('"sent by the gateway"', '"sent by the body controller"', {("message_description_changed", None, "sent by the gateway", "sent by the body controller")}),
], ids=["cycle_time", "value_label", "comment"])
def test_the_statements_of_a_29_bit_id_written_without_its_flag_are_kept(tmp_path, old_text, new_text, expected):
    """BO_ 2048 (above 0x7FF, no extended flag) is read as the 29-bit ID 0x800 with a warning; its
    CM_, BA_ and VAL_ lines name it by 2048 too. Only the BO_ line was rewritten, so they named no
    message and were lost: each edit printed 'no differences'."""
    old = _dbc(tmp_path, "old", _UNFLAGGED)
    new = _dbc(tmp_path, "new", _UNFLAGGED.replace(old_text, new_text))
    got = {(c.kind, c.signal, c.old, c.new) for c in _dbs(old, new)}
    assert got == expected
    assert load_model(str(old)).by_id(0x800).cycle_ms == 100


def test_nodes_of_two_dbcs_are_compared(tmp_path):
    """A node added to BU_, and a node's CM_ BU_ edited, printed 'no differences' (the left list of
    the probe): compatible (a node alone sends and reads nothing) and docs. Against a spec a
    database's comments are not compared, so the comment edit says nothing there."""
    old = _dbc(tmp_path, "old", _PLAIN + 'CM_ BU_ ECU1 "Body controller";\n')
    new = _dbc(tmp_path, "new", (_PLAIN + 'CM_ BU_ ECU1 "Body control module";\n'))
    new.write_text(new.read_text(encoding="utf-8").replace("BU_: GW ECU1 ECU2", "BU_: GW ECU1 ECU2 LOGGER"), encoding="utf-8")
    got = {(c.kind, c.cls, c.subject, c.old, c.new) for c in _dbs(old, new)}
    assert got == {("node_added", "compatible", "bus", None, "LOGGER"),
                   ("node_description_changed", "docs", "bus", "Body controller", "Body control module")}
    assert {(c.kind, c.old) for c in _dbs(new, old) if c.kind == "node_removed"} == {("node_removed", "LOGGER")}
    code, out, _ = run_cli("diff", old, new)
    assert code == 0 and "node LOGGER added" in out


def test_a_dbc_and_the_dbc_canspec_writes_from_its_import_do_not_differ(tmp_path):
    """The written DBC declares `BA_DEF_DEF_ "SpecSignalName" ""`; read as the name of every signal
    (the attribute's default, once defaults counted), the comparison used the spec's lower-case
    names on that side: `SPEED` → `speed` reported as a rename of every signal of opendbc's files.
    A comment part that begins `spec name: ` is the user's text when the signal carries no name."""
    dbc = _dbc(tmp_path, "source", _PLAIN + 'CM_ SG_ 768 GEAR "spec name: as the driver calls it";\n')
    assert run_cli("import", dbc, "-o", tmp_path / "imported")[0] == 0
    assert run_cli("gen", tmp_path / "imported", "-o", tmp_path / "gen", "-t", "dbc")[0] == 0
    (written,) = (tmp_path / "gen" / "dbc").glob("*.dbc")
    assert 'BA_DEF_DEF_  "SpecSignalName" "";' in written.read_text(encoding="utf-8")
    assert _dbs(dbc, written) == []
    assert "spec name: as the driver calls it" in written.read_text(encoding="utf-8")
