"""The one literal layer: how a number or a text is written in each target language. Every
target and template writes literals through these (templates call them as filters), so a
language's syntax rules live in one place and each has a test."""

from __future__ import annotations

import json
import re
from fractions import Fraction

from canspec.ir.encoding import decimal_text

# --- numbers, every language -----------------------------------------------------------------


def num(value: Fraction | int | None) -> str:
    """Exact decimal text: 0.02, -1080, 0.0015 (docs, DBC, comments)."""
    return "" if value is None else decimal_text(Fraction(value))


def float_lit(value: Fraction | int) -> str:
    """A floating-point literal of an exact decimal, valid as a C double, a Rust f64, a Python
    float and a TypeScript number: 0.1, -1080.0, 0.0015 (each parses to the nearest double)."""
    text = decimal_text(Fraction(value))
    return text if any(c in text for c in ".eE") else f"{text}.0"


def double_repr(value: float) -> str:
    """The shortest text that reads back as this double, as a float literal: 0.1, 1e-07, 3.0."""
    text = repr(float(value)).replace("e+", "e")
    return text if any(c in text for c in ".e") or text in ("inf", "-inf", "nan") else f"{text}.0"


def hex32(value: int) -> str:
    return f"0x{value:08X}"


def hex_byte(value: int) -> str:
    return f"0x{value:02X}"


def grouped_int(value: int) -> str:
    """Decimal below 2^16, else hex in groups of four digits (Rust and Python: readable masks)."""
    if abs(value) < 1 << 16:
        return str(value)
    digits = f"{abs(value):X}"
    groups = [digits[max(i - 4, 0) : i] for i in range(len(digits), 0, -4)][::-1]
    return ("-" if value < 0 else "") + "0x" + "_".join(groups)


# --- C ---------------------------------------------------------------------------------------


def c_uint(value: int, bits: int = 32) -> str:
    """An unsigned C constant: `5u`, or `UINT64_C(...)` beyond 32 bits."""
    if value < 0:
        raise ValueError(f"negative unsigned literal {value}")
    return f"UINT64_C({value})" if bits > 32 or value > 0xFFFFFFFF else f"{value}u"


def c_int(value: int, bits: int = 32) -> str:
    """A signed C constant of the given width: `-5` in parentheses, `INT64_C(...)` / `INT64_MIN`
    beyond 32 bits (the most negative value has no literal of its own)."""
    if bits > 32 or not -(2**31) < value < 2**31:
        return f"INT64_C({value})" if value > -(2**63) else "INT64_MIN"
    return f"{value}" if value >= 0 else f"({value})"


def c_hex(value: int, bits: int = 32) -> str:
    return f"UINT64_C(0x{value:X})" if bits > 32 or value > 0xFFFFFFFF else f"0x{value:X}u"


def _escaped(text: str, control: str) -> str:
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(control.format(ord(ch)))
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


_QUESTIONS = re.compile(r"\?(?=\?)")  # a `?` followed by another: a backslash between them


def c_string(text: str) -> str:
    """A C string literal, UTF-8 kept; other control characters as 3-digit octal escapes (which,
    unlike hex escapes, cannot swallow a following digit); `??` split so no trigraph forms."""
    return _QUESTIONS.sub("?\\\\", _escaped(text, "\\{:03o}"))


def c_comment(text: str) -> str:
    """Text inside a C block comment, on one line: `*/`, `/*` and `??` (a trigraph) broken up so
    the comment neither ends early nor warns; line breaks and other control characters as spaces."""
    flat = "".join(" " if ord(ch) < 0x20 or ord(ch) == 0x7F else ch for ch in text)
    return _QUESTIONS.sub("?\\\\", flat.replace("*/", "*\\/").replace("/*", "/\\*"))


# --- Rust, Python, TypeScript, TOML ------------------------------------------------------------


def rust_string(text: str) -> str:
    return _escaped(text, "\\u{{{:x}}}")


def py_string(text: str) -> str:
    """A Python (and JSON, TypeScript, TOML basic) string literal, UTF-8 kept."""
    return json.dumps(text, ensure_ascii=False)


def _one_line(text: str, control: str) -> str:
    text = " ".join(text.split())  # newlines (and every other whitespace run) as one space
    return re.sub(r"[\x00-\x08\x0e-\x1f\x7f]", lambda m: control.format(ord(m.group())), text)


def py_doc(text: str) -> str:
    """Text for one line of a Python docstring: backslashes doubled and a quote before a quote (or
    at the end) escaped, so the docstring reads back as the text and never ends early; other control
    characters as escapes; whitespace runs, newlines included, as one space."""
    return re.sub(r'"(?="|$)', '\\\\"', _one_line(text.replace("\\", "\\\\"), "\\x{:02x}"))


def py_comment(text: str) -> str:
    """Text for a Python `#` comment: one line; other control characters shown as `\\xNN`."""
    return _one_line(text, "\\x{:02x}")


ts_string = py_string
toml_string = py_string


def ts_value(value: int | str) -> str:
    """A TypeScript literal type / value of a JSON enum member."""
    return json.dumps(value, ensure_ascii=False)


def py_value(value: bool | float | str | None) -> str:
    """A Python literal of a JSON scalar: "N", 3, -1.5, True, None."""
    if isinstance(value, str):
        return py_string(value)
    if isinstance(value, float):
        return double_repr(value)
    return repr(value)


def rust_value(value: bool | float | str) -> str:
    """A Rust literal of a JSON scalar: "N", 3, -1.5, true (an f64 where the value is a float)."""
    if isinstance(value, str):
        return rust_string(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    return double_repr(value) if isinstance(value, float) else str(value)


# --- DBC ---------------------------------------------------------------------------------------


def dbc_string(text: str) -> str:
    """DBC strings cannot escape quotes: replace them."""
    return '"' + text.replace("\\", "/").replace('"', "'") + '"'


# --- spreadsheets (XLSX) -----------------------------------------------------------------------

SHEET_DIGITS = 15  # significant digits Excel keeps and shows


def sheet_number(value: Fraction | int) -> int | float | str:
    """A spreadsheet cell for an exact decimal: a number when Excel holds and shows it exactly (at
    most 15 significant digits: 0.02, -1080), else its exact decimal text (2^64 - 1, 1.844674407370955e19
    would be wrong by thousands)."""
    text = decimal_text(Fraction(value))
    if len(text.lstrip("-").replace(".", "").strip("0")) > SHEET_DIGITS:
        return text
    return float(text) if "." in text else int(text)


FILTERS = {
    "num": num,
    "float_lit": float_lit,
    "hex32": hex32,
    "hex_byte": hex_byte,
    "c_string": c_string,
    "c_comment": c_comment,
    "rust_string": rust_string,
    "py_string": py_string,
    "py_doc": py_doc,
    "py_comment": py_comment,
    "toml_string": toml_string,
    "dbc_string": dbc_string,
}
