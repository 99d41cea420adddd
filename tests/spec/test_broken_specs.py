"""Issue 9, bad input: a corpus of broken specs. Every one gets a clear `file:line` error
(or, where no line exists — a missing path, a directory — the path itself), a non-zero exit and
never a traceback, from `canspec check` and from `canspec gen` (which then writes nothing)."""

from __future__ import annotations

import errno
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from canspec_cli import FIXTURES, ROOT, assert_no_traceback, canspec_env, run_canspec

BROKEN = FIXTURES / "broken"
VALID_CAN = (FIXTURES / "valid" / "minimal_can.yaml").read_text(encoding="utf-8")

# Committed corpus: file → (line:col of the first error, words the message must hold).
CORPUS = {
    "syntax_unclosed_flow.yaml": ("9:13", "expected ',' or '}'"),
    "syntax_tab_indent.yaml": ("19:1", "cannot start any token"),
    "syntax_bad_indent.yaml": ("19:7", "YAML syntax error"),
    "syntax_two_documents.yaml": ("26:1", "found another document"),
    "wrong_type_len_text.yaml": ("21:45", "len: expected integer, got text 'two'"),
    "wrong_type_signals_null.yaml": ("21:8", "expected object, got nothing (null)"),
    "wrong_type_messages_mapping.yaml": ("14:3", "messages: expected array, got a mapping"),
    "wrong_type_id_bool.yaml": ("15:9", "id: expected integer, got boolean True"),
    "wrong_type_nodes_text.yaml": ("6:8", "nodes: expected array, got text"),
    "absurd_factor_1e400.yaml": ("22:58", "factor must be a finite number within the range of a double [nonfinite]"),
    "absurd_factor_underflow.yaml": ("22:58", "factor must be a finite number within the range of a double [nonfinite]"),
    "absurd_offset_1e400.yaml": ("22:71", "offset must be a finite number within the range of a double [nonfinite]"),
    "absurd_range_1e400.yaml": ("22:96", "range must be finite numbers within the range of a double [nonfinite]"),
    "absurd_start_2_70.yaml": ("22:38", "extends beyond the 8-byte frame of 'command' [signal-beyond-dlc]"),
    "absurd_len_2_70.yaml": ("22:46", "length 1180591620717411303424 is not a valid bit field [signal-length]"),
    "absurd_len_negative.yaml": ("22:46", "length -16 is not a valid bit field [signal-length]"),
    "absurd_dlc_100.yaml": ("20:10", "DLC 100 of 'command' is not a CAN frame length [dlc-range]"),
    "absurd_id_negative.yaml": ("15:9", "does not fit 29 bits [id-range]"),
    "absurd_value_2_70.yaml": ("21:71", "value 1180591620717411303424 (0x400000000000000000) does not fit the 2-bit field"),
    "absurd_cycle_2_70.yaml": ("19:15", "cycle time 1180591620717411303424 ms"),
    "absurd_schema_version.yaml": ("2:17", "unsupported schema_version 1180591620717411303424"),
    "absurd_type_max.yaml": ("9:36", "type 'U8': max must be a finite number"),
    "absurd_counter_range_nan.yaml": ("24:59", "range must be finite numbers within the range of a double [nonfinite]"),
    "absurd_multiframe_negative.yaml": ("33:52", "length -2 is not a valid bit field [signal-length]"),
    "duplicate_key_flow.yaml": ("21:48", "duplicate key 'start' (first defined at line 21) [yaml-duplicate-key]"),
    "duplicate_key_top.yaml": ("26:1", "duplicate key 'nodes' (first defined at line 6)"),
    "unknown_key_top.yaml": ("13:1", "unknown key 'messagse' in file [schema]"),
    "unknown_key_bus.yaml": ("5:91", "unknown key 'baud' in bus [schema]"),
    "nonscalar_key.yaml": ("19:5", "a mapping key must be a scalar"),
    "recursive_alias.yaml": ("8:5", "recursive node"),
    "billion_laughs.yaml": ("16:19", "YAML aliases expand this file to more than 5,000,000 values"),
    "bundle_missing_file.yaml": ("7:5", "bundle file 'no_such_file.yaml' does not exist"),
}


def check_fails(path: Path | str, where: str, words: str, cwd: Path = BROKEN) -> subprocess.CompletedProcess[str]:
    proc = run_canspec("check", path, cwd=cwd, timeout=120)
    assert_no_traceback(proc)
    assert proc.returncode == 1, proc.stderr
    first = proc.stderr.splitlines()[0] if proc.stderr else ""
    assert first.startswith(f"{where}: error: "), proc.stderr
    assert words in proc.stderr, proc.stderr
    return proc


def test_corpus_is_complete() -> None:
    assert sorted(p.name for p in BROKEN.glob("*.yaml")) == sorted(CORPUS)


@pytest.mark.parametrize("name", sorted(CORPUS))
def test_broken_spec(name: str) -> None:
    line_col, words = CORPUS[name]
    check_fails(name, f"{name}:{line_col}", words)


@pytest.mark.parametrize("name", ["syntax_unclosed_flow.yaml", "absurd_factor_1e400.yaml", "billion_laughs.yaml"])
def test_gen_on_broken_spec_writes_nothing(name: str, tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = run_canspec("gen", BROKEN / name, "-o", out)
    assert_no_traceback(proc)
    assert proc.returncode == 1 and "nothing written" in proc.stderr, proc.stderr
    assert not out.exists()


# Generated at test time: binary content, sizes and file-system states a repository cannot hold.
def _write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


GENERATED = {
    "not_utf8.yaml": (lambda: VALID_CAN.encode().replace("模式".encode(), b"mod\xe9"), "22:29", "not valid UTF-8 (byte 0xE9)"),
    "utf16.yaml": (lambda: VALID_CAN.encode("utf-16"), "1:1", "not valid UTF-8"),
    "nul_char.yaml": (lambda: VALID_CAN.replace("name: CTRL", "name: C\0TRL").encode(), "9:13", "character U+0000 is not allowed"),
    "bom_broken.yaml": (lambda: b"\xef\xbb\xbf" + VALID_CAN.replace("cycle_ms: 20", "cycle_ms: -20").encode(), "20:15", "[cycle-time]"),
    "top_list.yaml": (lambda: b"- schema_version: 1\n", "1:1", "expected a mapping at the top of the file, got a list"),
    "top_scalar.yaml": (lambda: b"just some text\n", "1:1", "got text 'just some text'"),
    "deep_nesting.yaml": (lambda: b"schema_version: 1\nkind: bundle\nfiles: " + b"[" * 100_000 + b"]" * 100_000 + b"\n", "3:", "YAML nesting is too deep"),
    # A big file (200,000 comment lines) with its error at the end: counted to the right line.
    "big_with_error_at_end.yaml": (lambda: ("# filler\n" * 200_000 + VALID_CAN.replace("len: 16", "len: 0")).encode(), "200023:46", "[signal-length]"),
}


@pytest.mark.parametrize("name", sorted(GENERATED))
def test_generated_broken_input(name: str, tmp_path: Path) -> None:
    make, line_col, words = GENERATED[name]
    _write(tmp_path / name, make())
    proc = run_canspec("check", name, cwd=tmp_path)
    assert_no_traceback(proc)
    # "3:" — for deep nesting the column is where the parser gave up; the line is what matters.
    assert proc.returncode == 1 and proc.stderr.startswith(f"{name}:{line_col}") and words in proc.stderr, proc.stderr


def test_bom_is_ignored(tmp_path: Path) -> None:
    _write(tmp_path / "bom.yaml", b"\xef\xbb\xbf" + VALID_CAN.encode())
    proc = run_canspec("check", "bom.yaml", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr


@pytest.mark.parametrize("content, words", [(b"", "file is empty"), (b"  \n\n\t\n", "file is empty"), (b"# only a comment\n", "file holds no data")])
def test_empty_files(content: bytes, words: str, tmp_path: Path) -> None:
    _write(tmp_path / "empty.yaml", content)
    check_fails("empty.yaml", "empty.yaml", words, cwd=tmp_path)


def test_huge_file_is_refused_before_reading(tmp_path: Path) -> None:
    huge = tmp_path / "huge.yaml"
    with huge.open("wb") as fh:  # sparse: 40 MiB on paper, nothing on disk
        fh.truncate(40 * 2**20)
    check_fails("huge.yaml", "huge.yaml", "file is 40 MiB; spec files are limited to 32 MiB", cwd=tmp_path)


def test_paths_that_are_not_specs(tmp_path: Path) -> None:
    (tmp_path / "empty_dir").mkdir()
    (tmp_path / "a_file.yaml").write_text(VALID_CAN, encoding="utf-8")
    check_fails("empty_dir", "empty_dir", "directory has no canspec.yaml bundle file", cwd=tmp_path)
    check_fails("no_such.yaml", "no_such.yaml", "no such file or directory", cwd=tmp_path)
    check_fails("a_file.yaml/inner.yaml", "a_file.yaml/inner.yaml", "no such file or directory", cwd=tmp_path)
    os.symlink("nowhere.yaml", tmp_path / "dangling.yaml")
    check_fails("dangling.yaml", "dangling.yaml", "no such file or directory", cwd=tmp_path)


def test_devices_and_pipes_are_refused_without_reading(tmp_path: Path) -> None:
    """A device or FIFO has no size to check: /dev/zero would be read without end, a FIFO blocks
    the open. Both are refused from their file type, as a spec path and as a bundle entry."""
    os.mkfifo(tmp_path / "pipe.yaml")
    check_fails("pipe.yaml", "pipe.yaml", "is not a regular file (a device, pipe or socket)", cwd=tmp_path)
    check_fails("/dev/zero", "/dev/zero", "is not a regular file (a device, pipe or socket)", cwd=tmp_path)
    (tmp_path / "canspec.yaml").write_text("schema_version: 1\nkind: bundle\nfiles:\n  - pipe.yaml\n", encoding="utf-8")
    check_fails("canspec.yaml", "canspec.yaml:4:5", "bundle file 'pipe.yaml' is not a regular file", cwd=tmp_path)


def test_a_bundle_file_listed_twice(tmp_path: Path) -> None:
    (tmp_path / "can.yaml").write_text(VALID_CAN, encoding="utf-8")
    (tmp_path / "canspec.yaml").write_text("schema_version: 1\nkind: bundle\nfiles:\n  - can.yaml\n  - ./can.yaml\n", encoding="utf-8")
    check_fails("canspec.yaml", "canspec.yaml:5:5", "bundle file './can.yaml' is listed twice (also as entry 1)", cwd=tmp_path)


@pytest.mark.parametrize(
    "entry, where, words",
    [
        ("0: [off, 关, extra, more]", "12:8", "value_tables.mode.0: expected at most 2 items, got 4"),
        ("0: []", "12:8", "value_tables.mode.0: expected at least 1 item, got 0"),
        ("0: [1, 关]", "12:9", "value_tables.mode.0.0: expected string, got number 1"),
        ("-1: [off, 关]", None, "value -1 (-0x1) does not fit the 2-bit field 'mode' of 'command' (0..3)"),
    ],
)
def test_value_table_entries_are_judged_in_their_own_form(tmp_path: Path, entry: str, where: str | None, words: str) -> None:
    """An entry is a label or a [name, 中文] list: a list is told what is wrong with it as a list,
    not that it is not a string; a negative raw value is written -0x1, not 0x-1."""
    assert "    0: [off, 关]\n" in VALID_CAN
    (tmp_path / "vt.yaml").write_text(VALID_CAN.replace("    0: [off, 关]\n", f"    {entry}\n"), encoding="utf-8")
    proc = run_canspec("check", "vt.yaml", cwd=tmp_path, timeout=120)
    assert_no_traceback(proc)
    assert proc.returncode == 1 and words in proc.stderr, proc.stderr
    if where is not None:
        assert proc.stderr.startswith(f"vt.yaml:{where}: error: {words}"), proc.stderr


def test_read_errors_are_reported_in_process(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """The EACCES/EIO path itself, independent of who runs the tests (root reads anything)."""
    from canspec import cli

    spec = tmp_path / "spec.yaml"
    spec.write_text(VALID_CAN, encoding="utf-8")
    for code in (errno.EACCES, errno.EIO):

        def refuse(self: Path, code: int = code) -> bytes:
            raise OSError(code, os.strerror(code), str(self))

        monkeypatch.setattr(Path, "read_bytes", refuse)
        assert cli.main(["check", str(spec)]) == 1
        err = capsys.readouterr().err
        assert f"error: cannot read file: {os.strerror(code)}" in err and "Traceback" not in err


def _unprivileged_prefix() -> list[str] | None:
    """A command prefix under which file permissions apply: none needed for a normal user; for
    root, drop the capabilities that bypass them (root keeps its uid, so it can still run the
    interpreter it installed packages into). None if that is impossible here."""
    if os.geteuid() != 0:
        return []
    setpriv = shutil.which("setpriv")
    if setpriv is None:
        return None
    caps = "-dac_override,-dac_read_search"
    return [setpriv, f"--bounding-set={caps}", f"--inh-caps={caps}"]


def test_unreadable_file_and_directories(tmp_path: Path) -> None:
    prefix = _unprivileged_prefix()
    if prefix is None:
        pytest.skip("running as root without setpriv: file permissions cannot block root's reads here")
    secret = tmp_path / "secret.yaml"
    secret.write_text(VALID_CAN, encoding="utf-8")
    secret.chmod(0)
    probe = subprocess.run([*prefix, sys.executable, "-c", f"open({str(secret)!r}).read()"], capture_output=True, text=True, check=False)
    if probe.returncode == 0 or (prefix and probe.returncode != 0 and "PermissionError" not in probe.stderr):
        pytest.skip(f"cannot run without permission overrides here (as uid {os.geteuid()}): {probe.stderr.strip()[-200:]}")
    locked = tmp_path / "locked"  # a spec directory we may not list or enter
    locked.mkdir()
    (locked / "canspec.yaml").write_text(VALID_CAN, encoding="utf-8")
    locked.chmod(0)
    try:
        for target, words in (
            ("secret.yaml", "secret.yaml: error: cannot read file: Permission denied"),
            ("locked", "locked/canspec.yaml: error: cannot access: Permission denied"),
            ("locked/canspec.yaml", "locked/canspec.yaml: error: cannot access: Permission denied"),
        ):
            proc = subprocess.run(
                [*prefix, sys.executable, "-m", "canspec", "check", target],
                cwd=tmp_path,
                env=canspec_env(),
                capture_output=True,
                text=True,
                timeout=120,
                check=False,
            )
            assert_no_traceback(proc)
            assert proc.returncode == 1 and words in proc.stderr, proc.stderr
    finally:
        locked.chmod(0o755)
        secret.chmod(0o644)


def test_gen_into_unwritable_places(tmp_path: Path) -> None:
    (tmp_path / "a_file").write_text("x")
    proc = run_canspec("gen", ROOT / "spec", "-o", tmp_path / "a_file", "-t", "dbc")
    assert_no_traceback(proc)
    assert proc.returncode == 1 and "exists and is not a directory" in proc.stderr, proc.stderr
    proc = run_canspec("gen", ROOT / "spec", "-o", tmp_path / "a_file" / "sub", "-t", "dbc")
    assert_no_traceback(proc)
    assert proc.returncode == 1 and "cannot write" in proc.stderr, proc.stderr


def test_merge_keys_and_anchors_are_not_duplicates(tmp_path: Path) -> None:
    """`<<: *base` then an explicit key overrides the merged one (YAML merge semantics); the
    first of several merged mappings wins; only keys written twice are duplicates."""
    from canspec.spec.yamlsource import load_yaml

    text = VALID_CAN.replace("  - {name: CTRL, sa: 0xA0}\n", "  - &ctrl {name: CTRL, sa: 0xA0}\n  - {<<: *ctrl, name: TELE, sa: 0xD0}\n")
    (tmp_path / "merge.yaml").write_text(text, encoding="utf-8")
    proc = run_canspec("check", "merge.yaml", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    (tmp_path / "order.yaml").write_text("a: &a {x: 1, y: 1}\nb: &b {x: 2, z: 2}\nc: {<<: [*a, *b], z: 3}\n", encoding="utf-8")
    assert load_yaml(tmp_path / "order.yaml")["c"] == {"x": 1, "y": 1, "z": 3}
