"""What a spec keeps only for its DBC (tests/fixtures/valid/dbc_kept_facts.yaml), read back by
cantools from the generated DBC and compared with the fixture's YAML read on its own: the source's
attributes with their definitions and values, a further sender, a signal's own receivers, comments
with quotes, and `dbc_as_imported` ([min|max] the documented range as written; none of
canspec's own GenMsgSendType, ProtocolType and DBName)."""

from __future__ import annotations

from pathlib import Path

import cantools
import pytest
import yaml
from canspec.pipeline import compile_spec
from canspec.targets.dbc import render_dbc
from repo_paths import ROOT

FIXTURE = ROOT / "tests" / "fixtures" / "valid" / "dbc_kept_facts.yaml"


@pytest.fixture(scope="module")
def db(tmp_path_factory) -> cantools.database.Database:
    compiled = compile_spec(FIXTURE, targets=["dbc"])
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    path = Path(tmp_path_factory.mktemp("kept")) / "kept.dbc"
    path.write_bytes(next(iter(render_dbc(compiled.spec).values())))
    return cantools.database.load_file(path, strict=True)


@pytest.fixture(scope="module")
def source() -> dict:
    return yaml.safe_load(FIXTURE.read_text(encoding="utf-8"))


def _values(obj) -> dict:
    return {name: a.value for name, a in obj.dbc.attributes.items()}


def test_definitions_are_the_specs(db, source) -> None:
    defs = db.dbc.attribute_definitions
    kinds = {"network": None, "node": "BU_", "message": "BO_", "signal": "SG_"}
    for name, d in source["dbc_attributes"].items():
        got = defs[name]
        assert (got.kind, got.type_name) == (kinds[d["object"]], d["type"]), name
        assert (got.minimum, got.maximum) == ((d["min"], d["max"]) if "min" in d else (None, None)), name
        assert list(got.choices or []) == d.get("values", []), name
        assert got.default_value == d.get("default"), name
    assert "DBName" not in defs and "ProtocolType" not in defs


def test_values_of_every_object(db, source) -> None:
    assert _values(db)["Manufacturer"] == source["dbc_attributes"]["Manufacturer"]["value"]
    body = next(n for n in db.nodes if n.name == "BODY")
    assert _values(body) == {"NodeLayer": 2} and body.comment == 'Body "controller"'
    msg = db.get_message_by_name("door_status")
    want = source["messages"][0]
    assert msg.send_type == want["dbc_attributes"]["GenMsgSendType"]
    assert _values(msg)["GenMsgDelayTime"] == want["dbc_attributes"]["GenMsgDelayTime"]
    assert _values(msg.get_signal_by_name("door_fl"))["GenSigStartValue"] == 1.5
    assert _values(msg.get_signal_by_name("speed"))["GenSigComment"] == "raw 0xFFFF: invalid"


def test_senders_receivers_comments_and_ranges(db, source) -> None:
    msg, want = db.get_message_by_name("door_status"), source["messages"][0]
    assert msg.senders == [want["sender"], *want["dbc_senders"]]
    door, speed = msg.get_signal_by_name("door_fl"), msg.get_signal_by_name("speed")
    assert door.receivers == want["signals"][0]["receivers"] and sorted(speed.receivers) == sorted(want["receivers"])
    assert door.comment == 'front left, "driver"' and msg.comment == want["desc"]
    assert (door.minimum, door.maximum) == tuple(want["signals"][0]["range"])
    assert (speed.minimum, speed.maximum) == (0, 655.35)  # no range: what the bits carry ([0|0] in a source, the same values)
    assert db.get_message_by_name("tester_request").comment is None  # no layout note as imported
