"""`canspec import` as a user runs it: each dirty-DBC repair is a warning at its source line with
what was decided; --strict refuses; unreadable input is one error line with file:line, never a
traceback; several sources merge, and a clash names both; ARXML, KCD and SYM written by cantools
from a DBC import to the same messages."""

from __future__ import annotations

from pathlib import Path

import cantools
import pytest
from canspec_cli import FIXTURES, assert_no_traceback, run_canspec

DIRTY = """VERSION ""

NS_ :

BS_:

BU_: ECU GW

BO_ 291 STATUS: 8 ECU
 SG_ SPEED : 0|16@1+ (.25,0) [0|1000] "km/h" GW
 SG_ 0_COUNTER : 16|4@1+ (1,0) [0|15] "" GW

BO_ 1075054137 TOO_WIDE: 8 ECU
 SG_ X : 0|8@1+ (1,0) [0|255] "" GW

BO_ 2047 OK_STD: 2 GW
 SG_ Gear : 7|4@0+ (1,0) [0|15] "" ECU

BO_ 4660 NO_EXT_FLAG: 8 GW
 SG_ Level : 0|8@1+ (1,0) [0|255] "" ECU

CM_ "Bus comment"
CM_ 291 "Status frame";
CM_ SG_ 2047 "no signal name";
VAL_ 2047 Gear 0 "P" 1 "R" 2 "N" 3 "D" ;
VAL_ 2047 Missing 0 "x" ;
"""

# line numbers in DIRTY of what each repair warns about
EXPECTED = {
    10: "number written without a leading 0",
    11: "name '0_COUNTER' starts with a digit",
    13: "does not fit 29 bits: message left out",
    19: "ID 0x1234 of NO_EXT_FLAG is above 0x7FF but has no extended flag: taken as 29-bit",
    22: "CM_ without its closing ';'",
    23: "CM_ without an object type before ID 291",
    24: "CM_ SG_ without a signal name: dropped",
    26: "VAL_ for signal Missing of message 2047, which has no such signal: dropped",
}


@pytest.fixture
def dirty(tmp_path: Path) -> Path:
    path = tmp_path / "dirty.dbc"
    path.write_text(DIRTY, encoding="utf-8")
    return path


def test_every_repair_is_a_warning_at_its_line(dirty: Path, tmp_path: Path) -> None:
    r = run_canspec("import", dirty, "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    for line, text in EXPECTED.items():
        assert any(w.startswith(f"{dirty}:{line}: warning: ") and text in w for w in r.stderr.splitlines()), (line, text, r.stderr)
    assert "Traceback" not in r.stderr
    checked = run_canspec("check", tmp_path / "out")
    assert checked.returncode == 0, checked.stderr
    spec = (tmp_path / "out" / "dirty.yaml").read_text(encoding="utf-8")
    assert "dbc_name: \"0_COUNTER\"" in spec and "factor: 0.25" in spec and "id: 0x1234" in spec and "extended: true" in spec


def test_the_generated_dbc_keeps_the_sources_names(dirty: Path, tmp_path: Path) -> None:
    assert run_canspec("import", dirty, "-o", tmp_path / "out").returncode == 0
    assert run_canspec("gen", tmp_path / "out", "-o", tmp_path / "gen", "--target", "dbc").returncode == 0
    text = (tmp_path / "gen" / "dbc" / "dirty.dbc").read_text(encoding="utf-8")
    assert " SG_ 0_COUNTER : 16|4@1+" in text and "BO_ 291 STATUS: 8 ECU" in text and 'VAL_ 2047 Gear 0 "P" 1 "R" 2 "N" 3 "D" ;' in text


def test_strict_turns_warnings_into_errors_and_writes_nothing(dirty: Path, tmp_path: Path) -> None:
    r = run_canspec("import", "--strict", dirty, "-o", tmp_path / "out")
    assert r.returncode == 1 and f"{dirty}:10: error: " in r.stderr and "nothing written" in r.stderr
    assert not (tmp_path / "out").exists()


def test_unreadable_input_is_one_line_with_its_place(tmp_path: Path) -> None:
    bad = tmp_path / "bad.dbc"
    bad.write_text('VERSION ""\nBO_ 12 X: 8 A\n SG_ S : 0|8@1+ (1,0) [0|1 "" A\n', encoding="utf-8")
    r = run_canspec("import", bad, "-o", tmp_path / "out")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {bad}:3: not a readable DBC") and "Traceback" not in r.stderr
    for name, text in (("missing.dbc", None), ("notes.txt", "x")):
        path = tmp_path / name
        if text is not None:
            path.write_text(text, encoding="utf-8")
        r = run_canspec("import", path, "-o", tmp_path / "out")
        assert r.returncode == 1 and r.stderr.count("\n") == 1 and str(path) in r.stderr, r.stderr


@pytest.mark.parametrize(("line", "says"), [
    ("BO_ 12 X: 99999999 A", "message X is 99999999 bytes long; a CAN frame holds at most 64"),
    ("BO_ 12 X: 8 A\n SG_ S : 0|9999999999@1+ (1,0) [0|1] \"\" A", "signal S: start bit 0, 9999999999 bits: no CAN frame has these bits"),
    ("BO_ 12 X: 8 A\n SG_ S : 999999999|8@0+ (1,0) [0|1] \"\" A", "signal S: start bit 999999999, 8 bits: no CAN frame has these bits"),
])
def test_sizes_no_frame_has_are_refused_before_the_reader_takes_them(tmp_path: Path, line: str, says: str) -> None:
    """cantools builds its codec bit by bit: a fuzzed length of 10^10 bits took 24 GB before the kernel killed it."""
    bad = tmp_path / "huge.dbc"
    bad.write_text(f'VERSION ""\n\nBU_: A\n\n{line}\n', encoding="utf-8")
    r = run_canspec("import", bad, "-o", tmp_path / "out", timeout=60)
    at = 5 + line.count("\n")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {bad}:{at}: {says}") and "hint:" in r.stderr, r.stderr
    assert not (tmp_path / "out").exists()


def test_two_sources_merge_and_a_clash_names_both(tmp_path: Path) -> None:
    a, b = tmp_path / "a.dbc", tmp_path / "b.dbc"
    a.write_text('VERSION ""\nBU_: X\nBO_ 16 ONE: 1 X\n SG_ S : 0|8@1+ (1,0) [0|0] "" X\n', encoding="utf-8")
    b.write_text('VERSION ""\nBU_: Y\nBO_ 17 TWO: 1 Y\n SG_ S : 0|8@1+ (1,0) [0|0] "" Y\n', encoding="utf-8")
    r = run_canspec("import", a, b, "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    spec = (tmp_path / "out" / "a.yaml").read_text(encoding="utf-8")
    assert "name: one" in spec and "name: two" in spec and "{name: \"Y\"}" in spec  # Y is a YAML boolean word: quoted
    b.write_text('VERSION ""\nBU_: Y\nBO_ 16 OTHER: 1 Y\n SG_ S : 0|8@1+ (1,0) [0|0] "" Y\n', encoding="utf-8")
    r = run_canspec("import", a, b, "-o", tmp_path / "out2")
    assert r.returncode == 1 and str(a) in r.stderr and str(b) in r.stderr and "ID 0x10" in r.stderr


@pytest.mark.parametrize("fmt", ["kcd", "sym"])
def test_other_formats_written_by_cantools_import_the_same_messages(fmt: str, tmp_path: Path) -> None:
    """cantools writes the fixture's DBC (with `dbc_signal_names: unique`: SYM and KCD keep one
    definition per name) as KCD / SYM; importing either gives the same frames and fields."""
    spec = tmp_path / "unique.yaml"
    text = (FIXTURES / "valid" / "english_standard_bus.yaml").read_text(encoding="utf-8")
    spec.write_text(text.replace("title: Body bus}", "title: Body bus, dbc_signal_names: unique}"), encoding="utf-8")
    assert run_canspec("gen", spec, "-o", tmp_path / "gen", "--target", "dbc").returncode == 0
    db = cantools.database.load_file(str(tmp_path / "gen" / "dbc" / "body_bus.dbc"))
    source = tmp_path / f"body.{fmt}"
    source.write_text(db.as_kcd_string() if fmt == "kcd" else db.as_sym_string(), encoding="utf-8")
    r = run_canspec("import", source, "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    assert run_canspec("gen", tmp_path / "out", "-o", tmp_path / "back", "--target", "dbc").returncode == 0
    (written,) = (tmp_path / "back" / "dbc").glob("*.dbc")
    back = cantools.database.load_file(str(written))
    assert sorted((m.frame_id, m.length) for m in back.messages) == sorted((m.frame_id, m.length) for m in db.messages)
    for m in db.messages:
        mine = back.get_message_by_frame_id(m.frame_id)
        assert {(s.name, s.start, s.length, s.byte_order, s.is_signed, s.scale, s.offset) for s in m.signals} == \
               {(s.name, s.start, s.length, s.byte_order, s.is_signed, s.scale, s.offset) for s in mine.signals}


def test_a_motorola_fd_float_dbc_comes_back_as_it_was(tmp_path: Path) -> None:
    """The FD fixture's DBC (Motorola and Intel fields, floats, FD with and without BRS) imported and
    generated again: cantools reads the same frames, fields, FD flags and bus attributes."""
    assert run_canspec("gen", FIXTURES / "valid" / "motorola_fd_float.yaml", "-o", tmp_path / "gen", "--target", "dbc").returncode == 0
    source = tmp_path / "gen" / "dbc" / "chassis_fd.dbc"
    r = run_canspec("import", source, "-o", tmp_path / "spec")
    assert r.returncode == 0, r.stderr
    assert run_canspec("gen", tmp_path / "spec", "-o", tmp_path / "back", "--target", "dbc").returncode == 0
    a, b = (cantools.database.load_file(str(p)) for p in (source, tmp_path / "back" / "dbc" / "chassis_fd.dbc"))

    def facts(db):  # type: ignore[no-untyped-def]
        return {(m.frame_id, m.length, m.is_fd, str(m.dbc.attributes.get("CANFD_BRS").value) if "CANFD_BRS" in m.dbc.attributes else None,
                 frozenset((s.name, s.start, s.length, s.byte_order, s.is_signed, s.is_float, s.scale, s.offset, s.minimum, s.maximum)
                           for s in m.signals)) for m in db.messages}

    assert facts(a) == facts(b)
    assert b.dbc.attributes["BaudrateCANFD"].value == 2_000_000


def test_a_multiplexed_dbc_comes_back_as_it_was(tmp_path: Path) -> None:
    """The multiplexed fixture's DBC (a nested multiplexer, pages of ranges through SG_MUL_VAL_,
    overlapping pages, a Motorola page field) imported and generated again: cantools reads the same
    multiplexers, pages and fields, and decodes every page's frame alike."""
    assert run_canspec("gen", FIXTURES / "valid" / "multiplexed.yaml", "-o", tmp_path / "gen", "--target", "dbc").returncode == 0
    (source,) = (tmp_path / "gen" / "dbc").glob("*.dbc")
    r = run_canspec("import", source, "-o", tmp_path / "spec")
    assert r.returncode == 0 and "0 warning(s)" in r.stderr + r.stdout, r.stderr
    assert run_canspec("gen", tmp_path / "spec", "-o", tmp_path / "back", "--target", "dbc").returncode == 0
    a, b = (cantools.database.load_file(str(p)) for p in (source, tmp_path / "back" / "dbc" / source.name))

    def facts(db):  # type: ignore[no-untyped-def]
        return {(m.frame_id, frozenset((s.name, s.start, s.length, s.byte_order, s.scale, s.is_multiplexer, s.multiplexer_signal,
                                        tuple(sorted(s.multiplexer_ids or ()))) for s in m.signals)) for m in db.messages}

    assert facts(a) == facts(b) and any(s.multiplexer_signal for m in a.messages for s in m.signals)
    for m in a.messages:  # one frame per value of the top multiplexer (its nested ones at 0): the same fields, the same values
        top = next(s for s in m.signals if s.is_multiplexer and not s.multiplexer_ids)
        for value in range(min(1 << top.length, 32)):
            data = bytes([value]) + bytes(range(1, m.length))
            try:
                want = m.decode(data, decode_choices=False)
            except Exception:  # noqa: BLE001 - cantools refuses a value no page has: so must the re-import's DBC
                with pytest.raises(Exception):  # noqa: B017
                    b.get_message_by_frame_id(m.frame_id).decode(data, decode_choices=False)
                continue
            assert b.get_message_by_frame_id(m.frame_id).decode(data, decode_choices=False) == want


def _dbc(tmp_path: Path, name: str, body: str) -> Path:
    path = tmp_path / name
    path.write_text(f'VERSION ""\n\nNS_ :\n\nBS_:\n\nBU_: ECU CTRL\n\n{body}', encoding="utf-8")
    return path


COMMAND = 'BO_ 2550247584 command: 8 CTRL\n SG_ mode : 0|2@1+ (1,0) [0|1] "" ECU\n'


def test_two_signals_of_one_name_in_a_message_are_refused_naming_both_lines(tmp_path: Path) -> None:
    """CM_ and VAL_ name a signal by its name: with two `mode`s which one they mean has no reading
    (this ended in an internal KeyError in import and in diff)."""
    dup = _dbc(tmp_path, "dup.dbc", COMMAND + ' SG_ mode : 8|16@1+ (0.1,-100) [-100|100] "km/h" ECU\n\nVAL_ 2550247584 mode 0 "off" 1 "on" ;\n')
    says = f"{dup}:11: message command has two signals named mode (lines 10 and 11)"
    r = run_canspec("import", dup, "-o", tmp_path / "out")
    assert r.returncode == 1 and r.stderr.startswith(f"canspec import: {says}") and "hint:" in r.stderr, r.stderr
    assert_no_traceback(r)
    assert not (tmp_path / "out").exists()
    base = _dbc(tmp_path, "base.dbc", COMMAND)
    r = run_canspec("diff", base, dup)
    assert r.returncode == 2 and f"canspec diff: {says}" in r.stderr, r.stderr
    assert_no_traceback(r)


def test_an_sg_line_repeated_word_for_word_is_dropped_with_a_warning(tmp_path: Path) -> None:
    twice = _dbc(tmp_path, "twice.dbc", COMMAND + COMMAND.splitlines()[1] + "\n")
    r = run_canspec("import", twice, "-o", tmp_path / "out")
    assert r.returncode == 0 and f"{twice}:11: warning: SG_ line of signal mode repeats line 10 of message command word for word: dropped" \
        in r.stderr, r.stderr
    assert (tmp_path / "out" / "twice.yaml").read_text(encoding="utf-8").count("{name: mode,") == 1


def test_a_cycle_time_that_is_not_a_number_is_a_warning_at_its_ba_line(tmp_path: Path) -> None:
    """GenMsgCycleTime defined as STRING holds text: no cycle time (this was an internal ValueError)."""
    weird = _dbc(tmp_path, "weird.dbc", COMMAND + '\nBA_DEF_ BO_ "GenMsgCycleTime" STRING ;\nBA_DEF_DEF_ "GenMsgCycleTime" "abc";\n'
                 'BA_ "GenMsgCycleTime" BO_ 2550247584 "fast";\n')
    r = run_canspec("import", weird, "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    assert f"{weird}:14: warning: GenMsgCycleTime of message command is 'fast', not a number of milliseconds: " \
           "message taken without a cycle time" in r.stderr, r.stderr
    assert "cycle_ms" not in (tmp_path / "out" / "weird.yaml").read_text(encoding="utf-8")


@pytest.mark.parametrize("attribute", ["VFrameFormat", "Mode"])
def test_an_enum_value_that_is_no_index_of_its_values_is_dropped_at_its_line(tmp_path: Path, attribute: str) -> None:
    """A BA_ line holds an ENUM attribute's index: 99 of VFrameFormat's 16 values made cantools fail
    ('list index out of range', no line), 7 of a two-value ENUM was an internal IndexError."""
    enums = ('BA_DEF_ BO_ "VFrameFormat" ENUM "StandardCAN","ExtendedCAN","reserved","J1939PG"' + ',"reserved"' * 10
             + ',"StandardCAN_FD","ExtendedCAN_FD";\nBA_DEF_ BO_ "Mode" ENUM "A","B";\n')
    bad = _dbc(tmp_path, "bad.dbc", COMMAND + "\n" + enums + f'BA_ "{attribute}" BO_ 2550247584 {99 if attribute == "VFrameFormat" else 7};\n'
               + 'BA_ "Mode" BO_ 2550247584 1;\n')
    r = run_canspec("import", bad, "-o", tmp_path / "out")
    assert_no_traceback(r)
    size, value = (16, 99) if attribute == "VFrameFormat" else (2, 7)
    assert r.returncode == 0 and f"{bad}:14: warning: BA_ {attribute} value {value} is not an index of its ENUM's {size} values " \
        f"(0..{size - 1}): dropped" in r.stderr, r.stderr
    written = (tmp_path / "out" / "bad.yaml").read_text(encoding="utf-8")
    assert "dbc_attributes: {Mode: B}" in written, written  # the valid BA_ line after it is kept
    assert run_canspec("import", "--strict", bad, "-o", tmp_path / "strict").returncode != 0


def test_attribute_defaults_state_the_bus_rates_and_bit_rate_switching(tmp_path: Path) -> None:
    """An object without a BA_ value has its definition's BA_DEF_DEF_ default: the bus rates that only
    a default states were taken as not given (500 kbit/s and 2000 kbit/s assumed, with a warning),
    and a CANFD_BRS default "0" as bit-rate switching on."""
    fd = 'BO_ 2550247585 fast: 16 CTRL\n SG_ x : 0|8@1+ (1,0) [0|255] "" ECU\n'
    defs = ('BA_DEF_ "Baudrate" INT 0 1000000;\nBA_DEF_ "BaudrateCANFD" INT 0 16000000;\nBA_DEF_ BO_ "CANFD_BRS" ENUM "0","1";\n'
            'BA_DEF_ BO_ "VFrameFormat" ENUM "StandardCAN","ExtendedCAN","reserved","J1939PG"' + ',"reserved"' * 10
            + ',"StandardCAN_FD","ExtendedCAN_FD";\nBA_DEF_DEF_ "Baudrate" 250000;\nBA_DEF_DEF_ "BaudrateCANFD" 5000000;\n'
            'BA_DEF_DEF_ "CANFD_BRS" "0";\nBA_DEF_DEF_ "VFrameFormat" "StandardCAN";\nBA_ "VFrameFormat" BO_ 2550247585 15;\n')
    src = _dbc(tmp_path, "defaults.dbc", COMMAND + fd + "\n" + defs)
    r = run_canspec("import", "--strict", src, "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr  # --strict: no rate assumed
    written = (tmp_path / "out" / "defaults.yaml").read_text(encoding="utf-8")
    assert "bitrate: 250000" in written and "data_bitrate: 5000000" in written and "brs: false" in written, written
    db = cantools.database.load_file(str(src))
    assert db.get_message_by_name("fast").is_fd and db.dbc.attribute_definitions["CANFD_BRS"].default_value == "0"


def test_an_output_that_is_a_file_is_one_error_line_and_nothing_written(tmp_path: Path) -> None:
    dbc, afile = _dbc(tmp_path, "base.dbc", COMMAND), tmp_path / "afile"
    afile.write_bytes(b"")
    for out, says in ((afile, f"-o {afile}: exists and is not a directory"), (afile / "sub", f"cannot write {afile / 'sub'}: ")):
        r = run_canspec("import", dbc, "-o", out)
        assert r.returncode == 1 and f"canspec import: {says}" in r.stderr, r.stderr
        assert_no_traceback(r)
    assert afile.read_bytes() == b""


def test_files_import_did_not_write_or_that_were_edited_are_kept_unless_forced(tmp_path: Path) -> None:
    """Another spec's canspec.yaml, or an imported spec edited since, is not replaced without
    --force; the same import again, or a changed source over an unedited import, replaces."""
    dbc, out = _dbc(tmp_path, "base.dbc", COMMAND), tmp_path / "out"
    out.mkdir()
    (out / "canspec.yaml").write_text("kind: bundle\n", encoding="utf-8")
    r = run_canspec("import", dbc, "-o", out)
    assert r.returncode == 1 and "canspec.yaml already there, not written by canspec import or edited since: nothing written" in r.stderr
    assert "--force" in r.stderr and [p.name for p in out.iterdir()] == ["canspec.yaml"]
    assert run_canspec("import", "--force", dbc, "-o", out).returncode == 0
    assert run_canspec("import", dbc, "-o", out).returncode == 0  # the same import again
    dbc.write_text(dbc.read_text(encoding="utf-8").replace("mode", "state"), encoding="utf-8")
    assert run_canspec("import", dbc, "-o", out).returncode == 0  # a changed source over an unedited import
    spec = out / "base.yaml"
    assert "state" in spec.read_text(encoding="utf-8")
    spec.write_text(spec.read_text(encoding="utf-8") + "# my note\n", encoding="utf-8")
    r = run_canspec("import", dbc, "-o", out)
    assert r.returncode == 1 and "base.yaml already there" in r.stderr and spec.read_text(encoding="utf-8").endswith("# my note\n")
    assert run_canspec("import", "--force", dbc, "-o", out).returncode == 0 and "# my note" not in spec.read_text(encoding="utf-8")


def test_a_protocol_named_canspec_keeps_its_spec_beside_the_bundle(tmp_path: Path) -> None:
    dbc = _dbc(tmp_path, "canspec.dbc", COMMAND)
    assert run_canspec("import", dbc, "-o", tmp_path / "out").returncode == 0
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["canspec.yaml", "canspec_spec.yaml"]
    checked = run_canspec("check", tmp_path / "out")
    assert checked.returncode == 0 and "1 messages" in checked.stderr, checked.stderr
