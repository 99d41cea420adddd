"""The overlap rule under multiplexing: fields that can be present in one frame (the same page, a
page and the fields of every frame, a multiplexer and its own pages) may not share a bit; fields
of different pages may, at any depth of extended multiplexing."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec.pipeline import compile_spec

HEAD = """schema_version: 1
kind: can_protocol
protocol: {name: fixture, version: 1.0.0}
bus: {bitrate: 500000, id_format: standard, addressing: none, byte_order: little_endian}
nodes: [{name: ECU}, {name: HOST}]
messages:
  - name: report
    id: 0x310
    sender: ECU
    receivers: [HOST]
    signals:
"""


def rules(tmp_path: Path, signals: str) -> list[str]:
    path = tmp_path / "spec.yaml"
    path.write_text(HEAD + signals, encoding="utf-8")
    return sorted(p.rule for p in compile_spec(path, targets=["dbc"]).problems)


@pytest.mark.parametrize(("signals", "expected"), [
    pytest.param("""      - {name: mode, start: 0, len: 4}
      - {name: a, start: 8, len: 16, mux: {by: mode, values: [0]}}
      - {name: b, start: 16, len: 16, mux: {by: mode, values: [[1, 3]]}}
""", [], id="different-pages"),
    pytest.param("""      - {name: mode, start: 0, len: 4}
      - {name: a, start: 8, len: 16, mux: {by: mode, values: [0, 2]}}
      - {name: b, start: 16, len: 16, mux: {by: mode, values: [[2, 3]]}}
""", ["signal-overlap"], id="pages-share-a-value"),
    pytest.param("""      - {name: mode, start: 0, len: 4}
      - {name: a, start: 8, len: 16, mux: {by: mode, values: [0]}}
      - {name: always, start: 20, len: 8}
""", ["signal-overlap"], id="page-and-every-frame"),
    pytest.param("""      - {name: mode, start: 0, len: 4}
      - {name: a, start: 2, len: 16, mux: {by: mode, values: [0]}}
""", ["signal-overlap"], id="field-over-its-multiplexer"),
    pytest.param("""      - {name: mode, start: 0, len: 4}
      - {name: sub, start: 4, len: 4, mux: {by: mode, values: [1]}}
      - {name: a, start: 8, len: 16, mux: {by: sub, values: [0]}}
      - {name: b, start: 8, len: 16, mux: {by: sub, values: [1]}}
      - {name: c, start: 4, len: 20, mux: {by: mode, values: [2]}}
""", [], id="extended-different-pages"),
    pytest.param("""      - {name: mode, start: 0, len: 4}
      - {name: sub, start: 4, len: 4, mux: {by: mode, values: [1]}}
      - {name: a, start: 8, len: 16, mux: {by: sub, values: [0]}}
      - {name: c, start: 20, len: 8, mux: {by: mode, values: [1]}}
""", ["signal-overlap"], id="extended-same-outer-page"),
])
def test_overlap_only_where_present_together(tmp_path: Path, signals: str, expected: list[str]) -> None:
    assert rules(tmp_path, signals) == expected


def test_reserved_bits_are_in_every_frame(tmp_path: Path) -> None:
    found = rules(tmp_path, """      - {name: mode, start: 0, len: 4}
      - {role: reserved, start: 8, len: 8, mux: {by: mode, values: [0]}}
""")
    assert found == ["mux-role"]
