"""The transcription checked against the OCR text itself (spec/source/), independently of the
YAML: message list (§2), every table's start bits and lengths (§3), and every printed factor and
offset. Every difference must be a recorded erratum, listed here with its ID."""

from __future__ import annotations

import re
from fractions import Fraction

from repo_paths import GATEWAY_DOC, ROOT

DOC = GATEWAY_DOC

# (start, length) the spec has but the OCR'd table does not, and the reverse, per §3 section.
SPEC_ONLY = {
    "3.3": {(32, 8), (40, 16)},  # E13: reserved bits 32..55 normalised to the R-GATE/Tele split
    "3.5": {(38, 2), (48, 4), (52, 4), (56, 4)},  # E15 (cut row), E16 (version split)
    "3.8": {(48, 16)},  # E21: row 4 lost its name; OCR breaks its columns
    "3.11": {(32, 4), (36, 4), (40, 4)},  # E16
    "3.14": {(20, 2), (32, 2), (48, 4), (52, 4), (56, 4)},  # OCR splits rows 11 and 16 across columns; E16
    "3.23": {(48, 4), (52, 4), (56, 4)},  # E16
}
DOC_ONLY = {
    "3.3": {(32, 10), (42, 14)},  # E13
    "3.5": {(48, 12)},  # E16
    "3.11": {(10, 4), (32, 12)},  # a garbled duplicate of row 18 reads "10 10 4"; E16
    "3.14": {(48, 12)},
    "3.23": {(48, 12)},
}
# Printed factor/offset that the spec deliberately does not follow, by (section, start).
SCALING_EXCEPTIONS: dict[tuple[str, int], str] = {}


def document_sections() -> dict[str, str]:
    text = DOC.read_text(encoding="utf-8")
    parts = re.split(r"\n3\.(\d+) ", text)
    return {f"3.{parts[i]}": parts[i + 1] for i in range(1, len(parts), 2)}


ROW = re.compile(r"^(?:<mark>)?(\d+)(?:</mark>)?\t(?:<mark>)?(\d+)(?:</mark>)?\t(\d+)\t(.*)$", re.MULTILINE)


def test_message_list_of_section_2(can):
    text = DOC.read_text(encoding="utf-8")
    section2 = text[text.index("2 网络报文列表") : text.index("3 报文定义")]
    rows = re.findall(r"(0x[0-9A-F]{8})\t(\S+)\t(\S+)\t(\d+)ms", section2)
    assert len(rows) == 25
    by_id = {m.frame_id: m for m in can.messages}
    for frame_id, sender, receiver, cycle in rows:
        msg = by_id[int(frame_id, 16)]
        assert msg.cycle_ms == int(cycle), frame_id
        expected_sender = {"Tele": "RC", "R-GATE": "R_GATE"}.get(sender, sender)  # E02
        assert msg.sender == expected_sender, frame_id
        if receiver == "ALL":  # E03: ALL = every other node
            assert set(msg.receivers) == {n.name for n in can.nodes} - {msg.sender}
        else:
            assert msg.receivers == (receiver,)
    assert {m.frame_id for m in can.messages} == {int(r[0], 16) for r in rows}


def test_every_section_is_a_message(can):
    sections = {m.section for m in can.messages}
    assert sections == {f"3.{i}" for i in range(1, 25)} | {"2"}  # E04: 0x1808A0B0 has no section


def test_bit_layout_of_every_table(can):
    sections = document_sections()
    for msg in can.messages:
        if msg.section == "2":
            continue
        doc_fields = {(int(s), int(n)) for _, s, n, _ in ROW.findall(sections[msg.section]) if int(n)}  # skip the "6 0 0 05 B0 C0" PGN row
        spec_fields = {(s.start, s.length) for s in msg.signals}
        assert spec_fields - doc_fields == SPEC_ONLY.get(msg.section, set()), msg.name
        assert doc_fields - spec_fields == DOC_ONLY.get(msg.section, set()), msg.name


SCALE = re.compile(r"(?:比例尺|比例|精度)\s*[:：]?\s*(-?\s*[\d.]+)")
OFFSET = re.compile(r"偏移\s*[:：]?\s*(-\s*[\d.]+|[\d.]+)")


def document_rows(can):
    """(message, spec signal at the row's start bit or None, start bit, the row's text after the
    length column) for every §3 table row of the document."""
    sections = document_sections()
    for msg in can.messages:
        if msg.section == "2":
            continue
        by_start = {s.start: s for s in msg.signals}
        for _, start, _, rest in ROW.findall(sections[msg.section]):
            yield msg, by_start.get(int(start)), int(start), rest


def test_printed_factors_and_offsets(can):
    checked = 0
    for msg, sig, start, rest in document_rows(can):
        scale, offset = SCALE.search(rest), OFFSET.search(rest)
        if sig is None or (msg.section, start) in SCALING_EXCEPTIONS:
            continue
        if scale:
            assert sig.factor == Fraction(scale.group(1).replace(" ", "")), (msg.name, sig.name)
            checked += 1
        if offset:
            assert sig.offset == Fraction(offset.group(1).replace(" ", "")), (msg.name, sig.name)
            checked += 1
    assert checked >= 60


def test_documented_ranges_where_printed(can):
    """Ranges like '-1080~1080' in the 物理范围 column equal the spec's documented range."""
    rng = re.compile(r"^(-?[\d.]+)\s*(?:\[~\]|~|-)\s*(-?[\d,.]+)")
    compared = 0
    fixed = {("vehicle_state_3", "battery_max_temp"), ("autocar_speed_command", "gear_cmd")}  # E22, E11
    for msg, sig, _, rest in document_rows(can):
        cols = rest.split("\t")
        if sig is None or len(cols) < 2 or sig.doc_min is None or (msg.name, sig.name) in fixed:
            continue
        m = rng.match(cols[1].replace("<mark>", "").replace(" ", ""))
        if m:
            lo, hi = Fraction(m.group(1)), Fraction(m.group(2).replace(",", ""))
            assert (sig.doc_min, sig.doc_max) == (lo, hi), (msg.name, sig.name, cols[1])
            compared += 1
    assert compared >= 150


def test_every_erratum_is_recorded_and_used():
    errata_md = (ROOT / "spec" / "ERRATA.md").read_text(encoding="utf-8")
    recorded = set(re.findall(r"^\| ([EJH]\d\d) \|", errata_md, re.MULTILINE))
    used = set()
    for path in (ROOT / "spec").rglob("*.yaml"):
        used |= set(re.findall(r"\b([EJH]\d\d)\b", path.read_text(encoding="utf-8")))
    assert used <= recorded, f"referenced in YAML but not in ERRATA.md: {sorted(used - recorded)}"
    assert recorded <= used, f"recorded but not pointed to from the YAML: {sorted(recorded - used)}"
