"""Lay sheets out as an XLSX workbook with XlsxWriter, byte-for-byte reproducibly.

Every sheet: a bold bilingual header row that stays in view (frozen, with the sheet's key columns),
a filter on every column, fixed column widths, wrapped multi-line cells in rows tall enough for
them (set here: LibreOffice does not fit row heights when it opens a file), thin borders,
alternate shading by message, a font with Chinese glyphs, and a landscape A3 page set-up that
prints one page wide with the header repeated.

Reproducible: the creation date is fixed (docProps created = modified), and the package is
re-zipped with fixed entry dates and attributes and stored uncompressed, so the bytes depend on
neither the clock, the platform nor the zlib build (deflate output differs between zlib and
zlib-ng)."""

from __future__ import annotations

import io
import math
import unicodedata
import zipfile
from datetime import datetime, timezone
from typing import Any

from canspec.targets.xlsx.model import Sheet

FONT = "Microsoft YaHei"  # 微软雅黑: Chinese and Latin glyphs; LibreOffice substitutes a CJK font where it is missing
FONT_SIZE = 10
HEADER_FILL = "#DCE6F1"
BAND_FILL = "#F3F6FA"
BORDER_COLOUR = "#B7B7B7"
HEADER_PAD = 4  # points around the header's lines
LINE_HEIGHT = 15  # points per text line at FONT_SIZE, with the taller CJK fallback fonts
A3 = 8
ZIP_EPOCH = (1980, 1, 1, 0, 0, 0)
HEADER = -1  # the header row's "band"


def _formats(wb: Any) -> dict[tuple[bool, bool, int], Any]:
    """(wrap, center, band) → cell format; band 0/1 shade data rows, HEADER is the header row."""
    base = {"valign": "top", "border": 1, "border_color": BORDER_COLOUR}
    out = {}
    for wrap in (False, True):
        for center in (False, True):
            align = {"align": "center"} if center else {}
            for band in (0, 1):
                out[(wrap, center, band)] = wb.add_format({**base, **align, "text_wrap": wrap, **({"bg_color": BAND_FILL} if band else {})})
            out[(wrap, center, HEADER)] = wb.add_format({**base, **align, "bold": True, "text_wrap": True, "valign": "vcenter", "bg_color": HEADER_FILL})
    return out


def _text_width(line: str) -> int:
    """Width in Excel character units: CJK and other wide characters take two."""
    return sum(2 if unicodedata.east_asian_width(ch) in "WF" else 1 for ch in line)


def text_lines(text: str, width: float) -> int:
    """Lines a wrapped text takes in a column `width` characters wide."""
    room = max(width * 0.9 - 1, 1)  # generous: a row too tall wastes space, one too short hides text
    return sum(max(1, math.ceil(_text_width(line) / room)) for line in text.split("\n"))


def row_lines(s: Sheet, row: tuple[object, ...]) -> int:
    """Text lines the row's tallest wrapped cell needs."""
    return max([1] + [text_lines(v, c.width) for c, v in zip(s.columns, row) if c.wrap and isinstance(v, str)])


def _write_sheet(wb: Any, s: Sheet, formats: dict[tuple[bool, bool, int], Any]) -> None:
    ws = wb.add_worksheet(s.name)
    for c, col in enumerate(s.columns):
        ws.set_column(c, c, col.width)
        ws.write_string(0, c, col.header, formats[(True, col.center, HEADER)])
    ws.set_row(0, max(text_lines(c.header, c.width) for c in s.columns) * LINE_HEIGHT + HEADER_PAD)
    for r, row in enumerate(s.rows, start=1):
        band = s.bands[r - 1] if s.bands else 0
        lines = row_lines(s, row)
        if lines > 1:
            ws.set_row(r, lines * LINE_HEIGHT)
        for c, value in enumerate(row):
            fmt = formats[(s.columns[c].wrap, s.columns[c].center, band)]
            if value is None or value == "":
                ws.write_blank(r, c, None, fmt)
            elif isinstance(value, str):  # never write(): it would turn "=…" into a formula and URLs into links
                ws.write_string(r, c, value, fmt)
            else:
                ws.write_number(r, c, value, fmt)
    ws.freeze_panes(1, s.freeze_cols)
    ws.autofilter(0, 0, max(len(s.rows), 1), len(s.columns) - 1)
    ws.set_landscape()
    ws.set_paper(A3)
    ws.fit_to_pages(1, 0)
    ws.repeat_rows(0)


def canonical_zip(data: bytes) -> bytes:
    """The same package with fixed entry metadata, entries in XlsxWriter's order ([Content_Types].xml first)."""
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(data)) as src, zipfile.ZipFile(out, "w", zipfile.ZIP_STORED) as dst:
        for info in src.infolist():
            entry = zipfile.ZipInfo(info.filename, ZIP_EPOCH)
            entry.create_system = 0
            entry.external_attr = 0
            dst.writestr(entry, src.read(info))
    return out.getvalue()


def workbook(sheets: list[Sheet], properties: dict[str, str], created: datetime) -> bytes:
    try:
        import xlsxwriter
    except ImportError:
        raise RuntimeError("the xlsx target needs XlsxWriter: pip install 'XlsxWriter==3.2.9' (a canspec dependency)") from None
    buf = io.BytesIO()
    wb = xlsxwriter.Workbook(buf, {"in_memory": True, "default_format_properties": {"font_name": FONT, "font_size": FONT_SIZE}})
    wb.set_properties({**properties, "created": created.replace(tzinfo=timezone.utc)})
    formats = _formats(wb)
    for s in sheets:
        _write_sheet(wb, s, formats)
    wb.close()
    return canonical_zip(buf.getvalue())
