"""One table of literals, every language (Kaitai's TranslatorSpec `everybody(...)` style): each row
is one value and the text each language's Literals writes for it, so a value whose syntax differs
between languages shows up as one row. Then every row is read back by the language itself — C by
gcc, Rust by rustc, Python by its parser, TypeScript (JavaScript) by node — and must give the value.
The expected texts are written by hand from each language's literal syntax, not taken from the code."""

from __future__ import annotations

import ast
import shutil
import subprocess
from fractions import Fraction

import pytest
from canspec.render.literals import PYTHON, RUST, TYPESCRIPT, C, Literals

LANGUAGES: dict[str, Literals] = {"c": C, "python": PYTHON, "rust": RUST, "ts": TYPESCRIPT}


def everybody(text: str, **others: str) -> dict[str, str]:
    """The same text in every language, except the ones named (`everybodyExcept`)."""
    assert set(others) <= set(LANGUAGES), others
    return {lang: others.get(lang, text) for lang in LANGUAGES}


INTEGERS = [
    (0, everybody("0")),
    (1023, everybody("1023")),
    (-1080, everybody("-1080", c="(-1080)")),
    (0xFFFF, everybody("65535")),
    (0x1_2345, everybody("74565", rust="0x1_2345")),  # Rust: hex in groups of four beyond 2^16 (masks read better)
    (-0x1_0000, everybody("-65536", c="(-65536)", rust="-0x1_0000")),
    (2**31 - 1, everybody("2147483647", rust="0x7FFF_FFFF")),
    (-(2**31), everybody("-2147483648", c="INT64_C(-2147483648)", rust="-0x8000_0000")),  # C: no int literal of its own
    (2**63 - 1, everybody("9223372036854775807", c="INT64_C(9223372036854775807)", rust="0x7FFF_FFFF_FFFF_FFFF")),
    (-(2**63), everybody("-9223372036854775808", c="INT64_MIN", rust="-0x8000_0000_0000_0000")),
]

HEXES = [  # (value, minimum digits)
    (0, 0, everybody("0x0", c="0x0u")),
    (0x3FF, 0, everybody("0x3FF", c="0x3FFu")),
    (0xA, 2, everybody("0x0A", c="0x0Au")),
    (0x1234, 8, everybody("0x00001234", c="0x00001234u")),
    (0xFFFFFFFF, 0, everybody("0xFFFFFFFF", c="0xFFFFFFFFu")),
    (2**32, 0, everybody("0x100000000", c="UINT64_C(0x100000000)")),
    (2**64 - 1, 0, everybody("0xFFFFFFFFFFFFFFFF", c="UINT64_C(0xFFFFFFFFFFFFFFFF)")),
]

# C writes the spec's exact decimal; Python and Rust the shortest text that reads back as the double;
# TypeScript that text as JavaScript prints numbers (`e+`).
DOUBLES = [
    (Fraction(1, 10), everybody("0.1")),
    (Fraction(1, 50), everybody("0.02")),
    (Fraction(-1080), everybody("-1080.0")),
    (Fraction(3, 2000), everybody("0.0015")),
    (Fraction(1, 10**7), everybody("1e-07", c="0.0000001")),
    (Fraction(10**22), everybody("1e22", c="10000000000000000000000.0", ts="1e+22")),
    (Fraction(2**63), everybody("9.223372036854776e18", c="9223372036854775808.0", ts="9.223372036854776e+18")),
    (Fraction(-(2**53) - 1), everybody("-9007199254740992.0", c="-9007199254740993.0", ts="-9007199254740992.0")),
]

STRINGS = [
    ("plain", everybody('"plain"')),
    ('say "hi" \\', everybody('"say \\"hi\\" \\\\"')),
    ("tab\tnewline\n", everybody('"tab\\tnewline\\n"')),
    ("bell\x07", everybody('"bell\\u0007"', c='"bell\\007"', rust='"bell\\u{7}"')),
    ("del\x7f", everybody('"del\x7f"', c='"del\\177"', rust='"del\\u{7f}"')),  # JSON leaves DEL as it is
    ("nul-ish\x017", everybody('"nul-ish\\u00017"', c='"nul-ish\\0017"', rust='"nul-ish\\u{1}7"')),  # octal: 3 digits, then the 7
    ("trigraph ??= ???", everybody('"trigraph ??= ???"', c='"trigraph ?\\?= ?\\?\\?"')),
    ("中文 °C m/s²", everybody('"中文 °C m/s²"')),
]


@pytest.mark.parametrize("lang", LANGUAGES)
def test_every_row_in_every_language(lang: str) -> None:
    lit = LANGUAGES[lang]
    assert [lit.integer(v) for v, _ in INTEGERS] == [row[lang] for _, row in INTEGERS]
    assert [lit.hex(v, digits) for v, digits, _ in HEXES] == [row[lang] for _, _, row in HEXES]
    assert [lit.double(v) for v, _ in DOUBLES] == [row[lang] for _, row in DOUBLES]
    assert [lit.string(s) for s, _ in STRINGS] == [row[lang] for _, row in STRINGS]


def test_number_is_an_integer_or_a_double() -> None:
    for lit in LANGUAGES.values():
        assert lit.number(Fraction(-1080), integral=True) == lit.integer(-1080)
        assert lit.number(Fraction(-1080), integral=False) == lit.double(-1080)
        with pytest.raises(ValueError, match="not an integer"):
            lit.number(Fraction(1, 2), integral=True)


# --- each language reads its texts back -----------------------------------------------------------


def expected_values() -> list[object]:
    """What every program prints, record by record: integers, hex values, doubles, strings."""
    return [*(v for v, _ in INTEGERS), *(v for v, _, _ in HEXES), *(float(v) for v, _ in DOUBLES), *(s for s, _ in STRINGS)]


def parse_records(out: bytes) -> list[object]:
    records = out.split(b"\0")[:-1]
    n_int, n_hex, n_dbl = len(INTEGERS), len(HEXES), len(DOUBLES)
    numbers = [int(r) for r in records[: n_int + n_hex]]
    doubles = [float(r) for r in records[n_int + n_hex : n_int + n_hex + n_dbl]]
    return [*numbers, *doubles, *(r.decode("utf-8") for r in records[n_int + n_hex + n_dbl :])]


def need(tool: str) -> str:
    exe = shutil.which(tool)
    assert exe is not None, f"{tool} missing (bash .ci/setup installs it)"
    return exe


def test_c_reads_every_row(tmp_path) -> None:
    lines = [f'printf("%lld", (long long){C.integer(v)}); putchar(0);' for v, _ in INTEGERS]
    lines += [f'printf("%llu", (unsigned long long){C.hex(v, d)}); putchar(0);' for v, d, _ in HEXES]
    lines += [f'printf("%.17g", {C.double(v)}); putchar(0);' for v, _ in DOUBLES]
    lines += [f"fputs({C.string(s)}, stdout); putchar(0);" for s, _ in STRINGS]
    src = tmp_path / "t.c"
    src.write_text("#include <stdint.h>\n#include <stdio.h>\nint main(void) {\n" + "\n".join(lines) + "\nreturn 0;\n}\n", encoding="utf-8")
    flags = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-trigraphs"]
    subprocess.run([need("gcc"), *flags, str(src), "-o", str(tmp_path / "t")], check=True)
    out = subprocess.run([str(tmp_path / "t")], capture_output=True, check=True).stdout
    assert parse_records(out) == expected_values()


def test_rust_reads_every_row(tmp_path) -> None:
    lines = [f'{{ let v: i128 = {RUST.integer(v)}; print!("{{}}\\0", v); }}' for v, _ in INTEGERS]
    lines += [f'{{ let v: u128 = {RUST.hex(v, d)}; print!("{{}}\\0", v); }}' for v, d, _ in HEXES]
    lines += [f'{{ let v: f64 = {RUST.double(v)}; print!("{{:?}}\\0", v); }}' for v, _ in DOUBLES]
    lines += [f'print!("{{}}\\0", {RUST.string(s)});' for s, _ in STRINGS]
    src = tmp_path / "t.rs"
    src.write_text("fn main() {\n" + "\n".join(lines) + "\n}\n", encoding="utf-8")
    subprocess.run([need("rustc"), "-D", "warnings", "-o", str(tmp_path / "t"), str(src)], check=True, cwd=tmp_path)
    out = subprocess.run([str(tmp_path / "t")], capture_output=True, check=True).stdout
    assert parse_records(out) == expected_values()


def test_python_reads_every_row() -> None:
    texts = [PYTHON.integer(v) for v, _ in INTEGERS] + [PYTHON.hex(v, d) for v, d, _ in HEXES]
    texts += [PYTHON.double(v) for v, _ in DOUBLES] + [PYTHON.string(s) for s, _ in STRINGS]
    assert [ast.literal_eval(t) for t in texts] == expected_values()


def test_typescript_reads_every_row() -> None:
    """JavaScript numbers are doubles: integers and hex values compare as the nearest double."""
    texts = [TYPESCRIPT.integer(v) for v, _ in INTEGERS] + [TYPESCRIPT.hex(v, d) for v, d, _ in HEXES] + [TYPESCRIPT.double(v) for v, _ in DOUBLES]
    program = "".join(f'process.stdout.write(String({t}) + "\\0");\n' for t in texts)
    program += "".join(f'process.stdout.write({TYPESCRIPT.string(s)} + "\\0");\n' for s, _ in STRINGS)
    out = subprocess.run([need("node"), "-e", program], capture_output=True, check=True).stdout
    records = out.split(b"\0")[:-1]
    numbers = [float(r) for r in records[: len(texts)]]
    assert numbers == [float(v) for v in expected_values()[: len(texts)]]
    assert [r.decode("utf-8") for r in records[len(texts) :]] == [s for s, _ in STRINGS]
