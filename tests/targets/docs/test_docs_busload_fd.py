"""The bus-load page of a CAN FD protocol (tests/fixtures/valid/motorola_fd_float.yaml): its figures
worked out by hand from ISO 11898-1:2015's field lengths (tests/ir/test_busload_fd.py shows the
working), and the FD formula stated only where a frame is FD."""

from __future__ import annotations

from canspec.pipeline import compile_spec
from canspec.targets import docs
from docs_support import ROOT

FIXTURE = ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml"


def _busload(path):  # type: ignore[no-untyped-def]
    result = compile_spec(path)
    assert result.spec is not None, [p.format() for p in result.problems]
    return docs.render_docs(result.spec)["docs/busload.md"].decode("utf-8")


def test_busload_page_of_an_fd_bus_states_both_phases():
    page = _busload(FIXTURE)
    assert "500 kbit/s bus (CAN FD data phase: 2000000 bit/s)" in page
    # 0x1A0 classic 8 bytes, 11-bit: 135 bits; 0x2B0 64 bytes with BRS: 33 + 679 / 4; 0x3C0 12 bytes without BRS: 33 + 154
    assert "| 8 | 10 ms | 1 | 135 | 100.0 | 13500.0 | 2.70 % |" in page
    assert "| 64 FD BRS | 50 ms | 1 | 33 + 679 (BRS) = 202.75 | 20.0 | 4055.0 | 0.81 % |" in page
    assert "| 12 FD | 100 ms | 1 | 33 + 154 = 187 | 10.0 | 1870.0 | 0.37 % |" in page
    # 13500 + 4055 + 1870 = 19425 bit/s of 500000: 3.885 % rounds half up to 3.89 %
    assert "19425.0 bit/s = **3.89 %** of 500000 bit/s" in page
    assert "### CAN FD" in page and "17-bit CRC (*n* ≤ 16) or the 21-bit CRC (*n* > 16)" in page and ": 27 or 32 bits." in page


def test_busload_page_of_a_classic_bus_has_no_fd_formula():
    page = _busload(ROOT / "spec")
    assert "CAN FD" not in page and "data phase" not in page


def test_an_event_driven_fd_frame_is_listed_with_its_length(tmp_path):
    text = FIXTURE.read_text(encoding="utf-8")
    assert text.count("    cycle_ms: 50\n") == 1
    path = tmp_path / "fd_event.yaml"
    path.write_text(text.replace("    cycle_ms: 50\n", ""), encoding="utf-8")
    page = _busload(path)
    # radar_objects, 64 bytes with BRS: 33 + 679 / 4 = 202.75 nominal bit times; the figures lose its 4055 bit/s
    assert "| radar_objects | ADAS | 64 FD BRS | 202.75 |" in page and "15370.0 bit/s" in page
