"""The literal layer (render/literals.py) beyond the shared table of test_literals_table.py: C widths and
comments, Python docstrings and comments, JSON scalars, DBC strings, document hex, spreadsheet cells —
each checked against the language itself where a compiler is at hand."""

from __future__ import annotations

import ast
import subprocess
from fractions import Fraction

import pytest
from canspec.render import literals
from canspec.render.literals import PYTHON, RUST, TYPESCRIPT, C

NASTY = [
    "plain",
    'quote " and backslash \\',
    "tab\tnewline\n",
    "bell\x07 del\x7f nul-ish\x01",
    "trigraph ??= ??( ???=",
    "中文 °C m/s²",
    "digit after control \x017",
]


def test_c_integers():
    """Widths beyond the shared table (test_literals_table.py): a 64-bit context types even small constants."""
    assert C.unsigned(255) == "255u"
    assert C.unsigned(2**40, 64) == "UINT64_C(1099511627776)" and C.unsigned(5, 64) == "UINT64_C(5)"
    assert C.integer(-5, 64) == "INT64_C(-5)"
    assert C.hex(0x3FF, bits=64) == "UINT64_C(0x3FF)"
    with pytest.raises(ValueError):
        C.unsigned(-1)
    with pytest.raises(ValueError):
        C.hex(-1)


def test_c_comments_stay_one_comment(tmp_path):
    """Spec text in a C comment cannot end it, open a nested one, form a trigraph or a line splice."""
    texts = [*NASTY, "ends */ early", "opens /* another", "/**/ and */*", "back\\\nslash", "???/"]
    comments = [C.comment(t) for t in texts]
    assert all("*/" not in c and "/*" not in c and "??" not in c and "\n" not in c for c in comments)
    src = tmp_path / "c.c"
    src.write_text("".join(f"/* {c} */ int v{i};\n" for i, c in enumerate(comments)), encoding="utf-8")
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-trigraphs", "-c", str(src), "-o", str(tmp_path / "c.o")], check=True)


def test_python_docstring_and_comment_text():
    for s in NASTY + ['ends in a quote"', 'triple """ inside', '""', "\\"]:
        doc = PYTHON.doc(s)
        assert ast.literal_eval(f'"""{doc}"""') == " ".join(s.split()), s  # reads back as the one-line text
        assert ast.literal_eval(f'"""x {doc}"""') == "x " + " ".join(s.split()), s
        comment = PYTHON.comment(s)
        assert "\n" not in comment and not any(ord(c) < 0x20 for c in comment), s
        assert ast.parse(f"x = 1  # {comment}\n")


def test_dbc_strings_read_back_by_cantools():
    # The oracle is cantools reading a DBC comment written with the literal: a quote survives as a
    # quote, a backslash (which no reader unescapes) arrives as "/".
    import cantools

    text = literals.dbc_string('say "hi" \\ now')
    dbc = f'VERSION ""\n\nBU_: N\n\nBO_ 1 M: 8 N\n SG_ s : 0|8@1+ (1,0) [0|0] "" N\n\nCM_ BO_ 1 {text};\n'
    db = cantools.database.load_string(dbc, database_format="dbc")
    assert db.messages[0].comment == 'say "hi" / now'


def test_sheet_numbers_are_exact_or_text():
    # Excel keeps 15 significant digits: a number cell only where that is the exact value.
    assert literals.sheet_number(Fraction(1, 50)) == 0.02 and isinstance(literals.sheet_number(Fraction(1, 50)), float)
    assert literals.sheet_number(-1080) == -1080 and isinstance(literals.sheet_number(-1080), int)
    assert literals.sheet_number(10**20) == 10**20  # one significant digit: exact as a double
    assert literals.sheet_number(123456789012345) == 123456789012345
    assert literals.sheet_number(1234567890123456) == "1234567890123456"
    assert literals.sheet_number(2**64 - 1) == "18446744073709551615"
    assert literals.sheet_number(Fraction(2**64 - 1, 1000)) == "18446744073709551.615"
    assert literals.sheet_number(Fraction(-3, 10**20)) == -3e-20


def test_json_scalars_in_python_and_rust():
    for value in ["N", 'q"\\', 3, -7, -1.5, 1e-07, 3.4028234663852886e38, True, False, None]:
        assert ast.literal_eval(PYTHON.value(value)) == value
    assert [RUST.value(v) for v in ("N", 3, 70000, -1.5, 1e22, True)] == ['"N"', "3", "70000", "-1.5", "1e22", "true"]
    assert [TYPESCRIPT.value(v) for v in ("N", 3, -1.5, 1e22, True)] == ['"N"', "3", "-1.5", "1e+22", "true"]


def test_hex_in_documents_and_markdown_cells():
    assert [literals.hex_text(v) for v in (0, 0x3FF, -0x10)] == ["0x0", "0x3FF", "-0x10"]
    assert literals.hex_text(0xA, 8) == "0x0000000A" and literals.hex_byte(0xA) == "0x0A"
    assert literals.md_cell("a | b\nc") == "a \\| b c"
