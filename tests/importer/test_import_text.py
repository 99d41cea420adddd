"""`canspec import` and `canspec diff` on a source's text as a user runs them: its encoding (UTF-8,
--encoding, else a cp1252 or GB18030 guess said as a warning at its line), binary data and huge
lines refused in a line of stderr, and what cantools reads without a line number (an attribute it
cannot convert, a wrapped ID, a self-multiplexed signal, its own log lines) said at the source line."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec.importer.encoding import decode
from canspec_cli import assert_no_traceback, run_canspec

from importer.test_import_cli import COMMAND, _dbc

CANTOOLS_DBC = Path(__file__).parent / "cantools_files" / "dbc"


def _commented(tmp_path: Path, name: str, comment: str, encoding: str) -> Path:
    path = tmp_path / name
    path.write_bytes(f'VERSION ""\n\nBU_: ECU CTRL\n\n{COMMAND}\nCM_ SG_ 2550247584 mode "{comment}";\n'.encode(encoding))
    return path  # the comment is on line 8


def _desc(out: Path) -> str:
    (spec,) = (p for p in out.glob("*.yaml") if p.name != "canspec.yaml")
    return spec.read_text(encoding="utf-8")


def test_chinese_gbk_text_is_read_as_gb18030_with_a_warning_at_its_line(tmp_path: Path) -> None:
    dbc = _commented(tmp_path, "gbk.dbc", "模式选择（N·m）", "gbk")
    r = run_canspec("import", dbc, "-o", tmp_path / "out")
    assert r.returncode == 0 and f"{dbc}:8: warning: not UTF-8; its non-ASCII text reads as Chinese: read as GB18030" in r.stderr, r.stderr
    assert 'desc: "模式选择（N·m）"' in _desc(tmp_path / "out")
    r = run_canspec("import", "--encoding", "gbk", dbc, "-o", tmp_path / "named")
    assert r.returncode == 0 and "UTF-8" not in r.stderr and 'desc: "模式选择（N·m）"' in _desc(tmp_path / "named"), r.stderr


def test_latin_text_stays_cp1252_with_the_hint_and_strict_refuses_the_guess(tmp_path: Path) -> None:
    """"für Geräte" decodes as GBK too (FC 72 is one character): the guess must not take it."""
    dbc = _commented(tmp_path, "latin1.dbc", "Modus für Geräte", "cp1252")
    r = run_canspec("import", dbc, "-o", tmp_path / "out")
    assert r.returncode == 0 and f"{dbc}:8: warning: not UTF-8: read as cp1252 (Western European); if the text is Chinese, " \
        "pass --encoding gbk (or gb18030)" in r.stderr, r.stderr
    assert 'desc: "Modus für Geräte"' in _desc(tmp_path / "out")
    r = run_canspec("import", "--strict", dbc, "-o", tmp_path / "strict")
    assert r.returncode == 1 and f"{dbc}:8: error: not UTF-8" in r.stderr and not (tmp_path / "strict").exists(), r.stderr
    r = run_canspec("import", "--encoding", "utf-8", dbc, "-o", tmp_path / "utf8")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {dbc}:8: not utf-8 text (byte 0xFC"), r.stderr
    r = run_canspec("import", "--encoding", "nonesuch", dbc, "-o", tmp_path / "x")
    assert r.returncode == 2 and "unknown encoding 'nonesuch'" in r.stderr, r.stderr


@pytest.mark.parametrize("text", ["Größe", "créé réécrire", "für Geräte", "Temperatur °C ±5", "µs"])
def test_western_text_is_never_guessed_chinese(text: str) -> None:
    read, (line, warning) = decode(f'CM_ "{text}";\n'.encode("cp1252"), None)  # type: ignore[misc]
    assert read == f'CM_ "{text}";\n' and line == 1 and "read as cp1252" in warning


@pytest.mark.parametrize("name", ["abs.dbc", "choices.dbc", "cp1252.dbc", "vehicle.dbc"])
def test_real_cp1252_dbcs_are_read_as_cp1252(name: str) -> None:
    data = (CANTOOLS_DBC / name).read_bytes()
    text, (_, warning) = decode(data, None)  # type: ignore[misc]
    assert text == data.decode("cp1252") and "read as cp1252" in warning


def test_diff_passes_encoding_to_both_revisions(tmp_path: Path) -> None:
    """One GBK character reads as two Latin letters in cp1252 ("是" is "ÊÇ"): the guess stays
    cp1252, and --encoding gbk is how the user says otherwise, for both revisions."""
    old, new = _commented(tmp_path, "old.dbc", "是", "gbk"), _commented(tmp_path, "new.dbc", "否", "gbk")
    guessed = run_canspec("diff", old, new, "--format", "json")
    assert guessed.returncode == 0 and '"old": "ÊÇ"' in guessed.stdout and "--encoding gbk" in guessed.stderr, guessed.stderr
    named = run_canspec("diff", "--encoding", "gbk", old, new, "--format", "json")
    assert named.returncode == 0 and '"old": "是"' in named.stdout and '"new": "否"' in named.stdout, named.stdout + named.stderr
    assert "UTF-8" not in named.stderr


def test_binary_data_and_huge_lines_are_one_short_line(tmp_path: Path) -> None:
    nul = tmp_path / "nul.dbc"
    nul.write_bytes(b'VERSION ""\n' + b"\0" * (1 << 20))
    r = run_canspec("import", nul, "-o", tmp_path / "out")
    assert r.returncode == 1 and r.stderr == f"canspec import: {nul}: not a text file (binary data at byte offset 11)\n", r.stderr[:300]
    big = tmp_path / "big.dbc"
    big.write_text('VERSION ""\n\nBU_: A\n\nCM_ "' + "x" * 3_000_000 + "\nBO_ 1 X: 8 A\n", encoding="utf-8")
    r = run_canspec("import", big, "-o", tmp_path / "out")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {big}:5: not a readable DBC") and len(r.stderr) < 600, r.stderr[:300]
    assert "more characters)" in r.stderr


def test_errors_cantools_gives_without_a_line_are_at_their_line(tmp_path: Path) -> None:
    baud = _dbc(tmp_path, "baud.dbc", COMMAND + '\nBA_DEF_  "Baudrate" STRING;\nBA_DEF_DEF_ "Baudrate" "";\nBA_ "Baudrate" "fast";\n')
    r = run_canspec("import", baud, "-o", tmp_path / "out")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {baud}:14: not a readable DBC: ") and "'fast'" in r.stderr, r.stderr
    huge = _dbc(tmp_path, "huge.dbc", COMMAND.replace("2550247584", "99999999999") + 'CM_ SG_ 99999999999 mode "Mode";\n')
    r = run_canspec("import", huge, "-o", tmp_path / "out2")
    assert f"{huge}:9: warning: ID 99999999999 (0x174876E7FF) of command does not fit 29 bits: message left out" in r.stderr, r.stderr
    assert "0x4876E7FF" not in r.stderr.upper()
    assert_no_traceback(r)


def test_sg_mul_val_naming_a_signal_its_own_multiplexer_is_said_at_its_line(tmp_path: Path) -> None:
    body = COMMAND.replace(" mode :", " mode m1M :") + ' SG_ speed : 8|8@1+ (1,0) [0|1] "" ECU\n\nSG_MUL_VAL_ 2550247584 mode mode 1-1;\n'
    dbc = _dbc(tmp_path, "self.dbc", body)
    r = run_canspec("import", dbc, "-o", tmp_path / "out")
    assert f"{dbc}:13: warning: message command: SG_MUL_VAL_ names signal mode as its own multiplexer: left out" in r.stderr, r.stderr
    assert "None" not in r.stderr


def test_cantools_log_lines_become_canspec_messages_at_their_lines(tmp_path: Path) -> None:
    """cantools logs a message that replaces another in its lookup tables on stderr, unformatted."""
    dupid = _dbc(tmp_path, "dupid.dbc", COMMAND + "\n" + COMMAND.replace("command", "command2"))
    r = run_canspec("import", dupid, "-o", tmp_path / "out")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {dupid}:12: messages command (line 9) and command2 (line 12) "
                                                     "have one frame ID, 0x1801B0A0") and "Overwriting" not in r.stderr, r.stderr
    assert not (tmp_path / "out").exists()
    dupname = _dbc(tmp_path, "dupname.dbc", COMMAND + "\n" + COMMAND.replace("2550247584", "100"))
    r = run_canspec("import", dupname, "-o", tmp_path / "out")
    assert r.returncode == 0 and "Overwriting" not in r.stderr, r.stderr
    assert f"{dupname}:12: warning: message name command is given to two messages (lines 9, 12): both kept" in r.stderr, r.stderr
    assert "dbc_name: command" in _desc(tmp_path / "out")
