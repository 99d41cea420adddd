"""Decoding works for any valid spec: random specs of the anyspec strategy (11/29-bit IDs, J1939
or not, fields of 1..64 bits, value tables, counters, checksums, event-driven and DLC-0
messages), random frames of every message, decoded in bulk (tables and text) and compared with
the reference codec frame by frame (raw values exactly, physical values, labels, checksum
flags, the text line), and the health report's counts with the independent monitor model of
tests/runtime/model.py."""

from __future__ import annotations

import random
import sys
from pathlib import Path

import numpy as np
from canspec.pipeline import compile_spec
from canspec.logs import bulktext
from canspec.reference import codec
from canspec.logs import frames as fr
from canspec.logs.bulk import Decoder
from canspec.logs.loghealth import HealthReport
from hypothesis import HealthCheck, given, settings

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from anyspec import strategy
from runtime.model import ModelMonitor


def random_batch(msgs, n, rng):
    picks = [msgs[rng.randrange(len(msgs))] for _ in range(n)]
    words = [rng.getrandbits(8 * m.dlc) for m in picks]
    for i, m in enumerate(picks):
        if m.checksum is not None and rng.random() < 0.7:  # mostly intact
            w = words[i] & ~(0xFF << 8 * m.checksum.byte)
            words[i] = w | codec.xor_checksum(m, w) << 8 * m.checksum.byte
    batch = fr.Batch(np.arange(n) * 0.01 + 100.0, np.zeros(n, np.int32), np.array([m.frame_id for m in picks], np.uint32),
                     np.array([m.is_extended for m in picks]), np.zeros(n, np.uint8), np.array([m.dlc for m in picks], np.uint8),
                     np.array(words, np.uint64), np.arange(1, n + 1), channels=("can0",))
    return picks, words, batch


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(strategy.specs())
def test_bulk_decoding_of_any_spec_equals_the_reference_codec(tmp_path_factory, spec):
    path = spec.write(tmp_path_factory.mktemp("spec"))
    compiled = compile_spec(path)
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    msgs = compiled.spec.can.messages
    rng = random.Random(len(spec.text()))
    picks, words, batch = random_batch(msgs, 400, rng)
    decoder = Decoder(msgs, raw=True)
    decoded = decoder.decode(batch)
    assert decoded.fits.all() and not len(decoded.unknown) and not len(decoded.wrong_length)
    for msg in msgs:
        mine = [w for m, w in zip(picks, words) if m is msg]
        if not mine:
            assert msg.name not in decoded.tables
            continue
        table = decoded.tables[msg.name].to_pydict()
        layout = decoder.layout(msg.name)
        for s in msg.data_signals:
            raws = [codec.raw_value(s, w) for w in mine]
            assert table[layout.names[f"r:{s.name}"]] == raws, (msg.name, s.name)
            assert table[s.name] == [float(codec.physical_number(s, r)) for r in raws], (msg.name, s.name)
            if s.labels:
                assert table[layout.names[f"l:{s.name}"]] == [(lb.name if (lb := s.label_of(r)) else None) for r in raws]
        if msg.checksum is not None:
            assert table[layout.names["checksum_ok"]] == [codec.checksum_ok(msg, w.to_bytes(msg.dlc, "little")) for w in mine]
        assert bulktext.message_texts(msg, np.array(mine, np.uint64), {}) == [codec.text_decoder(msg)(w) for w in mine]
    report = HealthReport(msgs)
    for name, rows in decoded.groups.items():
        report.feed_message(compiled.spec.can.message(name), batch.timestamp[rows], batch.word[rows])
    model = ModelMonitor(compiled.spec.can, counter_tolerance=1, valid_after=2)  # the README's defaults
    for i, (m, w) in enumerate(zip(picks, words)):
        model.frame(100_000 + 10 * i, m.frame_id, m.is_extended, w.to_bytes(m.dlc, "little"))
    for record in report.result({})["messages"]:
        msg = compiled.spec.can.message(record["message"])
        assert record["frames"] == len([m for m in picks if m is msg])
        want = model.msgs[msg.name].stats
        got = {k: record[k] for k in ("counter_repeats", "counter_jumps", "lost_frames", "checksum_errors")} | {"timeouts": record["gaps"]}
        assert got == {k: want[k] for k in got}, msg.name
