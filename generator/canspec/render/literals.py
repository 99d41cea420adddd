"""The one literal layer: how a number or a text is written in each target language. Every
target and template writes literals through these (templates call them as filters), so a
language's syntax rules live in one place and each has a test."""

from __future__ import annotations

import json
import re
from abc import ABC, abstractmethod
from fractions import Fraction
from functools import lru_cache

from canspec.ir.encoding import decimal_text

# --- text of numbers, shared by the languages -----------------------------------------------


def num(value: Fraction | int | None) -> str:
    """Exact decimal text: 0.02, -1080, 0.0015 (docs, DBC, comments)."""
    return "" if value is None else decimal_text(Fraction(value))


def hex_byte(value: int) -> str:
    """A byte in documents (DBC comments, docs, spreadsheets): 0x0A."""
    return hex_text(value, 2)


def hex_text(value: int, digits: int = 0) -> str:
    """Hex as every language here and every document writes it: 0x3FF, -0x10, 0x0A (digits: at least)."""
    return f"-0x{-value:0{digits}X}" if value < 0 else f"0x{value:0{digits}X}"


@lru_cache(maxsize=1 << 16)  # the same factors, offsets and bounds recur in every message
def _exact_decimal(value: Fraction | float) -> str:
    """A floating-point literal of an exact decimal: 0.1, -1080.0, 0.0015 (each parses to the nearest double)."""
    text = decimal_text(Fraction(value))
    return text if any(c in text for c in ".eE") else f"{text}.0"


def _shortest(value: Fraction | float) -> str:
    """The shortest text that reads back as this double, as a float literal: 0.1, 1e-07, 3.0."""
    text = repr(float(value)).replace("e+", "e")
    return text if any(c in text for c in ".e") or text in ("inf", "-inf", "nan") else f"{text}.0"


def _grouped(value: int) -> str:
    """Decimal below 2^16, else hex in groups of four digits (readable masks; Rust and Python read it)."""
    if abs(value) < 1 << 16:
        return str(value)
    digits = f"{abs(value):X}"
    groups = [digits[max(i - 4, 0) : i] for i in range(len(digits), 0, -4)][::-1]
    return ("-" if value < 0 else "") + "0x" + "_".join(groups)


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


def _one_line(text: str, control: str) -> str:
    text = " ".join(text.split())  # newlines (and every other whitespace run) as one space
    return re.sub(r"[\x00-\x08\x0e-\x1f\x7f]", lambda m: control.format(ord(m.group())), text)


def _json_text(text: str) -> str:
    """A JSON string, UTF-8 kept: also a Python, TypeScript and TOML basic string literal."""
    return json.dumps(text, ensure_ascii=False)


toml_string = _json_text


# --- the interface every language answers (Kaitai's CommonLiterals) ---------------------------


class Literals(ABC):
    """How one language writes an integer, a double, a string and a hex constant. Every target
    writes its literals through its language's instance (C, PYTHON, RUST, TYPESCRIPT), so a
    syntax rule lives in one place and tests/render/test_literals_table.py checks each language
    on the same values."""

    @abstractmethod
    def integer(self, value: int) -> str: ...

    @abstractmethod
    def double(self, value: Fraction | float) -> str: ...

    @abstractmethod
    def string(self, text: str) -> str: ...

    @abstractmethod
    def hex(self, value: int, digits: int = 0) -> str: ...

    def number(self, value: Fraction | int, integral: bool) -> str:
        """An integer literal where the quantity is integral (then the value must be an integer), else a double."""
        if not integral:
            return self.double(value)
        if Fraction(value).denominator != 1:
            raise ValueError(f"{value} is not an integer")
        return self.integer(int(value))


class CLiterals(Literals):
    """C99: integer constants typed by width (`5u`, `(-5)`, `INT64_C(...)`), doubles as the exact
    decimal of the spec's value, strings in the execution character set's escapes."""

    def integer(self, value: int, bits: int = 32) -> str:
        """A signed constant: negative ones in parentheses, `INT64_C(...)` / `INT64_MIN` beyond 32 bits
        (the most negative value has no literal of its own)."""
        if bits > 32 or not -(2**31) < value < 2**31:
            return f"INT64_C({value})" if value > -(2**63) else "INT64_MIN"
        return f"{value}" if value >= 0 else f"({value})"

    def unsigned(self, value: int, bits: int = 32) -> str:
        """An unsigned constant: `5u`, or `UINT64_C(...)` beyond 32 bits."""
        if value < 0:
            raise ValueError(f"negative unsigned literal {value}")
        return f"UINT64_C({value})" if bits > 32 or value > 0xFFFFFFFF else f"{value}u"

    def double(self, value: Fraction | float) -> str:
        return _exact_decimal(value)

    def string(self, text: str) -> str:
        """UTF-8 kept; other control characters as 3-digit octal escapes (which, unlike hex escapes,
        cannot swallow a following digit); `??` split so no trigraph forms."""
        return _QUESTIONS.sub("?\\\\", _escaped(text, "\\{:03o}"))

    def hex(self, value: int, digits: int = 0, bits: int = 32) -> str:
        """An unsigned hex constant: `0x3FFu`, `UINT64_C(0x...)` beyond 32 bits."""
        if value < 0:
            raise ValueError(f"negative unsigned literal {value}")
        text = hex_text(value, digits)
        return f"UINT64_C({text})" if bits > 32 or value > 0xFFFFFFFF else f"{text}u"

    def comment(self, text: str) -> str:
        """Text inside a block comment, on one line: `*/`, `/*` and `??` (a trigraph) broken up so
        the comment neither ends early nor warns; line breaks and other control characters as spaces."""
        flat = "".join(" " if ord(ch) < 0x20 or ord(ch) == 0x7F else ch for ch in text)
        return _QUESTIONS.sub("?\\\\", flat.replace("*/", "*\\/").replace("/*", "/\\*"))


class PythonLiterals(Literals):
    """Python 3: plain decimal integers, the shortest double that reads back, JSON-style strings."""

    def integer(self, value: int) -> str:
        return str(value)

    def double(self, value: Fraction | float) -> str:
        return _shortest(value)

    def string(self, text: str) -> str:
        return _json_text(text)

    def hex(self, value: int, digits: int = 0) -> str:
        return hex_text(value, digits)

    def value(self, value: bool | float | str | None) -> str:
        """A JSON scalar: "N", 3, -1.5, True, None."""
        if isinstance(value, str):
            return self.string(value)
        return self.double(value) if isinstance(value, float) else repr(value)

    def doc(self, text: str) -> str:
        """Text for one line of a docstring: backslashes doubled and a quote before a quote (or at the
        end) escaped, so the docstring reads back as the text and never ends early; other control
        characters as escapes; whitespace runs, newlines included, as one space."""
        return re.sub(r'"(?="|$)', '\\\\"', _one_line(text.replace("\\", "\\\\"), "\\x{:02x}"))

    def comment(self, text: str) -> str:
        """Text for a `#` comment: one line; other control characters shown as `\\xNN`."""
        return _one_line(text, "\\x{:02x}")


class RustLiterals(Literals):
    """Rust: integers in decimal below 2^16, else grouped hex (untyped: the context types them),
    the shortest f64 that reads back, strings with `\\u{..}` escapes."""

    def integer(self, value: int) -> str:
        return _grouped(value)

    def double(self, value: Fraction | float) -> str:
        return _shortest(value)

    def string(self, text: str) -> str:
        return _escaped(text, "\\u{{{:x}}}")

    def hex(self, value: int, digits: int = 0) -> str:
        return hex_text(value, digits)

    def value(self, value: bool | float | str) -> str:
        """A JSON scalar: "N", 3, -1.5, true (an f64 where the value is a float; an integer in decimal, as the spec writes it)."""
        if isinstance(value, str):
            return self.string(value)
        if isinstance(value, bool):
            return "true" if value else "false"
        return self.double(value) if isinstance(value, float) else str(value)


class TypeScriptLiterals(Literals):
    """TypeScript: numbers as Python and JSON write them (`1e+22`; integers beyond 2^53 become the
    nearest double, as JSON.parse reads them), JSON strings."""

    def integer(self, value: int) -> str:
        return str(value)

    def double(self, value: Fraction | float) -> str:
        return repr(float(value))

    def string(self, text: str) -> str:
        return _json_text(text)

    def hex(self, value: int, digits: int = 0) -> str:
        return hex_text(value, digits)

    def value(self, value: bool | float | str) -> str:
        """A literal type / value of a JSON scalar."""
        if isinstance(value, str):
            return self.string(value)
        if isinstance(value, bool):
            return "true" if value else "false"
        return self.double(value) if isinstance(value, float) else self.integer(value)


C = CLiterals()
PYTHON = PythonLiterals()
RUST = RustLiterals()
TYPESCRIPT = TypeScriptLiterals()


# --- DBC ---------------------------------------------------------------------------------------


def dbc_string(text: str) -> str:
    """A DBC string: a quote escaped as \\" (cantools and canmatrix read it back as a quote); a
    backslash, which no reader unescapes, written as "/"."""
    return '"' + text.replace("\\", "/").replace('"', '\\"') + '"'


# --- Markdown ----------------------------------------------------------------------------------


def md_cell(text: str) -> str:
    """Text in one Markdown table cell: a `|` escaped, line breaks as spaces."""
    return text.replace("|", "\\|").replace("\n", " ")


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
