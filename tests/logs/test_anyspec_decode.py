"""Decoding works for any valid spec: random specs of the anyspec strategy (11/29-bit IDs, J1939
or not, fields of 1..64 bits, value tables, counters, checksums, event-driven and DLC-0
messages, and whatever else it draws: Motorola fields, CAN FD lengths, IEEE floats), random
frames of every message (FD frames through the batch's data matrix), decoded in bulk (tables and text) and compared with
the reference codec frame by frame (raw values exactly, physical values, labels, checksum
flags, the text line), and the health report's counts with the independent monitor model of
tests/runtime/model.py."""

from __future__ import annotations

import random
import sys
from pathlib import Path

from canspec.logs import bulktext
from canspec.logs import frames as fr
from canspec.logs.bulk import Decoder
from canspec.logs.candump import Frame
from canspec.logs.fields import MessageFrames
from canspec.logs.loghealth import HealthReport
from canspec.pipeline import compile_spec
from canspec.reference import codec
from canspec.targets import target_problems
from hypothesis import HealthCheck, given, settings

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from anyspec import strategy
from runtime.model import ModelMonitor


def random_batch(msgs, n, rng):
    """n random frames of the messages (checksums mostly intact): the messages, the frames' bytes, the batch."""
    picks = [msgs[rng.randrange(len(msgs))] for _ in range(n)]
    payloads = []
    for m in picks:
        w = rng.getrandbits(8 * m.dlc)
        if m.checksum is not None and rng.random() < 0.7:
            w = (w & ~(0xFF << 8 * m.checksum.byte)) | codec.xor_checksum(m, w) << 8 * m.checksum.byte
        payloads.append(w.to_bytes(m.dlc, "little"))
    frames = [Frame(100.0 + 0.01 * i, "can0", m.frame_id, m.is_extended, p, flags=fr.FD * m.is_fd) for i, (m, p) in enumerate(zip(picks, payloads))]
    return picks, payloads, fr.from_frames(frames, range(1, n + 1))


def same(a, b):
    """Equal floats, NaN equal to NaN (a float field's NaN patterns decode to NaN)."""
    return len(a) == len(b) and all(x == y or (x != x and y != y) for x, y in zip(a, b))  # noqa: PLR0124


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(strategy.specs())
def test_bulk_decoding_of_any_spec_equals_the_reference_codec(tmp_path_factory, spec):
    path = spec.write(tmp_path_factory.mktemp("spec"))
    compiled = compile_spec(path, targets=())
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    refused = [p.format() for p in target_problems(compiled.spec, ["python"]) if p.severity == "error"]
    assert not refused, refused  # decode is built on the Python bindings: a drawn (valid) spec must pass their check
    check_decoding(compiled.spec.can, random.Random(len(spec.text())))


def test_bulk_decoding_of_motorola_fd_and_floats_equals_the_reference_codec():
    """The fixture with Motorola fields crossing bytes, 12- and 64-byte FD frames and float32/64 in
    both orders, whatever the random specs happen to draw."""
    compiled = compile_spec(Path(__file__).resolve().parents[1] / "fixtures" / "valid" / "motorola_fd_float.yaml")
    assert compiled.spec is not None
    can = compiled.spec.can
    assert can.has_fd and can.has_big_endian and can.has_float
    check_decoding(can, random.Random(24))


SHORT_MOTOROLA = """\
schema_version: 1
kind: can_protocol
protocol: {name: short_frames, version: 1.0.0}
bus: {bitrate: 500000, id_format: standard, addressing: none, byte_order: big_endian}
nodes: [{name: A}, {name: B}]
messages:
  - {name: three, id: 0x10, sender: A, receivers: [B], cycle_ms: 10, dlc: 3, signals: [
      {name: a, start: 7, len: 10}, {name: b, start: 13, len: 10, factor: 0.5}, {name: c, start: 19, len: 4, signed: true}]}
  - {name: five, id: 0x11, sender: A, receivers: [B], cycle_ms: 10, dlc: 5, signals: [
      {name: x, start: 7, len: 1}, {name: f, start: 15, len: 32, float: true}, {name: y, start: 0, len: 7, byte_order: little_endian}]}
  - {name: one, id: 0x12, sender: A, receivers: [B], cycle_ms: 10, dlc: 1, signals: [{name: n, start: 5, len: 3, signed: true}]}
"""


def test_bulk_decoding_of_motorola_fields_in_short_frames(tmp_path):
    """Motorola fields of frames shorter than 8 bytes (the big-endian word of a 1-, 3- and 5-byte frame)."""
    (tmp_path / "short.yaml").write_text(SHORT_MOTOROLA)
    compiled = compile_spec(tmp_path / "short.yaml")
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    check_decoding(compiled.spec.can, random.Random(5))


def check_decoding(can, rng):
    msgs = can.messages
    picks, payloads, batch = random_batch(msgs, 400, rng)
    decoder = Decoder(msgs, raw=True)
    decoded = decoder.decode(batch)
    assert decoded.fits.all() and not len(decoded.unknown) and not len(decoded.wrong_length)
    for msg in msgs:
        mine = [p for m, p in zip(picks, payloads) if m is msg]
        if not mine:
            assert msg.name not in decoded.tables
            continue
        table = decoded.tables[msg.name].to_pydict()
        layout = decoder.layout(msg.name)
        for s in msg.data_signals:  # a page's field is null in the rows whose multiplexers select another page
            raws = [codec.unpack(msg, p).get(s.name) for p in mine]
            assert table[layout.names[f"r:{s.name}"]] == raws, (msg.name, s.name)
            assert same(table[s.name], [None if r is None else float(codec.physical_number(s, r)) for r in raws]), (msg.name, s.name)
            if s.labels:
                assert table[layout.names[f"l:{s.name}"]] == [(lb.name if r is not None and (lb := s.label_of(r)) else None) for r in raws]
        if msg.checksum is not None:
            assert table[layout.names["checksum_ok"]] == [codec.checksum_ok(msg, p) for p in mine]
        texts = bulktext.message_texts(MessageFrames.of(msg, batch, decoded.groups[msg.name]), {})
        assert texts == [codec.text_decoder(msg)(codec.frame_word(p)) for p in mine]
    report = HealthReport(msgs)
    for name, rows in decoded.groups.items():
        msg = can.message(name)
        report.feed_message(msg, batch.timestamp[rows], MessageFrames.of(msg, batch, rows).payloads())
    model = ModelMonitor(can, counter_tolerance=1, valid_after=2)  # the README's defaults
    for i, (m, p) in enumerate(zip(picks, payloads)):
        model.frame(100_000 + 10 * i, m.frame_id, m.is_extended, p)
    for record in report.result({})["messages"]:
        msg = can.message(record["message"])
        assert record["frames"] == len([m for m in picks if m is msg])
        want = model.msgs[msg.name].stats
        got = {k: record[k] for k in ("counter_repeats", "counter_jumps", "lost_frames", "checksum_errors")} | {"timeouts": record["gaps"]}
        assert got == {k: want[k] for k in got}, msg.name
