"""The matrix as a file: the same bytes on every run (no clock, no time zone, no platform or zlib in
them), and the layout a reviewer works in — frozen header and key column, filters, widths, wrapped
text, a font with Chinese glyphs, shading by message, an A3 landscape print set-up."""

from __future__ import annotations

import io
import itertools
import os
import subprocess
import sys
import zipfile

from repo_paths import CANSPEC_ENV, GENERATED, ROOT
from xlsx_support import MATRIX, read

XLSX = GENERATED / "xlsx" / "kaiwo_gateway.xlsx"


def gen(out, tz: str) -> bytes:
    env = {**CANSPEC_ENV, "TZ": tz}
    r = subprocess.run([sys.executable, "-m", "canspec", "gen", "spec", "-o", str(out), "--target", "xlsx"], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=300, check=False)
    assert r.returncode == 0, r.stderr
    return (out / "xlsx" / "kaiwo_gateway.xlsx").read_bytes()


def test_gen_twice_gives_the_same_bytes(tmp_path):
    first = gen(tmp_path / "a", "UTC")
    os.utime(ROOT / "spec" / "canspec.yaml")  # a newer file time changes nothing either
    second = gen(tmp_path / "b", "Asia/Shanghai")
    assert first == second == XLSX.read_bytes()


def test_package_metadata_is_fixed():
    with zipfile.ZipFile(XLSX) as z:
        infos = z.infolist()
        assert infos[0].filename == "[Content_Types].xml"
        assert {i.date_time for i in infos} == {(1980, 1, 1, 0, 0, 0)}
        assert {i.compress_type for i in infos} == {zipfile.ZIP_STORED}
        core = z.read("docProps/core.xml").decode()
    # spec/history/changelog.yaml dates V2.0.5 2020-09-12: that, not the clock, is the creation date.
    assert '<dcterms:created xsi:type="dcterms:W3CDTF">2020-09-12T00:00:00Z</dcterms:created>' in core
    assert '<dcterms:modified xsi:type="dcterms:W3CDTF">2020-09-12T00:00:00Z</dcterms:modified>' in core
    book = read(XLSX.read_bytes())
    assert "sha256" in book.wb.properties.description and book.wb.properties.creator == "canspec"


def test_matrix_layout():
    book = read(XLSX.read_bytes())
    ws = book.wb[MATRIX]
    headers = book.headers(MATRIX)
    last = ws.cell(row=1, column=len(headers)).column_letter
    assert ws.freeze_panes == "B2"  # header row and message name stay in view
    assert ws.auto_filter.ref == f"A1:{last}{ws.max_row}"
    assert all(ws.column_dimensions[ws.cell(row=1, column=c).column_letter].width >= 7 for c in range(1, len(headers) + 1))
    head = ws["A1"]
    assert head.font.b and head.alignment.wrap_text and head.fill.fgColor.rgb.endswith("DCE6F1")
    assert ws.row_dimensions[1].height >= 30  # room for the Chinese and the English line
    desc = headers.index("信号描述\nDescription") + 1
    cells = [ws.cell(row=r, column=desc) for r in range(2, ws.max_row + 1)]
    assert all(c.alignment.wrap_text and c.alignment.vertical == "top" for c in cells)
    assert {c.font.name for c in ws["A"]} == {"Microsoft YaHei"}
    # Shading alternates by message: every row of a message shares its band, neighbours differ.
    bands = {}
    for r in range(2, ws.max_row + 1):
        bands.setdefault(ws.cell(row=r, column=1).value, set()).add(ws.cell(row=r, column=1).fill.fgColor.rgb)
    assert all(len(b) == 1 for b in bands.values())
    order = list(bands)
    assert all(bands[a] != bands[b] for a, b in itertools.pairwise(order))
    assert ws.page_setup.orientation == "landscape" and ws.page_setup.paperSize == 8  # A3
    assert ws.sheet_properties.pageSetUpPr.fitToPage and ws.page_setup.fitToHeight == 0  # one page wide (fitToWidth 1 is the default)
    assert ws.print_title_rows == "$1:$1"  # the header on every printed page


def test_every_sheet_is_frozen_and_filtered():
    book = read(XLSX.read_bytes())
    for ws in book.wb.worksheets:
        assert ws.freeze_panes is not None and ws.freeze_panes.endswith("2"), ws.title
        assert ws.auto_filter.ref and ws.auto_filter.ref.startswith("A1:"), ws.title


def test_opens_as_a_zip_of_xml_parts():
    with zipfile.ZipFile(io.BytesIO(XLSX.read_bytes())) as z:
        names = set(z.namelist())
    assert {"xl/workbook.xml", "xl/sharedStrings.xml", "xl/styles.xml", "docProps/core.xml"} <= names
    assert sum(n.startswith("xl/worksheets/sheet") for n in names) == 6
