"""A source's bytes as text. UTF-8 first; a named --encoding when the user gives one; otherwise a
file that is not UTF-8 is read as cp1252 (what Vector's tools write in Western Europe) or, when its
text is plainly Chinese, as GB18030 — and either guess is a warning at the first line it applies to,
naming the --encoding that says otherwise.

The GB18030 guess is deliberately narrow, because Latin text decodes as GBK too ("für" is `f` and
the character of bytes FC 72): every run of non-ASCII bytes must decode by itself (no ASCII byte
taken as a trail byte) into Chinese characters, CJK punctuation or the symbols GB2312 carries,
with at least one ideograph, and must not read as plausible cp1252 text: Western text has its
accented letters and technical symbols alone or in pairs ("Größe", "créé"), a Chinese comment runs
for several characters. Anything else stays cp1252, with the hint."""

from __future__ import annotations

import codecs
import re
import unicodedata

CHINESE_HINT = "if the text is Chinese, pass --encoding gbk (or gb18030)"
_RUN = re.compile(rb"[\x80-\xff]+")
WESTERN_RUN = 3  # bytes: the longest run of accented letters or symbols taken for cp1252 text
# What a cp1252 comment holds beside accented Latin letters.
_WESTERN_SYMBOLS = set("\u00a0°±µ²³·×÷€§©®™–—‘’“”…«»¿¡")


class TextError(Exception):
    """Bytes that are no text: the line (or None) and why; load.py adds the file's name."""

    def __init__(self, line: int | None, text: str) -> None:
        super().__init__(text)
        self.line = line


def decode(data: bytes, encoding: str | None) -> tuple[str, tuple[int, str] | None]:
    """The text, and (1-based line, warning) when its encoding was a guess."""
    if (nul := data.find(b"\0")) >= 0 and not data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        raise TextError(None, f"not a text file (binary data at byte offset {nul})")
    if encoding is not None:
        return _named(data, encoding), None
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return _named(data, "utf-16"), None
    try:
        return data.decode("utf-8-sig"), None
    except UnicodeDecodeError:
        pass
    runs = [m.group(0) for m in _RUN.finditer(data)]
    line = data[:_RUN.search(data).start()].count(b"\n") + 1  # type: ignore[union-attr]  # not UTF-8: a non-ASCII byte exists
    if _chinese(runs) and not all(len(run) <= WESTERN_RUN and _western(run) for run in runs):
        return data.decode("gb18030"), (line, "not UTF-8; its non-ASCII text reads as Chinese: read as GB18030 "
                                              "(pass --encoding NAME if it is another encoding)")
    try:
        text = data.decode("cp1252")
    except UnicodeDecodeError as exc:
        raise TextError(data[:exc.start].count(b"\n") + 1, f"neither UTF-8 nor cp1252 (byte 0x{data[exc.start]:02X}) "
                        f"(hint: pass --encoding NAME; {CHINESE_HINT})") from None
    return text, (line, f"not UTF-8: read as cp1252 (Western European); {CHINESE_HINT}")


def _named(data: bytes, encoding: str) -> str:
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        raise TextError(data[:exc.start].count(b"\n") + 1, f"not {encoding} text (byte 0x{data[exc.start]:02X} at byte offset {exc.start})") from None


def _chinese(runs: list[bytes]) -> bool:
    ideographs = 0
    for run in runs:
        try:
            text = run.decode("gb18030")
        except UnicodeDecodeError:
            return False
        for ch in text:
            if unicodedata.name(ch, "").startswith("CJK UNIFIED IDEOGRAPH"):
                ideographs += 1
            elif not (0x3000 <= ord(ch) <= 0x303F or 0xFF01 <= ord(ch) <= 0xFFEF or _gb2312_symbol(ch)):
                return False
    return ideographs > 0


def _western(run: bytes) -> bool:
    try:
        text = run.decode("cp1252")
    except UnicodeDecodeError:
        return False
    return all(unicodedata.name(ch, "").startswith("LATIN") or ch in _WESTERN_SYMBOLS for ch in text)


def _gb2312_symbol(ch: str) -> bool:
    """A character of GB2312's symbol rows (lead bytes A1..A9: °, ±, ·, ×, ℃, ‰, №, Greek, circled
    numbers, fullwidth forms): what a Chinese DBC's units and comments hold beside ideographs."""
    encoded = ch.encode("gb18030")
    return len(encoded) == 2 and 0xA1 <= encoded[0] <= 0xA9
