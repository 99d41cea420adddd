"""What the JSON targets cannot express is refused by `canspec check` (their `Target.check`) with
a rule ID and the element's location, never a failed generation: one spec per way of breaking
each rule (the rule fixtures under tests/fixtures/invalid/ show one each), and the specs just
inside each rule generate every JSON target."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec.generation import generate
from canspec.pipeline import compile_spec

HEAD = """schema_version: 1
kind: json_protocol
protocol: {{name: {name}, version: 1.0.0}}
parties: [{{name: a}}, {{name: b}}]
types:
  U8: {{json: integer, min: 0, max: 255}}
  S8: {{json: integer, min: -128, max: 127}}
  F: {{json: number}}
  B: {{json: boolean}}
  T: {{json: string, max_length: 3}}
{types}messages:
"""


def spec_text(messages: str, types: str = "", name: str = "p") -> str:
    return HEAD.format(name=name, types=types) + messages


def problems(tmp_path: Path, text: str) -> list[tuple[str, int]]:
    path = tmp_path / "spec.yaml"
    path.write_text(text, encoding="utf-8")
    compiled = compile_spec(path)
    return [(p.rule, p.loc.line if p.loc else 0) for p in compiled.errors]


def msg(name: str, fields: str, extra: str = "", frm: str = "a", to: str = "b") -> str:
    return f"  - {{name: {name}, from: {frm}, to: {to}, fields: {fields}{extra}}}\n"


REFUSED = {
    "json-integer-range": [
        ("an integer type without bounds", msg("m", "[{name: x, type: I}]"), "  I: {json: integer}\n"),
        ("an integer type below -(2^53 - 1)", msg("m", "[{name: x, type: I}]"), "  I: {json: integer, min: -9007199254740992, max: 0}\n"),
    ],
    "json-field-shape": [
        ("an enum on a boolean", msg("m", "[{name: x, type: B, enum: {1: one}}]"), ""),
        ("a range on a string", msg("m", "[{name: x, type: T, range: [0, 1]}]"), ""),
        ("an enum on a number", msg("m", "[{name: x, type: F, enum: {1: one}}]"), ""),
        ("a sentinel on a string", msg("m", "[{name: x, type: T, sentinel: {1: one}}]"), ""),
        ("decimals on a boolean", msg("m", "[{name: x, type: B, decimals: 1}]"), ""),
        ("enum and sentinel together", msg("m", "[{name: x, type: U8, enum: {1: one}, sentinel: {2: two}}]"), ""),
    ],
    "json-field-values": [
        ("a sentinel outside the type", msg("m", "[{name: x, type: U8, range: [0, 9], sentinel: {-1: unknown}}]"), ""),
        ("a string enum value longer than the type allows", msg("m", "[{name: x, type: T, enum: {ABCD: long}}]"), ""),
        ("an integer enum key on a string field", msg("m", "[{name: x, type: T, enum: {1: one}}]"), ""),
        ("a string enum key on an integer field", msg("m", "[{name: x, type: U8, enum: {A: one}}]"), ""),
        ("an empty range", msg("m", "[{name: x, type: F, range: [5, 1]}]"), ""),
        ("a range with no integer", msg("m", "[{name: x, type: U8, range: [0.2, 0.8]}]"), ""),
        ("a range outside the type", msg("m", "[{name: x, type: U8, range: [300, 400]}]"), ""),
        ("a string type no string fits", msg("m", "[{name: x, type: W}]"), "  W: {json: string, min_length: 3, max_length: 2}\n"),
    ],
    "json-command-key": [
        ("a string cmd key", msg("m", "[{name: cmd, type: T}]", ", cmd: 1, role: request"), ""),
        ("a plain message with a cmd key beside commands",
         msg("m", "[{name: cmd, type: U8}]", ", cmd: 1, role: request") + msg("n", "[{name: cmd, type: U8}, {name: y, type: U8}]"), ""),
    ],
    "json-reply-match": [
        ("two replies to one request",
         msg("q", "[{name: cmd, type: U8}]", ", cmd: 1, role: request")
         + msg("r1", "[{name: cmd, type: U8}, {name: res, type: S8}]", ", cmd: 1, role: reply, reply_to: q", "b", "a")
         + msg("r2", "[{name: cmd, type: U8}, {name: err, type: S8}]", ", cmd: 1, role: reply, reply_to: q", "b", "a"), ""),
    ],
    "json-binding-name": [
        ("two enum values alike", msg("m", "[{name: x, type: U8, enum: {1: a_b, 2: a__b}}]"), ""),
        ("two sentinels alike",
         msg("m", "[{name: x, type: S8, range: [0, 9], sentinel: {-1: y_z}}, {name: x_y, type: S8, range: [0, 9], sentinel: {-1: z}}]"), ""),
    ],
    "json-schema-file": [
        ("a message named like a receiver's schema", msg("to_b", "[{name: x, type: U8}]"), ""),
    ],
}


@pytest.mark.parametrize(("rule", "why", "messages", "types"), [(r, *case) for r, cases in REFUSED.items() for case in cases],
                         ids=lambda v: v if isinstance(v, str) and len(v) < 60 else None)
def test_refused_with_its_rule(tmp_path, rule, why, messages, types):
    found = problems(tmp_path, spec_text(messages, types))
    assert found and {r for r, _ in found} == {rule}, (why, found)
    assert all(line > 0 for _, line in found), found


def test_keyword_protocol_names_are_refused(tmp_path):
    assert {r for r, _ in problems(tmp_path, spec_text(msg("m", "[{name: x, type: U8}]"), name="class"))} == {"json-protocol-name"}


def test_two_protocols_of_one_name_are_refused(tmp_path):
    for part in ("one", "two"):
        (tmp_path / f"{part}.yaml").write_text(spec_text(msg(f"m_{part}", "[{name: x, type: U8}]")), encoding="utf-8")
    (tmp_path / "canspec.yaml").write_text("schema_version: 1\nkind: bundle\nfiles: [one.yaml, two.yaml]\n", encoding="utf-8")
    compiled = compile_spec(tmp_path / "canspec.yaml")
    assert [(p.rule, p.loc.file.endswith("two.yaml") if p.loc else None) for p in compiled.errors] == [("json-protocol-name", True)]


ACCEPTED = [
    ("integer types at ±(2^53 - 1)", msg("m", "[{name: x, type: I}]"), "  I: {json: integer, min: -9007199254740991, max: 9007199254740991}\n"),
    ("a range reaching past its type", msg("m", "[{name: x, type: U8, range: [-5, 400]}]"), ""),
    ("a range holding only its sentinel's neighbours", msg("m", "[{name: x, type: S8, range: [3, 3], sentinel: {-1: none}}]"), ""),
    ("decimals on an integer", msg("m", "[{name: x, type: U8, decimals: 0}]"), ""),
    ("a cmd key without commands", msg("m", "[{name: cmd, type: T}]"), ""),
    ("a command without its number on the wire", msg("m", "[{name: x, type: U8}]", ", cmd: 7, role: request"), ""),
    ("names alike once escaped are still distinct", msg("m", "[{name: self, type: U8}, {name: self_value, type: U8}, {name: to_json, type: U8}]"), ""),
    ("a message without fields, and one with the same keys as another",
     msg("m", "[]") + msg("n", "[{name: x, type: U8}]") + msg("o", "[{name: x, type: S8}]", "", "b", "a"), ""),
]


@pytest.mark.parametrize(("why", "messages", "types"), ACCEPTED, ids=[a[0] for a in ACCEPTED])
def test_just_inside_the_rules_every_json_target_generates(tmp_path, why, messages, types):
    path = tmp_path / "spec.yaml"
    path.write_text(spec_text(messages, types), encoding="utf-8")
    compiled = compile_spec(path)
    assert compiled.spec is not None, [p.format() for p in compiled.problems]
    outputs = generate(compiled.spec, ["jsonschema", "json_bindings", "json_vectors"])
    assert all(outputs.values()), why
