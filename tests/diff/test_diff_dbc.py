"""DBC inputs go through cantools into the same comparison model as specs."""

from __future__ import annotations

import pytest
from diff_helpers import ROOT, diff_paths

pytest.importorskip("cantools")

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
    dbc = _mutated(tmp_path, 'BA_ "SigType" SG_ 2550571184 counter_1806A0B0 11;', 'BA_ "SigType" SG_ 2550571184 counter_1806A0B0 1;')
    assert {(c.kind, c.cls, c.frame_id) for c in diff_paths(SPEC, dbc)} == {("signal_role_changed", "wire", 0x1806A0B0)}
