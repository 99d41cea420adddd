"""The reconstructed revisions reproduce the document's change record (expected changes
written from the record's items, spec/source/gateway_v2.0.5beta1.ocr.txt 变更记录表), and `canspec check`
holds each revision's declared changelog to the computed diff."""

from __future__ import annotations

import shutil

import pytest
from canspec.diff.history import changelog_problems
from canspec.pipeline import compile_spec
from diff_helpers import ROOT, diff_paths, run_cli, run_subprocess

SPEC = ROOT / "spec"
HISTORY = SPEC / "history"

# From the change record: (kind, frame ID, signal) per item, all in formerly reserved bits.
RECORD = {
    "2.0.5": {  # 1、新增无法进入无人驾驶故障状态 0x1813A0B0 2、…远程驾驶故障状态 0x1813A0B0 3、…驾驶模式复位指令 0x1805B0A0, 0x1805B0C0, 0x1805B0D0
        ("signal_added", 0x1813A0B0, "unmanned_entry_fault"),
        ("signal_added", 0x1813A0B0, "remote_entry_fault"),
        ("signal_added", 0x1805B0A0, "drive_mode_reset"),
        ("signal_added", 0x1805B0C0, "drive_mode_reset"),
        ("signal_added", 0x1805B0D0, "drive_mode_reset"),
    },
    "2.0.4": {  # items 2–6 (items 1, 7, 8 give no old values: not reconstructable)
        ("message_added", 0x1807B0D0, None),
        ("signal_added", 0x1805B0A0, "lock_cmd"),
        ("signal_added", 0x1807B0A0, "pto_enable"),
        ("signal_added", 0x1805B0C0, "lock_cmd"),
        ("signal_added", 0x1807B0C0, "pto_enable"),
    },
    "2.0.3": {  # 1、增加上装电机故障、上装电机过热 0x1813A0B0
        ("signal_added", 0x1813A0B0, "body_motor_fault"),
        ("signal_added", 0x1813A0B0, "body_motor_overheat"),
    },
}
PAIRS = [("2.0.4", SPEC, "2.0.5"), ("2.0.3", HISTORY / "v2.0.4", "2.0.4"), ("2.0.2", HISTORY / "v2.0.3", "2.0.3")]


@pytest.mark.parametrize("old, new, version", PAIRS, ids=[p[2] for p in PAIRS])
def test_consecutive_revisions_reproduce_the_record(old, new, version):
    changes = diff_paths(HISTORY / f"v{old}", new)
    assert {(c.kind, c.frame_id, c.signal) for c in changes} == RECORD[version]
    assert {c.cls for c in changes} == {"compatible"}  # additions in reserved bits and a new message


def test_v204_to_v205_text_report():
    code, out, _ = run_cli("diff", HISTORY / "v2.0.4", SPEC, "--format", "text")
    assert code == 0
    assert "drive_mode_reset (bit 28) added in formerly reserved bits" in out
    assert "unmanned_entry_fault (bits 28..31) added in formerly reserved bits" in out
    assert "remote_entry_fault (bits 44..47) added in formerly reserved bits" in out
    assert "5 change(s): 0 wire-breaking, 0 source-breaking, 5 compatible, 0 docs" in out
    assert "suggested version bump: minor (2.0.4 → 2.1.0)" in out
    assert "note: 2.0.4 → 2.0.5 is a patch bump; the changes suggest minor" in out


@pytest.mark.parametrize("revision", ["v2.0.4", "v2.0.3", "v2.0.2"])
def test_revisions_pass_check_and_changelog_ends_at_their_version(revision):
    compiled = compile_spec(HISTORY / revision)
    assert compiled.spec is not None, [p.format() for p in compiled.errors]
    assert compiled.spec.version == revision[1:]
    assert compiled.spec.changelog.versions[-1].version == revision[1:]
    assert changelog_problems(HISTORY / revision, compiled.spec) == []


def test_revision_changelogs_are_the_record_cut_at_their_version(spec):
    full = spec.changelog.versions
    for revision in ("v2.0.4", "v2.0.3", "v2.0.2"):
        log = compile_spec(HISTORY / revision).spec.changelog
        assert log.versions == full[: len(log.versions)]


def test_shipped_changelog_agrees_with_the_diff(spec):
    assert changelog_problems(SPEC, spec) == []


def _copy_spec(tmp_path):
    dest = tmp_path / "spec"
    shutil.copytree(SPEC, dest)
    return dest


def _check(dest):
    compiled = compile_spec(dest)
    assert compiled.spec is not None
    return changelog_problems(dest, compiled.spec)


def _edit(path, old, new):
    text = path.read_text(encoding="utf-8")
    assert text.count(old) == 1
    path.write_text(text.replace(old, new), encoding="utf-8")


def test_missing_entry_is_an_error_with_location(tmp_path):
    dest = _copy_spec(tmp_path)
    log = dest / "history" / "changelog.yaml"
    _edit(log, "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n", "")
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-missing"]
    assert "signal_added 0x1805B0D0 tele_control_command_1.drive_mode_reset" in problems[0].message
    line = log.read_text(encoding="utf-8").splitlines().index("  - version: 2.0.5") + 1
    assert problems[0].loc.file.endswith("history/changelog.yaml") and problems[0].loc.line == line


def test_invented_entry_is_an_error_with_location(tmp_path):
    dest = _copy_spec(tmp_path)
    log = dest / "history" / "changelog.yaml"
    invented = "          - {kind: signal_removed, message: 0x1812A0B0, signal: pto_state}\n"
    _edit(log, "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n",
          "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n" + invented)
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-invented"]
    line = log.read_text(encoding="utf-8").splitlines().index(invented.rstrip("\n")) + 1
    assert problems[0].loc.line == line


def test_item_with_ids_only_is_checked_by_message(tmp_path):
    dest = _copy_spec(tmp_path)
    log = dest / "history" / "changelog.yaml"
    _edit(log, "        ids: [0x1813A0B0]\n        changes:\n          - {kind: signal_added, message: 0x1813A0B0, signal: unmanned_entry_fault}\n",
          "        ids: [0x1812A0B0]\n")
    rules = sorted(p.rule for p in _check(dest))
    assert rules == ["changelog-invented", "changelog-missing"]  # 0x1812A0B0 did not change; unmanned_entry_fault unrecorded


def test_spec_change_without_record_is_an_error(tmp_path):
    dest = _copy_spec(tmp_path)
    _edit(dest / "can" / "gateway.yaml", "    cycle_ms: 500\n", "    cycle_ms: 1000\n")
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-missing"] and "message_cycle_changed 0x18FFAF00" in problems[0].message


def test_previous_must_be_the_version_before(tmp_path):
    dest = _copy_spec(tmp_path)
    _edit(dest / "history" / "changelog.yaml", "previous: v2.0.4\n", "previous: v2.0.3\n")
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-previous"] and "version 2.0.3" in problems[0].message


def test_previous_that_does_not_load(tmp_path):
    dest = _copy_spec(tmp_path)
    _edit(dest / "history" / "changelog.yaml", "previous: v2.0.4\n", "previous: v9.9.9\n")
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-previous"] and "does not load" in problems[0].message


def test_check_command_fails_on_a_changelog_error(tmp_path):
    dest = _copy_spec(tmp_path)
    _edit(dest / "history" / "changelog.yaml", "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n", "")
    code, _, err = run_subprocess("check", "-q", dest)
    assert code == 1 and "history/changelog.yaml:" in err and "[changelog-missing]" in err and "Traceback" not in err
    assert run_subprocess("check", "-q", SPEC)[0] == 0


def test_since_must_match_the_diff(tmp_path):
    dest = _copy_spec(tmp_path)
    gateway = dest / "can" / "gateway.yaml"
    _edit(gateway, "values: pto_state, errata: [E35]}", "values: pto_state, errata: [E35], since: 2.0.5}")
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-since"] and "'pto_state' of 0x1812A0B0" in problems[0].message
    line = next(i for i, text in enumerate(gateway.read_text(encoding="utf-8").splitlines(), 1) if "name: pto_state" in text)
    assert problems[0].loc.line == line


@pytest.mark.parametrize("entry, message", [
    ("{kind: signal_exploded, message: 0x1805B0D0, signal: drive_mode_reset}", "is not one of"),
    ("{kind: unreconstructed, message: 0x1805B0D0}", "'reason' is required"),
    ("{kind: signal_added, message: 0x1805B0D0, signal: Drive_Mode}", "does not match"),
])
def test_schema_shapes_declared_changes(tmp_path, entry, message):
    dest = _copy_spec(tmp_path)
    log = dest / "history" / "changelog.yaml"
    _edit(log, "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n", f"          - {entry}\n")
    errors = compile_spec(dest).errors
    line = next(i for i, text in enumerate(log.read_text(encoding="utf-8").splitlines(), 1) if entry in text)
    assert len(errors) == 1 and errors[0].rule == "schema" and message in errors[0].message
    assert errors[0].loc.file.endswith("history/changelog.yaml") and errors[0].loc.line == line


def test_a_bus_change_is_recorded_with_message_bus(tmp_path):
    """A bit rate change belongs to no message: the check asks for `message: bus`, and accepts it."""
    dest = _copy_spec(tmp_path)
    _edit(dest / "can" / "gateway.yaml", "  bitrate: 250000\n", "  bitrate: 500000\n")
    problems = _check(dest)
    assert [p.rule for p in problems] == ["changelog-missing"] and "message: bus}" in problems[0].hint
    _edit(dest / "history" / "changelog.yaml", "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n",
          "          - {kind: signal_added, message: 0x1805B0D0, signal: drive_mode_reset}\n          - {kind: bus_bitrate_changed, message: bus}\n")
    assert _check(dest) == []
