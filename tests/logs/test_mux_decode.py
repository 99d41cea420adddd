"""`canspec decode` on a multiplexed message (tests/fixtures/valid/multiplexed.yaml): every output
holds a frame's multiplexers and the fields of the pages they select, and nothing of the other
pages. The oracle is cantools reading the generated DBC (it decodes exactly the selected pages); for
a frame whose multiplexer value selects no page, which cantools refuses, the reference codec."""

from __future__ import annotations

import json
import random
import subprocess
import sys

import cantools
import numpy as np
import pytest
from canspec.generation import generate
from canspec.logs import bulktext
from canspec.logs import frames as fr
from canspec.logs.fields import MessageFrames
from canspec.pipeline import compile_spec
from canspec.reference import codec
from oracle import decode
from repo_paths import CANSPEC_ENV, ROOT

MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"


def expected(msg, db, data: bytes, **options) -> dict[str, object]:  # type: ignore[no-untyped-def]
    """cantools' decoding of the frame (`options` as cantools takes them), or, where it refuses a multiplexer
    value that selects no page, the reference codec's physical values."""
    try:
        return db.get_message_by_name(msg.name).decode(data, **options)  # type: ignore[no-any-return]
    except cantools.database.DecodeError as exc:
        assert "multiplexer" in str(exc), exc
        raw = codec.unpack(msg, data)
        if options.get("scaling", True) is False:
            return raw
        named = options.get("decode_choices", True)
        return {n: label.name if named and (label := msg.signal(n).label_of(r)) else codec.physical_number(msg.signal(n), r) for n, r in raw.items()}


@pytest.fixture(scope="module")
def bus(tmp_path_factory):
    """The fixture's protocol, its generated DBC in cantools, and a candump log of random frames (every page drawn)."""
    out = tmp_path_factory.mktemp("mux_decode")
    spec = compile_spec(MUX).spec
    db = cantools.database.load_string(generate(spec, ["dbc"])["dbc"]["dbc/mux_bus.dbc"].decode("utf-8"), database_format="dbc")
    rng = random.Random(24)
    frames = [(m, rng.getrandbits(8 * m.dlc).to_bytes(m.dlc, "little")) for m in spec.can.messages for _ in range(400)]
    log = out / "bus.log"
    log.write_text("".join(f"({1.0 + i / 1000:.6f}) can0 {m.frame_id:03X}#{d.hex().upper()}\n" for i, (m, d) in enumerate(frames)), encoding="utf-8")
    return spec.can, db, frames, log


def test_every_page_is_drawn(bus):
    can, db, frames, _ = bus
    layouts = {tuple(expected(m, db, d)) for m, d in frames}
    assert len(layouts) >= 7, layouts  # mode 0, 1/4..6, 2 with channel 0, 1..3 and none, no page; host_command's two


def test_bulk_text_equals_the_per_frame_text_decoder(bus):
    can, _, frames, _ = bus
    for msg in can.messages:
        payloads = [d for m, d in frames if m is msg]
        words = np.array([int.from_bytes(d, "little") for d in payloads], dtype=np.uint64)
        texts = bulktext.message_texts(MessageFrames(msg, words, fr.data_matrix(payloads)), {})  # classic frames: no data matrix
        assert texts == [codec.text_decoder(msg)(int.from_bytes(d, "little")) for d in payloads], msg.name


def test_json_and_csv_hold_only_the_selected_pages(bus):
    can, db, frames, log = bus
    run = [sys.executable, "-m", "canspec", "decode", "--spec", str(MUX), str(log), "--format"]
    records = [json.loads(line) for line in subprocess.run([*run, "json"], capture_output=True, text=True, env=CANSPEC_ENV, check=True).stdout.splitlines()]
    assert len(records) == len(frames)
    for record, (msg, data) in zip(records, frames):
        theirs = expected(msg, db, data)
        assert set(record["signals"]) == set(theirs), (msg.name, data.hex())
        for name, value in theirs.items():
            mine = record["signals"][name]
            assert mine == str(value) if isinstance(mine, str) else mine == pytest.approx(value, abs=1e-9), (name, data.hex())
    rows = subprocess.run([*run, "csv"], capture_output=True, text=True, env=CANSPEC_ENV, check=True).stdout.splitlines()[1:]
    assert len(rows) == sum(len(expected(m, db, d)) for m, d in frames)


def test_tables_are_null_where_a_frame_holds_another_page(bus):
    can, db, frames, log = bus
    tables = decode(log, can.messages).tables
    for msg in can.messages:
        rows = tables[msg.name].to_pylist()
        sent = [d for m, d in frames if m is msg]
        assert len(rows) == len(sent)
        for row, data in zip(rows, sent):
            raw = expected(msg, db, data, decode_choices=False, scaling=False)
            phys = expected(msg, db, data, decode_choices=False)
            for sig in msg.data_signals:
                if sig.name in raw:
                    assert row[f"{sig.name}_raw"] == raw[sig.name] and row[sig.name] == pytest.approx(phys[sig.name], abs=1e-9), (sig.name, data.hex())
                else:
                    assert row[sig.name] is None and row[f"{sig.name}_raw"] is None and row.get(f"{sig.name}_label") is None, (sig.name, data.hex())
