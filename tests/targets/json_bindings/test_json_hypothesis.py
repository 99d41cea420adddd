"""Arbitrary JSON through the Python bindings (issue 9): nothing but the documented
ValidationError ever comes out, and the bindings accept exactly what the generated schemas
accept (checked with jsonschema), as the whole protocol and per receiver."""

from __future__ import annotations

from typing import Any

import jsonschema
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

KEYS = ["ts", "bn", "tr", "bk", "st", "g", "m", "vts", "pL", "spd", "located", "lng", "lat", "alt", "angle", "satCnt", "cmd", "res", "ro"]
EXAMPLES = [
    {"ts": 1653531739951, "bn": 59842, "tr": 0, "bk": 0, "st": 100, "g": "N", "m": 0, "vts": 0},
    {"ts": 0, "bn": 9120, "g": "N", "m": 0, "pL": 85, "spd": 45, "located": True,
     "lng": 116.261115, "lat": 39.948574, "alt": 396.9, "angle": 32.2, "satCnt": 8},
    {"cmd": 3, "res": 0, "bn": 9120, "ro": True},
    {"cmd": 1, "bn": 9120},
]

scalars = st.one_of(
    st.none(), st.booleans(), st.integers(min_value=-(2**70), max_value=2**70),
    st.integers(min_value=-300, max_value=300), st.floats(allow_nan=False, allow_infinity=False),
    st.sampled_from([0, 1, 2, 3, 4, 5, 6, -1, -2, -3, -4, 100, 100.0, 2**53 - 1, 2**53, 3.5e38, "N", "D", "R", "P", "-", "X", "", 1.5, 2.0]),
    st.text(max_size=3),
)
json_values = st.recursive(scalars, lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=3), inner, max_size=3), max_leaves=8)
# Objects built from the protocol's keys, and mutations of real messages, reach deep into the rules.
protocol_objects = st.dictionaries(st.sampled_from(KEYS), scalars, max_size=14)
mutated = st.builds(
    lambda base, drop, changes: {**{k: v for k, v in base.items() if k not in drop}, **changes},
    st.sampled_from(EXAMPLES), st.sets(st.sampled_from(KEYS), max_size=2), st.dictionaries(st.sampled_from(KEYS + ["x"]), scalars, max_size=2),
)
anything = st.one_of(json_values, protocol_objects, mutated)

SETTINGS = settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True)


@pytest.fixture(scope="module")
def validators(schemas):
    return {name: jsonschema.Draft202012Validator(s) for name, s in schemas.items()}


def _read(rd, obj: Any, receiver: str | None):
    try:
        return rd.parse(obj, receiver)
    except rd.ValidationError as e:
        assert isinstance(e.field, str) and e.code in {"object", "required", "unexpected", "type", "type_range", "enum", "range", "length", "cmd"}
        assert e.message in rd.MESSAGES or e.message == "message"
        return None


@SETTINGS
@given(obj=anything)
def test_bindings_raise_only_validation_errors_and_agree_with_schemas(rd, validators, obj):
    for receiver, schema in ((None, "protocol"), ("vehicle", "to_vehicle"), ("autonomous", "to_autonomous")):
        msg = _read(rd, obj, receiver)
        assert (msg is not None) == validators[schema].is_valid(obj), (receiver, obj)
        if msg is not None:
            assert validators[msg.NAME].is_valid(msg.to_json())
            assert rd.parse(msg.to_json(), receiver) == msg


@SETTINGS
@given(obj=anything)
def test_each_message_class_agrees_with_its_schema(rd, validators, obj):
    for name, cls in rd.MESSAGES.items():
        try:
            cls.from_json(obj)
            ok = True
        except rd.ValidationError as e:
            ok = False
            assert e.message == name
        assert ok == validators[name].is_valid(obj), (name, obj)
