"""`canspec diff` on the command line: formats, --fail-on exit codes, bad inputs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from diff_helpers import BASE, ROOT, edited, run_cli

SPEC = ROOT / "spec"

# One fixture pair per strictest class (edits of tests/diff/fixtures/base.yaml).
PAIRS = {
    "none": [],
    "docs": [("    title: Status\n", "    title: Status frame\n")],
    "compatible": [("    cycle_ms: 20\n", "    cycle_ms: 50\n")],
    "source": [("  - name: command\n", "  - name: host_command\n")],
    "wire": [("start: 0, len: 16, factor: 0.1,", "start: 0, len: 16, factor: 0.2,")],
}
# Exit status expected for each --fail-on level, by the pair's strictest class.
EXPECTED = {
    "wire": {"none": 0, "docs": 0, "compatible": 0, "source": 0, "wire": 1},
    "source": {"none": 0, "docs": 0, "compatible": 0, "source": 1, "wire": 1},
    "compatible": {"none": 0, "docs": 0, "compatible": 1, "source": 1, "wire": 1},
    "any": {"none": 0, "docs": 1, "compatible": 1, "source": 1, "wire": 1},
}


@pytest.mark.parametrize("level", list(EXPECTED))
@pytest.mark.parametrize("pair", list(PAIRS))
def test_fail_on_exit_codes(tmp_path, level, pair):
    new = edited(tmp_path, PAIRS[pair])
    code, _, err = run_cli("diff", BASE, new, "--fail-on", level)
    assert code == EXPECTED[level][pair]
    assert ("at or above --fail-on" in err) == bool(code)


@pytest.mark.parametrize("pair", list(PAIRS))
def test_without_fail_on_exit_is_zero(tmp_path, pair):
    assert run_cli("diff", BASE, edited(tmp_path, PAIRS[pair]))[0] == 0


@pytest.mark.parametrize("pair, bump, version", [("none", "none", "1.0.0"), ("docs", "patch", "1.0.1"), ("compatible", "minor", "1.1.0"),
                                                 ("source", "major", "2.0.0"), ("wire", "major", "2.0.0")])
def test_json_summary_suggests_the_bump(tmp_path, pair, bump, version):
    code, out, _ = run_cli("diff", BASE, edited(tmp_path, PAIRS[pair]), "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["format"] == "canspec-diff/1"
    assert data["summary"]["bump"] == bump and data["summary"]["suggested_version"] == version
    assert data["summary"]["strictest"] == (None if pair == "none" else pair)
    # every fixture pair keeps version 1.0.0: a change without a version bump is pointed out
    assert data["summary"]["note"] == (None if pair == "none" else "the new revision's version (1.0.0) is not above the old one (1.0.0)")


def test_json_change_fields():
    _, out, _ = run_cli("diff", SPEC / "history" / "v2.0.4", SPEC, "--format", "json")
    data = json.loads(out)
    assert data["old"]["version"] == "2.0.4" and data["new"]["version"] == "2.0.5"
    first = data["changes"][0]
    assert first == {
        "kind": "signal_added", "class": "compatible", "frame_id": "0x1805B0A0", "message": "autocar_control_command_1", "signal": "drive_mode_reset",
        "detail": "drive_mode_reset (bit 28) added in formerly reserved bits", "old": None, "new": "drive_mode_reset"}
    assert data["summary"]["counts"] == {"wire": 0, "source": 0, "compatible": 5, "docs": 0}
    assert data["summary"]["note"] == "2.0.4 → 2.0.5 is a patch bump; the changes suggest minor"


def test_markdown_report():
    _, out, _ = run_cli("diff", SPEC / "history" / "v2.0.3", SPEC / "history" / "v2.0.4", "--format", "markdown")
    assert out.startswith("# Protocol diff: kaiwo_gateway 2.0.3 → kaiwo_gateway 2.0.4\n")
    assert "| compatible | 5 |" in out
    assert "## `0x1807B0D0` tele_control_command_2" in out
    assert "| compatible | `message_added` |  | tele_control_command_2 added (6 signals) |" in out


def _bad(run_cli, *argv):
    code, out, err = run_cli("diff", *argv)
    assert code == 2 and out == "" and "Traceback" not in err
    return err


def test_missing_input(tmp_path):
    err = _bad(run_cli, tmp_path / "nope.yaml", SPEC)
    assert "nope.yaml: no such file or directory" in err


def test_unreadable_dbc(tmp_path):
    bad = tmp_path / "bad.dbc"
    bad.write_text("BO_ this is not a dbc\n", encoding="utf-8")
    assert "bad.dbc:1: not a readable DBC" in _bad(run_cli, SPEC, bad)  # with the line, as canspec import says it


def test_wrong_file_type(tmp_path):
    other = tmp_path / "notes.txt"
    other.write_text("hello\n", encoding="utf-8")
    assert "not a spec (.yaml) or database (.dbc, .arxml, .kcd, .sym) file" in _bad(run_cli, other, SPEC)


def test_spec_with_errors(tmp_path):
    broken = edited(tmp_path, [("len: 16, factor: 0.1", "len: 70, factor: 0.1")])
    err = _bad(run_cli, BASE, broken)
    assert "the spec has errors (run `canspec check" in err and "new.yaml:" in err


def test_yaml_syntax_error(tmp_path):
    broken = tmp_path / "broken.yaml"
    broken.write_text("schema_version: 1\nkind: [unclosed\n", encoding="utf-8")
    assert "broken.yaml" in _bad(run_cli, broken, BASE)


def test_directory_without_bundle(tmp_path):
    assert "no canspec.yaml" in _bad(run_cli, tmp_path, BASE)


# Byte order, FD frames, BRS, IEEE floats and multiplexing are compared: each pair differs only in
# that (a multiplexer value m8 → m9 is a wire break a diff that ignored multiplexing would miss).
_DBC_HEAD = 'VERSION "tiny 1.0.0"\n\nNS_ :\n\nBS_:\n\nBU_: ECU LOGGER\n\nBO_ 256 status: 8 ECU\n'
_DBC_FRAME_FORMAT = ('BA_DEF_ BO_ "VFrameFormat" ENUM "StandardCAN","ExtendedCAN"' + ',"reserved"' * 12 + ',"StandardCAN_FD","ExtendedCAN_FD";\n'
                     'BA_DEF_ BO_ "CANFD_BRS" ENUM "0","1";\nBA_DEF_DEF_ "VFrameFormat" "StandardCAN";\nBA_DEF_DEF_ "CANFD_BRS" "1";\n')
_PLAIN_SIGNALS = ' SG_ speed : 0|16@1+ (0.1,0) [0|6553.5] "km/h" LOGGER\n SG_ level : 16|32@1- (1,0) [0|0] "" LOGGER\n'
_MUX_SIGNALS = ' SG_ mode M : 0|8@1+ (1,0) [0|255] "" LOGGER\n SG_ speed m8 : 8|16@1+ (0.1,0) [0|6553.5] "km/h" LOGGER\n'
_FD = 'BA_ "VFrameFormat" BO_ 256 14;\n'


def _dbc(tmp_path, name: str, signals: str, tail: str = "") -> Path:
    path = tmp_path / f"{name}.dbc"
    path.write_text(_DBC_HEAD + signals + "\n" + _DBC_FRAME_FORMAT + tail, encoding="utf-8")
    return path


@pytest.mark.parametrize(("old", "new", "expected"), [
    ((_PLAIN_SIGNALS, ""), (_PLAIN_SIGNALS, _FD), {("message_fd_changed", "wire", None)}),
    ((_PLAIN_SIGNALS, ""), (_PLAIN_SIGNALS, "SIG_VALTYPE_ 256 level : 1;\n"), {("signal_float_changed", "wire", "level")}),
    ((_PLAIN_SIGNALS, ""), (_PLAIN_SIGNALS.replace("16|32@1-", "16|32@0-"), ""), {("signal_byte_order_changed", "wire", "level")}),
    ((_PLAIN_SIGNALS, _FD), (_PLAIN_SIGNALS, _FD + 'BA_ "CANFD_BRS" BO_ 256 0;\n'), {("message_brs_changed", "compatible", None)}),
    ((_MUX_SIGNALS, ""), (_MUX_SIGNALS.replace(" m8 ", " m9 "), ""), {("signal_mux_changed", "wire", "speed")}),
    # the page's field in every frame, and `mode`, marked M but selecting nothing, a plain field (the import warns)
    ((_MUX_SIGNALS, ""), (_MUX_SIGNALS.replace(" m8 ", " "), ""), {("signal_mux_changed", "wire", "speed"), ("signal_mux_changed", "wire", "mode")}),
    ((_MUX_SIGNALS, ""), (_MUX_SIGNALS, "SG_MUL_VAL_ 256 speed mode 8-9;\n"), {("signal_mux_changed", "wire", "speed")}),
], ids=["fd_frame", "float_signal", "byte_order", "brs", "m8_to_m9", "page_to_every_frame", "page_widened"])
def test_dbcs_differing_in_byte_order_fd_or_float_are_classified(tmp_path, old, new, expected):
    old_dbc, new_dbc = _dbc(tmp_path, "old", *old), _dbc(tmp_path, "new", *new)
    code, out, err = run_cli("diff", old_dbc, new_dbc, "--format", "json", "--fail-on", "wire")
    assert {(c["kind"], c["class"], c["signal"]) for c in json.loads(out)["changes"]} == expected, err
    assert code == (1 if any(cls == "wire" for _, cls, _ in expected) else 0)
