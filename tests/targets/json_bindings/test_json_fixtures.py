"""Any valid JSON protocol, every JSON target: for each valid spec fixture holding a JSON
protocol (tests/fixtures/valid/), the JSON Schemas agree with the spec's own vectors under
Python jsonschema and ajv; the Python bindings pass ruff, mypy --strict and their vector runner;
the Rust bindings pass clippy -D warnings and their vector runner; the TypeScript declarations
and reader compile under tsc --strict with every valid case typed as its message, and the reader
gives every vector's verdict, fault and dispatch. Batched (fixture_batch.py)."""

from __future__ import annotations

import json

import jsonschema
import pytest
from fixture_batch import Output, ajv, generate_all, python_lint, python_runner, rust_workspace, typescript, typescript_readers
from json_support import fields_at_fault, run

# What the fixtures must exercise between them (the features this test exists for).
FEATURES = ("json_english_only", "json_keywords", "json_string_enums", "json_bundle_protocols", "json_no_messages", "minimal_json")


@pytest.fixture(scope="module")
def outputs(tmp_path_factory) -> list[Output]:
    return generate_all(tmp_path_factory.mktemp("json-fixtures"))


def _each_case(outputs: list[Output]):
    for o in outputs:
        for protocol, cases in o.cases.items():
            for c in cases:
                yield o, protocol, c


def test_the_fixtures_hold_json_protocols(outputs):
    assert set(FEATURES) <= {o.fixture for o in outputs}
    assert any(len(o.protocols) > 1 for o in outputs), "a spec with several JSON protocols"
    for o in outputs:
        for protocol, cases in o.cases.items():
            assert cases or o.fixture == "json_no_messages", (o.fixture, protocol)


def test_schemas_agree_with_the_vectors_under_jsonschema(outputs):
    bad, validators = [], {}

    def validator(o: Output, protocol: str, name: str) -> jsonschema.Draft202012Validator:
        key = (o.fixture, protocol, name)
        if key not in validators:
            schema = o.schema(protocol, name)
            jsonschema.Draft202012Validator.check_schema(schema)
            validators[key] = jsonschema.Draft202012Validator(schema)
        return validators[key]

    for o, protocol, c in _each_case(outputs):
        own = validator(o, protocol, c["message"])
        verdicts = (own.is_valid(c["json"]), validator(o, protocol, f"to_{c['receiver']}").is_valid(c["json"]),
                    validator(o, protocol, "protocol").is_valid(c["json"]))
        if verdicts != (c["valid"], c["as_received"] is not None, c["as_any"] is not None):
            bad.append((o.fixture, c["id"], verdicts))
        elif not c["valid"] and c["field"] not in fields_at_fault(own, c["json"]):
            bad.append((o.fixture, c["id"], "field", c["field"], fields_at_fault(own, c["json"])))
    assert bad == [], bad[:20]


def test_schemas_agree_with_the_vectors_under_ajv(outputs):
    results = ajv(outputs)
    bad = []
    for o, protocol, c in _each_case(outputs):
        r = results[(o.fixture, protocol, c["id"])]
        if (r["own"], r["received"], r["any"]) != (c["valid"], c["as_received"] is not None, c["as_any"] is not None):
            bad.append((o.fixture, c["id"], r))
        elif not c["valid"] and c["field"] not in r["own_fields"]:
            bad.append((o.fixture, c["id"], "field", c["field"], r["own_fields"]))
    assert len(results) == sum(1 for _ in _each_case(outputs))
    assert bad == [], bad[:20]


def test_python_bindings_run_their_vectors(outputs):
    for o in outputs:
        out = python_runner(o)
        assert out.endswith(f"{sum(len(c) for c in o.cases.values())} passed, 0 failed\n"), (o.fixture, out)


def test_python_bindings_pass_ruff_and_mypy_strict(outputs, tmp_path):
    python_lint(outputs, tmp_path)


def test_rust_bindings_pass_clippy_and_run_their_vectors(outputs, tmp_path):
    runners = rust_workspace(outputs, tmp_path)
    for o in outputs:
        for protocol, cases in o.cases.items():
            proc = run([str(runners[o.unit(protocol)]), "--check", str(o.vectors)], f"Rust vector runner ({o.unit(protocol)})")
            assert f"{len(cases)} passed, 0 failed" in proc.stdout, (o.unit(protocol), proc.stdout, proc.stderr[-3000:])


def test_typescript_declarations_pass_tsc_strict(outputs, tmp_path):
    typescript(outputs, tmp_path)


def test_typescript_readers_run_their_vectors(outputs, tmp_path):
    runners = typescript_readers(outputs, tmp_path)
    bad = []
    for o in outputs:
        for protocol, cases in o.cases.items():
            proc = run([*runners[o.unit(protocol)], str(o.vectors)], f"TypeScript reader runner ({o.unit(protocol)})")
            results = {r["id"]: r for r in json.loads(proc.stdout)}
            assert len(results) == len(cases), o.unit(protocol)
            for c in cases:
                r = results[c["id"]]
                want = {"valid": c["valid"], **({} if c["valid"] else {"field": c["field"], "rule": c["rule"]})}
                got = {k: r.get(k) for k in want}
                if got != want or (r["as_received"], r["as_any"]) != (c["as_received"], c["as_any"]) or not r["text"]:
                    bad.append((o.unit(protocol), c["id"], r, want, c["as_received"], c["as_any"]))
    assert bad == [], bad[:20]
