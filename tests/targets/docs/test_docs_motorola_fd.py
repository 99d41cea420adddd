"""The handbook of a Motorola / CAN FD / float bus (tests/fixtures/valid/motorola_fd_float.yaml).

The bit diagrams are read back from their SVG geometry and compared with two oracles that do not
come from canspec's bit arithmetic: cantools reading the generated DBC (one frame bit set at a
time: which signal's value changes, and which of its value bits it is) and cells written out by
hand from the DBC convention for a few known fields. The tables are compared with the fixture's
YAML itself (byte order, float type) and with ISO 11898-1's DLC codes."""

from __future__ import annotations

import re
import struct
import xml.etree.ElementTree as ET
from functools import cache
from pathlib import Path

import pytest
import yaml
from canspec.pipeline import compile_spec
from canspec.targets import docs, registry
from canspec.targets.docs import svg
from dbc_names import load_with_spec_names
from docs_support import ROOT

FIXTURE = ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml"
SVG = "{http://www.w3.org/2000/svg}"
BITS_LABEL = re.compile(r"^(?:(\d+) bits?|bits (\d+)–(\d+) of (\d+))$")


@cache
def _spec():  # type: ignore[no-untyped-def]
    result = compile_spec(FIXTURE)
    assert result.spec is not None, [p.format() for p in result.problems]
    return result.spec


@cache
def _pages() -> dict[str, str]:
    return {rel.removeprefix("docs/"): data.decode("utf-8") for rel, data in docs.render_docs(_spec()).items()}


def _yaml_messages() -> dict[str, dict]:
    data = yaml.safe_load(FIXTURE.read_text(encoding="utf-8"))
    return {m["name"]: m for m in data["messages"]}


def _diagrams(name: str) -> list[str]:
    """The message's SVG files in frame order, as its page links them."""
    page = _pages()[f"messages/{name}.md"]
    return [_pages()[f"messages/{f}"] for f in re.findall(r"!\[[^\]]*\]\(([^)]+\.svg)\)", page)]


def _drawn(name: str) -> dict[tuple[int, int], tuple[str, int]]:
    """(byte, bit) → (signal, value bit) as the diagrams draw it: the rows' byte labels give each
    row's byte, a span's rectangle its bits, its label the value bits (rising with the bits)."""
    out: dict[tuple[int, int], tuple[str, int]] = {}
    for text in _diagrams(name):
        root = ET.fromstring(text[text.index("<svg"):])
        rows = {int(t.get("y")) // svg.CELL_H * svg.CELL_H: int(t.text) for t in root.iter(f"{SVG}text")
                if t.get("font-weight") == "bold" and t.get("x") == str(svg.LEFT // 2)}
        for g in root.iter(f"{SVG}g"):
            rect = g.find(f"{SVG}rect")
            x, y, w = int(rect.get("x")) - 2, int(rect.get("y")) - 2, int(rect.get("width")) + 4
            byte = rows[(y + svg.CELL_H // 2 + 5) // svg.CELL_H * svg.CELL_H]
            hi = 7 - (x - svg.LEFT) // svg.CELL_W
            width = w // svg.CELL_W
            m = BITS_LABEL.match([t.text for t in g.iter(f"{SVG}text")][1])
            assert m, g.get("data-signal")
            value_lo = 0 if m.group(1) else int(m.group(2))
            assert m.group(1) or int(m.group(3)) - value_lo + 1 == width
            for k in range(width):  # the span's lowest bit holds value bit value_lo
                cell = (byte, hi - width + 1 + k)
                assert cell not in out, f"{cell} drawn twice"
                out[cell] = (g.get("data-signal"), value_lo + k)
    return out


@pytest.fixture(scope="module")
def db(tmp_path_factory):  # type: ignore[no-untyped-def]
    (rel, data), = registry()["dbc"].render(_spec()).items()
    path = tmp_path_factory.mktemp("dbc") / Path(rel).name
    path.write_bytes(data)
    return load_with_spec_names(path)


def _bit_pattern(sig, value) -> int:  # type: ignore[no-untyped-def]
    """The raw bits cantools decoded: a float's IEEE pattern, an integer's two's complement."""
    if sig.is_float:
        fmt = ">f" if sig.length == 32 else ">d"
        return int.from_bytes(struct.pack(fmt, value), "big")
    return int(value) & ((1 << sig.length) - 1)


def _cantools_cells(db, name: str, dlc: int) -> dict[tuple[int, int], tuple[str, int]]:  # type: ignore[no-untyped-def]
    """(byte, bit) → (signal, value bit) by cantools: decode frames with one bit set."""
    msg = db.get_message_by_name(name)
    out = {}
    for byte in range(dlc):
        for bit in range(8):
            data = bytearray(dlc)
            data[byte] = 1 << bit
            decoded = msg.decode(bytes(data), decode_choices=False, scaling=False)
            for sig in msg.signals:
                pattern = _bit_pattern(sig, decoded[sig.name])
                if pattern:
                    assert pattern & (pattern - 1) == 0, (sig.name, byte, bit)
                    out[(byte, bit)] = (sig.name, pattern.bit_length() - 1)
    return out


@pytest.mark.parametrize("name", ["wheel_speeds", "radar_objects", "body_status"])
def test_diagrams_put_every_bit_where_cantools_finds_it(db, name):
    msg = _spec().can.message(name)
    assert _drawn(name) == _cantools_cells(db, name, msg.dlc)


def _cells(*runs: tuple[int, int, int]) -> set[tuple[int, int]]:
    return {(byte, bit) for byte, hi, lo in runs for bit in range(lo, hi + 1)}


# Known fields, written out from the DBC convention (start = the MSB of a Motorola field, which runs
# down to bit 0 and on from bit 7 of the next byte; start = the LSB of an Intel field, running up).
KNOWN = {
    ("wheel_speeds", "speed_fr"): (_cells((2, 7, 0), (3, 7, 3)), (2, 7), (3, 3)),  # start 23, 13 bits: MSB byte 2 bit 7, LSB byte 3 bit 3
    ("wheel_speeds", "yaw_rate"): (_cells((3, 2, 0), (4, 7, 0)), (3, 2), (4, 0)),
    ("wheel_speeds", "torque"): (_cells((5, 7, 2), (6, 3, 0)), (6, 3), (5, 2)),  # Intel, start 42, 10 bits
    ("radar_objects", "distance"): (_cells((1, 0, 0), (2, 7, 0), (3, 7, 0), (4, 7, 0), (5, 7, 1)), (1, 0), (5, 1)),  # float32 at start 8
    ("radar_objects", "wide_id"): (_cells(*((b, 7, 0) for b in range(32, 37))), (32, 7), (36, 0)),  # past byte 32
    ("radar_objects", "timestamp"): (_cells(*((b, 7, 0) for b in range(16, 24))), (23, 7), (16, 0)),  # float64 Intel
    ("radar_objects", "tail"): (_cells((62, 7, 0), (63, 3, 0)), (63, 3), (62, 0)),
    ("body_status", "mileage"): (_cells(*((b, 7, 0) for b in range(8))), (0, 7), (7, 0)),  # float64 Motorola
}


@pytest.mark.parametrize("key", sorted(KNOWN), ids=lambda k: f"{k[0]}.{k[1]}")
def test_known_fields_are_drawn_on_their_bits(key):
    name, signal = key
    cells, msb, lsb = KNOWN[key]
    drawn = _drawn(name)
    assert {c for c, (s, _) in drawn.items() if s == signal} == cells
    length = _spec().can.message(name).signal(signal).length
    assert drawn[msb] == (signal, length - 1) and drawn[lsb] == (signal, 0)


def test_a_64_byte_fd_frame_is_drawn_in_parts_of_16_rows():
    parts = _diagrams("radar_objects")
    assert len(parts) == 4 and len(_diagrams("body_status")) == 1 and len(_diagrams("wheel_speeds")) == 1
    seen = []
    for text in parts:
        root = ET.fromstring(text[text.index("<svg"):])
        rows = [int(t.text) for t in root.iter(f"{SVG}text") if t.get("font-weight") == "bold" and t.get("x") == str(svg.LEFT // 2)]
        assert len(rows) == 16 and int(root.get("height")) == svg.TOP + 16 * svg.CELL_H + 8
        seen += rows
    assert seen == list(range(64))
    assert "511" in parts[-1] and ">511</text>" in parts[-1]  # the last cell's bit number, 8 × 63 + 7


def _signal_rows(page: str) -> dict[str, dict[str, str]]:
    lines = [ln for ln in page.splitlines() if ln.startswith("| ")]
    head = next(ln for ln in lines if ln.startswith("| Signal |"))
    cols = [c.strip() for c in head.strip("|").split("|")]
    rows = {}
    for ln in lines[lines.index(head) + 1:]:
        cells = [c.strip() for c in ln.strip("|").split("|")]
        if not cells[0].startswith("`"):
            break
        rows[cells[0].strip("`")] = dict(zip(cols, cells))
    return rows


@pytest.mark.parametrize("name", ["wheel_speeds", "radar_objects", "body_status"])
def test_signal_tables_state_byte_order_and_float_type_as_the_yaml_does(name):
    default = yaml.safe_load(FIXTURE.read_text(encoding="utf-8"))["bus"]["byte_order"]
    rows = _signal_rows(_pages()[f"messages/{name}.md"])
    for sig in _yaml_messages()[name]["signals"]:
        row = rows[sig["name"]]
        assert row["Byte order"] == {"big_endian": "Motorola", "little_endian": "Intel"}[sig.get("byte_order", default)], sig["name"]
        want = f"float{sig['len']}" if sig.get("float") else "signed" if sig.get("signed") else "unsigned"
        assert row["Type"] == want, sig["name"]
        if sig.get("float") and "range" not in sig:
            assert row["Encodable range"].startswith(f"any float{sig['len']}, NaN, ±Inf"), sig["name"]
        assert "⚠" not in row["Encodable range"] or not sig.get("float"), sig["name"]


def test_message_headers_state_fd_brs_and_length():
    # DLC codes of ISO 11898-1:2015: 12 bytes → 9, 64 bytes → 15.
    pages = _pages()
    radar, body, wheels = (pages[f"messages/{n}.md"] for n in ("radar_objects", "body_status", "wheel_speeds"))
    assert "| Frame format | CAN FD with bit-rate switch (BRS): the data phase at 2000 kbit/s |" in radar
    assert "| DLC | 64 bytes (DLC code 15) |" in radar
    assert "| Frame format | CAN FD, no bit-rate switch: the data phase at the nominal bit rate |" in body
    assert "| DLC | 12 bytes (DLC code 9) |" in body
    assert "| Frame format | classic CAN |" in wheels and "| DLC | 8 bytes |" in wheels


def test_overview_states_data_bitrate_byte_order_and_fd_lengths():
    index = _pages()["index.md"]
    assert "| Data bit rate (CAN FD) | 2000000 bit/s (2000 kbit/s)" in index
    assert "| Byte order | Motorola (big_endian), unless a signal says otherwise |" in index
    assert "64 FD BRS" in index and "| 12 FD |" in index
    load = _pages()["busload.md"]
    assert "| 64 FD BRS |" in load and "| 12 FD |" in load and "| 8 |" in load
    section = index[index.index("## Byte order {#byte-order}"):index.index("## Messages")]
    # The worked example: a 12-bit Motorola field at start 3 holds byte 0 bits 3..0 (value bits 11..8)
    # then byte 1 bits 7..0; the same field in Intel byte 0 bits 7..3 (value bits 4..0), byte 1 bits 6..0.
    assert "| 0 | · | · | · | · | 11 | 10 | 9 | 8 |\n| 1 | 7 | 6 | 5 | 4 | 3 | 2 | 1 | 0 |" in section
    assert "| 0 | 4 | 3 | 2 | 1 | 0 | · | · | · |\n| 1 | · | 11 | 10 | 9 | 8 | 7 | 6 | 5 |" in section


def test_intel_only_bus_keeps_its_tables():
    """A bus without Motorola fields, floats or FD frames shows none of their columns or rows."""
    result = compile_spec(ROOT / "tests" / "fixtures" / "valid" / "minimal_can.yaml")
    pages = {rel.removeprefix("docs/"): data.decode("utf-8") for rel, data in docs.render_docs(result.spec).items()}
    assert any(rel.startswith("messages/") for rel in pages)
    for rel, text in pages.items():
        if rel.startswith("messages/") and rel.endswith(".md"):
            assert not any(word in text for word in ("Byte order", "Type |", "Frame format", "DLC code", "Motorola")), rel
    index = pages["index.md"]
    assert "Intel (little_endian)" in index and "Motorola" not in index and "{#byte-order}" not in index and "Data bit rate" not in index


def _readme_example() -> dict[str, dict[tuple[int, int], int]]:
    """spec/README.md's worked example (the two grids side by side): order → (byte, bit) → value bit."""
    text = (ROOT / "spec" / "README.md").read_text(encoding="utf-8")
    out: dict[str, dict[tuple[int, int], int]] = {"motorola": {}, "intel": {}}
    for line in text.splitlines():
        m = re.match(r"^ byte (\d)\s+(.+?)\s+byte (\d)\s+(.+?)\s*$", line)
        if m:
            for order, byte, cells in (("motorola", m.group(1), m.group(2)), ("intel", m.group(3), m.group(4))):
                for bit, value in zip(range(7, -1, -1), cells.split()):
                    if value != "·":
                        out[order][(int(byte), bit)] = int(value)
    return out


def test_the_readme_example_is_what_cantools_reads_from_a_dbc():
    import cantools

    dbc = ('VERSION ""\n\n\nNS_ :\n\nBS_:\n\nBU_: A\n\n\nBO_ 16 m: 8 A\n SG_ motorola : 3|12@0+ (1,0) [0|0] "" A\n\n'
           'BO_ 17 i: 8 A\n SG_ intel : 3|12@1+ (1,0) [0|0] "" A\n\n')
    db = cantools.database.load_string(dbc, "dbc")
    example = _readme_example()
    for order, frame in (("motorola", "m"), ("intel", "i")):
        want = {}
        for byte in range(8):
            for bit in range(8):
                data = bytearray(8)
                data[byte] = 1 << bit
                value = db.get_message_by_name(frame).decode(bytes(data))[order]
                if value:
                    want[(byte, bit)] = value.bit_length() - 1
        assert example[order] == want, order


def test_tooltips_name_the_start_bit_order_and_float_type():
    titles = [t.text for text in _diagrams("radar_objects") for t in ET.fromstring(text[text.index("<svg"):]).iter(f"{SVG}title")]
    assert "distance: start 8 (MSB, Motorola), length 32, float32" in titles
    assert "timestamp: start 128, length 64, float64" in titles and "wide_id: start 263 (MSB, Motorola), length 40" in titles
