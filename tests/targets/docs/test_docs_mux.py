"""Multiplexing in the handbook and the matrix (tests/fixtures/valid/multiplexed.yaml): one bit
diagram per page layout, each drawing exactly the fields a frame of that page holds, and a column
saying when each field is present — both checked against the page structure the fixture's own
comment states (mode 0: temperature; mode 1 or 4…6: pressure and level; mode 2: the multiplexer
channel, whose pages are gain (0) and voltage (1…3); status and the counter in every frame)."""

from __future__ import annotations

import re
from pathlib import Path

import openpyxl
import pytest
from canspec_cli import run_canspec
from repo_paths import ROOT

MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"
EVERY_FRAME = {"mode", "status", "counter"}
PAGES = {  # caption → fields drawn
    "mode = 0": EVERY_FRAME | {"temperature"},
    "mode = 1, 4…6": EVERY_FRAME | {"pressure", "level"},
    "mode = 2, channel = 0": EVERY_FRAME | {"channel", "gain"},
    "mode = 2, channel = 1…3": EVERY_FRAME | {"channel", "voltage"},
}
PRESENT = {
    "mode": "multiplexer; every frame", "status": "every frame", "counter": "every frame", "temperature": "mode = 0",
    "pressure": "mode = 1, 4…6", "level": "mode = 1, 4…6", "channel": "multiplexer; mode = 2", "gain": "mode = 2 and channel = 0",
    "voltage": "mode = 2 and channel = 1…3",
}


@pytest.fixture(scope="module")
def out(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("mux")
    proc = run_canspec("gen", "--target", "docs", "--target", "xlsx", "-o", root, MUX)
    assert proc.returncode == 0, proc.stderr
    return root


def test_one_diagram_per_page_with_that_pages_fields(out: Path) -> None:
    page = (out / "docs" / "messages" / "sensor_report.md").read_text(encoding="utf-8")
    shown = re.findall(r"!\[sensor_report bit layout, ([^\]]+)\]\((sensor_report\.page-\d\.svg)\)", page)
    assert [caption for caption, _ in shown] == list(PAGES)
    for caption, file in shown:
        svg = (out / "docs" / "messages" / file).read_text(encoding="utf-8")
        drawn = set(re.findall(r"<title>(\w+): start", svg))
        assert drawn == PAGES[caption], (caption, drawn)


def test_the_signal_table_says_when_each_field_is_present(out: Path) -> None:
    page = (out / "docs" / "messages" / "sensor_report.md").read_text(encoding="utf-8")
    rows = {m.group(1): m.group(2).replace("`", "") for m in re.finditer(r"^\| `(\w+)` \|.*\| ([^|]+) \|$", page, re.MULTILINE)}
    assert rows == PRESENT


def test_the_matrix_has_a_multiplexing_column(out: Path) -> None:
    ws = openpyxl.load_workbook(next((out / "xlsx").glob("*.xlsx")))["通信矩阵 Matrix"]
    header = [str(c.value) for c in ws[1]]
    name, mux = header.index("信号名称\nSignal name"), next(i for i, h in enumerate(header) if h.endswith("Multiplexing"))
    got = {r[name]: r[mux] for r in ws.iter_rows(min_row=2, values_only=True) if r[0] == "sensor_report"}
    want = {k: (v.replace("multiplexer; every frame", "多路复用器 Multiplexer").replace("multiplexer", "多路复用器 Multiplexer")
                if "multiplexer" in v else None if v == "every frame" else v) for k, v in PRESENT.items()}
    assert got == want
