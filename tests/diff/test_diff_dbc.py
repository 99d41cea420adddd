"""DBC inputs go through cantools into the same comparison model as specs."""

from __future__ import annotations

import json

import cantools
import pytest
from canspec.diff.inputs import load_model
from diff_helpers import ROOT, diff_paths, run_cli

DBC = ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"
SPEC = ROOT / "spec"


def test_generated_dbc_matches_the_spec_both_ways():
    assert [c for c in diff_paths(DBC, SPEC) if c.cls != "docs"] == []
    assert [c for c in diff_paths(SPEC, DBC) if c.cls != "docs"] == []


def test_dbc_against_previous_revision_shows_the_205_additions():
    changes = diff_paths(ROOT / "spec" / "history" / "v2.0.4", DBC)
    assert {(c.kind, c.frame_id, c.signal, c.cls) for c in changes} == {
        ("signal_added", 0x1813A0B0, "unmanned_entry_fault", "compatible"),
        ("signal_added", 0x1813A0B0, "remote_entry_fault", "compatible"),
        ("signal_added", 0x1805B0A0, "drive_mode_reset", "compatible"),
        ("signal_added", 0x1805B0C0, "drive_mode_reset", "compatible"),
        ("signal_added", 0x1805B0D0, "drive_mode_reset", "compatible"),
    }


def _mutated(tmp_path, old: str, new: str):
    text = DBC.read_text(encoding="utf-8")
    assert text.count(old) == 1
    path = tmp_path / "edited.dbc"
    path.write_text(text.replace(old, new), encoding="utf-8")
    return path


def test_dbc_edits_are_classed(tmp_path):
    # vehicle_speed of Vehicle State 1: offset -50 → -40 is a rescale (wire) and a range change
    dbc = _mutated(tmp_path, " SG_ vehicle_speed : 16|8@1+ (1,-50) [-50|200]", " SG_ vehicle_speed : 16|8@1+ (1,-40) [-40|210]")
    got = {(c.kind, c.cls, c.signal) for c in diff_paths(SPEC, dbc)}
    assert got == {("signal_rescaled", "wire", "vehicle_speed"), ("signal_range_changed", "wire", "vehicle_speed")}


def test_dbc_choice_rename_is_source_breaking(tmp_path):
    dbc = _mutated(tmp_path, 'VAL_ 2550378656 gear_cmd 0 "neutral" 1 "drive"', 'VAL_ 2550378656 gear_cmd 0 "gear_n" 1 "drive"')
    assert {(c.kind, c.cls, c.frame_id) for c in diff_paths(SPEC, dbc)} == {("value_renamed", "source", 0x1803B0A0)}


def test_dbc_counter_role_from_sigtype(tmp_path):
    dbc = _mutated(tmp_path, 'BA_ "SigType" SG_ 2550571184 counter 11;', 'BA_ "SigType" SG_ 2550571184 counter 1;')
    assert {(c.kind, c.cls, c.frame_id) for c in diff_paths(SPEC, dbc)} == {("signal_role_changed", "wire", 0x1806A0B0)}


# A DBC written as vehicle DBCs in the wild are (opendbc's style): Motorola signals crossing bytes,
# Intel ones among them, receivers XXX, no canspec attributes, an FD frame of 32 bytes with floats.
MOTOROLA = ROOT / "tests" / "diff" / "fixtures" / "motorola_vehicle.dbc"


def test_a_motorola_dbc_against_itself_has_no_differences():
    assert diff_paths(MOTOROLA, MOTOROLA) == []
    code, out, _ = run_cli("diff", MOTOROLA, MOTOROLA, "--fail-on", "any")
    assert code == 0 and "no differences" in out


def test_the_model_puts_motorola_fields_where_cantools_does():
    """Each integer field's bits as diff's model holds them = the bits cantools sets encoding that field all ones."""
    db = cantools.database.load_file(str(MOTOROLA), strict=True)
    model = load_model(str(MOTOROLA))
    checked = 0
    for msg in db.messages:
        for sig in msg.signals:
            if sig.is_float:
                continue
            ones = -1 if sig.is_signed else (1 << sig.length) - 1
            data = msg.encode({s.name: ones if s is sig else 0 for s in msg.signals}, scaling=False, strict=False)
            set_bits = {8 * byte + bit for byte, value in enumerate(data) for bit in range(8) if value >> bit & 1}  # the DBC's numbering
            assert model.by_name(msg.name).signal(sig.name).bits == set_bits, sig.name
            checked += 1
    assert checked == 19  # every integer field of the file


@pytest.mark.parametrize(("old", "new", "expected"), [
    # the same two bytes, the other order (Motorola start 55 is byte 6's MSB; Intel starts at byte 6's LSB)
    (" SG_ WHEEL_SPEED_RL : 55|16@0+", " SG_ WHEEL_SPEED_RL : 48|16@1+", ("signal_byte_order_changed", "wire", "WHEEL_SPEED_RL")),
    ("SIG_VALTYPE_ 1024 LAT_DIST : 1;\n", "", ("signal_float_changed", "wire", "LAT_DIST")),
    ('BA_ "VFrameFormat" BO_ 1024 14;', 'BA_ "VFrameFormat" BO_ 1024 14;\nBA_ "CANFD_BRS" BO_ 1024 0;', ("message_brs_changed", "compatible", None)),
], ids=["byte_order", "float", "brs"])
def test_motorola_dbc_edits_are_classed(tmp_path, old, new, expected):
    text = MOTOROLA.read_text(encoding="utf-8")
    assert text.count(old) == 1
    edited_dbc = tmp_path / "edited.dbc"
    edited_dbc.write_text(text.replace(old, new), encoding="utf-8")
    assert {(c.kind, c.cls, c.signal) for c in diff_paths(MOTOROLA, edited_dbc)} == {expected}


def test_a_long_frame_without_its_fd_flag_is_refused(tmp_path):
    """32 bytes and VFrameFormat 0: the import takes it as CAN FD (no classic frame is that long), so
    a change of that flag is one diff could not see: it refuses the file, naming the message."""
    edited = _mutated_text(MOTOROLA, tmp_path, 'BA_ "VFrameFormat" BO_ 1024 14;', 'BA_ "VFrameFormat" BO_ 1024 0;')
    code, _, err = run_cli("diff", MOTOROLA, edited)
    assert code == 2 and "cannot compare" in err and "RADAR_TRACK_FD has 32 bytes but no CAN FD frame format" in err, err


def test_a_signal_the_import_leaves_out_is_refused(tmp_path):
    """Intel from bit 55 leaves the 8-byte frame: the import leaves the signal out, so diff refuses."""
    edited = _mutated_text(MOTOROLA, tmp_path, " SG_ WHEEL_SPEED_RL : 55|16@0+", " SG_ WHEEL_SPEED_RL : 55|16@1+")
    code, _, err = run_cli("diff", MOTOROLA, edited)
    assert code == 2 and "edited.dbc:48: signal WHEEL_SPEED_RL of WHEEL_SPEEDS leaves its 8-byte frame: left out" in err, err


def _mutated_text(source, tmp_path, old: str, new: str):
    text = source.read_text(encoding="utf-8")
    assert text.count(old) == 1
    path = tmp_path / "edited.dbc"
    path.write_text(text.replace(old, new), encoding="utf-8")
    return path


def test_two_dbcs_compare_their_comments(tmp_path):
    """Between two databases the comments are compared (class docs); between a spec and its DBC they
    are not: the DBC's comments are composed from the spec's names and descriptions."""
    dbc = _mutated(tmp_path, 'CM_ BO_ 2550247584 "智能控制器 EPS 命令 | AUTOCAR EPS Command | §3.1";',
                   'CM_ BO_ 2550247584 "智能控制器 EPS 命令 | AUTOCAR EPS Command | §3.1 (edited)";')
    text = dbc.read_text(encoding="utf-8").replace('counter "心跳值 | 每次递增加1";', 'counter "心跳值 | 每次加1";', 1)
    dbc.write_text(text, encoding="utf-8")
    code, out, _ = run_cli("diff", DBC, dbc, "--format", "json")
    changes = {(c["kind"], c["class"], c.get("signal")) for c in json.loads(out)["changes"]}
    assert code == 0 and changes == {("message_description_changed", "docs", None), ("signal_description_changed", "docs", "counter")}, out
    code, out, _ = run_cli("diff", SPEC, DBC, "--format", "json")
    assert code == 0 and not [c for c in json.loads(out)["changes"] if c["kind"].endswith("description_changed")], out
