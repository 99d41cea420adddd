"""The JSON-protocol model every JSON target reads: dispatch plans, rule texts, reply pairs,
and the shape of the generated Python package (stdlib only)."""

from __future__ import annotations

import ast
import dataclasses

import pytest
from canspec.ir import json_fields as jsonmodel
from canspec.reference import jsonvalue
from json_support import PY_BINDINGS


@pytest.fixture(scope="module")
def pm(spec):
    (proto,) = spec.json
    return jsonmodel.model(proto)


def test_whole_protocol_plan(pm):
    p = pm.any_plan
    assert p.command_values == (1, 2, 3, 4)
    for _cmd, group in p.commands:
        assert group[0].markers == ("res",) and group[-1].markers == ()
        assert group[0].message.endswith("_reply") and group[-1].message.endswith("_request")
    assert [(b.message, b.markers) for b in p.plain] == [("control", ("tr", "bk", "st", "vts")), ("status", ())]


def test_direction_plans_need_no_markers(pm):
    plans = {p.receiver: p for p in pm.receiver_plans}
    to_vehicle, to_autonomous = plans["vehicle"], plans["autonomous"]
    assert set(to_vehicle.messages) == {"status", "shutdown_request", "restart_request", "record_request", "photo_request"}
    assert set(to_autonomous.messages) == {"control", "shutdown_reply", "restart_reply", "record_reply", "photo_reply"}
    for p in (to_vehicle, to_autonomous):
        assert all(len(g) == 1 for _, g in p.commands) and len(p.plain) == 1


@pytest.mark.parametrize(("obj", "expected"), [
    ({"cmd": 1, "bn": 1}, "shutdown_request"),
    ({"cmd": 1.0, "bn": 1, "res": 0}, "shutdown_reply"),
    ({"cmd": True, "bn": 1}, None),
    ({"cmd": "1", "bn": 1}, None),
    ({"cmd": 5}, None),
    ({"tr": 1}, "control"),
    ({"pL": 1}, "status"),
    ({}, "status"),
    ([], None),
])
def test_select(pm, obj, expected):
    assert jsonvalue.select(pm.protocol, pm.any_plan, obj) == expected


def test_messages_no_key_tells_apart_are_tried_in_order(spec):
    """A message with the same keys as another (here one with another direction) is read as the
    first of them the object is valid as; the last is the group's default."""
    (proto,) = spec.json
    twin = dataclasses.replace(proto.message("photo_request"), name="photo_twin", sender="vehicle", receiver="autonomous")
    twin_proto = dataclasses.replace(proto, messages=(*proto.messages, twin))
    p = jsonmodel.model(twin_proto).any_plan
    group = dict(p.commands)[4]
    assert [(b.message, b.markers, b.tried) for b in group] == [("photo_reply", ("res",), False), ("photo_request", (), True), ("photo_twin", (), False)]
    assert jsonvalue.select(twin_proto, p, {"cmd": 4, "bn": 1}) == "photo_request"
    assert jsonvalue.select(twin_proto, p, {"cmd": 4, "bn": -1}) == "photo_twin"  # valid as neither: the default reports it
    assert "a message valid as photo_request is photo_request" in "; ".join(p.rules)


def test_rule_texts(pm):
    status = pm.message("status")
    assert status.rule("pL").value_rule == "must be within [0, 100] or -1 (unknown)"
    assert status.rule("satCnt").type_range_rule == "must be within [0, 255] (U8)"
    assert pm.message("control").rule("g").value_rule == 'must be one of "N", "D", "R", "P"'
    assert pm.message("photo_reply").rule("cmd").value_rule == "must be 4 (the cmd of photo_reply)"
    assert {e.name for e in pm.enums} == {"ControlGear", "StatusGear", "Mode", "Res"}


def test_reply_pairs(pm):
    assert [(p.request, p.reply, p.cmd, p.echoed, p.result, p.extra) for p in pm.pairs] == [
        ("shutdown_request", "shutdown_reply", 1, ("bn",), "res", ()),
        ("restart_request", "restart_reply", 2, ("bn",), "res", ()),
        ("record_request", "record_reply", 3, ("bn",), "res", ("ro",)),
        ("photo_request", "photo_reply", 4, ("bn",), "res", ()),
    ]
    assert pm.replies_by_cmd


def test_python_bindings_use_only_the_standard_library():
    allowed = {"__future__", "enum", "json", "math", "dataclasses", "typing"}
    for path in (PY_BINDINGS / "remote_driving").glob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                assert {a.name.split(".")[0] for a in node.names} <= allowed, path
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                assert node.module.split(".")[0] in allowed, (path, node.module)


def test_clashing_binding_identifiers_are_refused(spec):
    from canspec.targets.json_bindings import names

    (proto,) = spec.json
    ctrl = proto.message("control")
    fields = (*ctrl.fields[:-1], dataclasses.replace(ctrl.fields[-1], name="tr"))
    clashing = dataclasses.replace(spec, json=(dataclasses.replace(proto, messages=(dataclasses.replace(ctrl, fields=fields), *proto.messages[1:])),))
    assert [(p.rule, p.message) for p in names.problems(clashing)] == [
        ("json-binding-name", "two fields of 'control' would share the name 'tr' in the generated bindings")
    ]
    assert list(names.problems(spec)) == []
