"""The literal layer (render/literals.py): each language's syntax, checked against the language
itself where a compiler is at hand (gcc for C, Python's own parser, json for TypeScript)."""

from __future__ import annotations

import ast
import json
import subprocess
from fractions import Fraction

import pytest
from canspec.render import literals

NASTY = ['plain', 'quote " and backslash \\', "tab\tnewline\n", "bell\x07 del\x7f nul-ish\x01", "trigraph ??= ??( ???=", "中文 °C m/s²", "digit after control \x017"]


def test_numbers():
    assert literals.float_lit(Fraction(-1080)) == "-1080.0"
    assert literals.float_lit(Fraction(1, 10)) == "0.1"
    assert literals.float_lit(Fraction(3, 2000)) == "0.0015"
    assert literals.double_repr(1e-7) == "1e-07" and literals.double_repr(3.0) == "3.0" and literals.double_repr(1e22) == "1e22"
    assert literals.grouped_int(1023) == "1023"
    assert literals.grouped_int((1 << 64) - 1) == "0xFFFF_FFFF_FFFF_FFFF"
    assert literals.grouped_int(-0x1_0000) == "-0x1_0000"
    assert eval(literals.grouped_int(0x1_2345)) == 0x12345  # also a valid Python literal  # noqa: S307


def test_c_integers():
    assert literals.c_uint(255) == "255u"
    assert literals.c_uint(2**40, 64) == "UINT64_C(1099511627776)"
    assert literals.c_int(-1080) == "(-1080)"
    assert literals.c_int(-(2**63), 64) == "INT64_MIN"
    assert literals.c_hex(0x3FF) == "0x3FFu"
    with pytest.raises(ValueError):
        literals.c_uint(-1)


def test_c_strings_compile_to_the_same_bytes(tmp_path):
    src = tmp_path / "s.c"
    body = ",\n".join(literals.c_string(s) for s in NASTY)
    src.write_text(f'#include <stdio.h>\nstatic const char *const S[] = {{{body}}};\nint main(void) {{ for (unsigned i = 0; i < sizeof S / sizeof *S; i++) {{ fputs(S[i], stdout); putchar(0); }} return 0; }}\n', encoding="utf-8")
    exe = tmp_path / "s"
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-trigraphs", str(src), "-o", str(exe)], check=True)
    out = subprocess.run([str(exe)], capture_output=True, check=True).stdout
    assert out.split(b"\0")[:-1] == [s.encode("utf-8") for s in NASTY]


def test_c_comments_stay_one_comment(tmp_path):
    """Spec text in a C comment cannot end it, open a nested one, form a trigraph or a line splice."""
    texts = [*NASTY, "ends */ early", "opens /* another", "/**/ and */*", "back\\\nslash", "???/"]
    comments = [literals.c_comment(t) for t in texts]
    assert all("*/" not in c and "/*" not in c and "??" not in c and "\n" not in c for c in comments)
    src = tmp_path / "c.c"
    src.write_text("".join(f"/* {c} */ int v{i};\n" for i, c in enumerate(comments)), encoding="utf-8")
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-trigraphs", "-c", str(src), "-o", str(tmp_path / "c.o")], check=True)


def test_python_and_typescript_strings():
    for s in NASTY:
        assert ast.literal_eval(literals.py_string(s)) == s
        assert json.loads(literals.ts_string(s)) == s


def test_python_docstring_and_comment_text():
    for s in NASTY + ['ends in a quote"', 'triple """ inside', '""', "\\"]:
        doc = literals.py_doc(s)
        assert ast.literal_eval(f'"""{doc}"""') == " ".join(s.split()), s  # reads back as the one-line text
        assert ast.literal_eval(f'"""x {doc}"""') == "x " + " ".join(s.split()), s
        comment = literals.py_comment(s)
        assert "\n" not in comment and not any(ord(c) < 0x20 for c in comment), s
        assert ast.parse(f"x = 1  # {comment}\n")


def test_rust_strings_compile_to_the_same_bytes(tmp_path):
    src = tmp_path / "s.rs"
    body = ", ".join(literals.rust_string(s) for s in NASTY)
    src.write_text(f"fn main() {{ for s in [{body}] {{ print!(\"{{}}\\0\", s); }} }}\n", encoding="utf-8")
    subprocess.run(["rustc", "-D", "warnings", "-o", str(tmp_path / "s"), str(src)], check=True, cwd=tmp_path)
    out = subprocess.run([str(tmp_path / "s")], capture_output=True, check=True).stdout
    assert out.split(b"\0")[:-1] == [s.encode("utf-8") for s in NASTY]


def test_dbc_strings_never_hold_a_quote():
    assert literals.dbc_string('say "hi" \\ now') == "\"say 'hi' / now\""


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
        assert ast.literal_eval(literals.py_value(value)) == value
    assert [literals.rust_value(v) for v in ("N", 3, -1.5, 1e22, True)] == ['"N"', "3", "-1.5", "1e22", "true"]
