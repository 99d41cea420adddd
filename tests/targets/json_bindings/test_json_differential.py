"""Differential fuzzing over seeded random mutations of the vector cases: the Python bindings,
Python jsonschema, ajv, the Rust bindings and the TypeScript reader must give the same verdict
on every message, the bindings the same field and rule at fault. The mutations (dropped keys,
keys set to odd values, added keys) are written as a vectors-format file that the ajv script
and the Rust and TypeScript runners read like the real vectors."""

from __future__ import annotations

import copy
import json
import os
import random
from typing import Any

import jsonschema
from json_support import HERE, NODE_MODULES, SCHEMAS, require_tool, run

SEED = 20240526
COUNT = 1500
ODD_VALUES: list[Any] = [None, True, False, 0, -1, 1, 2, 3, 4, 5, 6, 7, -2, -3, -4, 100, 100.01, -100.01, 255, 256, 65536, -129, 32768,
                         2**53 - 1, 2**53, 2**64, 1.5, 2.0, -0.0, 1e300, 3.5e38, 180.000001, 360.1, "", "N", "D", "R", "P", "-", "X", "NN",
                         "1", [], {}, [1], {"a": 1}]
EXTRA_KEYS = ["x", "cmd", "res", "ro", "tr", "pL", "Spd", "bn"]


def mutate(rng: random.Random, obj: Any) -> Any:
    if not isinstance(obj, dict) or rng.random() < 0.03:
        return rng.choice(ODD_VALUES)
    out = copy.deepcopy(obj)
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        op = rng.random()
        if op < 0.25 and out:
            out.pop(rng.choice(sorted(out)))
        elif op < 0.85 and out:
            out[rng.choice(sorted(out))] = rng.choice(ODD_VALUES)
        else:
            out[rng.choice(EXTRA_KEYS)] = rng.choice(ODD_VALUES)
    return out


def fuzz_cases(cases: list[dict[str, Any]]) -> list[dict[str, Any]]:
    rng = random.Random(SEED)
    valid = [c for c in cases if c["valid"]]
    out = []
    for i in range(COUNT):
        base = rng.choice(valid)
        out.append({"id": f"fuzz/{i}", "message": base["message"], "receiver": base["receiver"], "json": mutate(rng, base["json"])})
    return out


def python_verdicts(rd, c: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    try:
        rd.MESSAGES[c["message"]].from_json(c["json"])
        out.update(valid=True)
    except rd.ValidationError as e:
        out.update(valid=False, field=e.field, rule=e.code)
    for label, receiver in (("as_received", c["receiver"]), ("as_any", None)):
        try:
            out[label] = rd.parse(c["json"], receiver).NAME
        except rd.ValidationError:
            out[label] = None
    return out


def test_five_implementations_agree_on_random_mutations(rd, cases, schemas, rust_runner, ts_runner, tmp_path):
    fuzz = fuzz_cases(cases)
    path = tmp_path / "fuzz.json"
    path.write_text(json.dumps({"format": 1, "protocols": [{"protocol": "remote_driving", "cases": fuzz}]}), encoding="utf-8")
    rust = {r["id"]: r for r in json.loads(run([str(rust_runner), str(path)], "Rust runner (fuzz)").stdout)}
    ts = {r["id"]: r for r in json.loads(run([*ts_runner, str(path)], "TypeScript runner (fuzz)").stdout)}
    node = require_tool("node")
    env = {**os.environ, "NODE_PATH": str(NODE_MODULES)}
    ajv = {r["id"]: r for r in json.loads(run([node, str(HERE / "node" / "ajv_check.cjs"), str(SCHEMAS), str(path)], "ajv (fuzz)", env=env).stdout)}
    validators = {name: jsonschema.Draft202012Validator(s) for name, s in schemas.items()}
    bad = []
    valid_count = 0
    for c in fuzz:
        py = python_verdicts(rd, c)
        valid_count += py["valid"]
        r, a = rust[c["id"]], ajv[c["id"]]
        own = validators[c["message"]].is_valid(c["json"])
        received = validators[f"to_{c['receiver']}"].is_valid(c["json"])
        whole = validators["protocol"].is_valid(c["json"])
        if not (py["valid"] == r["valid"] == a["own"] == own):
            bad.append((c["json"], "own", py["valid"], r["valid"], a["own"], own))
        elif not py["valid"] and (py["field"], py["rule"]) != (r["field"], r["rule"]):
            bad.append((c["json"], "fault", py, r.get("error")))
        if not ((py["as_received"] is not None) == (r["as_received"] is not None) == a["received"] == received):
            bad.append((c["json"], "received", py["as_received"], r["as_received"], a["received"], received))
        if not ((py["as_any"] is not None) == (r["as_any"] is not None) == a["any"] == whole):
            bad.append((c["json"], "any", py["as_any"], r["as_any"], a["any"], whole))
        if (py["as_received"], py["as_any"]) != (r["as_received"], r["as_any"]):
            bad.append((c["json"], "dispatch", py, r))
        t = ts[c["id"]]
        if {k: t.get(k) for k in py} != py or not t["text"]:
            bad.append((c["json"], "TypeScript", py, t))
    assert bad == [], bad[:10]
    assert 50 < valid_count < COUNT - 500  # the mutations reach both verdicts
