"""The generated Python bindings: every vector case (own message, receiver's reader, whole
protocol), round trips, errors that name field, value and rule, and the request/reply helpers
(checked against the reply schemas with jsonschema)."""

from __future__ import annotations

import json
import sys

import jsonschema
import py_runner
import pytest
from fixture_batch import RUFF_ARGS
from json_support import PY_BINDINGS, require_tool, run, same


def test_every_vector_case(rd, cases):
    """The runner `make roundtrip-json` uses: own verdict, fault, both dispatches, round trip."""
    bad = [(c["id"], why) for c in cases if (why := py_runner.check(rd, c))]
    assert bad == [], bad[:20]


def test_round_trip_through_text(rd, cases):
    for c in cases:
        if c["valid"]:
            text = json.dumps(rd.parse(c["json"]).to_json())
            assert same(json.loads(text), c["json"]), c["id"]
            assert rd.parse(json.loads(text)) == rd.parse(c["json"])


def test_error_names_field_value_and_rule(rd):
    with pytest.raises(rd.ValidationError) as info:
        rd.parse({"ts": 1, "bn": 2, "tr": 0, "bk": 100.5, "st": 0, "g": "N", "m": 3, "vts": 0})
    e = info.value
    assert (e.message, e.field, e.value, e.code) == ("control", "bk", 100.5, "range")
    assert str(e) == "control.bk: 100.5 must be within [0, 100]"
    with pytest.raises(rd.ValidationError, match=r"^status\.g: 'X' must be one of \"N\", \"D\", \"R\", \"P\", \"-\"$"):
        rd.Status.from_json({"ts": 0, "bn": 0, "g": "X", "m": 0, "pL": 1, "spd": 1, "located": True, "lng": 0, "lat": 0, "alt": 0, "angle": 0, "satCnt": 0})
    with pytest.raises(rd.ValidationError, match=r"^message\.cmd: 9 must be one of 1, 2, 3, 4 \(a known command\)$"):
        rd.parse({"cmd": 9, "bn": 1})
    with pytest.raises(rd.ValidationError, match=r"^shutdown_reply\.bn: None is required$"):
        rd.parse({"cmd": 1, "res": 0})


def test_construction_validates(rd):
    with pytest.raises(rd.ValidationError, match="satCnt"):
        rd.Status(ts=0, bn=0, gear="N", mode=3, power_level=-1, spd=-1, located=False, lng=0.0, lat=0.0, alt=0.0, angle=0.0, sat_cnt=256)
    s = rd.Status(ts=0, bn=0, gear="-", mode=5, power_level=rd.Status.POWER_LEVEL_UNKNOWN, spd=rd.Status.SPD_UNKNOWN, located=False,
                  lng=0.0, lat=0.0, alt=0.0, angle=0.0, sat_cnt=0)
    assert s.gear is rd.StatusGear.UNKNOWN and s.mode is rd.Mode.REMOTE
    assert s.to_json()["g"] == "-" and s.to_json()["pL"] == -1
    with pytest.raises(rd.ValidationError, match=r"control\.g: '-' must be one of"):  # '-' only in status (J04)
        rd.Control(ts=0, bn=0, tr=0, bk=0, st=0, gear="-", mode=3, vts=0)


def test_reply_helpers(rd, schemas):
    for req_cls, rep_cls in rd.REPLY_OF.items():
        request = req_cls.from_json({"cmd": req_cls.CMD, "bn": 41, **({"ro": True} if "ro" in req_cls.KEYS else {})})
        extra = {"ro": False} if "ro" in rep_cls.KEYS else {}
        for res in rd.Res:
            reply = request.reply(res, **extra)
            assert type(reply) is rep_cls and reply.bn == 41 and reply.res is res
            jsonschema.validate(reply.to_json(), schemas[rep_cls.NAME])
            assert request.is_answered_by(reply) and rd.is_reply_to(reply, request)
        other = rep_cls.from_json({**reply.to_json(), "bn": 42})
        assert not request.is_answered_by(other) and not rd.is_reply_to(other, request)
    # A reply of another command with the same bn answers nothing.
    shutdown = rd.ShutdownRequest(bn=7)
    assert not rd.is_reply_to(rd.RestartReply(res=0, bn=7), shutdown)


def test_pending_requests_match_by_cmd_and_bn(rd):
    pending = rd.PendingRequests()
    a, b, c = rd.ShutdownRequest(bn=1), rd.RecordRequest(bn=1, ro=True), rd.RecordRequest(bn=2, ro=False)
    for r in (a, b, c):
        pending.add(r)
    assert len(pending) == 3
    assert pending.match(rd.parse({"cmd": 3, "res": 0, "bn": 2, "ro": False})) is c
    assert pending.match(rd.parse({"cmd": 3, "res": 0, "bn": 2, "ro": False})) is None  # answered already
    assert pending.match(rd.parse({"cmd": 1, "res": -1, "bn": 1})) is a
    assert pending.match(rd.parse({"cmd": 2, "res": 0, "bn": 1})) is None  # no restart request with bn 1
    assert len(pending) == 1


def test_direction_tells_reply_from_request(rd):
    # Without direction, {cmd, bn} is a request; the vehicle-side sender of replies must include res.
    assert rd.parse({"cmd": 1, "bn": 5}).NAME == "shutdown_request"
    with pytest.raises(rd.ValidationError) as info:
        rd.parse({"cmd": 1, "bn": 5}, "autonomous")
    assert (info.value.message, info.value.field, info.value.code) == ("shutdown_reply", "res", "required")
    with pytest.raises(ValueError, match="unknown receiver"):
        rd.parse({}, "server")


def test_package_is_ruff_and_mypy_strict_clean():
    run([require_tool("ruff"), "check", *RUFF_ARGS, "."], "ruff check", cwd=PY_BINDINGS)
    run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir=/dev/null", "-p", "remote_driving"], "mypy --strict", cwd=PY_BINDINGS)
